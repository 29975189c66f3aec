#include "export/export_source.h"

#include <fmt/format.h>

namespace planet {

nlohmann::ordered_json exportProvenance(const PlanetDescription& planet, const ExportSource& source, double spacingM) {
  nlohmann::ordered_json j;
  j["preset"] = source.preset;
  j["planet_name"] = planet.name;
  j["preset_hash"] = fmt::format("{:016x}", descriptionHash(planet));
  j["seed_offset"] = source.seedOffset;
  j["radius_m"] = planet.radiusM;
  j["has_ocean"] = planet.hasOcean;
  j["sea_level_m"] = planet.seaLevelM;
  j["planet_frame"] = "+z is the north pole, +x latitude 0 longitude 0, +y longitude 90 E; metres";
  j["height"] = "metres above the sphere of radius_m along the direction from the planet's centre";
  j["detail"] = spacingM > 0.0 ? "filtered" : "full";
  j["spacing_m"] = spacingM;
  j["detail_note"] = spacingM > 0.0 ? "each layer limited to the octaves a spacing_m grid can show "
                                      "(terrainHeightM(planet, direction, spacing_m))"
                                    : "every octave, the heights planet height prints";
  return j;
}

std::string detailText(double spacingM) {
  return spacingM > 0.0 ? fmt::format("octaves limited to a {:.1f} m spacing", spacingM) : "full detail";
}

}  // namespace planet

// What every exported file says about where it came from (the heightmap's sidecar, the glTF's
// extras, the OBJ's comments): enough to trace it back to the terrain that made it, reproduce
// it, and check it against `planet height`.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "planet/planet_description.h"

namespace planet {

struct ExportSource {
  std::string preset;       // as given to --preset: a built-in name or a .toml path
  uint64_t seedOffset = 0;  // --seed: added to every layer's seed (0: the preset's own seeds)
};

// The preset as given, the planet's name, descriptionHash (16 hex digits, of the description
// with the seed offset applied), the seed offset, radius, ocean and sea level, the planet frame
// (+z north pole, +x latitude 0 / longitude 0, +y longitude 90° E), what a height means, and
// the octave limit: `spacingM` 0 is the full-detail surface `planet height` prints, else
// terrainHeightM's octave budget for that spacing (octave_budget.h).
nlohmann::ordered_json exportProvenance(const PlanetDescription& planet, const ExportSource& source, double spacingM);

// "full detail" or "octaves limited to a 1234.5 m spacing", for one-line summaries.
std::string detailText(double spacingM);

}  // namespace planet

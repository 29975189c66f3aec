#include "planet/ring_description.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/error.h"
#include "planet/toml_reader.h"

namespace planet {
namespace {

constexpr std::string_view kRingKeys[] = {"inner_radius_m",   "outer_radius_m", "seed",    "colour",
                                          "colour_variation", "opacity",        "octaves", "gaps"};

// Messages print numbers as %g does: "7.45e+07", "0.5", "nan".
std::string formatValue(double value) { return fmt::format("{:g}", value); }

void checkRadius(const char* key, double value) {
  if (!(std::isfinite(value) && value > 0.0))
    throw Error(fmt::format("ring {} must be a positive finite number of metres, got {}", key, formatValue(value)));
}

void checkColour(const char* key, const glm::dvec3& colour) {
  for (int i = 0; i < 3; ++i)
    if (!(colour[i] >= 0.0 && colour[i] <= 1.0))
      throw Error(fmt::format("ring {}[{}] must be in [0, 1], got {}", key, i, formatValue(colour[i])));
}

}  // namespace

void validateRingDescription(const RingDescription& ring) {
  checkRadius("inner_radius_m", ring.innerRadiusM);
  checkRadius("outer_radius_m", ring.outerRadiusM);
  if (!(ring.innerRadiusM < ring.outerRadiusM))
    throw Error(fmt::format("ring inner_radius_m ({}) must be below outer_radius_m ({})",
                            formatValue(ring.innerRadiusM), formatValue(ring.outerRadiusM)));
  // The shaders hold radii in float and the ring coordinate's scale as 1 / width: a width below
  // a millionth of the radius would be float noise.
  if (!(ring.outerRadiusM - ring.innerRadiusM >= 1e-6 * ring.outerRadiusM))
    throw Error(
        fmt::format("ring width outer_radius_m − inner_radius_m ({} m) must be at least 1e-6 of the outer radius",
                    formatValue(ring.outerRadiusM - ring.innerRadiusM)));
  checkColour("colour", ring.colour);
  checkColour("colour_variation", ring.colourVariation);
  if (!(ring.opacity >= 0.0 && ring.opacity <= 1.0))
    throw Error(fmt::format("ring opacity must be in [0, 1], got {}", formatValue(ring.opacity)));
  if (ring.octaves < 1 || ring.octaves > gpu::kRingMaxOctaves)
    throw Error(fmt::format("ring octaves must be in 1..{}, got {}", gpu::kRingMaxOctaves, ring.octaves));
  if (ring.gaps > gpu::kRingMaxGaps)
    throw Error(fmt::format("ring gaps must be in 0..{}, got {}", gpu::kRingMaxGaps, ring.gaps));
}

RingDescription parseRingTable(const toml::table& table, std::string_view where) {
  const std::string source(where);
  const toml_reader::Context context(source);
  // Unknown keys first, then each value's type and the ranges a key checks on its own; the
  // relations between keys (inner below outer) are validateRingDescription's.
  const toml_reader::TableReader reader(context, table, "the ring table", kRingKeys);
  constexpr Range kRadius{1.0, 1e13};
  RingDescription ring;
  ring.innerRadiusM = reader.number("inner_radius_m", kRadius).value_or(ring.innerRadiusM);
  ring.outerRadiusM = reader.number("outer_radius_m", kRadius).value_or(ring.outerRadiusM);
  ring.seed = uint32_t(reader.integer("seed", kSeedRange).value_or(ring.seed));
  ring.colour = reader.vector3("colour", kColorComponentRange).value_or(ring.colour);
  ring.colourVariation = reader.vector3("colour_variation", kColorComponentRange).value_or(ring.colourVariation);
  ring.opacity = reader.number("opacity", kUnitRange).value_or(ring.opacity);
  ring.octaves = uint32_t(reader.integer("octaves", Range{1.0, double(gpu::kRingMaxOctaves)}).value_or(ring.octaves));
  ring.gaps = uint32_t(reader.integer("gaps", Range{0.0, double(gpu::kRingMaxGaps)}).value_or(ring.gaps));
  // The message names the field; the line is that of the key it names first (the longer of two
  // at the same place: colour_variation, not colour), else the table's.
  try {
    validateRingDescription(ring);
  } catch (const Error& e) {
    const std::string message = e.what();
    std::string_view named;
    size_t namedAt = std::string::npos;
    for (std::string_view key : kRingKeys) {
      const size_t at = message.find(key);
      if (at != std::string::npos && (at < namedAt || (at == namedAt && key.size() > named.size()))) {
        named = key;
        namedAt = at;
      }
    }
    const toml::node* node = named.empty() ? nullptr : table.get(named);
    context.fail(node ? toml_reader::lineOf(*node) : reader.line(), message);
  }
  return ring;
}

}  // namespace planet

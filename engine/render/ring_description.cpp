#include "render/ring_description.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/error.h"
#include "render/ring_density.h"

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

const char* typeName(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "table";
    case toml::node_type::array: return "array";
    case toml::node_type::string: return "string";
    case toml::node_type::integer: return "integer";
    case toml::node_type::floating_point: return "float";
    case toml::node_type::boolean: return "boolean";
    case toml::node_type::date: return "date";
    case toml::node_type::time: return "time";
    case toml::node_type::date_time: return "date-time";
    default: return "nothing";
  }
}

// A key as quoted in a message: one line, not huge (a key may be as long as the file).
std::string shortened(std::string_view text) {
  std::string out;
  for (char c : text.substr(0, 60)) out += (uint8_t(c) < 0x20 || c == 0x7f) ? '?' : c;
  return text.size() > 60 ? out + "..." : out;
}

// Reads the ring table the way planet_description.cpp reads a preset's tables: unknown keys are
// rejected first (a typo is reported as itself), then each value's type is checked; ranges are
// validateRingDescription's.
class RingTableReader {
 public:
  RingTableReader(const toml::table& table, std::string_view where) : table_(table), where_(where) {
    for (auto&& [key, value] : table)
      if (std::find(std::begin(kRingKeys), std::end(kRingKeys), key.str()) == std::end(kRingKeys))
        fail(key.source().begin.line, fmt::format("unknown key '{}' in the ring table", shortened(key.str())));
  }

  [[noreturn]] void fail(uint32_t line, const std::string& message) const {
    if (line == 0) throw Error(fmt::format("{}: {}", where_, message));
    throw Error(fmt::format("{}:{}: {}", where_, line, message));
  }
  uint32_t tableLine() const { return table_.source().begin.line; }
  uint32_t lineOf(std::string_view key) const {
    const toml::node* node = table_.get(key);
    return node ? node->source().begin.line : table_.source().begin.line;
  }

  std::optional<double> number(std::string_view key) const {
    const toml::node* node = table_.get(key);
    if (!node) return std::nullopt;
    if (auto integer = node->as_integer()) return double(integer->get());
    if (auto floating = node->as_floating_point()) return floating->get();
    fail(lineOf(key), fmt::format("'{}' must be a number, got {}", key, typeName(*node)));
  }

  // An integer in [0, max].
  std::optional<uint32_t> integer(std::string_view key, int64_t max) const {
    const toml::node* node = table_.get(key);
    if (!node) return std::nullopt;
    auto integer = node->as_integer();
    if (!integer) fail(lineOf(key), fmt::format("'{}' must be an integer, got {}", key, typeName(*node)));
    const int64_t value = integer->get();
    if (value < 0 || value > max) fail(lineOf(key), fmt::format("{} must be in [0, {}], got {}", key, max, value));
    return uint32_t(value);
  }

  // [r, g, b] of numbers (ranges: validateRingDescription).
  std::optional<glm::dvec3> colour(std::string_view key) const {
    const toml::node* node = table_.get(key);
    if (!node) return std::nullopt;
    const toml::array* array = node->as_array();
    if (!array || array->size() != 3)
      fail(lineOf(key), fmt::format("'{}' must be an array of 3 numbers [r, g, b], got {}", key,
                                    array ? fmt::format("{} elements", array->size()) : typeName(*node)));
    glm::dvec3 result;
    for (size_t i = 0; i < 3; ++i) {
      const toml::node& element = *array->get(i);
      if (auto integer = element.as_integer())
        result[int(i)] = double(integer->get());
      else if (auto floating = element.as_floating_point())
        result[int(i)] = floating->get();
      else
        fail(element.source().begin.line, fmt::format("{}[{}] must be a number, got {}", key, i, typeName(element)));
    }
    return result;
  }

 private:
  const toml::table& table_;
  std::string_view where_;
};

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
  RingTableReader reader(table, where);
  RingDescription ring;
  ring.innerRadiusM = reader.number("inner_radius_m").value_or(ring.innerRadiusM);
  ring.outerRadiusM = reader.number("outer_radius_m").value_or(ring.outerRadiusM);
  ring.seed = reader.integer("seed", UINT32_MAX).value_or(ring.seed);
  ring.colour = reader.colour("colour").value_or(ring.colour);
  ring.colourVariation = reader.colour("colour_variation").value_or(ring.colourVariation);
  ring.opacity = reader.number("opacity").value_or(ring.opacity);
  ring.octaves = reader.integer("octaves", UINT32_MAX).value_or(ring.octaves);
  ring.gaps = reader.integer("gaps", UINT32_MAX).value_or(ring.gaps);
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
    reader.fail(named.empty() ? reader.tableLine() : reader.lineOf(named), message);
  }
  return ring;
}

gpu::RingParams ringGpuParams(const RingDescription& ring, double planetRadiusM, double sunAngularRadiusRad) {
  validateRingDescription(ring);
  if (!(std::isfinite(planetRadiusM) && planetRadiusM > 0.0))
    throw Error(fmt::format("ringed body radius must be a positive finite number of metres, got {}",
                            formatValue(planetRadiusM)));
  if (!(std::isfinite(sunAngularRadiusRad) && sunAngularRadiusRad >= 0.0 && sunAngularRadiusRad < 1.0))
    throw Error(fmt::format("sun angular radius must be in [0, 1) rad, got {}", formatValue(sunAngularRadiusRad)));
  gpu::RingParams p{};
  p.radii = glm::vec4(float(ring.innerRadiusM), float(ring.outerRadiusM),
                      float(1.0 / (ring.outerRadiusM - ring.innerRadiusM)), float(planetRadiusM));
  p.colour = glm::vec4(glm::vec3(ring.colour), float(ring.opacity));
  p.variation = glm::vec4(glm::vec3(ring.colourVariation), float(sunAngularRadiusRad));
  p.seedMix = ringHashCpu(ring.seed ^ 0x9e3779b9u);
  p.octaves = ring.octaves;
  p.gapCount = ring.gaps;
  // Gaps at seeded radii inside the middle 60 % of the ring, the first the widest (Cassini:
  // 4,700 km of Saturn's 62,000 km), each clearing 92-98 % of the opacity.
  for (uint32_t g = 0; g < ring.gaps; ++g) {
    const uint32_t h = ringHashCpu(p.seedMix + 0x632be5abu * (g + 1));
    const double a = double(h & 0xffffu) / 65535.0, b = double(h >> 16) / 65535.0;
    const double halfWidth = (g == 0 ? 0.02 + 0.015 * b : 0.004 + 0.008 * b);
    p.gaps[g] = glm::vec4(float(0.2 + 0.6 * a), float(halfWidth), float(0.92 + 0.06 * b), 0.0f);
  }
  return p;
}

}  // namespace planet

#include "planet/planet_description.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/error.h"
#include "core/file.h"

namespace planet {
namespace {

constexpr std::string_view kTopKeys[] = {"planet", "colors", "layer", "atmosphere", "clouds", "water", "stars"};
constexpr std::string_view kAtmosphereKeys[] = {"height_m",
                                                "rayleigh_scattering",
                                                "rayleigh_scale_height_m",
                                                "mie_scattering",
                                                "mie_extinction_ratio",
                                                "mie_absorption",
                                                "mie_scale_height_m",
                                                "mie_g",
                                                "ozone_absorption",
                                                "ozone_center_m",
                                                "ozone_width_m"};
constexpr std::string_view kCloudKeys[] = {"bottom_m", "top_m", "coverage", "sharpness",       "wavelength_m",
                                           "octaves",  "seed",  "wind_mps", "evolve_period_s", "opacity"};
constexpr std::string_view kWaterKeys[] = {"clarity_m", "wave_wavelength_m", "wave_slope"};
constexpr std::string_view kStarKeys[] = {"enabled", "seed", "faintest_magnitude", "brightness"};
constexpr std::string_view kPlanetKeys[] = {"name",        "radius_m",     "has_ocean",
                                            "sea_level_m", "height_scale", "base_height_m"};
constexpr std::string_view kColorKeys[] = {"scheme",     "beach_height_m", "snow_line_m", "ice_cap_latitude_deg",
                                           "deep_water", "shallow_water",  "beach",       "lowland",
                                           "highland",   "cliff",          "snow"};
constexpr std::string_view kLayerKeys[] = {"name", "type", "octaves",   "lacunarity",   "H",          "offset", "gain",
                                           "seed", "hash", "frequency", "wavelength_m", "amplitude_m"};

struct SchemeName {
  ColorScheme scheme;
  const char* name;
};
constexpr SchemeName kSchemeNames[] = {
    {ColorScheme::Earth, "earth"},
    {ColorScheme::Altitude, "altitude"},
    {ColorScheme::Moon, "moon"},
    {ColorScheme::Mars, "mars"},
};

// Shortest text that reads back to the same value, with a compact exponent ("1e8", "3e-7"),
// so messages quote ranges as written and canonicalForm is exact. Floats (colours) use their
// own shortest form ("0.3", not 0.30000001192092896).
template <typename Real>
std::string formatNumber(Real value) {
  if (value == Real(0)) value = Real(0);  // -0 prints as 0: equal values, equal text
  char buffer[64];
  std::string text(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
  size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  bool negative = exponent[0] == '-';
  size_t digits = exponent.find_first_not_of("+-0");
  return text.substr(0, e + 1) + (negative ? "-" : "") + exponent.substr(digits == std::string::npos ? 0 : digits);
}

std::string formatRange(Range range) {
  return fmt::format("[{}, {}]", formatNumber(range.min), formatNumber(range.max));
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

uint32_t lineOf(const toml::node& node) { return node.source().begin.line; }

// Where messages come from: "earth.toml:12: ..." (or "earth.toml: ..." without a line).
class Context {
 public:
  explicit Context(const std::string& source) : source_(source) {}

  [[noreturn]] void fail(uint32_t line, const std::string& message) const {
    if (line == 0) throw Error(fmt::format("{}: {}", source_, message));
    throw Error(fmt::format("{}:{}: {}", source_, line, message));
  }

  const std::string& source() const { return source_; }

 private:
  const std::string& source_;
};

// Text that toml++ would reject with a confusing message (or that is not text at all) is
// reported first: empty input, bytes over the size limit, control bytes, invalid UTF-8.
void checkText(const Context& context, std::string_view text) {
  if (text.size() > kMaxPresetBytes)
    context.fail(0, fmt::format("too large ({} bytes, limit {})", text.size(), kMaxPresetBytes));
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos)
    context.fail(0, "empty document (expected [planet], [colors] and [[layer]] tables)");
  uint32_t line = 1, column = 1;
  for (size_t i = 0; i < text.size();) {
    auto byte = uint8_t(text[i]);
    size_t length = byte < 0x80 ? 1 : (byte >> 5) == 0x6 ? 2 : (byte >> 4) == 0xe ? 3 : (byte >> 3) == 0x1e ? 4 : 0;
    bool valid = length != 0 && i + length <= text.size();
    uint32_t codePoint = length == 1 ? byte : byte & (0x7fu >> length);
    for (size_t k = 1; valid && k < length; ++k) {
      auto next = uint8_t(text[i + k]);
      valid = (next & 0xc0) == 0x80;
      codePoint = (codePoint << 6) | (next & 0x3fu);
    }
    // Overlong forms, UTF-16 surrogates and values past U+10FFFF are not UTF-8 either.
    constexpr uint32_t kMinForLength[] = {0, 0, 0x80, 0x800, 0x10000};
    valid = valid && codePoint >= kMinForLength[length] && codePoint <= 0x10ffff &&
            !(codePoint >= 0xd800 && codePoint <= 0xdfff);
    if (!valid)
      throw Error(
          fmt::format("{}:{}:{}: not UTF-8 text (invalid byte 0x{:02x})", context.source(), line, column, byte));
    if ((byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r') || byte == 0x7f)
      throw Error(fmt::format("{}:{}:{}: not TOML text (control byte 0x{:02x})", context.source(), line, column, byte));
    if (byte == '\n') {
      ++line;
      column = 0;
    }
    ++column;
    i += length;
  }
}

// toml++ builds one table per part of a dotted key or table header ([a.a.a], a.a.a = 1) and
// walks the tree recursively: tens of thousands of parts (a file of 100 kB, well under the
// size limit) overflow the stack. No preset key has more than two parts, so key paths are
// measured before toml++ sees the text. Values nest at most TOML_MAX_NESTED_VALUES deep
// (toml++ checks that), so the depth of the tree stays bounded.
constexpr int kMaxKeyParts = 8;

// Walks the text as TOML: strings and comments are skipped, '[' and '{' in values are tracked,
// and each key path (of a header, a key = value line or an inline table's entry) has its parts
// counted, and non-ASCII bytes outside strings and comments are refused. Malformed text is left
// to toml++ to report, which reads the text in the same order: a deep path is found here before
// toml++ reaches anything that it would reject.
class KeyDepthCheck {
 public:
  KeyDepthCheck(const Context& context, std::string_view text) : context_(context), text_(text) {}

  void run() {
    std::vector<char> open;  // '[' and '{' of the values around the scan position
    bool expectKey = true;   // at a line's start outside values, or after '{' or ',' in an inline table
    while (i_ < text_.size()) {
      const char c = text_[i_];
      // TOML allows non-ASCII text only in strings and comments, which are stepped over here.
      // It is rejected before toml++ sees it: toml++ 3.3 reaches __builtin_unreachable on most
      // such characters where it skips whitespace (upstream issues #190 and #295).
      if (uint8_t(c) >= 0x80)
        context_.fail(line_, "a non-ASCII character outside a string or a comment (TOML keys and values are ASCII)");
      if (c == '\n') {
        ++line_;
        ++i_;
        expectKey = expectKey || open.empty();
      } else if (c == ' ' || c == '\t' || c == '\r') {
        ++i_;
      } else if (c == '#') {
        i_ = std::min(text_.find('\n', i_), text_.size());
      } else if (expectKey) {
        expectKey = false;
        if (open.empty() && c == '[') {  // a header: [table] or [[array]]
          ++i_;
          if (i_ < text_.size() && text_[i_] == '[') ++i_;
        } else if (c == '}' && !open.empty() && open.back() == '{') {  // an empty inline table
          open.pop_back();
          ++i_;
          continue;
        }
        const int parts = keyPath();
        if (parts > kMaxKeyParts)
          context_.fail(line_, fmt::format("a key path of {} parts nests too deep (at most {})", parts, kMaxKeyParts));
        // Not a key at all (toml++ says what it is): step over it, but not over a line's end.
        if (parts == 0 && i_ < text_.size() && text_[i_] != '\n') ++i_;
      } else if (c == '"' || c == '\'') {
        string(true);
      } else {
        ++i_;
        if (c == '[' || c == '{') open.push_back(c);
        if ((c == ']' || c == '}') && !open.empty()) open.pop_back();
        expectKey = (c == '{') || (c == ',' && !open.empty() && open.back() == '{');
      }
    }
  }

 private:
  // Parts of the dotted key at i_ ("a", "b" and "c" of a . "b" . 'c'); stops after the last.
  int keyPath() {
    int parts = 0;
    while (true) {
      skipBlanks();
      if (i_ >= text_.size()) break;
      if (text_[i_] == '"' || text_[i_] == '\'') {
        string(false);
      } else {
        const size_t start = i_;
        while (i_ < text_.size() && isBareKeyByte(text_[i_])) ++i_;
        if (i_ == start) break;
      }
      ++parts;
      skipBlanks();
      if (i_ >= text_.size() || text_[i_] != '.') break;
      ++i_;
    }
    return parts;
  }

  // TOML 1.0 bare keys: ASCII letters, digits, '_' and '-'.
  static bool isBareKeyByte(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  }

  void skipBlanks() {
    while (i_ < text_.size() && (text_[i_] == ' ' || text_[i_] == '\t')) ++i_;
  }

  // Skips the string that starts at i_: basic ("...", with escapes) or literal ('...'), and
  // where `multiLine` allows, their triple-quoted forms (which may hold newlines).
  void string(bool multiLine) {
    const char quote = text_[i_];
    const bool basic = quote == '"';
    const std::string_view triple = basic ? R"(""")" : "'''";
    auto step = [&] { return basic && text_[i_] == '\\' && i_ + 1 < text_.size() && text_[i_ + 1] != '\n' ? 2 : 1; };
    if (multiLine && text_.substr(i_).starts_with(triple)) {
      i_ += 3;
      while (i_ < text_.size() && !text_.substr(i_).starts_with(triple)) {
        if (text_[i_] == '\n') ++line_;
        if (basic && text_[i_] == '\\') backslash();
        i_ += step();
      }
      i_ = std::min(i_ + 3, text_.size());
      // Up to two more quotes belong to the content ("""a"""" ends with a quote).
      for (int k = 0; k < 2 && i_ < text_.size() && text_[i_] == quote; ++k) ++i_;
      return;
    }
    ++i_;
    while (i_ < text_.size() && text_[i_] != quote && text_[i_] != '\n') {
      if (basic && text_[i_] == '\\') backslash();
      i_ += step();
    }
    if (i_ < text_.size() && text_[i_] == quote) ++i_;
  }

  // At a backslash in a basic string. toml++ 3.3 asks whether the characters after it are
  // whitespace (an escape, or a line-ending backslash whose following whitespace and newlines
  // are trimmed) and reaches __builtin_unreachable when the answer is sought for a non-ASCII
  // character (found by the fuzzer). No TOML escape is non-ASCII, so such text is refused here.
  void backslash() const {
    size_t k = i_ + 1;
    while (k < text_.size() && (text_[k] == ' ' || text_[k] == '\t' || text_[k] == '\r')) ++k;
    uint32_t line = line_;
    if (k < text_.size() && text_[k] == '\n')
      while (k < text_.size() && (text_[k] == ' ' || text_[k] == '\t' || text_[k] == '\r' || text_[k] == '\n'))
        line += text_[k++] == '\n';
    if (k < text_.size() && uint8_t(text_[k]) >= 0x80)
      context_.fail(line,
                    "a non-ASCII character after a backslash in a string: not a TOML escape (write it as \\uXXXX, "
                    "or start the line with an ASCII character after a line-ending backslash)");
  }

  const Context& context_;
  std::string_view text_;
  size_t i_ = 0;
  uint32_t line_ = 1;
};

// User text quoted in a message (a key, a value): at most `limit` bytes, cut at a character's
// start, with control characters (a quoted key may hold "\n") as '?' to keep the message one line.
std::string shortened(std::string_view text, size_t limit = 40) {
  size_t end = text.size();
  if (end > limit) {
    end = limit;
    while (end > 0 && (uint8_t(text[end]) & 0xc0) == 0x80) --end;
  }
  std::string out(text.substr(0, end));
  for (char& c : out)
    if (uint8_t(c) < 0x20 || c == 0x7f) c = '?';
  return end < text.size() ? out + "..." : out;
}

// One TOML table. Keys that are not in `known` are rejected up front, so a typo is reported
// as itself rather than as the required key it misspells; then values are read with their
// type and range checked.
class TableReader {
 public:
  TableReader(const Context& context, const toml::table& table, std::string displayName,
              std::span<const std::string_view> known)
      : context_(context), table_(table), displayName_(std::move(displayName)) {
    for (auto&& [key, value] : table) {
      if (std::find(known.begin(), known.end(), key.str()) == known.end())
        context_.fail(key.source().begin.line,
                      fmt::format("unknown key '{}' in {}", shortened(key.str()), displayName_));
    }
  }

  uint32_t line() const { return lineOf(table_); }
  const toml::node* find(std::string_view key) const { return table_.get(key); }

  [[noreturn]] void missing(std::string_view key) const {
    context_.fail(line(), fmt::format("missing key '{}' in {}", key, displayName_));
  }
  [[noreturn]] void wrongType(std::string_view key, const toml::node& node, const char* expected) const {
    context_.fail(lineOf(node), fmt::format("'{}' must be {}, got {}", key, expected, typeName(node)));
  }

  std::optional<double> number(std::string_view key, std::optional<Range> range = std::nullopt) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    double value;
    if (auto integer = node->as_integer())
      value = double(integer->get());
    else if (auto floating = node->as_floating_point())
      value = floating->get();
    else
      wrongType(key, *node, "a number");
    if (!range) return value;  // checked by its consumer (noise::validateNoiseSettings)
    if (!std::isfinite(value))
      context_.fail(lineOf(*node), fmt::format("{} must be a finite number, got {}", key, formatNumber(value)));
    if (!(value >= range->min && value <= range->max))
      context_.fail(lineOf(*node),
                    fmt::format("{} must be in {}, got {}", key, formatRange(*range), formatNumber(value)));
    return value;
  }
  double requiredNumber(std::string_view key, Range range) const {
    if (auto value = number(key, range)) return *value;
    missing(key);
  }

  std::optional<int64_t> integer(std::string_view key, Range range) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    auto integer = node->as_integer();
    if (!integer) wrongType(key, *node, "an integer");
    int64_t value = integer->get();
    if (!(double(value) >= range.min && double(value) <= range.max))
      context_.fail(lineOf(*node), fmt::format("{} must be in {}, got {}", key, formatRange(range), value));
    return value;
  }

  std::optional<bool> boolean(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    auto boolean = node->as_boolean();
    if (!boolean) wrongType(key, *node, "a boolean");
    return boolean->get();
  }

  std::optional<std::string> string(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    auto string = node->as_string();
    if (!string) wrongType(key, *node, "a string");
    return string->get();
  }
  std::string requiredString(std::string_view key) const {
    if (auto value = string(key)) return *value;
    missing(key);
  }

  // A name printed in logs and reports: one line, not empty, not huge.
  std::string name(std::string_view key) const {
    std::string value = requiredString(key);
    uint32_t at = lineOf(*find(key));
    if (value.empty() || value.size() > kMaxNameBytes)
      context_.fail(at, fmt::format("{} must be 1 to {} bytes long, got {}", key, kMaxNameBytes, value.size()));
    for (char c : value)
      if (uint8_t(c) < 0x20 || c == 0x7f) context_.fail(at, fmt::format("{} must not contain control characters", key));
    return value;
  }

  // [x, y, z], each in `range`; a single number stands for all three when `allowScalar`.
  std::optional<glm::dvec3> vector3(std::string_view key, Range range, bool allowScalar = false) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    auto component = [&](const toml::node& element, const std::string& label) {
      double value;
      if (auto integer = element.as_integer())
        value = double(integer->get());
      else if (auto floating = element.as_floating_point())
        value = floating->get();
      else
        context_.fail(lineOf(element), fmt::format("{} must be a number, got {}", label, typeName(element)));
      if (!(value >= range.min && value <= range.max))
        context_.fail(lineOf(element),
                      fmt::format("{} must be in {}, got {}", label, formatRange(range), formatNumber(value)));
      return value;
    };
    if (allowScalar && (node->is_integer() || node->is_floating_point())) {
      double value = component(*node, std::string(key));
      return glm::dvec3(value);
    }
    const toml::array* array = node->as_array();
    if (!array || array->size() != 3)
      context_.fail(lineOf(*node), fmt::format("'{}' must be {}an array of 3 numbers [r, g, b], got {}", key,
                                               allowScalar ? "a number or " : "",
                                               array ? fmt::format("{} elements", array->size()) : typeName(*node)));
    glm::dvec3 result;
    for (int i = 0; i < 3; ++i) result[i] = component(*array->get(size_t(i)), fmt::format("{}[{}]", key, i));
    return result;
  }

  // [r, g, b], linear, each in kColorComponentRange.
  std::optional<glm::vec3> color(std::string_view key) const {
    if (auto value = vector3(key, kColorComponentRange)) return glm::vec3(*value);
    return std::nullopt;
  }

 private:
  const Context& context_;
  const toml::table& table_;
  std::string displayName_;
};

// Runs `parse` (which throws planet::Error for a bad value) and prefixes its message with
// the file and line of the value that caused it.
template <typename Parse>
auto parseAt(const Context& context, uint32_t line, Parse parse) {
  try {
    return parse();
  } catch (const Error& e) {
    context.fail(line, e.what());
  }
}

const toml::table& requireTable(const Context& context, const toml::table& root, std::string_view key) {
  const toml::node* node = root.get(key);
  if (!node) context.fail(0, fmt::format("missing table [{}]", key));
  if (!node->is_table()) context.fail(lineOf(*node), fmt::format("'{}' must be a table, got {}", key, typeName(*node)));
  return *node->as_table();
}

PlanetColors readColors(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[colors]", kColorKeys);
  std::string schemeName = reader.requiredString("scheme");
  PlanetColors colors =
      defaultColors(parseAt(context, lineOf(*reader.find("scheme")), [&] { return parseColorScheme(schemeName); }));
  colors.beachHeightM = reader.number("beach_height_m", kBeachHeightRangeM).value_or(colors.beachHeightM);
  colors.snowLineM = reader.number("snow_line_m", kSnowLineRangeM).value_or(colors.snowLineM);
  colors.iceCapLatitudeDeg =
      reader.number("ice_cap_latitude_deg", kIceCapLatitudeRangeDeg).value_or(colors.iceCapLatitudeDeg);
  struct ColorKey {
    std::string_view key;
    glm::vec3 PlanetColors::*member;
  };
  const ColorKey colorKeys[] = {
      {"deep_water", &PlanetColors::deepWater},
      {"shallow_water", &PlanetColors::shallowWater},
      {"beach", &PlanetColors::beach},
      {"lowland", &PlanetColors::lowland},
      {"highland", &PlanetColors::highland},
      {"cliff", &PlanetColors::cliff},
      {"snow", &PlanetColors::snow},
  };
  for (const ColorKey& c : colorKeys)
    if (auto value = reader.color(c.key)) colors.*c.member = *value;
  return colors;
}

// An optional table: nullptr when absent, an error when the key holds something else.
const toml::table* optionalTable(const Context& context, const toml::table& root, std::string_view key) {
  const toml::node* node = root.get(key);
  if (!node) return nullptr;
  if (!node->is_table()) context.fail(lineOf(*node), fmt::format("'{}' must be a table, got {}", key, typeName(*node)));
  return node->as_table();
}

AtmosphereDescription readAtmosphere(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[atmosphere]", kAtmosphereKeys);
  AtmosphereDescription a;
  a.enabled = true;
  a.heightM = reader.number("height_m", kAtmosphereHeightRangeM).value_or(a.heightM);
  a.rayleighScattering = reader.vector3("rayleigh_scattering", kScatteringRange, true).value_or(a.rayleighScattering);
  a.rayleighScaleHeightM =
      reader.number("rayleigh_scale_height_m", kScaleHeightRangeM).value_or(a.rayleighScaleHeightM);
  a.mieScattering = reader.vector3("mie_scattering", kScatteringRange, true).value_or(a.mieScattering);
  a.mieExtinctionRatio = reader.number("mie_extinction_ratio", kMieExtinctionRatioRange).value_or(a.mieExtinctionRatio);
  a.mieAbsorption = reader.vector3("mie_absorption", kScatteringRange, true).value_or(a.mieAbsorption);
  a.mieScaleHeightM = reader.number("mie_scale_height_m", kScaleHeightRangeM).value_or(a.mieScaleHeightM);
  a.mieG = reader.number("mie_g", kMieGRange).value_or(a.mieG);
  a.ozoneAbsorption = reader.vector3("ozone_absorption", kScatteringRange, true).value_or(a.ozoneAbsorption);
  a.ozoneCenterM = reader.number("ozone_center_m", kOzoneAltitudeRangeM).value_or(a.ozoneCenterM);
  a.ozoneWidthM = reader.number("ozone_width_m", kOzoneAltitudeRangeM).value_or(a.ozoneWidthM);
  if (a.ozoneWidthM <= 0.0 && a.ozoneAbsorption != glm::dvec3(0.0))
    context.fail(lineOf(*reader.find("ozone_width_m")), "ozone_width_m must be above 0 when ozone_absorption is set");
  return a;
}

CloudDescription readClouds(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[clouds]", kCloudKeys);
  CloudDescription c;
  c.enabled = true;
  c.bottomM = reader.number("bottom_m", kCloudAltitudeRangeM).value_or(c.bottomM);
  c.topM = reader.number("top_m", kCloudAltitudeRangeM).value_or(c.topM);
  if (!(c.topM > c.bottomM)) {
    const toml::node* node = reader.find("top_m") ? reader.find("top_m") : reader.find("bottom_m");
    context.fail(node ? lineOf(*node) : reader.line(),
                 fmt::format("top_m ({}) must be above bottom_m ({})", formatNumber(c.topM), formatNumber(c.bottomM)));
  }
  c.coverage = reader.number("coverage", kUnitRange).value_or(c.coverage);
  c.sharpness = reader.number("sharpness", kSharpnessRange).value_or(c.sharpness);
  c.wavelengthM = reader.number("wavelength_m", kCloudWavelengthRangeM).value_or(c.wavelengthM);
  c.octaves = int(reader.integer("octaves", kCloudOctavesRange).value_or(c.octaves));
  c.seed = uint32_t(reader.integer("seed", kSeedRange).value_or(c.seed));
  c.windMps = reader.number("wind_mps", kWindRangeMps).value_or(c.windMps);
  c.evolvePeriodS = reader.number("evolve_period_s", kEvolvePeriodRangeS).value_or(c.evolvePeriodS);
  c.opacity = reader.number("opacity", kCloudOpacityRange).value_or(c.opacity);
  return c;
}

WaterDescription readWater(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[water]", kWaterKeys);
  WaterDescription w;
  w.clarityM = reader.number("clarity_m", kClarityRangeM).value_or(w.clarityM);
  w.waveWavelengthM = reader.number("wave_wavelength_m", kWaveWavelengthRangeM).value_or(w.waveWavelengthM);
  w.waveSlope = reader.number("wave_slope", kWaveSlopeRange).value_or(w.waveSlope);
  return w;
}

StarDescription readStars(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[stars]", kStarKeys);
  StarDescription s;
  s.enabled = reader.boolean("enabled").value_or(s.enabled);
  s.seed = uint32_t(reader.integer("seed", kSeedRange).value_or(s.seed));
  s.faintestMagnitude = reader.number("faintest_magnitude", kMagnitudeRange).value_or(s.faintestMagnitude);
  s.brightness = reader.number("brightness", kStarBrightnessRange).value_or(s.brightness);
  return s;
}

NoiseLayer readLayer(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[[layer]]", kLayerKeys);
  NoiseLayer layer;
  layer.name = reader.name("name");
  std::string type = reader.requiredString("type");
  layer.noise.type = parseAt(context, lineOf(*reader.find("type")), [&] {
    return noise::parseNoiseType(shortened(type));  // the cut is for the message: no type name is that long
  });
  std::optional<int64_t> octaves = reader.integer("octaves", {noise::kMinOctaves, noise::kMaxOctaves});
  if (!octaves) reader.missing("octaves");
  layer.noise.octaves = int(*octaves);
  layer.noise.lacunarity = reader.number("lacunarity").value_or(layer.noise.lacunarity);
  layer.noise.H = reader.number("H").value_or(layer.noise.H);
  layer.noise.offset = reader.number("offset");
  layer.noise.gain = reader.number("gain");
  layer.noise.seed = uint32_t(reader.integer("seed", kSeedRange).value_or(0));
  if (auto hash = reader.string("hash"))
    layer.noise.hash =
        parseAt(context, lineOf(*reader.find("hash")), [&] { return noise::parseNoiseHash(shortened(*hash)); });

  std::optional<double> frequency = reader.number("frequency", kFrequencyRange);
  std::optional<double> wavelength = reader.number("wavelength_m", kWavelengthRangeM);
  if (frequency && wavelength)
    context.fail(lineOf(*reader.find("wavelength_m")), "give either frequency or wavelength_m in [[layer]], not both");
  if (!frequency && !wavelength)
    context.fail(reader.line(), "missing key 'frequency' (or 'wavelength_m') in [[layer]]");
  layer.frequency = frequency ? *frequency : 1.0 / *wavelength;
  layer.amplitudeM = reader.requiredNumber("amplitude_m", kAmplitudeRangeM);

  try {
    noise::validateNoiseSettings(layer.noise);
  } catch (const Error& e) {
    context.fail(reader.line(), fmt::format("layer '{}': {}", layer.name, e.what()));
  }
  return layer;
}

std::vector<NoiseLayer> readLayers(const Context& context, const toml::table& root) {
  const toml::node* node = root.get("layer");
  if (!node) context.fail(0, "missing table [[layer]] (at least one noise layer)");
  const toml::array* array = node->as_array();
  if (array && array->empty()) context.fail(lineOf(*node), "at least one [[layer]] is required");
  if (!array || !array->is_array_of_tables())
    context.fail(lineOf(*node), fmt::format("'layer' must be an array of tables ([[layer]]), got {}",
                                            array ? "an array of values" : typeName(*node)));
  if (array->size() > size_t(kMaxLayers))
    context.fail(lineOf(*array->get(size_t(kMaxLayers))),
                 fmt::format("at most {} [[layer]] tables, got {}", kMaxLayers, array->size()));
  std::vector<NoiseLayer> layers;
  std::vector<uint32_t> lines;
  for (const toml::node& element : *array) {
    layers.push_back(readLayer(context, *element.as_table()));
    lines.push_back(lineOf(element));
    for (size_t i = 0; i + 1 < layers.size(); ++i)
      if (layers[i].name == layers.back().name)
        context.fail(lines.back(),
                     fmt::format("duplicate layer name '{}' (first at line {})", layers[i].name, lines[i]));
  }
  return layers;
}

// toml++ messages are single lines, but a stray control character must not split ours, and
// a key they quote may be as long as the file.
std::string oneLine(std::string_view text) { return shortened(text, 200); }

}  // namespace

const char* colorSchemeName(ColorScheme scheme) {
  for (const SchemeName& s : kSchemeNames)
    if (s.scheme == scheme) return s.name;
  return "unknown";
}

ColorScheme parseColorScheme(std::string_view name) {
  for (const SchemeName& s : kSchemeNames)
    if (name == s.name) return s.scheme;
  throw Error(fmt::format("unknown color scheme '{}' (expected earth, altitude, moon or mars)", shortened(name)));
}

PlanetColors defaultColors(ColorScheme scheme) {
  PlanetColors c;
  c.scheme = scheme;
  switch (scheme) {
    case ColorScheme::Earth:
      c.beachHeightM = 20.0;
      c.snowLineM = 3500.0;
      c.iceCapLatitudeDeg = 70.0;
      c.deepWater = {0.004f, 0.016f, 0.045f};
      c.shallowWater = {0.015f, 0.080f, 0.100f};
      c.beach = {0.480f, 0.400f, 0.240f};
      c.lowland = {0.050f, 0.110f, 0.020f};
      c.highland = {0.170f, 0.130f, 0.070f};
      c.cliff = {0.130f, 0.120f, 0.110f};
      c.snow = {0.850f, 0.870f, 0.900f};
      break;
    case ColorScheme::Altitude:
      c.deepWater = {0.0f, 0.0f, 0.3f};
      c.shallowWater = {0.0f, 0.3f, 0.6f};
      c.beach = {0.8f, 0.8f, 0.2f};
      c.lowland = {0.0f, 0.4f, 0.0f};
      c.highland = {0.6f, 0.3f, 0.0f};
      c.cliff = {0.3f, 0.3f, 0.3f};
      c.snow = {1.0f, 1.0f, 1.0f};
      break;
    case ColorScheme::Moon:
      c.deepWater = c.shallowWater = {0.0f, 0.0f, 0.0f};
      c.lowland = c.beach = {0.045f, 0.045f, 0.043f};
      c.highland = c.snow = {0.160f, 0.155f, 0.150f};
      c.cliff = {0.100f, 0.100f, 0.100f};
      break;
    case ColorScheme::Mars:
      c.iceCapLatitudeDeg = 80.0;
      c.deepWater = c.shallowWater = {0.0f, 0.0f, 0.0f};
      c.beach = {0.300f, 0.130f, 0.060f};
      c.lowland = {0.100f, 0.045f, 0.025f};
      c.highland = {0.380f, 0.160f, 0.070f};
      c.cliff = {0.200f, 0.100f, 0.060f};
      c.snow = {0.800f, 0.780f, 0.750f};
      break;
  }
  return c;
}

PlanetDescription parsePlanetDescription(std::string_view text, const std::string& sourceName) {
  const Context context(sourceName);
  checkText(context, text);
  KeyDepthCheck(context, text).run();
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(sourceName));
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("{}:{}:{}: {}", sourceName, e.source().begin.line, e.source().begin.column,
                            oneLine(e.description())));
  }
  for (auto&& [key, value] : root) {
    if (std::find(std::begin(kTopKeys), std::end(kTopKeys), key.str()) != std::end(kTopKeys)) continue;
    context.fail(key.source().begin.line, value.is_table()
                                              ? fmt::format("unknown table [{}]", shortened(key.str()))
                                              : fmt::format("unknown key '{}' at top level", shortened(key.str())));
  }

  PlanetDescription d;
  TableReader planet(context, requireTable(context, root, "planet"), "[planet]", kPlanetKeys);
  d.name = planet.name("name");
  d.radiusM = planet.requiredNumber("radius_m", kRadiusRangeM);
  std::optional<bool> hasOcean = planet.boolean("has_ocean");
  if (!hasOcean) planet.missing("has_ocean");
  d.hasOcean = *hasOcean;
  if (std::optional<double> seaLevel = planet.number("sea_level_m", kSeaLevelRangeM)) {
    if (!d.hasOcean) context.fail(lineOf(*planet.find("sea_level_m")), "sea_level_m needs has_ocean = true");
    d.seaLevelM = *seaLevel;
  }
  d.heightScale = planet.number("height_scale", kHeightScaleRange).value_or(1.0);
  d.baseHeightM = planet.number("base_height_m", kBaseHeightRangeM).value_or(0.0);
  d.colors = readColors(context, requireTable(context, root, "colors"));
  d.layers = readLayers(context, root);
  if (const toml::table* table = optionalTable(context, root, "atmosphere"))
    d.atmosphere = readAtmosphere(context, *table);
  if (const toml::table* table = optionalTable(context, root, "clouds")) {
    if (!d.atmosphere.enabled) context.fail(lineOf(*table), "[clouds] needs an [atmosphere] table");
    d.clouds = readClouds(context, *table);
    if (d.clouds.topM > d.atmosphere.heightM)
      context.fail(lineOf(*table), fmt::format("clouds top_m ({}) must be below the atmosphere's height_m ({})",
                                               formatNumber(d.clouds.topM), formatNumber(d.atmosphere.heightM)));
  }
  if (const toml::table* table = optionalTable(context, root, "water")) {
    if (!d.hasOcean) context.fail(lineOf(*table), "[water] needs has_ocean = true");
    d.water = readWater(context, *table);
  }
  if (const toml::table* table = optionalTable(context, root, "stars")) d.stars = readStars(context, *table);
  return d;
}

PlanetDescription loadPlanetDescription(const std::string& path) {
  // One byte past the limit tells "too large" (parsePlanetDescription says so) from "exactly at it".
  return parsePlanetDescription(readFileUpTo(path, kMaxPresetBytes), path);
}

std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  for (const EmbeddedPreset& preset : embeddedPresets()) names.emplace_back(preset.name);
  return names;
}

PlanetDescription resolvePreset(const std::string& nameOrFile) {
  if (nameOrFile.ends_with(".toml") || nameOrFile.find('/') != std::string::npos)
    return loadPlanetDescription(nameOrFile);
  for (const EmbeddedPreset& preset : embeddedPresets())
    if (nameOrFile == preset.name) return parsePlanetDescription(preset.text, nameOrFile + ".toml");
  std::string names;
  for (const EmbeddedPreset& preset : embeddedPresets())
    names += fmt::format("{}{}", names.empty() ? "" : ", ", preset.name);
  throw Error(fmt::format("unknown planet preset '{}' (built-in: {}; or a FILE.toml)", nameOrFile, names));
}

std::string canonicalForm(const PlanetDescription& d) {
  auto color = [](const glm::vec3& c) {
    return fmt::format("{},{},{}", formatNumber(c.x), formatNumber(c.y), formatNumber(c.z));
  };
  // Names carry their length, so no name can imitate the lines that follow it.
  std::string out = "planet-description v1\n";
  out += fmt::format("name={}:{}\nradius_m={}\nhas_ocean={}\nsea_level_m={}\nheight_scale={}\nbase_height_m={}\n",
                     d.name.size(), d.name, formatNumber(d.radiusM), d.hasOcean, formatNumber(d.seaLevelM),
                     formatNumber(d.heightScale), formatNumber(d.baseHeightM));
  const PlanetColors& c = d.colors;
  out +=
      fmt::format("scheme={}\nbeach_height_m={}\nsnow_line_m={}\nice_cap_latitude_deg={}\n", colorSchemeName(c.scheme),
                  formatNumber(c.beachHeightM), formatNumber(c.snowLineM), formatNumber(c.iceCapLatitudeDeg));
  out += fmt::format("deep_water={}\nshallow_water={}\nbeach={}\nlowland={}\nhighland={}\ncliff={}\nsnow={}\n",
                     color(c.deepWater), color(c.shallowWater), color(c.beach), color(c.lowland), color(c.highland),
                     color(c.cliff), color(c.snow));
  auto vector = [](const glm::dvec3& v) {
    return fmt::format("{},{},{}", formatNumber(v.x), formatNumber(v.y), formatNumber(v.z));
  };
  const AtmosphereDescription& a = d.atmosphere;
  out += fmt::format(
      "atmosphere={}\natmosphere.height_m={}\natmosphere.rayleigh_scattering={}\n"
      "atmosphere.rayleigh_scale_height_m={}\natmosphere.mie_scattering={}\natmosphere.mie_extinction_ratio={}\n"
      "atmosphere.mie_absorption={}\n"
      "atmosphere.mie_scale_height_m={}\natmosphere.mie_g={}\natmosphere.ozone_absorption={}\n"
      "atmosphere.ozone_center_m={}\natmosphere.ozone_width_m={}\n",
      a.enabled, formatNumber(a.heightM), vector(a.rayleighScattering), formatNumber(a.rayleighScaleHeightM),
      vector(a.mieScattering), formatNumber(a.mieExtinctionRatio), vector(a.mieAbsorption),
      formatNumber(a.mieScaleHeightM), formatNumber(a.mieG), vector(a.ozoneAbsorption), formatNumber(a.ozoneCenterM),
      formatNumber(a.ozoneWidthM));
  const CloudDescription& cl = d.clouds;
  out += fmt::format(
      "clouds={}\nclouds.bottom_m={}\nclouds.top_m={}\nclouds.coverage={}\nclouds.sharpness={}\n"
      "clouds.wavelength_m={}\nclouds.octaves={}\nclouds.seed={}\nclouds.wind_mps={}\nclouds.evolve_period_s={}\n"
      "clouds.opacity={}\n",
      cl.enabled, formatNumber(cl.bottomM), formatNumber(cl.topM), formatNumber(cl.coverage),
      formatNumber(cl.sharpness), formatNumber(cl.wavelengthM), cl.octaves, cl.seed, formatNumber(cl.windMps),
      formatNumber(cl.evolvePeriodS), formatNumber(cl.opacity));
  out += fmt::format("water.clarity_m={}\nwater.wave_wavelength_m={}\nwater.wave_slope={}\n",
                     formatNumber(d.water.clarityM), formatNumber(d.water.waveWavelengthM),
                     formatNumber(d.water.waveSlope));
  out += fmt::format("stars={}\nstars.seed={}\nstars.faintest_magnitude={}\nstars.brightness={}\n", d.stars.enabled,
                     d.stars.seed, formatNumber(d.stars.faintestMagnitude), formatNumber(d.stars.brightness));
  for (size_t i = 0; i < d.layers.size(); ++i) {
    const NoiseLayer& l = d.layers[i];
    const noise::NoiseSettings& n = l.noise;
    out += fmt::format(
        "layer.{0}.name={1}:{2}\nlayer.{0}.type={3}\nlayer.{0}.octaves={4}\nlayer.{0}.lacunarity={5}\n"
        "layer.{0}.H={6}\nlayer.{0}.offset={7}\nlayer.{0}.gain={8}\nlayer.{0}.seed={9}\nlayer.{0}.hash={10}\n"
        "layer.{0}.frequency={11}\nlayer.{0}.amplitude_m={12}\n",
        i, l.name.size(), l.name, noise::noiseTypeName(n.type), n.octaves, formatNumber(n.lacunarity),
        formatNumber(n.H), formatNumber(n.offset.value_or(noise::defaultOffset(n.type))),
        formatNumber(n.gain.value_or(noise::kDefaultGain)), n.seed, noise::noiseHashName(n.hash),
        formatNumber(l.frequency), formatNumber(l.amplitudeM));
  }
  return out;
}

uint64_t fnv1a64(std::string_view bytes) {
  uint64_t hash = 14695981039346656037ull;  // FNV-1a 64-bit offset basis
  for (char c : bytes) {
    hash ^= uint8_t(c);
    hash *= 1099511628211ull;  // FNV 64-bit prime
  }
  return hash;
}

uint64_t descriptionHash(const PlanetDescription& description) { return fnv1a64(canonicalForm(description)); }

}  // namespace planet

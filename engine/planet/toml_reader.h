// The TOML reading shared by the preset parsers (planet presets, scenes): messages that name
// the file, the line and the bad value; text checks that run before toml++ sees the text (it
// crashes or recurses without bound on some inputs); a reader per table that rejects unknown
// keys and checks each value's type and range. Engine-internal: it exposes toml++ types.
#pragma once

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <fmt/format.h>
#include <glm/glm.hpp>
#include <toml++/toml.h>

#include "core/error.h"
#include "planet/planet_description.h"

namespace planet::toml_reader {

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

std::string formatRange(Range range);
const char* typeName(const toml::node& node);
inline uint32_t lineOf(const toml::node& node) { return node.source().begin.line; }

// Where messages come from: "earth.toml:12: ..." (or "earth.toml: ..." without a line).
class Context {
 public:
  explicit Context(const std::string& source) : source_(source) {}

  // The message is made printable() whole: the source is a path the user chose and the
  // message may quote an error from deeper down, and either could hold a newline.
  [[noreturn]] void fail(uint32_t line, const std::string& message) const {
    if (line == 0) throw Error(printable(fmt::format("{}: {}", source_, message)));
    throw Error(printable(fmt::format("{}:{}: {}", source_, line, message)));
  }

  const std::string& source() const { return source_; }

 private:
  const std::string& source_;
};

// User text quoted in a message (a key, a value): at most `limit` bytes, cut at a character's
// start, with control characters (a quoted key may hold "\n") as '?' to keep the message one line.
std::string shortened(std::string_view text, size_t limit = 40);
// toml++ messages are single lines, but a stray control character must not split ours, and
// a key they quote may be as long as the file.
std::string oneLine(std::string_view text);

// The whole document: the text checks (size up to kMaxPresetBytes, UTF-8, no control bytes,
// key paths of at most a few parts; `expected` names what an empty document lacks), then
// toml++, whose errors become planet::Error with the file, line and column.
toml::table parseDocument(const Context& context, std::string_view text, std::string_view expected);

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

  // An element of an array value (`label` names it in messages, "key[1]"): a number in `range`.
  double element(const toml::node& element, const std::string& label, Range range) const {
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
  }

  // [x, y, z], each in `range`; a single number stands for all three when `allowScalar`.
  std::optional<glm::dvec3> vector3(std::string_view key, Range range, bool allowScalar = false) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    auto component = [&](const toml::node& item, const std::string& label) { return element(item, label, range); };
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

const toml::table& requireTable(const Context& context, const toml::table& root, std::string_view key);
// An optional table: nullptr when absent, an error when the key holds something else.
const toml::table* optionalTable(const Context& context, const toml::table& root, std::string_view key);

}  // namespace planet::toml_reader

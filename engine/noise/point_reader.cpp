#include "noise/point_reader.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "core/error.h"

namespace planet::noise {
namespace {

bool isSeparator(char c) { return c == ' ' || c == '\t' || c == ',' || c == '\r'; }

// The line as it can be quoted in a one-line message: printable ASCII only, bounded length.
std::string quotable(std::string_view text) {
  std::string out;
  for (char c : text.substr(0, 60)) out += (c >= 32 && c < 127) ? c : '?';
  if (text.size() > 60) out += "...";
  return out;
}

// One coordinate. A leading '+' is taken (std::from_chars does not), and a value too small
// for a float becomes ±0 or a denormal, as a float literal would; too large is an error.
std::from_chars_result parseCoordinate(std::string_view token, float& value) {
  const std::string_view digits = token.size() > 1 && token[0] == '+' ? token.substr(1) : token;
  const char* end = digits.data() + digits.size();
  std::from_chars_result result = std::from_chars(digits.data(), end, value);
  if (result.ec == std::errc::result_out_of_range) {
    double wide = 0.0;
    const std::from_chars_result again = std::from_chars(digits.data(), end, wide);
    if (again.ec == std::errc() && again.ptr == end && std::abs(wide) < std::numeric_limits<float>::min()) {
      value = float(wide);
      return again;
    }
  }
  return result;
}

}  // namespace

bool parsePointLine(std::string_view line, size_t lineNumber, glm::vec3& point) {
  size_t start = 0;
  while (start < line.size() && isSeparator(line[start])) ++start;
  line = line.substr(0, line.find('#'));  // a comment runs to the end of the line
  if (start >= line.size()) return false;

  float coords[3];
  int count = 0;
  size_t pos = start;
  while (pos < line.size()) {
    size_t end = pos;
    while (end < line.size() && !isSeparator(line[end])) ++end;
    std::string_view token = line.substr(pos, end - pos);
    if (count == 3)
      throw Error(fmt::format("line {}: expected 3 numbers 'x y z', got more: '{}'", lineNumber, quotable(line)));
    float value = 0.0f;
    auto [ptr, ec] = parseCoordinate(token, value);
    if (ec == std::errc::result_out_of_range)
      throw Error(fmt::format("line {}: '{}' is out of range for a float", lineNumber, quotable(token)));
    if (ec != std::errc() || ptr != token.data() + token.size())
      throw Error(fmt::format("line {}: '{}' is not a number", lineNumber, quotable(token)));
    if (!std::isfinite(value))
      throw Error(fmt::format("line {}: '{}' is not a finite number", lineNumber, quotable(token)));
    coords[count++] = value;
    pos = end;
    while (pos < line.size() && isSeparator(line[pos])) ++pos;
  }
  if (count != 3)
    throw Error(fmt::format("line {}: expected 3 numbers 'x y z', got {}: '{}'", lineNumber, count, quotable(line)));
  point = glm::vec3(coords[0], coords[1], coords[2]);
  return true;
}

std::vector<glm::vec3> readPoints(std::istream& in) {
  std::vector<glm::vec3> points;
  std::string line;
  size_t lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    // Editors on Windows may start a UTF-8 file with a byte order mark: not part of the point.
    if (lineNumber == 1 && line.starts_with("\xef\xbb\xbf")) line.erase(0, 3);
    glm::vec3 p;
    if (parsePointLine(line, lineNumber, p)) points.push_back(p);
  }
  return points;
}

}  // namespace planet::noise

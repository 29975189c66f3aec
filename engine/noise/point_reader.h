// Reads points "x y z" (separated by spaces, tabs or commas), one per line. '#' starts a
// comment that runs to the end of the line; blank lines are skipped; CRLF line ends, a leading
// UTF-8 byte order mark and a last line without a newline are accepted. Anything else is an
// error naming the line.
#pragma once

#include <istream>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace planet::noise {

// Throws planet::Error("line N: ...") on the first bad line: not exactly three numbers, a
// token that is not a number, or a non-finite value.
std::vector<glm::vec3> readPoints(std::istream& in);

// Parses one line; returns false for a blank or comment line. Throws like readPoints
// (with `lineNumber` in the message).
bool parsePointLine(std::string_view line, size_t lineNumber, glm::vec3& point);

}  // namespace planet::noise

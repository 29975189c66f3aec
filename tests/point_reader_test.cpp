// Point input of `planet noise`: accepted formats and one-line errors naming the line.
#include <cmath>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "noise/point_reader.h"

namespace planet::noise {
namespace {

std::string errorOf(const std::string& input) {
  std::istringstream in(input);
  try {
    readPoints(in);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(PointReader, AcceptsSpacesTabsCommasCommentsAndBlankLines) {
  std::istringstream in("# header\n1 2 3\n\n  4.5,\t-6e2 , 7\r\n-0.25 0 1e-3\n");
  std::vector<glm::vec3> points = readPoints(in);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[0], glm::vec3(1, 2, 3));
  EXPECT_EQ(points[1], glm::vec3(4.5f, -600.0f, 7.0f));
  EXPECT_EQ(points[2], glm::vec3(-0.25f, 0.0f, 1e-3f));
}

TEST(PointReader, BadLinesAreNamedWithTheirNumber) {
  EXPECT_EQ(errorOf("1 2 3\n1 2\n"), "line 2: expected 3 numbers 'x y z', got 2: '1 2'");
  EXPECT_EQ(errorOf("1 2 3 4\n"), "line 1: expected 3 numbers 'x y z', got more: '1 2 3 4'");
  EXPECT_EQ(errorOf("1 2 abc\n"), "line 1: 'abc' is not a number");
  EXPECT_EQ(errorOf("1 2 3\n\n1 nan 3\n"), "line 3: 'nan' is not a finite number");
  EXPECT_EQ(errorOf("inf 2 3\n"), "line 1: 'inf' is not a finite number");
  EXPECT_EQ(errorOf("1e40 2 3\n"), "line 1: '1e40' is out of range for a float");
  EXPECT_EQ(errorOf("1 2 3x\n"), "line 1: '3x' is not a number");
  EXPECT_EQ(errorOf(std::string("1 2 \x01\xff\xfe", 7)), "line 1: '" + std::string(3, '?') + "' is not a number");
}

TEST(PointReader, EmptyInputGivesNoPoints) {
  std::istringstream in("");
  EXPECT_TRUE(readPoints(in).empty());
}

// Hostile point streams (issue 7): each case is either read (to `points` points) or a one-line
// error, of bounded length, that starts with `says`.
TEST(PointReader, HostileStreamsAreReadOrGiveOneShortLineNamingTheLine) {
  std::mt19937 random(5);
  std::string binary(4096, '\0');
  for (char& c : binary) c = char(random());
  struct Case {
    const char* what;
    std::string input;
    size_t points;     // when `says` is empty
    std::string says;  // start of the error
  } cases[] = {
      {"empty", "", 0, ""},
      {"blank lines", "\n \n\t\r\n\n", 0, ""},
      {"comments only", "# x y z\n  # indented\n", 0, ""},
      {"comment after a point", "1 2 3 # the first\n", 1, ""},
      {"CRLF", "1 2 3\r\n4 5 6\r\n", 2, ""},
      {"no newline at the end", "1 2 3\n4 5 6", 2, ""},
      {"byte order mark",
       "\xef\xbb\xbf"
       "1 2 3\n",
       1, ""},
      {"plus signs", "+1 +2.5 +3e+2\n", 1, ""},
      {"negative", "-1 -2.5 -3e-2\n", 1, ""},
      {"largest floats", "3.4028234e38 -3.4028234e38 0\n", 1, ""},
      {"too small for a float", "1e-50 -1e-50 0\n", 1, ""},
      {"nan", "1 2 3\nnan 0 0\n", 0, "line 2: 'nan' is not a finite number"},
      {"inf", "0 inf 0\n", 0, "line 1: 'inf' is not a finite number"},
      {"-inf", "0 0 -infinity\n", 0, "line 1: '-infinity' is not a finite number"},
      {"1e39 overflows a float", "1e39 0 0\n", 0, "line 1: '1e39' is out of range for a float"},
      {"beyond double", "0 -1e400 0\n", 0, "line 1: '-1e400' is out of range for a float"},
      {"two numbers", "1 2\n", 0, "line 1: expected 3 numbers 'x y z', got 2: '1 2'"},
      {"four numbers", "\n1 2 3 4\n", 0, "line 2: expected 3 numbers 'x y z', got more: '1 2 3 4'"},
      {"one number", "7", 0, "line 1: expected 3 numbers 'x y z', got 1: '7'"},
      {"words", "x y z\n", 0, "line 1: 'x' is not a number"},
      {"hex", "0x10 0 0\n", 0, "line 1: '0x10' is not a number"},
      {"semicolons", "1;2;3\n", 0, "line 1: '1;2;3' is not a number"},
      {"binary garbage", binary, 0, "line "},
      {"latin-1", "1 2 \xb2\n", 0, "line 1: '?' is not a number"},
      {"UTF-8 minus sign",
       "\xe2\x88\x92"
       "1 2 3\n",
       0, "line 1: '???1' is not a number"},
      {"NUL byte", std::string("1 2 3\0\n", 7), 0, "line 1: '3?' is not a number"},
      {"NUL line", std::string("1 2 3\n\0\n", 8), 0, "line 2: '?' is not a number"},
      {"very long number", std::string(1 << 20, '9') + " 0 0\n", 0, "line 1: '999999999999"},
      {"very long line",
       [] {
         std::string line;
         for (int i = 0; i < 200000; ++i) line += "1 ";
         return line;
       }(),
       0, "line 1: expected 3 numbers 'x y z', got more: '1 1 1"},
      {"very long blank line", std::string(1 << 20, ' ') + "1 2 3\n", 1, ""},
  };
  for (const Case& c : cases) {
    std::istringstream in(c.input);
    std::string message;
    size_t points = 0;
    try {
      points = readPoints(in).size();
    } catch (const Error& e) {
      message = e.what();
    }
    if (c.says.empty()) {
      EXPECT_EQ(message, "") << c.what;
      EXPECT_EQ(points, c.points) << c.what;
    } else {
      EXPECT_TRUE(message.starts_with(c.says)) << c.what << "\n got: " << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << c.what;
      EXPECT_LT(message.size(), 200u) << c.what;
    }
  }
  // The accepted forms give the values written.
  std::istringstream in("\xef\xbb\xbf+1 2 3 # c\r\n1e-50 -1e-50 3.4028234e38");
  const std::vector<glm::vec3> points = readPoints(in);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0], glm::vec3(1, 2, 3));
  EXPECT_EQ(points[1], glm::vec3(0.0f, -0.0f, 3.4028234e38f));
  EXPECT_TRUE(std::signbit(points[1].y));
}

}  // namespace
}  // namespace planet::noise

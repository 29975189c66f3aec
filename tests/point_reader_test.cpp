// Point input of `planet noise`: accepted formats and one-line errors naming the line.
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

}  // namespace
}  // namespace planet::noise

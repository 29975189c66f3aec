// Percentiles of benchmark times on data whose answers are known by hand (linear interpolation
// between closest ranks, numpy's default).
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "core/statistics.h"
#include "test_support.h"

namespace planet::test {
namespace {

TEST(Statistics, PercentilesOfOneToHundredInterpolateBetweenRanks) {
  std::vector<double> values;
  for (int i = 100; i >= 1; --i) values.push_back(i);  // any order
  // h = 99 p / 100: p50 → 49.5 → 50.5, p95 → 94.05 → 95.05, p99 → 98.01 → 99.01.
  EXPECT_DOUBLE_EQ(percentile(values, 50.0), 50.5);
  EXPECT_DOUBLE_EQ(percentile(values, 95.0), 95.05);
  EXPECT_DOUBLE_EQ(percentile(values, 99.0), 99.01);
  EXPECT_DOUBLE_EQ(percentile(values, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(percentile(values, 100.0), 100.0);
  const Summary s = summarize(values);
  EXPECT_DOUBLE_EQ(s.median, 50.5);
  EXPECT_DOUBLE_EQ(s.p95, 95.05);
  EXPECT_DOUBLE_EQ(s.p99, 99.01);
  EXPECT_DOUBLE_EQ(s.max, 100.0);
}

TEST(Statistics, MedianOfOddAndEvenCountsAndOfOneValue) {
  EXPECT_DOUBLE_EQ(percentile(std::vector<double>{3.0, 1.0, 2.0}, 50.0), 2.0);
  EXPECT_DOUBLE_EQ(percentile(std::vector<double>{4.0, 1.0, 3.0, 2.0}, 50.0), 2.5);
  const Summary one = summarize(std::vector<double>{7.25});
  EXPECT_EQ(one.median, 7.25);
  EXPECT_EQ(one.p95, 7.25);
  EXPECT_EQ(one.p99, 7.25);
  EXPECT_EQ(one.max, 7.25);
  // Ten values: p95 lies between the two largest, h = 8.55.
  std::vector<double> ten = {10, 20, 30, 40, 50, 60, 70, 80, 90, 1000};
  EXPECT_NEAR(percentile(ten, 95.0), 90.0 + 0.55 * 910.0, 1e-9);
}

TEST(Statistics, EmptyOrNonFiniteDataAndBadPercentilesAreErrors) {
  EXPECT_NE(errorOf([] { percentile(std::vector<double>{}, 50.0); }).find("empty"), std::string::npos);
  EXPECT_NE(errorOf([] { summarize(std::vector<double>{1.0, std::nan("")}); }).find("non-finite"), std::string::npos);
  EXPECT_NE(errorOf([] { percentile(std::vector<double>{1.0}, 101.0); }).find("percentile 101 is outside [0, 100]"),
            std::string::npos);
  EXPECT_NE(errorOf([] { percentile(std::vector<double>{1.0}, std::numeric_limits<double>::infinity()); }), "");
}

}  // namespace
}  // namespace planet::test

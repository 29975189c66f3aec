#include "core/statistics.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"

namespace planet {
namespace {

std::vector<double> sortedCopy(std::span<const double> values) {
  if (values.empty()) throw Error("percentile of an empty series");
  for (double v : values)
    if (!std::isfinite(v)) throw Error(fmt::format("percentile of a series with the non-finite value {}", v));
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  return sorted;
}

double percentileOfSorted(const std::vector<double>& sorted, double p) {
  if (!(p >= 0.0 && p <= 100.0)) throw Error(fmt::format("percentile {} is outside [0, 100]", p));
  const double h = double(sorted.size() - 1) * p / 100.0;
  const size_t below = size_t(std::floor(h));
  if (below + 1 >= sorted.size()) return sorted.back();
  return sorted[below] + (h - double(below)) * (sorted[below + 1] - sorted[below]);
}

}  // namespace

double percentile(std::span<const double> values, double p) { return percentileOfSorted(sortedCopy(values), p); }

Summary summarize(std::span<const double> values) {
  const std::vector<double> sorted = sortedCopy(values);
  return {percentileOfSorted(sorted, 50.0), percentileOfSorted(sorted, 95.0), percentileOfSorted(sorted, 99.0),
          sorted.back()};
}

}  // namespace planet

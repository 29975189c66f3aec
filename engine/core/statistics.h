// Order statistics of measured times (benchmarks): percentiles by linear interpolation between
// the closest ranks, the definition of numpy's default and of R's type 7, so the figures can be
// recomputed from the CSV with either.
#pragma once

#include <span>

namespace planet {

// The p-th percentile (p in [0, 100]) of `values` (any order): with the values sorted as
// x[0] <= ... <= x[n-1] and h = (n - 1) * p / 100, x[floor h] + (h - floor h) * (x[floor h + 1] -
// x[floor h]). p = 50 is the median (the mean of the middle two for even n), p = 100 the
// maximum. Throws planet::Error for an empty span, p outside [0, 100] or a non-finite value.
double percentile(std::span<const double> values, double p);

// What a benchmark reports of one series of times.
struct Summary {
  double median = 0.0;
  double p95 = 0.0;
  double p99 = 0.0;
  double max = 0.0;
};

// The summary of `values`; throws like percentile().
Summary summarize(std::span<const double> values);

}  // namespace planet

// Noise with analytic gradients (issue 19, common/noise_gradient.glsl): the gradient of every
// fractal is the derivative of its value (central differences of the double reference), the
// value that comes with it is the plain value bit for bit, the GPU agrees with the float
// reference bit for bit on lavapipe, and `planet noise --gradient` prints `value dx dy dz`.
//
// Three groups in one program (tests/CMakeLists.txt): NoiseGradient.* (label unit),
// NoiseGradientGpu.* (gpu) and NoiseGradientCli.* (cli).
#include <algorithm>
#include <bit>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "bench/noise_validate.h"
#include "gpu_fixture.h"
#include "noise/noise_cpu.h"
#include "noise/noise_gpu.h"
#include "noise/noise_kernel.h"
#include "noise/permutation.h"
#include "test_support.h"

namespace planet::noise {
namespace {

constexpr NoiseType kAllTypes[] = {NoiseType::Simplex, NoiseType::Fbm,     NoiseType::Ridged, NoiseType::Hybrid,
                                   NoiseType::Hetero,  NoiseType::Cascade, NoiseType::Craters};

// The highest frequency a fractal samples (craters perturb their rims at twice an octave's).
double highestFrequency(const NoiseSettings& s) {
  const double top = std::pow(s.lacunarity, s.octaves - 1);
  return s.type == NoiseType::Craters ? 2.0 * top : s.type == NoiseType::Simplex ? 1.0 : top;
}

// The difference step: kRelativeStep of the finest period, rounded down to a power of two so
// that p ± h and p ± 2h are exact in double for the float points used here (a rounded step
// would err by ulp(p) / h, 2e-7 at |p| = 50).
double stepFor(const NoiseSettings& s, double relativeStep) {
  return std::ldexp(1.0, int(std::floor(std::log2(relativeStep / highestFrequency(s)))));
}

// Outcome of comparing an analytic gradient with differences of the value over a set of points.
struct DifferenceCheck {
  size_t axes = 0;           // (point, axis) pairs compared
  size_t kinks = 0;          // pairs with a kink within h
  double worstSmooth = 0.0;  // max |analytic - central| / scale away from kinks
  double worstKink = 0.0;    // max over kinks of min |analytic - one-sided| / scale
  double scale = 0.0;        // RMS of |gradient| over the points
};

// Compares gradient(p) with differences of value(p ± h·e) along every axis, relative to the
// RMS gradient. A kink within h shows as a jump of the analytic derivative: its second
// difference g(p+h) - 2g(p) + g(p-h) is O(h^2) where the value is smooth (and O(h) where only
// its slope is continuous, the craters' rims) but the size of the jump at a kink. Away from
// kinks the central difference must match; at a kink one of the second-order one-sided
// differences must (the side the value takes), not their mean.
template <typename ValueFn, typename GradientFn>
DifferenceCheck checkAgainstDifferences(const std::vector<glm::dvec3>& points, double h, double kinkJump, ValueFn value,
                                        GradientFn gradient) {
  DifferenceCheck check;
  std::vector<glm::dvec4> analytic(points.size());
  double sum2 = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    analytic[i] = gradient(points[i]);
    sum2 += analytic[i].y * analytic[i].y + analytic[i].z * analytic[i].z + analytic[i].w * analytic[i].w;
  }
  check.scale = std::sqrt(sum2 / double(points.size()));
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3& p = points[i];
    const double f0 = value(p);
    for (int axis = 0; axis < 3; ++axis) {
      glm::dvec3 step(0.0);
      step[axis] = h;
      const double a = analytic[i][axis + 1];
      const double fPlus = value(p + step), fMinus = value(p - step);
      const double jump = gradient(p + step)[axis + 1] - 2.0 * a + gradient(p - step)[axis + 1];
      ++check.axes;
      if (std::fabs(jump) > kinkJump * check.scale) {
        ++check.kinks;
        const double forward = (-3.0 * f0 + 4.0 * fPlus - value(p + 2.0 * step)) / (2.0 * h);
        const double backward = (3.0 * f0 - 4.0 * fMinus + value(p - 2.0 * step)) / (2.0 * h);
        check.worstKink =
            std::max(check.worstKink, std::min(std::fabs(a - forward), std::fabs(a - backward)) / check.scale);
      } else {
        check.worstSmooth = std::max(check.worstSmooth, std::fabs(a - (fPlus - fMinus) / (2.0 * h)) / check.scale);
      }
    }
  }
  return check;
}

NoiseSettings settingsOf(NoiseType type, NoiseHash hash = NoiseHash::Fast, int octaves = 8) {
  NoiseSettings s;
  s.type = type;
  s.hash = hash;
  s.octaves = octaves;
  return s;
}

std::vector<glm::dvec3> nearPoints(size_t count, uint32_t seed) {
  std::vector<glm::dvec3> points;
  for (const glm::vec3& p : validationPoints(count, false, seed)) points.emplace_back(p);
  return points;
}

// Tolerances of the difference checks, relative to the RMS gradient. With h ~ 1e-5 of the
// finest octave's period the differences' truncation errors are ~1e-10 of that octave's slope
// and their rounding errors ~1e-16 / 1e-5 of the value. Measured: at most 1e-8 with L = 2 and
// 5e-7 with L = 2.7 (the reference's own rounding of the points q·L, ulp(q)/(h·L^i)); a wrong
// derivative (a missed factor, a missed term of the product rule) errs by 1e-3 and more.
constexpr double kRelativeStep = 1e-5;
constexpr double kGradientTolerance = 1e-5;
// A jump of the derivative that marks a kink within h. A smaller, unmarked one moves the
// central difference by at most half of it, within kGradientTolerance.
constexpr double kKinkJump = kGradientTolerance;

TEST(NoiseGradient, MatchesCentralDifferencesOfTheDoubleReferenceForEveryTypeAndHash) {
  const std::vector<glm::dvec3> points = nearPoints(1500, 31);
  for (const ValidationCase& c : validationCases()) {
    if (c.farPoints) continue;  // 24 octaves 4e4 from the origin: no double step resolves them
    const NoiseSettings& s = c.settings;
    // Sharp faults jump (their gradient is 0 beside every step) and MPD is piecewise linear, with
    // kinks along every level's edges: NoiseGenerators.GradientsMatchCentralDifferences... checks
    // them where their derivatives exist.
    if (isGenerator(s.type)) continue;
    const double h = stepFor(s, kRelativeStep);
    DifferenceCheck check = checkAgainstDifferences(
        points, h, kKinkJump, [&](const glm::dvec3& p) { return evaluateCpuDouble(s, p); },
        [&](const glm::dvec3& p) { return evaluateCpuGradientDouble(s, p); });
    const std::string what = describe(s);
    EXPECT_GT(check.scale, 0.0) << what;
    EXPECT_LT(check.worstSmooth, kGradientTolerance) << what << ", h " << h;
    // The kinks (|N| and the weight clamps of ridged and hybrid) lie within h of a handful of
    // points at most; a gradient that jumps elsewhere would show here.
    EXPECT_LE(double(check.kinks), 0.005 * double(check.axes)) << what;
    EXPECT_LT(check.worstKink, kGradientTolerance) << what << ": not the one-sided derivative";
  }
}

TEST(NoiseGradient, KinksTakeTheOneSidedDerivativeOfTheBranchTaken) {
  // One octave of ridged noise, offset - |N|, squared: at N = 0 the slope jumps from
  // +2·offset·N' to -2·offset·N'. Walk along a line through a zero of N and step a point onto
  // each side: each gets the derivative of its own side, so they differ in sign.
  const NoiseSettings s = settingsOf(NoiseType::Ridged, NoiseHash::Fast, 1);
  const NoiseSettings n = settingsOf(NoiseType::Simplex);
  const glm::dvec3 origin(0.3, 0.2, 0.1), dir(1.0, 0.0, 0.0);
  double lo = 0.0, hi = 0.0;
  for (double t = 0.0; t < 3.0; t += 1e-3)
    if (evaluateCpuDouble(n, origin + t * dir) * evaluateCpuDouble(n, origin + (t + 1e-3) * dir) < 0) {
      lo = t;
      hi = t + 1e-3;
      break;
    }
  ASSERT_LT(lo, hi) << "no zero of N on the line";
  for (int i = 0; i < 60; ++i) {  // bisect the zero of N
    const double mid = 0.5 * (lo + hi);
    const bool sameAsLo =
        (evaluateCpuDouble(n, origin + mid * dir) < 0) == (evaluateCpuDouble(n, origin + lo * dir) < 0);
    (sameAsLo ? lo : hi) = mid;
  }
  const glm::dvec4 left = evaluateCpuGradientDouble(s, origin + lo * dir);
  const glm::dvec4 right = evaluateCpuGradientDouble(s, origin + hi * dir);
  const double slopeN = evaluateCpuGradientDouble(n, origin + lo * dir).y;
  EXPECT_NEAR(left.x, 1.0, 1e-9);  // (1 - |N|)^2 at the zero
  EXPECT_NEAR(std::fabs(left.y), 2.0 * std::fabs(slopeN), 1e-6 * std::fabs(slopeN));
  EXPECT_NEAR(right.y, -left.y, 1e-6 * std::fabs(slopeN));
}

TEST(NoiseGradient, ValueIsTheValueOfThePlainEvaluationBitForBit) {
  for (const ValidationCase& c : validationCases()) {
    const std::vector<glm::vec3> points = validationPoints(2000, c.farPoints, 32);
    std::vector<float> values(points.size());
    std::vector<glm::vec4> gradients(points.size());
    evaluateCpu(c.settings, points, values, 0);
    evaluateCpuGradient(c.settings, points, gradients, 0);
    size_t same = 0;
    for (size_t i = 0; i < points.size(); ++i)
      same += std::bit_cast<uint32_t>(values[i]) == std::bit_cast<uint32_t>(gradients[i].x);
    EXPECT_EQ(same, points.size()) << describe(c.settings) << " (" << c.label << ")";
    for (size_t i = 0; i < 50; ++i) {
      const glm::dvec3 p(points[i]);
      ASSERT_EQ(evaluateCpuDouble(c.settings, p), evaluateCpuGradientDouble(c.settings, p).x) << describe(c.settings);
    }
  }
}

// A double kernel as the terrain's evaluations use it (engine/planet/terrain_kernel.h).
NoiseKernel<double> doubleKernel(const NoiseSettings& s) {
  NoiseKernel<double> kernel;
  kernel.permutation = permutationTable(s.seed).data();
  return kernel;
}

TEST(NoiseGradient, FadedLastOctaveFadesTheGradientAsTheValue) {
  // Octave limiting weights the last octave by lastOctaveWeight; the gradient must be the
  // derivative of that faded value, and differ from the unfaded one.
  const std::vector<glm::dvec3> points = nearPoints(300, 33);
  for (NoiseType type : kAllTypes) {
    const NoiseSettings s = settingsOf(type, NoiseHash::Fast, 6);
    NoiseKernel<double> kernel = doubleKernel(s);
    gpu::NoiseParams faded = toNoiseParams(s);
    faded.lastOctaveWeight = 0.35f;
    DifferenceCheck check = checkAgainstDifferences(
        points, stepFor(s, kRelativeStep), kKinkJump,
        [&](const glm::dvec3& p) { return kernel.evaluateNoise(faded, p); },
        [&](const glm::dvec3& p) { return glm::dvec4(kernel.evaluateNoiseGradient(faded, p)); });
    EXPECT_LT(check.worstSmooth, kGradientTolerance) << noiseTypeName(type);
    EXPECT_LT(check.worstKink, kGradientTolerance) << noiseTypeName(type);
    if (type == NoiseType::Simplex) continue;  // one octave: nothing to fade
    const gpu::NoiseParams full = toNoiseParams(s);
    double change = 0.0;
    for (const glm::dvec3& p : points)
      change = std::max(change, glm::length(glm::dvec3(kernel.evaluateNoiseGradient(faded, p)) -
                                            glm::dvec3(kernel.evaluateNoiseGradient(full, p))));
    // Well above the tolerance, so that the check above tells faded from unfaded.
    EXPECT_GT(change, 10.0 * kGradientTolerance * check.scale)
        << noiseTypeName(type) << ": the fade left the gradient alone";
  }
}

TEST(NoiseGradient, RebasedWalkGradientIsWithRespectToTheOffsetInMetres) {
  // The terrain's rebased walk samples octave i at remainder_i + offset·scale_i. Tables for a
  // layer of frequency 2^-10 per metre anchored at `anchor` (in noise units; L = 2, all
  // values exact in float): the rebased walk at offset o is the plain walk at
  // anchor + o·2^-10, so its gradient with respect to o is 2^-10 times the plain one.
  const double frequency = std::ldexp(1.0, -10);
  const glm::dvec3 anchor(3.25, -1.5, 0.75);
  std::vector<glm::vec4> remainders(gpu::kNoiseMaxOctaves);
  std::vector<glm::uvec4> shifts(gpu::kNoiseMaxOctaves, glm::uvec4(0u));
  for (uint32_t i = 0; i < gpu::kNoiseMaxOctaves; ++i) {
    const double scale = std::ldexp(1.0, int(i));
    remainders[i] = glm::vec4(glm::dvec3(anchor * scale), float(frequency * scale));
  }
  const std::vector<glm::dvec3> offsets = nearPoints(200, 34);
  for (NoiseType type : kAllTypes) {
    for (NoiseHash hash : {NoiseHash::Fast, NoiseHash::Reference}) {
      const NoiseSettings s = settingsOf(type, hash, 6);
      NoiseKernel<double> kernel = doubleKernel(s);
      kernel.octaveRemainders = remainders.data();
      kernel.octaveShifts = shifts.data();
      const gpu::NoiseParams params = toNoiseParams(s);
      double worst = 0.0, scale = 0.0;
      for (const glm::dvec3& o : offsets) {
        NoiseKernel<double>::OctaveWalk walk;
        walk.q = glm::dvec3(0.0);
        walk.lacunarity = params.lacunarity;
        walk.offset = o;
        walk.layer = 0u;
        walk.octave = 0u;
        walk.rebased = 1u;
        const glm::dvec4 rebased = kernel.fractalNoiseGradient(params, walk);
        const glm::dvec4 plain = kernel.evaluateNoiseGradient(params, anchor + o * frequency);
        ASSERT_NEAR(rebased.x, plain.x, 1e-9 * std::max(1.0, std::fabs(plain.x))) << describe(s);
        worst = std::max(worst, glm::length(glm::dvec3(rebased.y, rebased.z, rebased.w) -
                                            frequency * glm::dvec3(plain.y, plain.z, plain.w)));
        scale = std::max(scale, frequency * glm::length(glm::dvec3(plain.y, plain.z, plain.w)));
      }
      EXPECT_GT(scale, 0.0) << describe(s);
      EXPECT_LT(worst, 1e-7 * scale) << describe(s);
    }
  }
}

using NoiseGradientGpu = test::GpuTest;

TEST_F(NoiseGradientGpu, MatchesTheFloatReferenceForEveryTypeHashAndParameterSet) {
  const ParityPolicy policy = parityPolicyFor(context());
  GpuNoise gpu(context());
  for (const ValidationCase& c : validationCases()) {
    const std::vector<glm::vec3> points = validationPoints(3000, c.farPoints, 35);
    std::vector<glm::vec4> gpuValues(points.size()), cpuValues(points.size());
    gpu.evaluateGradient(c.settings, points, gpuValues);
    evaluateCpuGradient(c.settings, points, cpuValues, 0);
    const ParityStats stats = compareGradients(gpuValues, cpuValues);
    EXPECT_TRUE(policy.accepts(stats)) << describe(c.settings) << " (" << c.label << "): max|err| " << stats.maxAbsError
                                       << ", max ULP " << stats.maxUlp << ", identical " << stats.identical << "/"
                                       << stats.count << "; policy: " << policy.description;
  }
}

TEST_F(NoiseGradientGpu, ValueAndGradientDispatchesShareOnePointSet) {
  // One GpuNoise alternates values and values with gradients on the same points (its output
  // buffer grows to a vec4 per point and back is not needed): each matches the reference, and
  // reading the wrong kind is an error, not four floats read as one.
  GpuNoise gpu(context());
  const std::vector<glm::vec3> points = validationPoints(5000, false, 36);
  gpu.setPoints(points);
  const NoiseSettings s = settingsOf(NoiseType::Hetero);
  std::vector<float> values(points.size()), cpuValues(points.size());
  std::vector<glm::vec4> gradients(points.size()), cpuGradients(points.size());
  evaluateCpu(s, points, cpuValues);
  evaluateCpuGradient(s, points, cpuGradients);
  const ParityPolicy policy = parityPolicyFor(context());
  for (int round = 0; round < 2; ++round) {
    gpu.dispatch(s);
    gpu.readValues(values);
    EXPECT_TRUE(policy.accepts(compareValues(values, cpuValues))) << round;
    EXPECT_THROW(gpu.readGradients(gradients), Error);
    gpu.dispatchGradient(s);
    gpu.readGradients(gradients);
    EXPECT_TRUE(policy.accepts(compareGradients(gradients, cpuGradients))) << round;
    EXPECT_THROW(gpu.readValues(values), Error);
  }
}

// planet noise --gradient, as a user runs it.
test::ShellRun planet(const std::string& args, const std::string& input) {
  return test::runShell(PLANET_EXE, args, input, test::processTempDir("noise_gradient_cli"));
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<double> numbersOf(const std::string& line) {
  std::istringstream fields(line);
  std::vector<double> numbers;
  for (double x; fields >> x;) numbers.push_back(x);
  return numbers;
}

TEST(NoiseGradientCli, GradientPrintsValueAndThreeDerivativesPerLine) {
  const std::string input = "0.1 0.2 0.3\n1.5,-2.25,3.75\n# comment\n\n12.3 -4.5 6.7\n";
  for (const char* type : {"simplex", "ridged", "craters"}) {
    const std::string args = fmt::format("noise --type {} --hash reference", type);
    const test::ShellRun plain = planet(args, input);
    const test::ShellRun run = planet(args + " --gradient", input);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");
    const std::vector<std::string> values = linesOf(plain.out);
    const std::vector<std::string> lines = linesOf(run.out);
    ASSERT_EQ(lines.size(), 3u) << run.out;
    ASSERT_EQ(values.size(), 3u) << plain.out;
    for (size_t i = 0; i < lines.size(); ++i) {
      ASSERT_EQ(numbersOf(lines[i]).size(), 4u) << type << ": '" << lines[i] << "'";
      EXPECT_EQ(lines[i].substr(0, lines[i].find(' ')), values[i]) << type << ": the value column is not the value";
    }
    // The float reference's numbers, %.9g (which round-trips a float).
    const glm::vec4 g =
        evaluateCpuGradient(settingsOf(parseNoiseType(type), NoiseHash::Reference), glm::vec3(1.5f, -2.25f, 3.75f));
    EXPECT_EQ(lines[1], fmt::format("{:.9g} {:.9g} {:.9g} {:.9g}", g.x, g.y, g.z, g.w)) << type;
    // The compute shader prints the same text (skipped without a Vulkan device).
    const test::ShellRun gpuRun = planet(args + " --gradient --backend gpu", input);
    if (gpuRun.err.find("no Vulkan") == std::string::npos) {
      EXPECT_EQ(gpuRun.exitCode, 0) << gpuRun.err;
      EXPECT_EQ(gpuRun.out, run.out) << type;
    }
  }
}

TEST(NoiseGradientCli, BadCombinationsGiveOneLineErrors) {
  struct Case {
    std::string args, input, mustContain;
  };
  const Case cases[] = {
      {"noise --type fbm --gradient --octaves 0", "1 2 3\n", "octaves must be in 1..32, got 0"},
      {"noise --type craters --gradient --offset 0.9", "1 2 3\n", "offset of craters"},
      {"noise --type fbm --gradient=maybe", "1 2 3\n", "--gradient"},
      {"noise --type fbm --gradient 1", "1 2 3\n", "not expected: 1"},
      {"noise --type fbm --gradient --backend tpu", "1 2 3\n", "unknown backend 'tpu'"},
      {"noise --type fbm --gradient", "1 2 3\n4 5\n", "line 2: expected 3 numbers"},
  };
  for (const Case& c : cases) {
    const test::ShellRun run = planet(c.args, c.input);
    EXPECT_EQ(run.exitCode, 2) << c.args;
    EXPECT_EQ(run.out, "") << c.args << ": printed before the error";
    EXPECT_NE(run.err.find(c.mustContain), std::string::npos) << c.args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << c.args << ": " << run.err;
  }
}

}  // namespace
}  // namespace planet::noise

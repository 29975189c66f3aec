// Properties a terrain author relies on: range, continuity, determinism, seed independence,
// hash quality, and that each fractal follows its formula (issue #2's definitions).
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "noise/noise_cpu.h"
#include "noise/noise_kernel.h"
#include "bench/noise_validate.h"

namespace planet::noise {
namespace {

constexpr NoiseHash kHashes[] = {NoiseHash::Fast, NoiseHash::Reference};

NoiseSettings settingsOf(NoiseType type, NoiseHash hash, uint32_t seed = 0, int octaves = 8) {
  NoiseSettings s;
  s.type = type;
  s.hash = hash;
  s.seed = seed;
  s.octaves = octaves;
  return s;
}

std::vector<float> evaluateAll(const NoiseSettings& s, const std::vector<glm::vec3>& points) {
  std::vector<float> values(points.size());
  evaluateCpu(s, points, values, 1);
  return values;
}

double correlation(const std::vector<float>& a, const std::vector<float>& b) {
  double ma = 0, mb = 0;
  for (size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= double(a.size());
  mb /= double(b.size());
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

TEST(NoiseProperties, SimplexStaysWithinMinusOneToOneAndUsesTheRange) {
  const std::vector<glm::vec3> points = validationPoints(200000, false, 3);
  for (NoiseHash hash : kHashes) {
    for (uint32_t seed : {0u, 5u}) {
      std::vector<float> v = evaluateAll(settingsOf(NoiseType::Simplex, hash, seed), points);
      auto [lo, hi] = std::minmax_element(v.begin(), v.end());
      EXPECT_GE(*lo, -1.0f) << noiseHashName(hash);
      EXPECT_LE(*hi, 1.0f) << noiseHashName(hash);
      EXPECT_LT(*lo, -0.7f) << "range barely used, hash " << noiseHashName(hash);
      EXPECT_GT(*hi, 0.7f) << "range barely used, hash " << noiseHashName(hash);
      double mean = 0;
      for (float x : v) mean += x;
      EXPECT_NEAR(mean / double(v.size()), 0.0, 0.02) << "biased, hash " << noiseHashName(hash);
    }
  }
}

TEST(NoiseProperties, SimplexIsContinuousAcrossCellBoundaries) {
  // March along random lines in steps of 1e-4: every step stays within a gradient bound of 20
  // (measured: 6.5), plus float rounding. With Gustavson's kernel radius^2 of 0.6 a
  // dropped corner left jumps of up to ~0.005 at simplex boundaries; a wrong corner choice, hash
  // or skew shows as jumps of order 0.1.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-20.0f, 20.0f);
  for (NoiseHash hash : kHashes) {
    NoiseSettings s = settingsOf(NoiseType::Simplex, hash, 3);
    float maxStep = 0.0f;
    for (int line = 0; line < 20; ++line) {
      glm::vec3 p(coord(rng), coord(rng), coord(rng));
      glm::vec3 dir = glm::normalize(glm::vec3(coord(rng), coord(rng), coord(rng)));
      float prev = evaluateCpu(s, p);
      for (int i = 1; i <= 20000; ++i) {
        float v = evaluateCpu(s, p + dir * (float(i) * 1e-4f));
        maxStep = std::max(maxStep, std::abs(v - prev));
        prev = v;
      }
    }
    std::printf("largest step of 1e-4 (hash %s): %.6f\n", noiseHashName(hash), maxStep);
    EXPECT_LT(maxStep, 20.0f * 1e-4f + 1e-5f) << "hash " << noiseHashName(hash);
  }
}

// The planes x = y, y = z and x = z through the origin are simplex faces at every scale, so a
// jump there is shared by every octave and adds up to a terrain seam. Points 2e-9 apart on
// either side (double reference) must agree to within the gradient times that distance; the
// 0.6 kernel differed by up to 4.9e-3 at a fifth of them.
TEST(NoiseProperties, SimplexHasNoJumpAcrossThePlanesThroughTheOrigin) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-3.0, 3.0);
  for (NoiseHash hash : kHashes) {
    NoiseSettings s = settingsOf(NoiseType::Simplex, hash, 0);
    double worst = 0.0;
    for (int i = 0; i < 3000; ++i) {
      const double a = coord(rng), c = coord(rng), e = 1e-9;
      for (int u = 0; u < 3; ++u) {
        const int v = (u + 1) % 3;  // the plane x_u = x_v; the third coordinate is c
        glm::dvec3 p(c);
        p[u] = p[v] = a;
        glm::dvec3 q = p;
        p[u] += e;
        q[v] += e;
        worst = std::max(worst, std::abs(evaluateCpuDouble(s, p) - evaluateCpuDouble(s, q)));
      }
    }
    EXPECT_LT(worst, 1e-6) << "hash " << noiseHashName(hash);
  }
}

TEST(NoiseProperties, SameInputsGiveSameBitsOnEveryThreadCount) {
  const std::vector<glm::vec3> points = validationPoints(50000, true, 4);
  for (NoiseHash hash : kHashes) {
    NoiseSettings s = settingsOf(NoiseType::Ridged, hash, 11, 12);
    std::vector<float> a = evaluateAll(s, points);
    std::vector<float> b(points.size());
    evaluateCpu(s, points, b, 4);
    EXPECT_EQ(a, b) << "hash " << noiseHashName(hash);
    EXPECT_EQ(a, evaluateAll(s, points)) << "hash " << noiseHashName(hash);
  }
}

TEST(NoiseProperties, DifferentSeedsGiveUncorrelatedNoise) {
  const std::vector<glm::vec3> points = validationPoints(50000, false, 5);
  for (NoiseHash hash : kHashes) {
    std::vector<float> a = evaluateAll(settingsOf(NoiseType::Simplex, hash, 1), points);
    std::vector<float> b = evaluateAll(settingsOf(NoiseType::Simplex, hash, 2), points);
    std::vector<float> c = evaluateAll(settingsOf(NoiseType::Simplex, hash, 1000000), points);
    EXPECT_LT(std::abs(correlation(a, b)), 0.05) << "hash " << noiseHashName(hash);
    EXPECT_LT(std::abs(correlation(a, c)), 0.05) << "hash " << noiseHashName(hash);
    EXPECT_GT(correlation(a, a), 0.999);
  }
}

TEST(NoiseProperties, FastHashSpreadsGradientsEvenly) {
  // Chi-square of the 12 gradient indices over a block of lattice points: a biased or
  // repeating hash shows as a large statistic (11 degrees of freedom; 99.9 % quantile 31.3).
  NoiseKernel<float> kernel;
  uint32_t seedMix = kernel.noiseSeedMix(17);
  std::array<double, 12> counts{};
  int n = 0;
  for (uint32_t i = 0; i < 40; ++i)
    for (uint32_t j = 0; j < 40; ++j)
      for (uint32_t k = 0; k < 40; ++k, ++n) counts[kernel.latticeGradient(i, j, k, gpu::kNoiseHashFast, seedMix)]++;
  double expected = n / 12.0, chi2 = 0;
  for (double c : counts) chi2 += (c - expected) * (c - expected) / expected;
  EXPECT_LT(chi2, 31.3);
}

TEST(NoiseProperties, FractalsFollowTheirFormulas) {
  // Each fractal recomputed here from single-octave N values, straight from the formulas.
  const glm::vec3 points[] = {{0.3f, -1.7f, 2.2f}, {10.5f, 3.25f, -7.75f}, {-40.1f, 22.2f, 5.9f}};
  const double L = 2.0, H = 0.8;
  for (NoiseHash hash : kHashes) {
    for (const glm::vec3& p : points) {
      NoiseSettings single = settingsOf(NoiseType::Simplex, hash, 9);
      std::vector<double> N;
      glm::vec3 q = p;
      for (int i = 0; i < 4; ++i, q *= float(L)) N.push_back(evaluateCpu(single, q));
      auto w = [&](int i) { return std::pow(L, -i * H); };
      auto eval = [&](NoiseType type, double offset, double gain) {
        NoiseSettings s = settingsOf(type, hash, 9, 4);
        s.lacunarity = L;
        s.H = H;
        s.offset = offset;
        s.gain = gain;
        return double(evaluateCpu(s, p));
      };
      double fbm = 0;
      for (int i = 0; i < 4; ++i) fbm += N[i] * w(i);
      EXPECT_NEAR(eval(NoiseType::Fbm, 0, 2), fbm, 1e-5);

      double offset = 1.0, gain = 2.0;
      double s = std::pow(offset - std::abs(N[0]), 2), ridged = s;
      for (int i = 1; i < 4; ++i) {
        double weight = std::clamp(s * gain, 0.0, 1.0);
        s = std::pow(offset - std::abs(N[i]), 2) * weight;
        ridged += s * w(i);
      }
      EXPECT_NEAR(eval(NoiseType::Ridged, offset, gain), ridged, 1e-5);

      offset = 0.7;
      double hybrid = (N[0] + offset) * w(0), weight = hybrid;
      for (int i = 1; i < 4; ++i) {
        weight = std::clamp(weight, 0.0, 1.0);
        double signal = (N[i] + offset) * w(i);
        hybrid += weight * signal;
        weight *= signal;
      }
      EXPECT_NEAR(eval(NoiseType::Hybrid, offset, 2), hybrid, 1e-5);

      double hetero = offset + N[0];
      for (int i = 1; i < 4; ++i) hetero += (N[i] + offset) * w(i) * hetero;
      EXPECT_NEAR(eval(NoiseType::Hetero, offset, 2), hetero, 1e-5);

      offset = 0.8;
      double cascade = 1;
      for (int i = 0; i < 4; ++i) cascade *= N[i] + offset;
      EXPECT_NEAR(eval(NoiseType::Cascade, offset, 2), cascade, 1e-5);
    }
  }
}

TEST(NoiseProperties, CascadeIgnoresH) {
  NoiseSettings a = settingsOf(NoiseType::Cascade, NoiseHash::Fast, 3);
  NoiseSettings b = a;
  b.H = 0.3;
  EXPECT_EQ(evaluateCpu(a, glm::vec3(1.1f, 2.2f, 3.3f)), evaluateCpu(b, glm::vec3(1.1f, 2.2f, 3.3f)));
}

TEST(NoiseProperties, HugeCoordinatesGiveFiniteDeterministicValues) {
  const glm::vec3 points[] = {{1e9f, -1e12f, 3e30f}, {-3.4e38f, 3.4e38f, 0.0f}, {12582912.0f, -12582912.0f, 5e7f}};
  for (NoiseHash hash : kHashes) {
    NoiseSettings s = settingsOf(NoiseType::Fbm, hash, 1, 32);
    for (const glm::vec3& p : points) {
      float v = evaluateCpu(s, p);
      EXPECT_TRUE(std::isfinite(v)) << p.x << " " << p.y << " " << p.z;
      EXPECT_EQ(v, evaluateCpu(s, p));
    }
  }
}

TEST(NoiseProperties, DoubleReferenceAgreesWithFloatNearTheOrigin) {
  const std::vector<glm::vec3> points = validationPoints(2000, false, 6);
  for (NoiseHash hash : kHashes) {
    NoiseSettings s = settingsOf(NoiseType::Fbm, hash, 21, 8);
    for (const glm::vec3& p : points)
      ASSERT_NEAR(evaluateCpu(s, p), evaluateCpuDouble(s, glm::dvec3(p)), 2e-4) << p.x << " " << p.y << " " << p.z;
  }
}

}  // namespace
}  // namespace planet::noise

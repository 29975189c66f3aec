// Properties of the crater fractal (noise.glsl, cratersNoise): each crater the hash places is a
// bowl below and a rim above its surroundings, values stay finite and bounded, the number of
// craters a surface cuts grows by L^2 per octave (N(>D) ~ D^-2), and the seed decides where
// they are.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "noise/noise_cpu.h"
#include "noise/noise_kernel.h"
#include "noise/permutation.h"
#include "bench/noise_validate.h"

namespace planet::noise {
namespace {

using Kernel = NoiseKernel<float>;
constexpr NoiseHash kHashes[] = {NoiseHash::Fast, NoiseHash::Reference};

NoiseSettings craters(NoiseHash hash, uint32_t seed, int octaves, double perturbation = 0.0) {
  NoiseSettings s;
  s.type = NoiseType::Craters;
  s.hash = hash;
  s.seed = seed;
  s.octaves = octaves;
  s.offset = perturbation;
  return s;
}

struct Crater {
  glm::dvec3 centre;  // octave units
  double radius;      // octave units
  double size;        // radius / the largest radius: the depth scale
};

// The crater of cell (i, j, k), if the cell holds one: the placement rule of noise.glsl, read
// off the kernel's own hash (the rim perturbation widens the margin from the cell's faces).
bool craterOfCell(const NoiseSettings& s, int i, int j, int k, Crater& crater) {
  const double eps = s.offset.value_or(defaultOffset(s.type));
  Kernel kernel;
  kernel.permutation = permutationTable(s.seed).data();
  const uint32_t seedMix = kernel.noiseSeedMix(s.seed);
  const uint32_t h = kernel.craterCellHash(uint32_t(i), uint32_t(j), uint32_t(k), uint32_t(s.hash), seedMix);
  const uint32_t h2 = kernel.lowbias32(h);
  if (double(h2 & 0xffffu) / 65536.0 >= double(Kernel::kCraterPresence)) return false;
  crater.size = Kernel::kCraterRadiusMin + (1.0 - Kernel::kCraterRadiusMin) * double(h2 >> 16u) / 65536.0;
  crater.radius = Kernel::kCraterRadiusMax * crater.size;
  const double margin = std::max(Kernel::kCraterReach * crater.radius * (1.0 + eps) - 0.5, 0.0);
  const double span = 1.0 - 2.0 * margin;
  crater.centre =
      glm::dvec3(i, j, k) + margin + span * glm::dvec3(h >> 16u, h & 0xffffu, kernel.lowbias32(h2) >> 16u) / 65536.0;
  return true;
}

// Craters with centres in the cells [lo, hi) of one octave.
std::vector<Crater> cratersIn(const NoiseSettings& s, glm::ivec3 lo, glm::ivec3 hi) {
  std::vector<Crater> found;
  Crater c;
  for (int k = lo.z; k < hi.z; ++k)
    for (int j = lo.y; j < hi.y; ++j)
      for (int i = lo.x; i < hi.x; ++i)
        if (craterOfCell(s, i, j, k, c)) found.push_back(c);
  return found;
}

// True when no other crater's reach (grown by the largest perturbation, 1 + eps) overlaps this
// one's (its profile is then alone).
bool isolated(const Crater& c, const std::vector<Crater>& all, double eps = 0.0) {
  for (const Crater& o : all) {
    if (&o == &c) continue;
    if (glm::length(o.centre - c.centre) < Kernel::kCraterReach * (1.0 + eps) * (o.radius + c.radius)) return false;
  }
  return true;
}

// Isolated craters whose neighbours all lie inside the cells [0, 12)^3 searched.
std::vector<Crater> isolatedCraters(const NoiseSettings& s) {
  const double eps = s.offset.value_or(defaultOffset(s.type));
  const std::vector<Crater> all = cratersIn(s, {0, 0, 0}, {12, 12, 12});
  std::vector<Crater> found;
  for (const Crater& c : all)
    if (glm::all(glm::greaterThan(c.centre, glm::dvec3(1.0))) && glm::all(glm::lessThan(c.centre, glm::dvec3(11.0))) &&
        isolated(c, all, eps))
      found.push_back(c);
  return found;
}

TEST(CraterProperties, IsolatedCratersAreBowlsBelowAndRimsAboveTheirSurroundings) {
  for (NoiseHash hash : kHashes) {
    const NoiseSettings s = craters(hash, 4, 1);
    const std::vector<Crater> all = cratersIn(s, {0, 0, 0}, {12, 12, 12});
    int checked = 0;
    for (const Crater& c : all) {
      const bool inner = glm::all(glm::greaterThan(c.centre, glm::dvec3(1.0))) &&
                         glm::all(glm::lessThan(c.centre, glm::dvec3(11.0)));  // neighbours all listed
      if (!inner || !isolated(c, all)) continue;
      ++checked;
      // Along a line through the centre: the floor at the centre, the rim at one radius, nothing
      // beyond the reach.
      auto at = [&](double t) { return double(evaluateCpu(s, glm::vec3(c.centre + glm::dvec3(t, 0.0, 0.0)))); };
      const double r = c.radius;
      const double floor = at(0.0), rim = std::max(at(r), at(-r)), outside = at(1.05 * Kernel::kCraterReach * r);
      EXPECT_NEAR(floor, -c.size, 1e-3) << noiseHashName(hash);
      EXPECT_NEAR(rim, Kernel::kCraterRim * c.size, 1e-3) << noiseHashName(hash);
      EXPECT_EQ(outside, 0.0) << noiseHashName(hash);
      EXPECT_LT(floor, outside - 0.4);
      EXPECT_GT(rim, outside + 0.1);
      // The height rises monotonically from the floor to the rim and falls from there to zero.
      double previous = floor;
      for (int step = 1; step <= 36; ++step) {
        const double t = r * Kernel::kCraterReach * step / 36.0, v = at(t);
        if (t <= r)
          EXPECT_GE(v, previous - 1e-6) << "bowl not rising at " << t / r << " radii";
        else
          EXPECT_LE(v, previous + 1e-6) << "ejecta not falling at " << t / r << " radii";
        previous = v;
      }
    }
    EXPECT_GT(checked, 20) << "too few isolated craters to test, hash " << noiseHashName(hash);
  }
}

TEST(CraterProperties, RimPerturbationMakesRimsNeitherRoundNorLevel) {
  // Around an isolated crater, along 36 directions in the plane through its centre: where the
  // bowl crosses the surrounding level (the floor's edge) and how high the rim rises. Without
  // perturbation both are the same in every direction (a circle, a level rim); with eps they vary
  // with the simplex value n at twice the octave's frequency: radius r (1 + eps n), rim height
  // kCraterRim (1 + eps n) size, so within eps of the unperturbed ones.
  for (double eps : {0.0, 0.25}) {
    const NoiseSettings s = craters(NoiseHash::Fast, 4, 1, eps);
    const std::vector<Crater> found = isolatedCraters(s);
    ASSERT_GT(found.size(), 10u) << eps;
    double largestEdgeSpread = 0.0, largestRimSpread = 0.0, sumEdgeSpread = 0.0, sumRimSpread = 0.0;
    for (const Crater& c : found) {
      const double r = c.radius;
      // Unperturbed: the bowl R - (1 + R)(1 - rho^2)^2 is 0 at rho^2 = 1 - sqrt(R / (1 + R)).
      const double R = Kernel::kCraterRim;
      const double edge0 = r * std::sqrt(1.0 - std::sqrt(R / (1.0 + R)));
      double edgeLo = 1e9, edgeHi = 0.0, rimLo = 1e9, rimHi = 0.0;
      for (int d = 0; d < 36; ++d) {
        const double angle = 2.0 * 3.14159265358979 * d / 36.0;
        const glm::dvec3 dir(std::cos(angle), std::sin(angle), 0.0);
        auto at = [&](double t) { return double(evaluateCpu(s, glm::vec3(c.centre + t * dir))); };
        // The floor's edge by bisection between the centre (below 0) and the rim (above).
        double lo = 0.0, hi = r * (1.0 + eps);
        for (int k = 0; k < 30; ++k) (at(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
        edgeLo = std::min(edgeLo, lo), edgeHi = std::max(edgeHi, lo);
        double rim = 0.0;
        for (int k = 0; k <= 60; ++k) rim = std::max(rim, at(r * (1.0 - eps + 2.0 * eps * k / 60.0 + 0.001)));
        rimLo = std::min(rimLo, rim), rimHi = std::max(rimHi, rim);
        EXPECT_GE(lo, edge0 * (1.0 - eps) - 1e-4) << "edge inside the perturbed circle, eps " << eps;
        EXPECT_LE(lo, edge0 * (1.0 + eps) + 1e-4) << "edge outside the perturbed circle, eps " << eps;
        EXPECT_GE(rim, R * c.size * (1.0 - eps) - 1e-4) << "rim too low, eps " << eps;
        EXPECT_LE(rim, R * c.size * (1.0 + eps) + 1e-4) << "rim too high, eps " << eps;
      }
      const double edgeSpread = (edgeHi - edgeLo) / r, rimSpread = (rimHi - rimLo) / c.size;
      largestEdgeSpread = std::max(largestEdgeSpread, edgeSpread);
      largestRimSpread = std::max(largestRimSpread, rimSpread);
      sumEdgeSpread += edgeSpread, sumRimSpread += rimSpread;
    }
    const double meanEdgeSpread = sumEdgeSpread / double(found.size());
    const double meanRimSpread = sumRimSpread / double(found.size());
    std::printf(
        "eps %.2f, %zu craters: floor edge varies by %.4f radii (mean; largest %.4f), rim height by %.4f "
        "size (largest %.4f)\n",
        eps, found.size(), meanEdgeSpread, largestEdgeSpread, meanRimSpread, largestRimSpread);
    if (eps == 0.0) {
      EXPECT_LT(largestEdgeSpread, 1e-5) << "an unperturbed crater is round";
      EXPECT_LT(largestRimSpread, 1e-5) << "an unperturbed rim is level";
    } else {
      EXPECT_GT(meanEdgeSpread, 0.02) << "perturbed craters should not be round";
      EXPECT_GT(meanRimSpread, 0.01) << "perturbed rims should not be level";
    }
  }
}

TEST(CraterProperties, ProfileIsContinuousWithoutRingsInTheSlope) {
  // Steps of 1e-4 along lines through three octaves: the height's change per step stays below
  // slope * step, and the change of that change is small too: a kink (a ring in the normals)
  // would show as a jump of slope * step. Unperturbed, to see the profile itself (the
  // perturbation inherits the simplex noise's tiny steps, see NoiseProperties).
  const NoiseSettings s = craters(NoiseHash::Fast, 9, 3, 0.0);
  double maxStep = 0.0, maxKink = 0.0;
  for (int line = 0; line < 8; ++line) {
    const glm::vec3 p(0.37f * line, 1.1f + 0.5f * line, -2.3f + 0.25f * line);
    const glm::vec3 dir = glm::normalize(glm::vec3(1.0f, 0.3f * line - 1.0f, 0.2f));
    double prev = evaluateCpu(s, p), prevStep = 0.0;
    for (int i = 1; i <= 20000; ++i) {
      const double v = evaluateCpu(s, p + dir * (float(i) * 1e-4f));
      const double step = v - prev;
      maxStep = std::max(maxStep, std::abs(step));
      if (i > 1) maxKink = std::max(maxKink, std::abs(step - prevStep));
      prev = v, prevStep = step;
    }
  }
  EXPECT_LT(maxStep, 0.01);
  EXPECT_LT(maxKink, 2e-4);
}

TEST(CraterProperties, ValuesAreFiniteAndBounded) {
  // At most 8 craters per octave overlap a point, each within [-1, rim * 1.5]: |v| <= 8 sum w_i.
  const std::vector<glm::vec3> points = validationPoints(100000, false, 12);
  for (NoiseHash hash : kHashes) {
    const NoiseSettings s = craters(hash, 3, 8, 0.5);
    std::vector<float> v(points.size());
    evaluateCpu(s, points, v, 1);
    double lo = 0.0, hi = 0.0, bound = 0.0;
    for (int i = 0; i < 8; ++i) bound += 8.0 * std::pow(2.0, -i);
    for (float x : v) {
      ASSERT_TRUE(std::isfinite(x));
      lo = std::min(lo, double(x)), hi = std::max(hi, double(x));
    }
    EXPECT_GE(lo, -bound);
    EXPECT_LE(hi, bound);
    EXPECT_LT(lo, -0.5) << "no deep floors, hash " << noiseHashName(hash);
    EXPECT_GT(hi, 0.15) << "no rims, hash " << noiseHashName(hash);
  }
  for (const glm::vec3& p : {glm::vec3(1e9f, -1e12f, 3e30f), glm::vec3(-3.4e38f, 3.4e38f, 0.0f)}) {
    const float v = evaluateCpu(craters(NoiseHash::Fast, 1, 32, 0.25), p);
    EXPECT_TRUE(std::isfinite(v)) << p.x << " " << p.y << " " << p.z;
  }
}

TEST(CraterProperties, CountsOnASurfaceGrowByLacunaritySquaredPerOctave) {
  // The plane z = 0.37 (octave-0 units) over 48 x 48 units; octave i sees it at z = 0.37 L^i over
  // 48 L^i cells. A crater is cut as a bowl when its centre lies within its radius of the plane.
  const NoiseSettings s = craters(NoiseHash::Fast, 5, 4);
  const double plane = 0.37, extent = 48.0, L = 2.0;
  std::vector<double> counts;
  for (int i = 0; i < 4; ++i) {
    const double scale = std::pow(L, i), z = plane * scale;
    const int n = int(extent * scale), kz = int(std::floor(z));
    double count = 0.0;
    for (const Crater& c : cratersIn(s, {0, 0, kz - 1}, {n, n, kz + 2}))
      if (std::abs(c.centre.z - z) < c.radius) ++count;
    counts.push_back(count);
  }
  EXPECT_GT(counts[0], 100.0);
  for (int i = 1; i < 4; ++i) {
    EXPECT_GT(counts[i] / counts[i - 1], 0.85 * L * L) << "octave " << i;
    EXPECT_LT(counts[i] / counts[i - 1], 1.15 * L * L) << "octave " << i;
  }
  // And the noise sees them: the centre's projection onto the plane lies in a bowl (single
  // octave, so the only other contributions are overlapping craters of the same size).
  const NoiseSettings single = craters(NoiseHash::Fast, 5, 1);
  int inBowl = 0, total = 0;
  for (const Crater& c : cratersIn(single, {0, 0, -1}, {24, 24, 2})) {
    if (std::abs(c.centre.z - plane) >= 0.5 * c.radius) continue;
    ++total;
    inBowl += evaluateCpu(single, glm::vec3(c.centre.x, c.centre.y, plane)) < 0.0f;
  }
  EXPECT_GT(total, 20);
  EXPECT_GT(inBowl, 0.9 * total);
}

TEST(CraterProperties, SameSeedSameCratersOtherSeedMovesThem) {
  const std::vector<glm::vec3> points = validationPoints(20000, false, 13);
  for (NoiseHash hash : kHashes) {
    std::vector<float> a(points.size()), b(points.size()), c(points.size());
    evaluateCpu(craters(hash, 21, 6, 0.25), points, a, 1);
    evaluateCpu(craters(hash, 21, 6, 0.25), points, b, 2);
    evaluateCpu(craters(hash, 22, 6, 0.25), points, c, 1);
    EXPECT_EQ(a, b) << noiseHashName(hash);
    size_t differ = 0;
    for (size_t i = 0; i < a.size(); ++i) differ += a[i] != c[i];
    EXPECT_GT(differ, a.size() / 2) << noiseHashName(hash);
    // The crater lists themselves differ too.
    const std::vector<Crater> first = cratersIn(craters(hash, 21, 1), {0, 0, 0}, {6, 6, 6});
    const std::vector<Crater> second = cratersIn(craters(hash, 22, 1), {0, 0, 0}, {6, 6, 6});
    size_t shared = 0;
    for (const Crater& x : first)
      for (const Crater& y : second) shared += glm::length(x.centre - y.centre) < 1e-6;
    EXPECT_LT(shared, first.size() / 10 + 1) << noiseHashName(hash);
  }
}

TEST(CraterProperties, DoubleReferenceAgreesWithFloat) {
  const std::vector<glm::vec3> points = validationPoints(2000, false, 14);
  for (NoiseHash hash : kHashes) {
    const NoiseSettings s = craters(hash, 7, 8, 0.25);
    for (const glm::vec3& p : points)
      ASSERT_NEAR(evaluateCpu(s, p), evaluateCpuDouble(s, glm::dvec3(p)), 2e-4) << p.x << " " << p.y << " " << p.z;
  }
}

}  // namespace
}  // namespace planet::noise

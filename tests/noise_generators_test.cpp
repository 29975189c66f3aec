// The generators of seeds 000 and 004 evaluated per point (issue 22, common/noise_generators.glsl):
// `faults` sums random great-circle steps, `mpd` and `mpd_ico` descend the subdivision of the
// octahedron and the icosahedron. The properties a user relies on: each fault is a step of twice
// its height across its circle and nowhere else, the fault planes are uniform on the sphere, a
// width makes the steps continuous; an MPD vertex keeps its value at every finer level, the
// surface has no cracks across the edges of base faces or of levels, offsets fall by 2^-H per
// level, the multifractal variant scales them by its parents; the gradients are the values'
// derivatives, and a planet with such layers renders the heights of the CPU float path.
//
// Two groups in one program (tests/CMakeLists.txt): NoiseGenerators.* (label unit) and
// NoiseGeneratorsGpu.* (gpu).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/noise_validate.h"
#include "core/error.h"
#include "gpu_fixture.h"
#include "noise/noise_cpu.h"
#include "noise/noise_kernel.h"
#include "planet/octave_budget.h"
#include "planet/planet_description.h"
#include "planet/terrain_height.h"
#include "planet/terrain_points_gpu.h"
#include "planet/terrain_rebase.h"

namespace planet::noise {
namespace {

NoiseSettings faultSettings(int count, double width, uint32_t seed = 0) {
  NoiseSettings s;
  s.type = NoiseType::Faults;
  s.faults = count;
  s.width = width;
  s.seed = seed;
  return s;
}

NoiseSettings mpdSettings(NoiseType type, int levels, double H = 1.0, uint32_t seed = 0) {
  NoiseSettings s;
  s.type = type;
  s.octaves = levels;
  s.H = H;
  s.seed = seed;
  return s;
}

// Fault i of `seed`: unit plane normal (xyz) and step height (w), as the shaders draw it.
glm::vec4 faultPlane(uint32_t seed, uint32_t i) {
  NoiseKernel<float> kernel;
  return kernel.faultPlane(i, kernel.noiseSeedMix(seed));
}

// `count` points of equal area on the unit sphere (the Fibonacci lattice).
std::vector<glm::dvec3> spherePoints(size_t count) {
  std::vector<glm::dvec3> points;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (size_t i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * double(i) + 1.0) / double(count);
    const double r = std::sqrt(1.0 - z * z);
    points.push_back({r * std::cos(golden * double(i)), r * std::sin(golden * double(i)), z});
  }
  return points;
}

// A unit vector perpendicular to n.
glm::dvec3 perpendicular(const glm::dvec3& n) {
  glm::dvec3 other = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(n, other));
}

TEST(NoiseGenerators, OneFaultIsAStepOfTwiceItsHeightAcrossItsCircle) {
  for (uint32_t seed : {0u, 5u, 1234u}) {
    const glm::vec4 plane = faultPlane(seed, 0);
    const glm::dvec3 n(plane.x, plane.y, plane.z);
    ASSERT_NEAR(glm::length(n), 1.0, 1e-6);
    ASSERT_GT(plane.w, 0.0f);
    ASSERT_LE(plane.w, 1.0f);
    const NoiseSettings s = faultSettings(1, 0.0, seed);
    // Everywhere: +r on the normal's side, -r on the other (the seed's two hemispheres).
    for (const glm::dvec3& p : spherePoints(2000)) {
      const float value = evaluateCpu(s, glm::vec3(p));
      EXPECT_EQ(value, glm::dot(glm::vec3(n), glm::vec3(p)) >= 0.0f ? plane.w : -plane.w) << seed;
    }
    // Across the circle, 1e-4 rad either side, at points all along it: a jump of exactly 2r.
    const glm::dvec3 u = perpendicular(n);
    const glm::dvec3 v = glm::cross(n, u);
    for (int k = 0; k < 64; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / 64.0;
      const glm::dvec3 onCircle = std::cos(angle) * u + std::sin(angle) * v;
      const float above = evaluateCpu(s, glm::vec3(onCircle + 1e-4 * n));
      const float below = evaluateCpu(s, glm::vec3(onCircle - 1e-4 * n));
      EXPECT_EQ(above - below, 2.0f * plane.w) << seed << " at " << angle;
    }
  }
}

TEST(NoiseGenerators, CrossingOneOfManyFaultsChangesTheSumByTwiceThatFaultsStep) {
  const uint32_t seed = 9;
  const int count = 40;
  const NoiseSettings s = faultSettings(count, 0.0, seed);
  int checked = 0;
  for (uint32_t k = 0; k < uint32_t(count); ++k) {
    const glm::vec4 plane = faultPlane(seed, k);
    const glm::dvec3 n(plane.x, plane.y, plane.z);
    const glm::dvec3 u = perpendicular(n);
    const glm::dvec3 v = glm::cross(n, u);
    for (int a = 0; a < 16; ++a) {
      const double angle = 2.0 * std::numbers::pi * (a + 0.5) / 16.0;
      const glm::dvec3 onCircle = std::cos(angle) * u + std::sin(angle) * v;
      const glm::dvec3 above = onCircle + 1e-4 * n, below = onCircle - 1e-4 * n;
      // Skip crossings where another circle passes between the two points.
      bool alone = true;
      for (uint32_t j = 0; j < uint32_t(count); ++j) {
        if (j == k) continue;
        const glm::vec4 other = faultPlane(seed, j);
        const glm::dvec3 m(other.x, other.y, other.z);
        if ((glm::dot(m, above) >= 0.0) != (glm::dot(m, below) >= 0.0)) alone = false;
      }
      if (!alone) continue;
      const float jump = evaluateCpu(s, glm::vec3(above)) - evaluateCpu(s, glm::vec3(below));
      // The sums differ in one term: exact up to the float rounding of sums of ~40 steps.
      EXPECT_NEAR(jump, 2.0f * plane.w, 2e-5f) << "fault " << k;
      ++checked;
    }
  }
  EXPECT_GT(checked, 500);
}

TEST(NoiseGenerators, FaultPlanesAreUniformOnTheSphereAndStepsUniformInZeroToOne) {
  const int count = 10000;
  glm::dvec3 mean(0.0), squares(0.0);
  double stepMean = 0.0;
  int upperCap = 0;  // normals within 30 degrees of +y: (1 - cos 30°) / 2 = 6.7 % of the sphere
  for (uint32_t i = 0; i < uint32_t(count); ++i) {
    const glm::vec4 plane = faultPlane(77, i);
    const glm::dvec3 n(plane.x, plane.y, plane.z);
    mean += n;
    squares += n * n;
    stepMean += plane.w;
    if (n.y > std::cos(std::numbers::pi / 6.0)) ++upperCap;
  }
  mean /= double(count);
  squares /= double(count);
  stepMean /= double(count);
  // Standard errors: mean component 1/sqrt(3N) = 0.0058, square 0.0030, cap fraction 0.0025,
  // step mean 0.0029; bounds at about 4 of them.
  EXPECT_LT(glm::length(mean), 0.03);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(squares[a], 1.0 / 3.0, 0.012) << a;
  EXPECT_NEAR(upperCap / double(count), (1.0 - std::cos(std::numbers::pi / 6.0)) / 2.0, 0.01);
  EXPECT_NEAR(stepMean, 0.5, 0.012);
}

TEST(NoiseGenerators, FaultWidthTurnsTheStepIntoAContinuousRamp) {
  const double width = 0.05;
  const NoiseSettings s = faultSettings(1, width, 3);
  const glm::vec4 plane = faultPlane(3, 0);
  const glm::dvec3 n(plane.x, plane.y, plane.z);
  const glm::dvec3 u = perpendicular(n);
  // Along a great circle through the fault's poles: sin(angle from the circle) = sin(t).
  float previous = 0.0f;
  float largestJump = 0.0f;
  const double step = 1e-4;
  for (int i = -1000; i <= 1000; ++i) {
    const double t = i * step;
    const float value = evaluateCpu(s, glm::vec3(std::cos(t) * u + std::sin(t) * n));
    if (i > -1000) largestJump = std::max(largestJump, std::abs(value - previous));
    previous = value;
    const double d = std::sin(t) / width;
    if (d >= 1.0) {
      EXPECT_EQ(value, plane.w) << t;
    }
    if (d <= -1.0) {
      EXPECT_EQ(value, -plane.w) << t;
    }
  }
  EXPECT_NEAR(evaluateCpu(s, glm::vec3(u)), 0.0f, 1e-6f);  // the middle of the ramp, on the circle
  // The ramp's steepest slope is 1.5 r / width per radian: one step of 1e-4 rad rises by at most
  // that much, where the sharp fault jumps by 2r.
  EXPECT_LE(largestJump, 1.5f * plane.w / float(width) * float(step) * 1.01f);
  EXPECT_GT(largestJump, 0.5f * 1.5f * plane.w / float(width) * float(step));
}

// The central projection of lattice point (i, j, k) (i + j + k = 2^level) of a base face.
glm::dvec3 latticePoint(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int i, int j, int k) {
  return double(i) * a + double(j) * b + double(k) * c;
}

TEST(NoiseGenerators, MpdVertexValuesDoNotChangeWithFinerLevels) {
  // Octahedron face +x +y +z: its lattice points are integer vectors, exact in float, so a
  // vertex's value must be the same to the last bit whatever the number of levels below it... up
  // to the rounding of the barycentric weights (1e-6 relative); icosahedron faces as well, whose
  // vertices carry the float rounding of their coordinates.
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  const double a = 1.0 / std::sqrt(1.0 + phi * phi), b = phi * a;
  struct Face {
    NoiseType type;
    glm::dvec3 a, b, c;
  };
  const Face faces[] = {{NoiseType::Mpd, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                        {NoiseType::MpdIco, {0, a, b}, {b, 0, a}, {a, b, 0}}};
  for (const Face& f : faces) {
    for (int level : {1, 3, 5}) {
      const int n = 1 << level;
      for (int i = 0; i <= n; i += 1)
        for (int j = 0; i + j <= n; j += 1) {
          const glm::vec3 p(latticePoint(f.a, f.b, f.c, i, j, n - i - j));
          const float coarse = evaluateCpu(mpdSettings(f.type, level, 0.8, 21), p);
          for (int finer : {level + 1, level + 4, 16}) {
            const float fine = evaluateCpu(mpdSettings(f.type, finer, 0.8, 21), p);
            EXPECT_NEAR(fine, coarse, 2e-5f) << noiseTypeName(f.type) << " level " << level << " vertex (" << i << ", "
                                             << j << ") evaluated with " << finer << " levels";
          }
        }
    }
  }
}

TEST(NoiseGenerators, MpdHasNoCracksAcrossBaseFacesOrLevelEdges) {
  // Walk great circles in steps of 2e-6 rad through base-face edges and vertices and thousands
  // of level edges: no step may change the value by more than the steepest slope found times
  // the step (a crack, two neighbours disagreeing on an edge, would jump by about an offset,
  // 2^-12 · 0.8 ≥ 1e-4 here at level 12).
  for (NoiseType type : {NoiseType::Mpd, NoiseType::MpdIco}) {
    const NoiseSettings s = mpdSettings(type, 12, 0.9, 4);
    const glm::dvec3 starts[] = {glm::normalize(glm::dvec3(1, 0.3, -0.002)), glm::normalize(glm::dvec3(0.2, 1, 0.001)),
                                 glm::normalize(glm::dvec3(0.001, 0.5, 1)), glm::normalize(glm::dvec3(0.01, 1, 0.01))};
    const glm::dvec3 directions[] = {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), glm::dvec3(1, 0, 0),
                                     glm::dvec3(1, 0, 1)};
    for (int w = 0; w < 4; ++w) {
      const glm::dvec3 p0 = starts[w];
      const glm::dvec3 t = glm::normalize(directions[w] - glm::dot(directions[w], p0) * p0);
      const double step = 2e-6;
      float largestJump = 0.0f, steepest = 0.0f;
      float previous = 0.0f;
      for (int i = 0; i <= 20000; ++i) {
        const double angle = (i - 10000) * step;
        const glm::dvec3 p = std::cos(angle) * p0 + std::sin(angle) * t;
        const glm::vec4 g = evaluateCpuGradient(s, glm::vec3(p));
        const glm::vec3 tangent = glm::vec3(-std::sin(angle) * p0 + std::cos(angle) * t);
        steepest = std::max(steepest, std::abs(glm::dot(glm::vec3(g.y, g.z, g.w), tangent)));
        if (i > 0) largestJump = std::max(largestJump, std::abs(g.x - previous));
        previous = g.x;
      }
      EXPECT_LE(largestJump, steepest * float(step) * 1.5f + 2e-6f)
          << noiseTypeName(type) << " walk " << w << ": steepest slope " << steepest;
    }
  }
}

TEST(NoiseGenerators, MpdOffsetsFallByTwoToTheMinusHPerLevel) {
  for (NoiseType type : {NoiseType::Mpd, NoiseType::MpdIco}) {
    for (double H : {0.5, 1.0}) {
      // RMS of what level l adds at random points, for l = 6..9: ratios 2^-H (the interpolated
      // offsets of a level are its offsets times hat functions, the same shape at every level).
      std::vector<double> added;
      const std::vector<glm::dvec3> points = spherePoints(20000);
      for (int level = 6; level <= 10; ++level) {
        double sum2 = 0.0;
        for (const glm::dvec3& p : points) {
          const double d = evaluateCpuDouble(mpdSettings(type, level, H, 8), p) -
                           evaluateCpuDouble(mpdSettings(type, level - 1, H, 8), p);
          sum2 += d * d;
        }
        added.push_back(std::sqrt(sum2 / double(points.size())));
      }
      for (size_t l = 1; l < added.size(); ++l)
        EXPECT_NEAR(added[l] / added[l - 1], std::pow(2.0, -H), 0.06 * std::pow(2.0, -H))
            << noiseTypeName(type) << " H " << H << " level " << l + 6;
    }
  }
}

TEST(NoiseGenerators, MultifractalOffsetsScaleWithTheirParents) {
  for (NoiseType type : {NoiseType::Mpd, NoiseType::MpdIco}) {
    NoiseSettings zero = mpdSettings(type, 10, 1.0, 2);
    zero.multifractal = true;
    zero.gain = 0.0;  // k = 0: no offset below the base vertices
    NoiseSettings coarse = zero;
    coarse.octaves = 1;
    NoiseSettings plain = mpdSettings(type, 10, 1.0, 2);
    NoiseSettings multi = plain;
    multi.multifractal = true;
    multi.gain = 2.0;
    double lowRough = 0.0, highRough = 0.0;
    int low = 0, high = 0, differs = 0;
    for (const glm::dvec3& p : spherePoints(4000)) {
      EXPECT_NEAR(evaluateCpuDouble(zero, p), evaluateCpuDouble(coarse, p), 1e-12);
      const double m = evaluateCpuDouble(multi, p);
      if (m != evaluateCpuDouble(plain, p)) ++differs;
      // What the finest four levels add, where the height so far is near 0 and where it is not.
      NoiseSettings before = multi;
      before.octaves = 6;
      const double base = evaluateCpuDouble(before, p);
      const double added = std::abs(m - base);
      if (std::abs(base) < 0.1) {
        lowRough += added;
        ++low;
      } else if (std::abs(base) > 0.4) {
        highRough += added;
        ++high;
      }
    }
    EXPECT_GT(differs, 3900) << noiseTypeName(type);
    ASSERT_GT(low, 100);
    ASSERT_GT(high, 100);
    // Offsets proportional to the parents' mean: the fine relief of high ground is several times
    // that of ground near 0 (mean |base| about 0.05 there against over 0.4).
    EXPECT_GT(highRough / high, 3.0 * lowRough / low) << noiseTypeName(type);
  }
}

TEST(NoiseGenerators, FadedLastLevelBlendsTheSurfacesWithAndWithoutIt) {
  NoiseKernel<double> kernel;
  for (NoiseType type : {NoiseType::Mpd, NoiseType::MpdIco}) {
    gpu::NoiseParams params = toNoiseParams(mpdSettings(type, 9, 0.8, 6));
    gpu::NoiseParams fewer = params;
    fewer.octaves = 8;
    for (const glm::dvec3& p : spherePoints(500)) {
      const double without = kernel.evaluateNoise(fewer, p);
      const double with = kernel.evaluateNoise(params, p);
      gpu::NoiseParams faded = params;
      faded.lastOctaveWeight = 0.25f;
      EXPECT_NEAR(kernel.evaluateNoise(faded, p), without + 0.25 * (with - without), 1e-12);
    }
  }
}

TEST(NoiseGenerators, GradientsMatchCentralDifferencesOfTheDoubleReference) {
  const NoiseSettings cases[] = {faultSettings(300, 0.2, 1), mpdSettings(NoiseType::Mpd, 7, 0.8, 3),
                                 mpdSettings(NoiseType::MpdIco, 7, 0.8, 3)};
  for (const NoiseSettings& s : cases) {
    int matched = 0, total = 0;
    for (const glm::dvec3& unit : spherePoints(300)) {
      const glm::dvec3 p = 3.0 * unit;  // not on the unit sphere: the radial derivative is 0
      const glm::dvec4 g = evaluateCpuGradientDouble(s, p);
      EXPECT_NEAR(glm::dot(glm::dvec3(g.y, g.z, g.w), unit), 0.0,
                  1e-9 * (1.0 + glm::length(glm::dvec3(g.y, g.z, g.w))));
      const double h = 1e-7;
      glm::dvec3 difference;
      for (int a = 0; a < 3; ++a) {
        glm::dvec3 e(0.0);
        e[a] = h;
        difference[a] = (evaluateCpuDouble(s, p + e) - evaluateCpuDouble(s, p - e)) / (2.0 * h);
      }
      ++total;
      // MPD is piecewise linear: a difference straddling a level edge is off; they are rare at this h.
      if (glm::length(difference - glm::dvec3(g.y, g.z, g.w)) <= 1e-5 * (1.0 + glm::length(difference))) ++matched;
    }
    EXPECT_GE(matched, total * 98 / 100) << describe(s);
  }
}

TEST(NoiseGenerators, OutOfRangeParametersAreOneLineErrorsNamingTheValue) {
  auto message = [](const NoiseSettings& s) {
    try {
      validateNoiseSettings(s);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(faultSettings(0, 0.0)), "faults (the number of great circles) must be in 1..10000, got 0");
  EXPECT_EQ(message(faultSettings(10001, 0.0)), "faults (the number of great circles) must be in 1..10000, got 10001");
  EXPECT_EQ(message(faultSettings(10, -0.1)), "width of faults must be in [0, 1.5] radians, got -0.1");
  EXPECT_EQ(message(faultSettings(10, NAN)), "width must be a finite number, got nan");
  EXPECT_EQ(message(mpdSettings(NoiseType::Mpd, 0)), "levels of mpd must be in 1..24, got 0");
  EXPECT_EQ(message(mpdSettings(NoiseType::MpdIco, 25)), "levels of mpd_ico must be in 1..24, got 25");
  EXPECT_EQ(message(faultSettings(10000, 1.5)), "no error");
  EXPECT_EQ(message(mpdSettings(NoiseType::Mpd, 24)), "no error");
}

TEST(NoiseGenerators, PresetLayersSampleTheUnitSphereAndRejectKeysOfOtherTypes) {
  for (const char* name : {"faults", "mpd"}) {
    const PlanetDescription planet = resolvePreset(name);
    bool generator = false;
    for (const NoiseLayer& layer : planet.layers) {
      if (!isGenerator(layer.noise.type)) continue;
      generator = true;
      EXPECT_EQ(layer.frequency, 1.0 / planet.radiusM) << name;
    }
    EXPECT_TRUE(generator) << name;
  }
  const std::string base =
      "[planet]\nname = \"T\"\nradius_m = 1000000\nhas_ocean = false\n[colors]\nscheme = \"altitude\"\n"
      "[[layer]]\nname = \"f\"\namplitude_m = 100\n";
  auto error = [&](const std::string& keys) {
    try {
      parsePlanetDescription(base + keys, "t.toml");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("type = \"faults\"\ncount = 10\n"), "no error");
  EXPECT_EQ(error("type = \"mpd_ico\"\nlevels = 10\nmultifractal = true\n"), "no error");
  EXPECT_EQ(error("type = \"faults\"\ncount = 10\noctaves = 3\n"),
            "t.toml:12: 'octaves' applies to fractal (not faults, mpd or mpd_ico) layers only, not to type 'faults'");
  EXPECT_EQ(error("type = \"faults\"\ncount = 10001\n"), "t.toml:11: count must be in [1, 10000], got 10001");
  EXPECT_EQ(error("type = \"faults\"\n"), "t.toml:7: missing key 'count' in [[layer]]");
  EXPECT_EQ(error("type = \"mpd\"\nlevels = 30\n"), "t.toml:11: levels must be in [1, 24], got 30");
  EXPECT_EQ(error("type = \"mpd\"\nlevels = 3\nwavelength_m = 1000\n"),
            "t.toml:12: 'wavelength_m' applies to fractal (faults, mpd and mpd_ico sample the unit sphere) layers "
            "only, not to type 'mpd'");
  EXPECT_EQ(error("type = \"mpd\"\nlevels = 3\nlacunarity = 2\n"),
            "t.toml:12: 'lacunarity' applies to fractal (each MPD level halves the edges) layers only, not to type "
            "'mpd'");
  EXPECT_EQ(error("type = \"faults\"\ncount = 3\nH = 0.5\n"),
            "t.toml:12: 'H' applies to fractal, mpd and mpd_ico layers only, not to type 'faults'");
  EXPECT_EQ(error("type = \"fbm\"\noctaves = 3\nfrequency = 1\ncount = 3\n"),
            "t.toml:13: 'count' applies to faults layers only, not to type 'fbm'");
}

TEST(NoiseGenerators, OctaveBudgetCountsMpdLevelsByTheirEdgeLength) {
  PlanetDescription planet = resolvePreset("mpd");
  const NoiseLayer& layer = planet.layers[0];
  ASSERT_TRUE(isMpd(layer.noise.type));
  // Level l's edges are (pi/2) R / 2^l; the budget keeps levels whose edges span at least
  // kOctaveWavelengthsPerSpacing samples: at a spacing of 100 m on the Earth's radius, levels up
  // to log2(pi/2 · 6371 km / 400 m) = 14.6.
  const OctaveBudget budget = octaveBudget(layer, 100.0);
  EXPECT_EQ(budget.octaves, 15u);
  EXPECT_NEAR(budget.lastOctaveWeight, 0.61, 0.02);
  EXPECT_EQ(octaveBudget(layer, 0.0).octaves, uint32_t(layer.noise.octaves));
}

using NoiseGeneratorsGpu = test::GpuTest;

TEST_F(NoiseGeneratorsGpu, PresetHeightsMatchTheCpuFloatPathAndTheDoubleReference) {
  for (const char* preset : {"faults", "mpd"}) {
    const PlanetDescription planet = resolvePreset(preset);
    const glm::dvec3 start = glm::normalize(glm::dvec3(0.3, -0.55, 0.78));
    const glm::dvec3 anchor = planet.radiusM * start;
    const OctaveTables tables = buildOctaveTables(planet, anchor);
    const glm::dvec3 east = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), start));
    std::vector<glm::vec3> offsets;
    std::vector<double> reference;
    for (int i = 0; i < 300; ++i) {  // 5 cm steps, then 1 km steps: near and far from the anchor
      const double distance = i < 200 ? 0.05 * i : 1000.0 * (i - 199);
      const double angle = distance / planet.radiusM;
      const glm::dvec3 d = std::cos(angle) * start + std::sin(angle) * east;
      offsets.push_back(glm::vec3(planet.radiusM * d - anchor));
      reference.push_back(terrainHeightM(planet, d));
    }
    GpuTerrainPoints terrain(context(), planet);
    std::vector<float> gpu = terrain.evaluate(tables, offsets);
    std::vector<float> cpu(offsets.size());
    for (size_t i = 0; i < offsets.size(); ++i) cpu[i] = terrainHeightRebased(planet, tables, offsets[i]);
    ParityStats parity = compareValues(gpu, cpu);
    EXPECT_TRUE(parityPolicyFor(context()).accepts(parity))
        << preset << ": identical " << parity.identical << "/" << parity.count << ", max|err| " << parity.maxAbsError;
    // Against the double reference: these layers see the point's direction in float, good to
    // ~1e-7 of the radius (0.64 m here; noise_generators.glsl), so a height differs by at most the
    // ground's slope times that: the faults' ramps rise 0.38 m per metre at most (1.5 · 80 m over
    // 5e-5 rad of 6,371 km; 1.5x for where two overlap), MPD's finest levels at H 0.5 up to
    // ~1.5 m per metre (2,500 m · 2^(l/2) over edges of 1e7 m / 2^l at level 22, summed over
    // the levels).
    const double slope = std::string(preset) == "faults" ? 0.38 * 1.5 : 1.5;
    double largest = 0.0;
    for (size_t i = 0; i < gpu.size(); ++i) largest = std::max(largest, std::abs(gpu[i] - reference[i]));
    EXPECT_LT(largest, slope * 0.64) << preset;
  }
}

}  // namespace
}  // namespace planet::noise

// Golden values of N(p) at seed 0 with the reference hash. They come from an independent
// computation: tools/golden/simplex_reference.py, a plain double-precision Python
// transcription of Gustavson's "Simplex noise demystified" (2005) sharing no code with
// shaders/common/noise.glsl, evaluated at the float-rounded test coordinates (kernel radius^2
// 0.5, scale 75: the project's continuous variant of Gustavson's 0.6 and 32). The crater
// fractal's come from tools/golden/crater_reference.py, written from the crater model that
// noise.glsl documents (it sums every cell within two of the point's, not the shader's 2x2x2).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "noise/noise_cpu.h"
#include "noise/noise_kernel.h"
#include "noise/permutation.h"

namespace planet::noise {
namespace {

struct Golden {
  double x, y, z, value;
};

// Output of `python3 tools/golden/simplex_reference.py`.
constexpr Golden kGolden[] = {
    {0.1, 0.2, 0.3, 0.48001603375764107},
    {1.5, -2.25, 3.75, -0.59356689453124922},
    {-7.3, 4.1, 0.9, -0.41371766878463812},
    {12.34, -56.78, 90.12, -0.2869910104036561},
    {100.5, 200.25, -300.125, -0.0069892539838214548},
    {0.71, 0.37, -0.43, 0.66546686348816286},
    {-0.5, -1.5, 2.5, -0.75352044753086489},
    {3.14159, 2.71828, 1.41421, 0.13466983807557631},
    {250.0, 13.5, 77.7, 0.067906268619398136},
    {-33.3, -66.6, -99.9, -0.059052175618945386},
};

struct CraterGolden {
  double x, y, z;
  int octaves;
  double lacunarity, H, perturbation, value;
};

// Output of `python3 tools/golden/crater_reference.py`: first the centre and a rim point of the
// crater of cell (0, 1, 4) (floor -size 0.737, rim 0.3 size), then points in and between craters.
constexpr CraterGolden kCraterGolden[] = {
    {0.70013427734375, 1.63897705078125, 4.2740936279296875, 1, 2.0, 1.0, 0.0, -0.73743438720703125},
    {0.9213646054267883, 1.63897705078125, 4.2740936279296875, 1, 2.0, 1.0, 0.0, 0.22123031616209946},
    {0.1, 0.2, 0.3, 1, 2.0, 1.0, 0.25, 0},
    {111.51, 97.13, 16.59, 1, 2.0, 1.0, 0.25, 0.18158560267514831},
    {1.69, -16.51, 52.87, 1, 2.0, 1.0, 0.0, -0.18262178142543367},
    {30.56, -8.1, 43.03, 4, 2.0, 1.0, 0.25, -0.22265649439864182},
    {85.33, -79.37, -39.19, 8, 2.0, 1.0, 0.25, 0.31123709652982334},
    {4.56, -50.63, -38.14, 6, 2.0, 0.8, 0.1, 0.13721403228813955},
    {96.87, 46.49, 101.73, 5, 2.7, 0.5, 0.35, 0.090418702183571273},
    {-48.03, 39.1, 5.99, 8, 1.97, 0.9, 0.5, -0.15263138743832155},
    {13.33, 51.85, -28.74, 3, 2.0, 1.0, 0.25, -0.12907608862073763},
    {25.06, 67.83, -28.74, 8, 2.0, 1.0, 0.25, 0.23322777734824396},
};

NoiseSettings referenceCraters(const CraterGolden& g) {
  NoiseSettings s;
  s.type = NoiseType::Craters;
  s.hash = NoiseHash::Reference;
  s.seed = 0;
  s.octaves = g.octaves;
  s.lacunarity = g.lacunarity;
  s.H = g.H;
  s.offset = g.perturbation;
  return s;
}

NoiseSettings referenceSimplex() {
  NoiseSettings s;
  s.type = NoiseType::Simplex;
  s.hash = NoiseHash::Reference;
  s.seed = 0;
  return s;
}

TEST(NoiseGolden, SimplexMatchesReferenceAtSeed0) {
  for (const Golden& g : kGolden) {
    // The golden values were computed at the float-rounded coordinates, so both sides
    // evaluate the same point. Float arithmetic loses about 1e-7 of the coordinates'
    // magnitude in the cell offsets, times a gradient of order 10.
    float value = evaluateCpu(referenceSimplex(), glm::vec3(float(g.x), float(g.y), float(g.z)));
    double magnitude = std::max({std::abs(g.x), std::abs(g.y), std::abs(g.z)});
    EXPECT_NEAR(value, g.value, 1e-6 + 1e-6 * magnitude) << "at (" << g.x << ", " << g.y << ", " << g.z << ")";
  }
}

TEST(NoiseGolden, DoubleReferenceMatchesIndependentComputationTightly) {
  for (const Golden& g : kGolden) {
    double value = evaluateCpuDouble(referenceSimplex(), glm::dvec3(float(g.x), float(g.y), float(g.z)));
    EXPECT_NEAR(value, g.value, 1e-6) << "at (" << g.x << ", " << g.y << ", " << g.z << ")";
  }
}

TEST(NoiseGolden, CratersMatchReferenceAtSeed0) {
  double worstFloat = 0.0, worstDouble = 0.0;
  for (const CraterGolden& g : kCraterGolden) {
    const glm::vec3 p(float(g.x), float(g.y), float(g.z));
    const double single = evaluateCpu(referenceCraters(g), p);
    const double twice = evaluateCpuDouble(referenceCraters(g), glm::dvec3(p));
    // Float: cell offsets, profiles and sums rounded to float (measured: 2.3e-6 at most). The
    // double reference walks unrounded octave points where the Python rounds them as the float
    // walk does: exact products for L = 2 (measured 1.2e-7), 3.4e-6 apart at L = 1.97.
    const double doubleTolerance = g.lacunarity == 2.0 ? 1e-6 : 1e-5;
    EXPECT_NEAR(single, g.value, 1e-5) << "float at (" << g.x << ", " << g.y << ", " << g.z << ")";
    EXPECT_NEAR(twice, g.value, doubleTolerance) << "double at (" << g.x << ", " << g.y << ", " << g.z << ")";
    worstFloat = std::max(worstFloat, std::abs(single - g.value));
    worstDouble = std::max(worstDouble, std::abs(twice - g.value));
  }
  std::printf("[ measured ] craters against the Python reference: float %.3g, double %.3g\n", worstFloat, worstDouble);
}

TEST(NoiseGolden, SimplexVanishesAtLatticeVertices) {
  // At a simplex-lattice vertex the own corner's offset is zero and every other corner is
  // outside the kernel radius, so N is exactly 0 for any hash and seed.
  for (NoiseHash hash : {NoiseHash::Fast, NoiseHash::Reference}) {
    NoiseSettings s = referenceSimplex();
    s.hash = hash;
    s.seed = 99;
    EXPECT_EQ(evaluateCpu(s, glm::vec3(0.0f)), 0.0f);
    // Skewed cell (1,1,1) unskews to (0.5, 0.5, 0.5); (2,0,0) to (2 - 1/3, -1/3, -1/3).
    EXPECT_EQ(evaluateCpu(s, glm::vec3(0.5f)), 0.0f);
    EXPECT_NEAR(evaluateCpu(s, glm::vec3(2.0f - 1.0f / 3.0f, -1.0f / 3.0f, -1.0f / 3.0f)), 0.0f, 1e-6f);
  }
}

TEST(NoiseGolden, ReferencePermutationIsPerlinsAtSeed0) {
  const auto& table = permutationTable(0);
  // Spot checks against Perlin's published table, including both halves of the doubled copy.
  EXPECT_EQ(table[0], 151u);
  EXPECT_EQ(table[1], 160u);
  EXPECT_EQ(table[255], 180u);
  EXPECT_EQ(table[256], 151u);
  EXPECT_EQ(table[511], 180u);
  std::vector<bool> seen(256, false);
  for (int i = 0; i < 256; ++i) seen[table[i]] = true;
  EXPECT_EQ(std::count(seen.begin(), seen.end(), true), 256) << "not a permutation";
}

TEST(NoiseGolden, OtherSeedsPermuteTheTable) {
  const auto& a = permutationTable(1);
  const auto& b = permutationTable(2);
  EXPECT_NE(a, permutationTable(0));
  EXPECT_NE(a, b);
  std::vector<bool> seen(256, false);
  for (int i = 0; i < 256; ++i) seen[a[i]] = true;
  EXPECT_EQ(std::count(seen.begin(), seen.end(), true), 256) << "seeded table is not a permutation";
  for (int i = 0; i < 256; ++i) EXPECT_EQ(a[i], a[i + 256]);
}

}  // namespace
}  // namespace planet::noise

// Golden values of N(p) at seed 0 with the reference hash. They come from an independent
// computation: tools/golden/simplex_reference.py, a plain double-precision Python
// transcription of Gustavson's "Simplex noise demystified" (2005) sharing no code with
// shaders/common/noise.glsl, evaluated at the float-rounded test coordinates (kernel radius^2
// 0.5, scale 75: the project's continuous variant of Gustavson's 0.6 and 32).
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

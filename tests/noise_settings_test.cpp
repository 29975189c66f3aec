// Noise parameters: defaults, ranges, and error messages that name the bad value.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "test_support.h"

#include "core/error.h"
#include "noise/noise_settings.h"

namespace planet::noise {
namespace {

using test::errorOf;

TEST(NoiseSettings, DefaultsMatchTheSpecification) {
  NoiseSettings s;
  EXPECT_EQ(s.octaves, 8);
  EXPECT_EQ(s.lacunarity, 2.0);
  EXPECT_EQ(s.H, 1.0);
  EXPECT_EQ(s.seed, 0u);
  EXPECT_EQ(s.hash, NoiseHash::Fast);
  EXPECT_EQ(defaultOffset(NoiseType::Ridged), 1.0);
  EXPECT_EQ(defaultOffset(NoiseType::Hybrid), 0.7);
  EXPECT_EQ(defaultOffset(NoiseType::Hetero), 0.7);
  EXPECT_EQ(defaultOffset(NoiseType::Cascade), 0.8);
  EXPECT_EQ(defaultOffset(NoiseType::Craters), 0.25);
  gpu::NoiseParams p = toNoiseParams(s);
  EXPECT_FLOAT_EQ(p.octaveWeight, 0.5f);  // 2^-1
  EXPECT_FLOAT_EQ(p.gain, 2.0f);
}

TEST(NoiseSettings, OutOfRangeValuesAreRejectedByName) {
  NoiseSettings s;
  s.octaves = 0;
  EXPECT_NE(errorOf([&] { validateNoiseSettings(s); }).find("octaves must be in 1..32, got 0"), std::string::npos);
  s.octaves = 33;
  EXPECT_NE(errorOf([&] { validateNoiseSettings(s); }).find("got 33"), std::string::npos);
  s.octaves = 1000;
  EXPECT_NE(errorOf([&] { validateNoiseSettings(s); }).find("got 1000"), std::string::npos);
  s.octaves = 32;
  EXPECT_EQ(errorOf([&] { validateNoiseSettings(s); }), "");
  for (double bad : {1.0, 0.5, 8.01, -2.0}) {
    s.lacunarity = bad;
    EXPECT_NE(errorOf([&] { validateNoiseSettings(s); }).find("lacunarity must be in (1, 8]"), std::string::npos)
        << bad;
  }
  s.lacunarity = 8.0;
  EXPECT_EQ(errorOf([&] { validateNoiseSettings(s); }), "");
  s.lacunarity = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(errorOf([&] { validateNoiseSettings(s); }).find("lacunarity must be a finite number"), std::string::npos);
  s.lacunarity = 2.0;
  s.H = std::numeric_limits<double>::infinity();
  EXPECT_NE(errorOf([&] { validateNoiseSettings(s); }).find("H must be a finite number"), std::string::npos);
  s.H = 1.0;
  s.offset = std::nan("");
  EXPECT_NE(errorOf([&] { validateNoiseSettings(s); }).find("offset"), std::string::npos);
}

TEST(NoiseSettings, CraterRimPerturbationOutsideZeroToHalfIsRejected) {
  // The crater shader's bound on the cells a crater reaches holds for perturbations up to 0.5.
  NoiseSettings s;
  s.type = NoiseType::Craters;
  for (double good : {0.0, 0.25, 0.5}) {
    s.offset = good;
    EXPECT_EQ(errorOf([&] { validateNoiseSettings(s); }), "") << good;
  }
  for (double bad : {-0.01, 0.51, 2.0}) {
    s.offset = bad;
    EXPECT_NE(errorOf([&] { validateNoiseSettings(s); }).find("offset of craters"), std::string::npos) << bad;
  }
  s.type = NoiseType::Ridged;  // other types keep |offset| <= 10
  EXPECT_EQ(errorOf([&] { validateNoiseSettings(s); }), "");
}

TEST(NoiseSettings, NamesParseAndUnknownNamesAreRejected) {
  EXPECT_EQ(parseNoiseType("ridged"), NoiseType::Ridged);
  EXPECT_EQ(parseNoiseType("cascade"), NoiseType::Cascade);
  EXPECT_EQ(parseNoiseHash("reference"), NoiseHash::Reference);
  EXPECT_NE(errorOf([] { parseNoiseType("perlin"); }).find("unknown noise type 'perlin'"), std::string::npos);
  EXPECT_NE(errorOf([] { parseNoiseHash("slow"); }).find("unknown noise hash 'slow'"), std::string::npos);
  for (NoiseType t : {NoiseType::Simplex, NoiseType::Fbm, NoiseType::Ridged, NoiseType::Hybrid, NoiseType::Hetero,
                      NoiseType::Cascade, NoiseType::Craters})
    EXPECT_EQ(parseNoiseType(noiseTypeName(t)), t);
}

}  // namespace
}  // namespace planet::noise

// City lights (issue 14, point 2) on the CPU: shaders/common/city_lights.glsl compiled as C++,
// the code terrain.frag runs. Where lights may be (habitability), the dusk fade, the constants
// the model is calibrated by, and the uniform block that carries a preset's lights.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "planet/planet_description.h"
#include "reference/city_lights_cpu.h"

namespace planet {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

float sinDeg(double degrees) { return float(std::sin(degrees * kDeg)); }

// Uniform random unit directions (deterministic).
std::vector<glm::vec3> directions(size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal;
  std::vector<glm::vec3> out;
  while (out.size() < count) {
    const glm::vec3 v(normal(rng), normal(rng), normal(rng));
    if (glm::length(v) > 1e-3f) out.push_back(glm::normalize(v));
  }
  return out;
}

// Lights come on through civil twilight: none while the sun is up, all of them once it is 6°
// below the horizon, and never fewer as the sun sinks (every 0.05° from 90° up to 90° down).
TEST(CityLightsCpu, DuskFadeIsMonotonicNoneWithTheSunUpAndFullBelowSixDegrees) {
  float previous = -1.0f;
  for (int i = 3600; i >= -3600; --i) {
    const float fade = lightsDuskFadeCpu(sinDeg(i * 0.025));
    EXPECT_GE(fade, previous) << "sun at " << i * 0.025 << " deg";
    previous = fade;
  }
  EXPECT_EQ(lightsDuskFadeCpu(sinDeg(0.0)), 0.0f);
  EXPECT_EQ(lightsDuskFadeCpu(sinDeg(10.0)), 0.0f);
  EXPECT_EQ(lightsDuskFadeCpu(sinDeg(-6.01)), 1.0f);
  EXPECT_EQ(lightsDuskFadeCpu(sinDeg(-60.0)), 1.0f);
  const float dusk = lightsDuskFadeCpu(sinDeg(-3.0));
  EXPECT_GT(dusk, 0.3f);
  EXPECT_LT(dusk, 0.7f);
}

// Land a city could stand on: low, flat, mild and watered; then each of what rules it out.
TEST(CityLightsCpu, NoLightsOnIceMountainsSteepSlopesOrDryLandAwayFromWater) {
  // 100 m up, a 3° slope (1 − cos 3° = 0.0014), 15 °C, moist, inland.
  const float plain = lightsHabitabilityCpu(100.0f, 0.0014f, 15.0f, 0.6f, 0.0f, 0.0f);
  EXPECT_GT(plain, 0.4f);
  EXPECT_EQ(lightsHabitabilityCpu(100.0f, 0.0014f, -12.0f, 0.6f, 1.0f, 1.0f), 0.0f);  // ice (snow below −10 °C)
  EXPECT_EQ(lightsHabitabilityCpu(100.0f, 0.0014f, -3.0f, 0.6f, 1.0f, 1.0f), 0.0f);   // tundra
  EXPECT_EQ(lightsHabitabilityCpu(3000.0f, 0.0014f, 15.0f, 0.6f, 1.0f, 1.0f), 0.0f);  // high mountains
  const float steep = float(1.0 - std::cos(25.0 * kDeg));
  EXPECT_EQ(lightsHabitabilityCpu(100.0f, steep, 15.0f, 0.6f, 1.0f, 1.0f), 0.0f);  // a 25° slope
  EXPECT_EQ(lightsHabitabilityCpu(100.0f, 0.0014f, 25.0f, 0.05f, 0.0f, 0.0f), 0.0f);  // inland desert
  // The desert's coast and its valley floors (the Nile) are lit; coasts are settled densest.
  EXPECT_GT(lightsHabitabilityCpu(100.0f, 0.0014f, 25.0f, 0.05f, 1.0f, 0.0f), 0.5f);
  EXPECT_GT(lightsHabitabilityCpu(100.0f, 0.0014f, 25.0f, 0.05f, 0.0f, 1.0f), 0.5f);
  EXPECT_GT(lightsHabitabilityCpu(100.0f, 0.0014f, 15.0f, 0.6f, 1.0f, 0.0f), 1.8f * plain);
  // Higher, steeper, colder, drier: never more.
  EXPECT_LE(lightsHabitabilityCpu(1500.0f, 0.0014f, 15.0f, 0.6f, 0.0f, 0.0f), plain);
  EXPECT_LE(lightsHabitabilityCpu(100.0f, 0.02f, 15.0f, 0.6f, 0.0f, 0.0f), plain);
  EXPECT_LE(lightsHabitabilityCpu(100.0f, 0.0014f, 1.0f, 0.6f, 0.0f, 0.0f), plain);
  EXPECT_LE(lightsHabitabilityCpu(100.0f, 0.0014f, 15.0f, 0.3f, 0.0f, 0.0f), plain);
}

// kLightsNoiseSigma is what the cities' threshold assumes: one octave's spread over the sphere,
// measured at 20,000 points (the standard error of a spread from that many is ~0.5 %).
TEST(CityLightsCpu, CityNoiseSpreadIsTheConstant) {
  const gpu::LightsParams p = lightsGpuParams(resolvePreset("earth").lights, 6.371e6);
  double sum = 0.0, squares = 0.0;
  const std::vector<glm::vec3> points = directions(20000, 1);
  for (const glm::vec3& d : points) {
    const double v = lightsNoiseCpu(p, d * p.shape.x, 0);
    sum += v;
    squares += v * v;
  }
  const double mean = sum / double(points.size());
  const double sigma = std::sqrt(squares / double(points.size()) - mean * mean);
  EXPECT_NEAR(sigma, 0.38, 0.38 * 0.02);
  EXPECT_NEAR(mean, 0.0, 0.01);
}

// What a pixel far away shows (the expected value, once the cities are below two pixels) is the
// mean of what the resolved pixels show, so lights neither brighten nor fade as the camera
// climbs: over 40,000 points of fully habitable land, within 25 % (a third of a stop) for
// coverages 0.1 .. 0.3 (measured: far/near 1.11, 0.99, 0.89). Below that the probit's logistic
// approximation drifts in the tail: at coverage 0.05 far pixels are 1.44 times as bright (a
// known limit, README). The lit share of near pixels follows the coverage.
TEST(CityLightsCpu, FarPixelsShowTheMeanOfTheNearOnes) {
  LightsDescription lights = resolvePreset("earth").lights;
  const std::vector<glm::vec3> points = directions(40000, 2);
  double previousNear = 0.0;
  for (double coverage : {0.1, 0.15, 0.3}) {
    lights.coverage = coverage;
    const gpu::LightsParams p = lightsGpuParams(lights, 6.371e6);
    double nearSum = 0.0, farSum = 0.0;
    for (const glm::vec3& d : points) {
      nearSum += lightsCoverCpu(p, d, 1.0f, 1e-7f);  // 0.6 m pixels: every octave resolved
      farSum += lightsCoverCpu(p, d, 1.0f, 0.05f);   // 300 km pixels: none
    }
    const double nearMean = nearSum / double(points.size()), farMean = farSum / double(points.size());
    EXPECT_NEAR(farMean / nearMean, 1.0, 0.25) << "coverage " << coverage;
    EXPECT_GT(nearMean, previousNear) << "coverage " << coverage;
    previousNear = nearMean;
  }
}

// The same point always gives the same light; another seed puts the cities elsewhere; no
// habitability, no light; values stay in [0, 1].
TEST(CityLightsCpu, LightsAreDeterministicPerSeedAndZeroWhereNoOneLives) {
  LightsDescription lights = resolvePreset("earth").lights;
  const gpu::LightsParams a = lightsGpuParams(lights, 6.371e6);
  lights.seed += 1;
  const gpu::LightsParams b = lightsGpuParams(lights, 6.371e6);
  int litA = 0, sameInB = 0;
  for (const glm::vec3& d : directions(2000, 3)) {
    const float value = lightsCoverCpu(a, d, 1.0f, 1e-6f);
    EXPECT_EQ(value, lightsCoverCpu(a, d, 1.0f, 1e-6f));
    EXPECT_GE(value, 0.0f);
    EXPECT_LE(value, 1.0f);
    EXPECT_EQ(lightsCoverCpu(a, d, 0.0f, 1e-6f), 0.0f);
    if (value > 0.01f) {
      ++litA;
      if (value == lightsCoverCpu(b, d, 1.0f, 1e-6f)) ++sameInB;
    }
  }
  EXPECT_GT(litA, 100);  // about a tenth of fully habitable land is lit at the earth's coverage
  EXPECT_LT(sameInB, litA / 10);
}

// The preset's radiance in VIIRS units becomes the renderer's (the sun's irradiance is 1) with
// the gain, the colour scaled to luminance 1; disabled lights give an all-zero block.
TEST(CityLightsCpu, GpuParamsCarryTheRadianceInTheRenderersUnits) {
  LightsDescription lights = resolvePreset("earth").lights;
  lights.radianceNw = 57.0;
  lights.gain = 1000.0;
  lights.color = glm::vec3(0.5f, 0.25f, 0.0f);
  const gpu::LightsParams p = lightsGpuParams(lights, 6.371e6);
  const double expected = 57.0 * 1e-5 / kSunIrradianceDnbWm2 * 1000.0;  // 1e-3 of the sun per sr
  const double luminance = 0.2126 * p.radiance.r + 0.7152 * p.radiance.g + 0.0722 * p.radiance.b;
  EXPECT_NEAR(luminance, expected, expected * 1e-5);
  EXPECT_NEAR(p.radiance.r / p.radiance.g, 2.0, 1e-5);
  EXPECT_FLOAT_EQ(p.radiance.w, float(lights.coverage));
  EXPECT_FLOAT_EQ(p.shape.x, float(6.371e6 / lights.citySizeM));
  lights.enabled = false;
  const gpu::LightsParams off = lightsGpuParams(lights, 6.371e6);
  EXPECT_EQ(off.radiance, glm::vec4(0.0f));
  EXPECT_EQ(off.seedMix, 0u);
}

}  // namespace
}  // namespace planet

// Erosion-like relief evaluated per point (issue 19 point 2, common/noise_erosion.glsl): `damped`
// is fBm whose finer octaves fade on steep ground and `eroded` fBm carved by gullies that run
// downhill. Their gradients are the derivatives of their values (central differences of the double
// reference), the GPU agrees with the float reference bit for bit on lavapipe, and the properties
// a user sees hold: gain 0 damps nothing, steep ground comes out smooth and flat ground keeps its
// detail, gullies run down the slope, nothing jumps, the octave fade is continuous, a planet
// with such layers renders the heights of the CPU float path, within 1 cm of the double reference,
// and octave limiting keeps its surface from swimming as it does for the other types.
//
// Two groups in one program (tests/CMakeLists.txt): NoiseErosion.* (label unit) and
// NoiseErosionGpu.* (gpu).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "bench/noise_validate.h"
#include "gpu_fixture.h"
#include "noise/noise_cpu.h"
#include "noise/noise_gpu.h"
#include "noise/noise_kernel.h"
#include "noise/permutation.h"
#include "planet/planet_gpu_data.h"
#include "planet/terrain_height.h"
#include "planet/terrain_points_gpu.h"
#include "planet/terrain_rebase.h"
#include "planet/clipmap_orientation.h"
#include "render/renderer.h"
#include "vk/buffer.h"

namespace planet::noise {
namespace {

constexpr NoiseHash kHashes[] = {NoiseHash::Fast, NoiseHash::Reference};

NoiseSettings settingsOf(NoiseType type, NoiseHash hash = NoiseHash::Fast, int octaves = 8) {
  NoiseSettings s;
  s.type = type;
  s.hash = hash;
  s.octaves = octaves;
  return s;
}

// The radius, in octave-0 lattice units, of the sphere a layer samples: a 400 km wavelength on the
// Earth (the mountains of the earth preset) gives 16.
constexpr double kSphereRadius = 16.0;

// `count` points of equal area on that sphere (the Fibonacci lattice).
std::vector<glm::dvec3> spherePoints(size_t count) {
  std::vector<glm::dvec3> points;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (size_t i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * double(i) + 1.0) / double(count);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    points.push_back(kSphereRadius * glm::dvec3(r * std::cos(golden * double(i)), r * std::sin(golden * double(i)), z));
  }
  return points;
}

glm::dvec3 gradientOf(const glm::dvec4& v) { return {v.y, v.z, v.w}; }

// The part of g along the sphere through p (what a viewer calls slope).
glm::dvec3 tangential(const glm::dvec3& p, const glm::dvec3& g) {
  const glm::dvec3 up = glm::normalize(p);
  return g - up * glm::dot(up, g);
}

// Second difference of f at p along the unit vector t, step h.
template <typename F>
double secondDifference(F f, const glm::dvec3& p, const glm::dvec3& t, double h) {
  return (f(p + h * t) - 2.0 * f(p) + f(p - h * t)) / (h * h);
}

// The difference step: kRelativeStep of the finest period, a power of two (as noise_gradient_test).
double stepFor(const NoiseSettings& s, double relativeStep) {
  return std::ldexp(1.0, int(std::floor(std::log2(relativeStep / std::pow(s.lacunarity, s.octaves - 1)))));
}

// Worst |analytic - central difference| over points and axes, relative to the RMS gradient.
template <typename ValueFn, typename GradientFn>
double worstDifference(const std::vector<glm::dvec3>& points, double h, ValueFn value, GradientFn gradient,
                       double* rms = nullptr) {
  std::vector<glm::dvec4> analytic;
  double sum2 = 0.0;
  for (const glm::dvec3& p : points) {
    analytic.push_back(gradient(p));
    sum2 += glm::dot(gradientOf(analytic.back()), gradientOf(analytic.back()));
  }
  const double scale = std::sqrt(sum2 / double(points.size()));
  if (rms) *rms = scale;
  double worst = 0.0;
  for (size_t i = 0; i < points.size(); ++i)
    for (int axis = 0; axis < 3; ++axis) {
      glm::dvec3 step(0.0);
      step[axis] = h;
      const double central = (value(points[i] + step) - value(points[i] - step)) / (2.0 * h);
      worst = std::max(worst, std::fabs(analytic[i][axis + 1] - central) / scale);
    }
  return worst;
}

std::vector<glm::dvec3> nearPoints(size_t count, uint32_t seed) {
  std::vector<glm::dvec3> points;
  for (const glm::vec3& p : validationPoints(count, false, seed)) points.emplace_back(p);
  return points;
}

// Parameter sets beyond planet validate's (which NoiseGradient.* and NoiseGradientGpu.* also run):
// gullies from the first octave on, rough and deep; strong damping; the defaults on the sphere.
std::vector<NoiseSettings> extraSettings() {
  std::vector<NoiseSettings> out;
  for (NoiseHash hash : kHashes) {
    NoiseSettings eroded = settingsOf(NoiseType::Eroded, hash, 7);
    eroded.offset = 1.0;
    eroded.lacunarity = 2.3;
    eroded.H = 0.7;
    eroded.gain = 4.0;
    eroded.seed = 9;
    out.push_back(eroded);
    NoiseSettings damped = settingsOf(NoiseType::Damped, hash, 7);
    damped.lacunarity = 2.5;
    damped.H = 0.5;
    damped.gain = 8.0;
    damped.seed = 11;
    out.push_back(damped);
  }
  return out;
}

// A double kernel as the terrain's evaluations use it.
NoiseKernel<double> doubleKernel(const NoiseSettings& s) {
  NoiseKernel<double> kernel;
  kernel.permutation = permutationTable(s.seed).data();
  return kernel;
}

TEST(NoiseErosion, DampedWithGainZeroIsFbmBitForBit) {
  const std::vector<glm::vec3> points = validationPoints(3000, false, 40);
  for (NoiseHash hash : kHashes) {
    NoiseSettings damped = settingsOf(NoiseType::Damped, hash);
    damped.gain = 0.0;
    const NoiseSettings fbm = settingsOf(NoiseType::Fbm, hash);
    std::vector<float> a(points.size()), b(points.size());
    evaluateCpu(damped, points, a);
    evaluateCpu(fbm, points, b);
    size_t same = 0;
    for (size_t i = 0; i < points.size(); ++i) same += std::bit_cast<uint32_t>(a[i]) == std::bit_cast<uint32_t>(b[i]);
    EXPECT_EQ(same, points.size()) << noiseHashName(hash);
    for (size_t i = 0; i < 100; ++i) {
      const glm::dvec4 g = evaluateCpuGradientDouble(damped, glm::dvec3(points[i]));
      const glm::dvec4 f = evaluateCpuGradientDouble(fbm, glm::dvec3(points[i]));
      ASSERT_EQ(g.x, f.x);
      ASSERT_LT(glm::length(gradientOf(g) - gradientOf(f)), 1e-12 * glm::length(gradientOf(f)));
    }
  }
}

TEST(NoiseErosion, DampedSmoothsSteepGroundAndKeepsTheDetailOfFlatGround) {
  // Rank points of the sphere by the slope of fBm's octaves before the last (the slope "so far"
  // that damps the last octave) and compare the fine-scale roughness, the second difference over a
  // quarter of the finest wavelength, of fBm and damped at the same points.
  const std::vector<glm::dvec3> points = spherePoints(4000);
  for (NoiseHash hash : kHashes) {
    const NoiseSettings fbm = settingsOf(NoiseType::Fbm, hash);
    const NoiseSettings damped = settingsOf(NoiseType::Damped, hash);
    const NoiseSettings shape = settingsOf(NoiseType::Fbm, hash, fbm.octaves - 1);
    const double h = 0.25 / std::pow(fbm.lacunarity, fbm.octaves - 1);
    struct Sample {
      double slope, fbm, damped;
    };
    std::vector<Sample> samples;
    for (const glm::dvec3& p : points) {
      const glm::dvec3 up = glm::normalize(p);
      const glm::dvec3 east = glm::normalize(glm::cross(glm::dvec3(0.0, 0.0, 1.0), up));
      const glm::dvec3 north = glm::cross(up, east);
      auto roughness = [&](const NoiseSettings& s) {
        auto f = [&](const glm::dvec3& q) { return evaluateCpuDouble(s, q); };
        return 0.5 * (std::fabs(secondDifference(f, p, east, h)) + std::fabs(secondDifference(f, p, north, h)));
      };
      samples.push_back({glm::length(tangential(p, gradientOf(evaluateCpuGradientDouble(shape, p)))), roughness(fbm),
                         roughness(damped)});
    }
    std::sort(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) { return a.slope < b.slope; });
    const size_t decile = samples.size() / 10;
    auto meanRatio = [&](size_t begin, size_t end) {
      double f = 0.0, d = 0.0;
      for (size_t i = begin; i < end; ++i) {
        f += samples[i].fbm;
        d += samples[i].damped;
      }
      return d / f;
    };
    const double steep = meanRatio(samples.size() - decile, samples.size());
    const double flat = meanRatio(0, decile);
    std::printf("%s: damped/fbm roughness on the steepest tenth %.3f, on the flattest tenth %.3f\n",
                noiseHashName(hash), steep, flat);
    // Measured: 0.08 and 0.81 (default gain 2).
    EXPECT_LT(steep, 0.3) << "steep ground is not smoother than fBm's";
    EXPECT_GT(flat, 0.7) << "flat ground lost its detail";
  }
}

TEST(NoiseErosion, GulliesRunDownTheSlope) {
  // One gully scale (octave 3) over a base of three octaves: the relief it adds curves across the
  // slope of the base (its downslope direction s along the sphere), not along it. Octave 3 of fBm,
  // the same lattice's plain noise, curves alike in both directions.
  const std::vector<glm::dvec3> points = spherePoints(3000);
  for (NoiseHash hash : kHashes) {
    NoiseSettings eroded = settingsOf(NoiseType::Eroded, hash, 4);
    eroded.offset = 3.0;
    NoiseSettings base = eroded;
    base.octaves = 3;
    const NoiseSettings fbm4 = settingsOf(NoiseType::Fbm, hash, 4);
    const NoiseSettings fbm3 = settingsOf(NoiseType::Fbm, hash, 3);
    const double h = 0.125 / std::pow(eroded.lacunarity, 3);  // an eighth of a gully's spacing
    auto added = [&](const NoiseSettings& with, const NoiseSettings& without) {
      return [&](const glm::dvec3& q) { return evaluateCpuDouble(with, q) - evaluateCpuDouble(without, q); };
    };
    double gullyAcross = 0.0, gullyAlong = 0.0, fbmAcross = 0.0, fbmAlong = 0.0;
    size_t sloped = 0;
    for (const glm::dvec3& p : points) {
      ASSERT_EQ(evaluateCpuDouble(base, p), evaluateCpuDouble(fbm3, p));  // the base is fBm
      const glm::dvec3 slope = tangential(p, gradientOf(evaluateCpuGradientDouble(base, p)));
      if (glm::length(slope) < 4.0) continue;  // steep enough for full-depth gullies (F > 0.9)
      ++sloped;
      const glm::dvec3 s = glm::normalize(slope);
      const glm::dvec3 c = glm::cross(glm::normalize(p), s);
      gullyAcross += std::fabs(secondDifference(added(eroded, base), p, c, h));
      gullyAlong += std::fabs(secondDifference(added(eroded, base), p, s, h));
      fbmAcross += std::fabs(secondDifference(added(fbm4, fbm3), p, c, h));
      fbmAlong += std::fabs(secondDifference(added(fbm4, fbm3), p, s, h));
    }
    std::printf("%s: %zu sloped points; curvature across / along the slope: gullies %.2f, fbm octave %.2f\n",
                noiseHashName(hash), sloped, gullyAcross / gullyAlong, fbmAcross / fbmAlong);
    ASSERT_GT(sloped, points.size() / 5);
    // Measured: 3.1 to 3.2 (the stripes of neighbouring cells blend out of phase along the slope
    // too, where a gully ends or jogs).
    EXPECT_GT(gullyAcross / gullyAlong, 2.5) << "the gullies do not run down the slope";
    EXPECT_NEAR(fbmAcross / fbmAlong, 1.0, 0.25) << "the measure sees a direction in isotropic noise";
  }
}

TEST(NoiseErosion, NothingJumpsAlongLines) {
  // 2,000 steps of 1e-4 along lines through cells of every scale: each step changes the value by
  // at most what the gradient at its ends allows. A seam at a cell border would not.
  const double step = 1e-4;
  for (NoiseType type : {NoiseType::Damped, NoiseType::Eroded}) {
    for (NoiseHash hash : kHashes) {
      const NoiseSettings s = settingsOf(type, hash);
      const std::vector<glm::dvec3> starts = nearPoints(6, 41);
      const std::vector<glm::dvec3> ends = nearPoints(6, 42);
      double worst = 0.0;
      for (size_t line = 0; line < starts.size(); ++line) {
        const glm::dvec3 dir = glm::normalize(ends[line] - starts[line]);
        glm::dvec4 a = evaluateCpuGradientDouble(s, starts[line]);
        for (int i = 1; i <= 2000; ++i) {
          const glm::dvec4 b = evaluateCpuGradientDouble(s, starts[line] + dir * (step * i));
          const double bound = step * std::max(glm::length(gradientOf(a)), glm::length(gradientOf(b)));
          worst = std::max(worst, std::fabs(b.x - a.x) / bound);
          a = b;
        }
      }
      EXPECT_LT(worst, 1.5) << describe(s) << ": a step larger than the gradient allows";
    }
  }
}

TEST(NoiseErosion, TheOctaveFadeIsContinuous) {
  // Octave limiting adds the last octave with a weight from 0 to 1: at 0 the value is that of one
  // octave less, and it moves linearly to the full value, for a base octave and a gully octave.
  const std::vector<glm::dvec3> points = nearPoints(200, 43);
  for (NoiseType type : {NoiseType::Damped, NoiseType::Eroded}) {
    for (int octaves : {3, 6}) {  // eroded: the last octave is of the base, then a gully octave
      const NoiseSettings s = settingsOf(type, NoiseHash::Fast, octaves);
      NoiseKernel<double> kernel = doubleKernel(s);
      const gpu::NoiseParams full = toNoiseParams(s);
      const gpu::NoiseParams fewer = toNoiseParams(settingsOf(type, NoiseHash::Fast, octaves - 1));
      double worstStart = 0.0, worstLinear = 0.0, change = 0.0;
      for (const glm::dvec3& p : points) {
        gpu::NoiseParams faded = full;
        faded.lastOctaveWeight = 1e-7f;
        const double start = kernel.evaluateNoise(faded, p);
        const double end = kernel.evaluateNoise(full, p);
        worstStart = std::max(worstStart, std::fabs(start - kernel.evaluateNoise(fewer, p)));
        change = std::max(change, std::fabs(end - start));
        for (float weight : {0.25f, 0.5f, 0.75f}) {
          faded.lastOctaveWeight = weight;
          const double expected = start + (end - start) * (double(weight) - 1e-7) / (1.0 - 1e-7);
          worstLinear = std::max(worstLinear, std::fabs(kernel.evaluateNoise(faded, p) - expected));
        }
      }
      EXPECT_LT(worstStart, 1e-6) << noiseTypeName(type) << " " << octaves << ": the faded-in octave pops";
      EXPECT_LT(worstLinear, 1e-9) << noiseTypeName(type) << " " << octaves;
      EXPECT_GT(change, 1e-3) << noiseTypeName(type) << " " << octaves << ": the last octave adds nothing";
    }
  }
}

// Tolerance relative to the RMS gradient, as noise_gradient_test's (a wrong term errs by 1e-3).
constexpr double kGradientTolerance = 1e-5;

TEST(NoiseErosion, GradientMatchesCentralDifferencesOfTheDoubleReference) {
  // planet validate's cases are checked by NoiseGradient.*; these add other parameters, points on
  // a sphere (where the slope along it steers both types), and a faded last octave.
  std::vector<glm::dvec3> points = nearPoints(400, 44);
  for (const glm::dvec3& p : spherePoints(400)) points.push_back(p);
  std::vector<NoiseSettings> all = extraSettings();
  for (NoiseHash hash : kHashes) {
    all.push_back(settingsOf(NoiseType::Damped, hash));
    all.push_back(settingsOf(NoiseType::Eroded, hash));
  }
  for (const NoiseSettings& s : all) {
    for (float weight : {1.0f, 0.35f}) {
      NoiseKernel<double> kernel = doubleKernel(s);
      gpu::NoiseParams params = toNoiseParams(s);
      params.lastOctaveWeight = weight;
      double rms = 0.0;
      const double worst = worstDifference(
          points, stepFor(s, 1e-5), [&](const glm::dvec3& p) { return kernel.evaluateNoise(params, p); },
          [&](const glm::dvec3& p) { return glm::dvec4(kernel.evaluateNoiseGradient(params, p)); }, &rms);
      EXPECT_GT(rms, 0.0) << describe(s);
      EXPECT_LT(worst, kGradientTolerance) << describe(s) << ", last octave weight " << weight;
    }
  }
}

TEST(NoiseErosion, TheRebasedWalkIsThePlainWalkAtTheAnchorPlusTheOffset) {
  // The terrain's rebased octave tables split the anchor into integers and a remainder; up (the
  // direction from the origin) is rebuilt from them. At an Earth-sized anchor the rebased walk
  // gives the plain walk's value, and its gradient with respect to the offset in metres is the
  // frequency times the plain one.
  PlanetDescription planet = resolvePreset("earth");
  for (NoiseType type : {NoiseType::Damped, NoiseType::Eroded}) {
    for (NoiseHash hash : kHashes) {
      NoiseLayer& layer = planet.layers[0];
      layer.noise = settingsOf(type, hash, 8);
      layer.noise.seed = 5;
      layer.frequency = 1.0 / 400000.0;
      const glm::dvec3 anchor = planet.radiusM * directionFromLatLon(45.25, 83.25);
      const OctaveTables tables = buildOctaveTables(planet, anchor);
      NoiseKernel<double> kernel = doubleKernel(layer.noise);
      kernel.octaveRemainders = tables.remainders.data();
      kernel.octaveShifts = tables.shifts.data();
      const gpu::NoiseParams params = toNoiseParams(layer.noise);
      double worstValue = 0.0, worstGradient = 0.0, scale = 0.0;
      for (const glm::dvec3& o : nearPoints(100, 45)) {
        const glm::dvec3 offset = o * 200.0;  // up to 10 km from the anchor
        NoiseKernel<double>::OctaveWalk walk;
        walk.q = glm::dvec3(0.0);
        walk.lacunarity = params.lacunarity;
        walk.offset = offset;
        walk.layer = 0u;
        walk.octave = 0u;
        walk.rebased = 1u;
        const glm::dvec4 rebased = kernel.fractalNoiseGradient(params, walk);
        const glm::dvec4 plain = kernel.evaluateNoiseGradient(params, (anchor + offset) * layer.frequency);
        worstValue = std::max(worstValue, std::fabs(rebased.x - plain.x));
        worstGradient = std::max(worstGradient, glm::length(gradientOf(rebased) - layer.frequency * gradientOf(plain)));
        scale = std::max(scale, layer.frequency * glm::length(gradientOf(plain)));
      }
      // The tables hold the remainders in float: ~1e-7 lattice units.
      EXPECT_LT(worstValue, 1e-5) << describe(layer.noise);
      EXPECT_LT(worstGradient, 1e-4 * scale) << describe(layer.noise);
    }
  }
}

using NoiseErosionGpu = test::GpuTest;

TEST_F(NoiseErosionGpu, MatchesTheFloatReferenceBitForBit) {
  const ParityPolicy policy = parityPolicyFor(context());
  GpuNoise gpu(context());
  std::vector<glm::vec3> points = validationPoints(3000, false, 46);
  for (const glm::dvec3& p : spherePoints(1000)) points.emplace_back(p);
  std::vector<NoiseSettings> all = extraSettings();
  for (NoiseHash hash : kHashes) {
    NoiseSettings faint = settingsOf(NoiseType::Eroded, hash, 12);
    faint.gain = 0.5;
    faint.H = 0.8;
    all.push_back(faint);
  }
  for (const NoiseSettings& s : all) {
    std::vector<float> gpuValues(points.size()), cpuValues(points.size());
    gpu.evaluate(s, points, gpuValues);
    evaluateCpu(s, points, cpuValues, 0);
    const ParityStats values = compareValues(gpuValues, cpuValues);
    EXPECT_TRUE(policy.accepts(values)) << describe(s) << ": identical " << values.identical << "/" << values.count
                                        << ", max|err| " << values.maxAbsError;
    std::vector<glm::vec4> gpuGradients(points.size()), cpuGradients(points.size());
    gpu.evaluateGradient(s, points, gpuGradients);
    evaluateCpuGradient(s, points, cpuGradients, 0);
    const ParityStats gradients = compareGradients(gpuGradients, cpuGradients);
    EXPECT_TRUE(policy.accepts(gradients)) << describe(s) << " (gradient): identical " << gradients.identical << "/"
                                           << gradients.count << ", max|err| " << gradients.maxAbsError;
  }
}

// The earth with eroded mountains and damped hills.
PlanetDescription erodedEarth() {
  PlanetDescription planet = resolvePreset("earth");
  for (NoiseLayer& layer : planet.layers) {
    if (layer.name == "mountains") {
      layer.noise.type = NoiseType::Eroded;
      layer.noise.offset = 3.0;
      layer.noise.gain.reset();
    }
    if (layer.name == "hills") layer.noise.type = NoiseType::Damped;
  }
  return planet;
}

TEST_F(NoiseErosionGpu, TerrainHeightsMatchTheCpuFloatPathAndTheDoubleReference) {
  const PlanetDescription planet = erodedEarth();
  ASSERT_TRUE(needsFullNoiseShaders(planet));
  // In the mountains of the earth preset (its belts mask them elsewhere).
  const glm::dvec3 start = directionFromLatLon(45.25, 83.25);
  const glm::dvec3 anchor = planet.radiusM * start;
  const OctaveTables tables = buildOctaveTables(planet, anchor);
  std::vector<glm::vec3> offsets;
  std::vector<double> reference;
  for (int i = 0; i < 300; ++i) {  // 5 cm steps, then 1 km steps: near and far from the anchor
    const double distance = i < 200 ? 0.05 * i : 1000.0 * (i - 199);
    const glm::dvec3 d = travelGreatCircle(start, 30.0, distance, planet.radiusM);
    offsets.push_back(glm::vec3(planet.radiusM * d - anchor));
    reference.push_back(terrainHeightM(planet, d));
  }
  GpuTerrainPoints terrain(context(), planet);
  const std::vector<float> gpu = terrain.evaluate(tables, offsets);
  std::vector<float> cpu(offsets.size());
  for (size_t i = 0; i < offsets.size(); ++i) cpu[i] = terrainHeightRebased(planet, tables, offsets[i]);
  const ParityStats parity = compareValues(gpu, cpu);
  EXPECT_TRUE(parityPolicyFor(context()).accepts(parity))
      << "identical " << parity.identical << "/" << parity.count << ", max|err| " << parity.maxAbsError;
  double relief = 0.0;
  for (size_t i = 200; i < gpu.size(); ++i) relief = std::max(relief, std::fabs(reference[i] - reference[200]));
  EXPECT_GT(relief, 100.0) << "no mountains along the path";
  for (size_t i = 0; i < 200; ++i)  // near the anchor: the 1 cm precision requirement
    ASSERT_NEAR(gpu[i], reference[i], 0.01) << "sample " << i;
  for (size_t i = 200; i < gpu.size(); ++i)  // up to 100 km away: float offsets of 1e5 m
    ASSERT_NEAR(gpu[i], reference[i], 0.05) << "sample " << i;
}

TEST_F(NoiseErosionGpu, TheTerrainPassEvaluatesTheErosionLayers) {
  // The terrain pass's heights pipeline is specialized on the layers and comes without the
  // crater and erosion code for planets that need neither (needsFullNoiseShaders): an eroded
  // planet must get the full variant, whose heights are the CPU's.
  const PlanetDescription planet = erodedEarth();
  PlanetDescription plain = resolvePreset("earth");  // its eroded mountains made ridged
  for (NoiseLayer& layer : plain.layers)
    if (layer.noise.type == noise::NoiseType::Eroded) layer.noise.type = noise::NoiseType::Ridged;
  ASSERT_FALSE(needsFullNoiseShaders(plain));
  ASSERT_TRUE(needsFullNoiseShaders(resolvePreset("earth")));
  ASSERT_TRUE(needsFullNoiseShaders(planet));
  auto heights = [&](HeightSource source) {
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.terrain.mesh = ClipmapParams{30, 8, 64};
    settings.terrain.patches = false;
    settings.terrain.heightSource = source;
    settings.terrain.frustumCulling = false;  // every vertex of the drawn rings is read back
    Renderer renderer(context(), planet, settings);
    renderer.render({45.25, 83.25, 1.0e4, 0.0, -30.0}, {});
    const size_t count = renderer.terrain().mesh().vertexCount();
    std::vector<glm::vec4> values(count);
    vk::readbackBuffer(context(), renderer.terrain().surfaceBuffer(), values.data(), count * sizeof(glm::vec4));
    return std::make_pair(values, renderer.terrain().frame());
  };
  const auto [gpu, frame] = heights(HeightSource::Compute);
  const auto [cpu, cpuFrame] = heights(HeightSource::Cpu);
  const uint32_t n = 64;
  double worst = 0.0, lowest = 1e30, highest = -1e30;
  for (uint32_t i = frame.heightFirstRing * n; i < (frame.heightLastRing + 1) * n; ++i) {
    worst = std::max(worst, double(std::abs(gpu[i].w - cpu[i].w)));
    lowest = std::min(lowest, double(cpu[i].w));
    highest = std::max(highest, double(cpu[i].w));
  }
  std::printf("eroded earth: compute vs CPU vertex heights differ by %.4f m at most (heights %.0f .. %.0f m)\n", worst,
              lowest, highest);
  EXPECT_GT(highest - lowest, 100.0);
  // The same float path but for the vertex angles' sin/cos (1.9 cm measured where the gullies are
  // steep); the variant without the erosion code would read the layers as simplex, hundreds of
  // metres off.
  EXPECT_LT(worst, 0.05);
}

// The height of the drawn surface (the mesh's triangles in their (theta, phi) parameterisation)
// at a planet direction: TerrainRender.DrawnSurfaceDoesNotSwimWhenTheCameraMoves's measure.
double drawnHeight(const TerrainPass& terrain, const std::vector<glm::vec4>& surface, const glm::dvec3& direction) {
  const ClipmapMesh& mesh = terrain.mesh();
  const glm::dvec2 thetaPhi = planetToLocalThetaPhi(terrain.frame().orientation, direction);
  const uint32_t outer = mesh.innermostRingAtOrAbove(thetaPhi.x);
  const uint32_t inner = outer + 1;
  EXPECT_LT(inner, mesh.ringCount()) << "test point inside the pole fan";
  const uint32_t n = mesh.params.numPhi;
  const double step = 2.0 * std::numbers::pi / n;
  const uint32_t i = std::min(uint32_t(thetaPhi.y / step), n - 1);
  const double u = thetaPhi.y / step - i;
  const double t = (mesh.ringTheta(outer) - thetaPhi.x) / (mesh.ringTheta(outer) - mesh.ringTheta(inner));
  auto h = [&](uint32_t ring, uint32_t k) { return double(surface[mesh.vertexIndex(ring, k % n)].w); };
  const double o0 = h(outer, i), o1 = h(outer, i + 1), n0 = h(inner, i), n1 = h(inner, i + 1);
  return u >= t ? o0 + u * (o1 - o0) + t * (n1 - o1) : o0 + t * (n0 - o0) + u * (n1 - n0);
}

TEST_F(NoiseErosionGpu, OctaveLimitingKeepsTheSurfaceStillAsForTheOtherTypes) {
  // The moon's rubble layer (ridged, 20 octaves down to 5 cm: the swimming test's hard case) made
  // damped and eroded: fixed points of the drawn surface 5..60 m from the camera's ground point
  // move by less than the stated 15 mm when the camera moves by 0.3 of the vertex spacing (the
  // bound of TerrainRender.DrawnSurfaceDoesNotSwimWhenTheCameraMoves).
  const double lat = 37.2, lon = -118.6;
  for (NoiseType type : {NoiseType::Eroded, NoiseType::Damped}) {
    PlanetDescription planet = resolvePreset("moon");
    for (NoiseLayer& layer : planet.layers)
      if (layer.name == "rubble") {
        layer.noise.type = type;
        layer.noise.offset.reset();
        layer.amplitudeM = 200.0;  // fBm-like values in about -1.5 .. 1.5
      }
    const glm::dvec3 ground = directionFromLatLon(lat, lon);
    std::vector<glm::dvec3> points;
    for (double distance : {5.0, 12.0, 25.0, 60.0})
      for (double bearing : {10.0, 100.0, 200.0, 300.0})
        points.push_back(travelGreatCircle(ground, bearing, distance, planet.radiusM));
    auto measure = [&](bool limitOctaves) {
      RenderSettings settings;
      settings.width = 160;
      settings.height = 90;
      settings.terrain.patches = false;
      settings.terrain.limitOctaves = limitOctaves;
      settings.terrain.frustumCulling = false;  // the points lie all round the camera
      Renderer renderer(context(), planet, settings);
      TerrainPass& terrain = renderer.terrain();
      auto surfaceNow = [&] {
        std::vector<glm::vec4> surface(terrain.mesh().vertexCount());
        vk::readbackBuffer(context(), terrain.surfaceBuffer(), surface.data(), surface.size() * sizeof(glm::vec4));
        return surface;
      };
      const double altitude = renderer.clampToGround({lat, lon, -1.0e5}).altitudeM + 8.0;
      renderer.render({lat, lon, altitude}, {});
      const std::vector<glm::vec4> surface0 = surfaceNow();
      std::vector<double> before;
      double spacing = 1e300;
      for (const glm::dvec3& p : points) {
        before.push_back(drawnHeight(terrain, surface0, p));
        const double theta = planetToLocalThetaPhi(terrain.frame().orientation, p).x;
        spacing = std::min(
            spacing, ringSpacingM(terrain.mesh().params, planet.radiusM, terrain.mesh().innermostRingAtOrAbove(theta)));
      }
      double worst = 0.0;
      for (double bearing : {0.0, 90.0, 180.0, 270.0}) {
        const glm::dvec3 moved = travelGreatCircle(ground, bearing, 0.3 * spacing, planet.radiusM);
        renderer.render({std::asin(moved.z) * 180.0 / std::numbers::pi,
                         std::atan2(moved.y, moved.x) * 180.0 / std::numbers::pi, altitude},
                        {});
        const std::vector<glm::vec4> surface = surfaceNow();
        for (size_t k = 0; k < points.size(); ++k)
          worst = std::max(worst, std::abs(drawnHeight(terrain, surface, points[k]) - before[k]));
      }
      return worst;
    };
    const double limited = measure(true), unlimited = measure(false);
    std::printf("%s rubble: surface change at fixed points %.4f m with octave limits, %.4f m without\n",
                noiseTypeName(type), limited, unlimited);
    // Measured with the mesh spun by parallel transport: eroded 5.8 mm (12.0 mm without limits),
    // damped 6.5 mm (5.5 mm without: its fine octaves are damped on all but flat ground, so there
    // is little for the limits to take away). With the spin from the pose (issue 11 point 8) the
    // same points fall elsewhere on the mesh: eroded 12.3 mm (8.0 mm without). An eroded octave
    // depends on the slope of all before it, so a point whose ring budget changes as the camera
    // moves changes by more than an fBm's would; the limits keep it within the bound, but are not
    // always below the unlimited figure, so only the bound is asserted.
    EXPECT_LT(limited, 0.015) << noiseTypeName(type);
  }
}

}  // namespace
}  // namespace planet::noise

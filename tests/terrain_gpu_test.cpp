// The GPU terrain (terrain_points.comp) against the CPU: the same float rebased path as
// terrainHeightRebased(), and within 1 cm of the double reference at Earth scale. The terrain
// pass's vertex heights and normals (terrain_heights.comp, specialized on the layers' types and
// hashes) against the CPU evaluation of the same vertices, for every type and hash. The height's
// analytic gradient (terrainHeightGradientSum, which gives the vertices their normals) against
// central differences of the double reference, its height bit-identical to the height sum's.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gpu_fixture.h"
#include "bench/noise_validate.h"
#include "planet/terrain_height.h"
#include "planet/terrain_kernel.h"
#include "planet/terrain_points_gpu.h"
#include "planet/terrain_rebase.h"
#include "reference/terrain_surface_cpu.h"
#include "render/renderer.h"
#include "vk/buffer.h"

namespace planet::test {
namespace {

using TerrainGpu = GpuTest;

TEST_F(TerrainGpu, HeightsMatchTheCpuFloatPathAndTheDoubleReference) {
  for (const char* preset : {"earth", "moon", "mars"}) {
    const PlanetDescription planet = resolvePreset(preset);
    const glm::dvec3 start = directionFromLatLon(-12.5, 77.25);
    const glm::dvec3 anchor = planet.radiusM * start;
    const OctaveTables tables = buildOctaveTables(planet, anchor);
    std::vector<glm::vec3> offsets;
    std::vector<double> reference;
    for (int i = 0; i < 300; ++i) {  // 5 cm steps, then 1 km steps: near and far from the anchor
      double distance = i < 200 ? 0.05 * i : 1000.0 * (i - 199);
      glm::dvec3 d = travelGreatCircle(start, 30.0, distance, planet.radiusM);
      offsets.push_back(glm::vec3(planet.radiusM * d - anchor));
      reference.push_back(terrainHeightM(planet, d));
    }
    GpuTerrainPoints terrain(context(), planet);
    std::vector<float> gpu = terrain.evaluate(tables, offsets);
    std::vector<float> cpu(offsets.size());
    for (size_t i = 0; i < offsets.size(); ++i) cpu[i] = terrainHeightRebased(planet, tables, offsets[i]);
    noise::ParityStats parity = noise::compareValues(gpu, cpu);
    EXPECT_TRUE(noise::parityPolicyFor(context()).accepts(parity))
        << preset << ": identical " << parity.identical << "/" << parity.count << ", max|err| " << parity.maxAbsError;
    for (size_t i = 0; i < 200; ++i)  // near the anchor: the 1 cm precision requirement
      ASSERT_NEAR(gpu[i], reference[i], 0.01) << preset << " sample " << i;
    for (size_t i = 200; i < gpu.size(); ++i)  // up to 100 km away: float offsets of 1e5 m
      ASSERT_NEAR(gpu[i], reference[i], 0.05) << preset << " sample " << i;
  }
}

// Eight layers (the most the shaders hold) of every fractal type, alternating hashes, some shaped:
// a transfer curve, a mask through a curve, and a mask by a masked layer.
PlanetDescription everyTypePlanet() {
  PlanetDescription planet = resolvePreset("moon");
  const NoiseLayer base = planet.layers[0];
  const noise::NoiseType types[] = {noise::NoiseType::Cascade, noise::NoiseType::Simplex, noise::NoiseType::Hetero,
                                    noise::NoiseType::Ridged,  noise::NoiseType::Fbm,     noise::NoiseType::Hybrid,
                                    noise::NoiseType::Craters, noise::NoiseType::Simplex};
  planet.layers.clear();
  for (uint32_t l = 0; l < 8; ++l) {
    NoiseLayer layer = base;
    layer.name = "layer" + std::to_string(l);
    layer.noise.type = types[l];
    layer.noise.offset.reset();  // the type's default
    layer.noise.hash = l % 2 ? noise::NoiseHash::Reference : noise::NoiseHash::Fast;
    layer.noise.seed = 17 * l;
    layer.noise.octaves = 6;
    layer.frequency = base.frequency * std::ldexp(1.0, int(l) - 3);
    layer.amplitudeM = 400.0 / (1.0 + l);
    layer.transfer.clear();  // the base layer's shaping is not copied
    layer.hypsometry.clear();
    layer.mask.clear();
    layer.maskCurve.clear();
    planet.layers.push_back(layer);
  }
  planet.layers[2].transfer = {{-1.0, -0.5}, {0.0, 0.2}, {0.5, 0.3}, {1.0, 1.5}};
  planet.layers[4].mask = "layer2";
  planet.layers[4].maskCurve = {{-0.5, 0.0}, {1.5, 2.0}};
  planet.layers[6].mask = "layer4";
  return planet;
}

// Angle in degrees between two unit vectors.
double angleDeg(const glm::vec3& a, const glm::vec3& b) {
  return std::acos(std::clamp(double(glm::dot(a, b)), -1.0, 1.0)) * 180.0 / 3.14159265358979;
}

// Each layer of the specialized pipeline must get its own type, hash, curves and mask; the
// normals, from the analytic gradient in both, must agree as well.
TEST_F(TerrainGpu, SpecializedVertexHeightsMatchTheCpuForEveryTypeAndHash) {
  const PlanetDescription planet = everyTypePlanet();
  auto surface = [&](HeightSource source) {
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.terrain.mesh = ClipmapParams{30, 8, 64};
    settings.terrain.patches = false;
    settings.terrain.heightSource = source;
    settings.terrain.frustumCulling = false;  // every vertex of the drawn rings is read back
    Renderer renderer(context(), planet, settings);
    renderer.render({12.0, -48.0, 2.0e4, 0.0, -30.0}, {});
    const size_t count = renderer.terrain().mesh().vertexCount();
    std::vector<glm::vec4> values(count), normals(count);
    vk::readbackBuffer(context(), renderer.terrain().surfaceBuffer(), values.data(), count * sizeof(glm::vec4));
    vk::readbackBuffer(context(), renderer.terrain().normalBuffer(), normals.data(), count * sizeof(glm::vec4));
    std::vector<glm::vec3> ups(count);  // the sphere normals
    for (size_t i = 0; i < count; ++i) ups[i] = glm::vec3(renderer.terrain().mesh().vertices[i].direction);
    return std::make_tuple(values, normals, ups, renderer.terrain().frame());
  };
  const auto [gpu, gpuNormals, ups, frame] = surface(HeightSource::Compute);
  const auto [cpu, cpuNormals, cpuUps, cpuFrame] = surface(HeightSource::Cpu);
  const uint32_t n = 64;
  double worst = 0.0, largest = 0.0, steepest = 0.0;
  std::vector<double> angles;
  for (uint32_t i = frame.heightFirstRing * n; i < (frame.heightLastRing + 1) * n; ++i) {
    worst = std::max(worst, double(std::abs(gpu[i].w - cpu[i].w)));
    largest = std::max(largest, double(std::abs(cpu[i].w)));
    angles.push_back(angleDeg(glm::vec3(gpuNormals[i]), glm::vec3(cpuNormals[i])));
    steepest = std::max(steepest, angleDeg(glm::vec3(cpuNormals[i]), ups[i]));
  }
  std::sort(angles.begin(), angles.end());
  const double worstAngle = angles.back(), p99 = angles[angles.size() * 99 / 100];
  std::printf(
      "8 layers of every type and hash: compute vs CPU heights differ by %.4f m at most (heights up to %.0f m), "
      "normals by %.5f deg (99th percentile %.5f deg; slopes up to %.2f deg)\n",
      worst, largest, worstAngle, p99, steepest);
  // The two evaluate the same float path; only sin/cos of the vertex angles round differently.
  EXPECT_GT(largest, 10.0);
  EXPECT_LT(worst, 0.01);
  // Far vertices (float offsets of tens of km) may straddle a kink of the noise (ridged's |N|, a
  // crater's rim) differently, where the gradient jumps.
  EXPECT_GT(steepest, 0.1);
  EXPECT_LT(p99, 0.025);
  EXPECT_LT(worstAngle, 0.1);
}

}  // namespace
}  // namespace planet::test

namespace planet::test {
namespace {

// terrainHeightGradientSum in the double reference: the plain walk of terrainHeightM at its point
// of the radius sphere in `direction`; vec4(height, dh/dp).
glm::dvec4 referenceHeightGradient(const PlanetDescription& planet, const glm::dvec3& direction, double spacingM) {
  const TerrainKernelLayers<double> layers = terrainKernelLayers<double>(planet, spacingM);
  noise::NoiseKernel<double> kernel;
  layers.attach(kernel, false);
  return kernel.terrainHeightGradientSum(planet.baseHeightM, planet.heightScale,
                                         planet.radiusM * glm::normalize(direction), 0u);
}

// The analytic gradient is the slope of the height: along two tangent directions at random
// points, central differences of terrainHeightM (1 cm steps, double) agree with it, through the
// earth's hypsometric curve, its masks of masked layers, and every fractal type.
TEST(TerrainGradient, TheReferenceGradientIsTheSlopeOfTheHeight) {
  const std::pair<const char*, PlanetDescription> planets[] = {{"earth", resolvePreset("earth")},
                                                               {"every type", everyTypePlanet()}};
  for (const auto& [name, planet] : planets) {
    std::mt19937 random(19);
    std::normal_distribution<double> normal;
    const double stepM = 0.001;
    int samples = 0, mismatches = 0;
    double steepest = 0.0, worst = 0.0;
    for (int i = 0; i < 300; ++i) {
      const glm::dvec3 d = glm::normalize(glm::dvec3(normal(random), normal(random), normal(random)));
      const glm::dvec3 east = glm::normalize(glm::cross(glm::dvec3(0.0, 0.0, 1.0), d));
      const glm::dvec3 north = glm::cross(d, east);
      // Octave budgets of a near and a far ring (the earth's ground layer goes down to 1 cm, finer
      // than a difference's step could follow); each fades its last octave in.
      const double spacingM = i % 2 ? 1.0 : 30.0;
      const glm::dvec4 g = referenceHeightGradient(planet, d, spacingM);
      ASSERT_EQ(g.x, terrainHeightM(planet, d, spacingM)) << name << " sample " << i;
      const glm::dvec3 gradient(g.y, g.z, g.w);
      for (const glm::dvec3& t : {east, north}) {
        const double plus = terrainHeightM(planet, planet.radiusM * d + stepM * t, spacingM);
        const double minus = terrainHeightM(planet, planet.radiusM * d - stepM * t, spacingM);
        const double difference = (plus - minus) / (2.0 * stepM);
        const double error = std::abs(difference - glm::dot(gradient, t));
        ++samples;
        // Relative to the gradient: a kink (ridged's |N|, a clamp, a curve's end knot) within the
        // step of a sample makes the difference a mean of two slopes there.
        if (error > 1e-4 * glm::length(gradient) + 1e-7)
          ++mismatches;
        else
          worst = std::max(worst, error / std::max(glm::length(gradient), 1e-9));
        steepest = std::max(steepest, glm::length(gradient));
      }
    }
    std::printf("%s: %d of %d slopes off by more than 1e-4 of the gradient; the rest within %.2g; steepest %.3f\n",
                name, mismatches, samples, worst, steepest);
    EXPECT_GT(steepest, 0.005) << name;  // slopes to measure
    EXPECT_LE(mismatches, samples / 100) << name;
  }
}

// The height beside the gradient is the height sum's, bit for bit, in the float path the CPU
// height source and the shaders evaluate (and so in the pictures: nothing moves).
TEST(TerrainGradient, TheFloatHeightIsTheHeightSumBitForBit) {
  const std::pair<const char*, PlanetDescription> planets[] = {
      {"earth", resolvePreset("earth")}, {"mars", resolvePreset("mars")}, {"every type", everyTypePlanet()}};
  for (const auto& [name, planet] : planets) {
    const glm::dvec3 start = directionFromLatLon(-12.5, 77.25);
    const OctaveTables tables = buildOctaveTables(planet, planet.radiusM * start);
    int differing = 0;
    for (int i = 0; i < 200; ++i) {
      const double distance = i < 100 ? 0.5 * i : 500.0 * (i - 99);
      const glm::dvec3 d = travelGreatCircle(start, 60.0, distance, planet.radiusM);
      const glm::vec3 offset(planet.radiusM * d - planet.radiusM * start);
      const double spacingM = i % 3 ? 0.0 : 20.0;
      const TerrainKernelLayers<float> layers = terrainKernelLayers<float>(planet, spacingM);
      noise::NoiseKernel<float> kernel;
      kernel.octaveRemainders = tables.remainders.data();
      kernel.octaveShifts = tables.shifts.data();
      layers.attach(kernel, true);
      const glm::vec4 g =
          kernel.terrainHeightGradientSum(float(planet.baseHeightM), float(planet.heightScale), offset, 0u);
      differing += g.x != terrainHeightRebased(planet, tables, offset, spacingM);
    }
    EXPECT_EQ(differing, 0) << name;
  }
}

// surfaceNormalCpu (the formula of terrain_vertex_surface.glsl) is the normal of r = (R + h(d)) d:
// orthogonal to the surface's displacement along two tangent steps, on a made-up height with a
// known gradient.
TEST(TerrainGradient, TheNormalFormulaIsTheDisplacedSurfacesNormal) {
  const float radiusM = 1000.0f;
  const glm::vec3 slope(0.3f, -0.2f, 0.7f);  // dh/dp, planet frame
  auto height = [&](const glm::vec3& d) { return 50.0f + glm::dot(slope, radiusM * d); };
  const glm::mat3 localToPlanet = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(1.0f, 2.0f, 3.0f)));
  const glm::vec3 up = glm::normalize(glm::vec3(0.2f, 0.1f, 1.0f));  // local frame
  const glm::vec3 d = localToPlanet * up;
  const glm::vec3 n = surfaceNormalCpu(glm::vec4(height(d), slope), up, localToPlanet, radiusM);
  const glm::vec3 east = glm::normalize(glm::cross(glm::vec3(0.0f, 0.0f, 1.0f), up));
  const glm::vec3 north = glm::cross(up, east);
  for (const glm::vec3& t : {east, north}) {
    const float step = 1e-3f;
    auto surface = [&](float s) {
      const glm::vec3 u = glm::normalize(up + s * t);
      return (radiusM + height(localToPlanet * u)) * u;
    };
    const glm::vec3 along = glm::normalize(surface(step) - surface(-step));
    EXPECT_NEAR(glm::dot(n, along), 0.0f, 1e-3f);
  }
  EXPECT_GT(glm::dot(n, up), 0.0f);   // outward
  EXPECT_LT(glm::dot(n, up), 0.99f);  // tilted by the slope
}

}  // namespace
}  // namespace planet::test

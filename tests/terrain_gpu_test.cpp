// The GPU terrain (terrain_points.comp) against the CPU: the same float rebased path as
// terrainHeightRebased(), and within 1 cm of the double reference at Earth scale. The terrain
// pass's vertex heights (terrain_heights.comp, specialized on the layers' types and hashes)
// against the CPU evaluation of the same vertices, for every type and hash.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_fixture.h"
#include "bench/noise_validate.h"
#include "planet/terrain_height.h"
#include "planet/terrain_points_gpu.h"
#include "planet/terrain_rebase.h"
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
// each layer of the specialized pipeline must get its own type, hash, curves and mask.
TEST_F(TerrainGpu, SpecializedVertexHeightsMatchTheCpuForEveryTypeAndHash) {
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
  // Shaped layers too: a transfer curve, a mask through a curve, and a mask by a masked layer.
  planet.layers[2].transfer = {{-1.0, -0.5}, {0.0, 0.2}, {0.5, 0.3}, {1.0, 1.5}};
  planet.layers[4].mask = "layer2";
  planet.layers[4].maskCurve = {{-0.5, 0.0}, {1.5, 2.0}};
  planet.layers[6].mask = "layer4";
  auto surface = [&](HeightSource source) {
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.terrain.mesh = ClipmapParams{30, 8, 64};
    settings.terrain.patches = false;
    settings.terrain.heightSource = source;
    Renderer renderer(context(), planet, settings);
    renderer.render({12.0, -48.0, 2.0e4, 0.0, -30.0}, {});
    std::vector<glm::vec4> values(renderer.terrain().mesh().vertexCount());
    vk::readbackBuffer(context(), renderer.terrain().surfaceBuffer(), values.data(), values.size() * sizeof(glm::vec4));
    return std::make_pair(values, renderer.terrain().frame());
  };
  const auto [gpu, frame] = surface(HeightSource::Compute);
  const auto [cpu, cpuFrame] = surface(HeightSource::Cpu);
  const uint32_t n = 64;
  double worst = 0.0, largest = 0.0;
  for (uint32_t i = frame.heightFirstRing * n; i < (frame.heightLastRing + 1) * n; ++i) {
    worst = std::max(worst, double(std::abs(gpu[i].w - cpu[i].w)));
    largest = std::max(largest, double(std::abs(cpu[i].w)));
  }
  std::printf(
      "8 layers of every type and hash: compute vs CPU heights differ by %.4f m at most (heights up to %.0f m)\n",
      worst, largest);
  // The two evaluate the same float path; only sin/cos of the vertex angles round differently.
  EXPECT_GT(largest, 10.0);
  EXPECT_LT(worst, 0.01);
}

}  // namespace
}  // namespace planet::test

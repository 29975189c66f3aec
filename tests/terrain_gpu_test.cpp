// The GPU terrain (terrain_points.comp) against the CPU: the same float rebased path as
// terrainHeightRebased(), and within 1 cm of the double reference at Earth scale.
#include <gtest/gtest.h>

#include "gpu_fixture.h"
#include "noise/validate.h"
#include "planet/terrain_height.h"
#include "planet/terrain_points_gpu.h"
#include "planet/terrain_rebase.h"

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

}  // namespace
}  // namespace planet::test

// The sky's tables on lavapipe (issue 21, point 1): the GPU's multiple-scattering table against
// the double CPU reference of the same source, and single rays through the tables
// (shaders/sky_ray.comp) against the CPU reference's sky radiance.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_fixture.h"
#include "reference/atmosphere_model.h"
#include "render/sky_tables.h"
#include "vk/commands.h"

namespace planet::test {
namespace {

using SkyTablesGpu = GpuTest;

PlanetDescription clearSky(const char* preset) {
  PlanetDescription planet = resolvePreset(preset);
  planet.clouds.enabled = false;
  return planet;
}

// Relative difference, against a floor that keeps the night side's near-zeros from counting.
double relative(double actual, double expected, double floor) {
  return std::abs(actual - expected) / std::max(std::abs(expected), floor);
}

// Float on the GPU (its sampler's filtering, its transmittance table) against double on the CPU
// (its own double transmittance table, read the same way): Ψ_ms within 1 % of the value (or of
// a thousandth of the table's largest), f_ms within 10⁻⁴.
TEST_F(SkyTablesGpu, MultipleScatteringTableMatchesCpuReference) {
  for (const char* preset : {"earth", "mars"}) {
    const PlanetDescription planet = clearSky(preset);
    SkyTables tables(context(), planet);
    const auto start = std::chrono::steady_clock::now();
    vk::submitAndWait(context(), [&](VkCommandBuffer cmd) { tables.recordBuild(cmd, nullptr); });
    const double gpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const std::vector<glm::vec4> gpuTable = tables.readMultipleScattering();
    const auto cpuStart = std::chrono::steady_clock::now();
    const MultipleScatteringTable cpuTable = multipleScatteringTable(tables.atmosphere());
    const double cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpuStart).count();
    ASSERT_EQ(gpuTable.size(), cpuTable.psi.size());
    double largest = 0.0;
    for (const glm::dvec3& psi : cpuTable.psi) largest = std::max({largest, psi.r, psi.g, psi.b});
    double worst = 0.0, worstTransfer = 0.0;
    for (size_t i = 0; i < gpuTable.size(); ++i) {
      for (int c = 0; c < 3; ++c) worst = std::max(worst, relative(gpuTable[i][c], cpuTable.psi[i][c], 1e-3 * largest));
      worstTransfer = std::max(worstTransfer, std::abs(double(gpuTable[i].a) - cpuTable.transfer[i].g));
    }
    std::printf(
        "%s: multiple-scattering table %ux%u, tables built on the GPU in %.0f ms, on the CPU in %.0f ms; "
        "GPU vs CPU: Ψ_ms within %.2e (relative), f_ms within %.2e\n",
        preset, gpu::kMultiScatteringSize, gpu::kMultiScatteringSize, gpuMs, cpuMs, worst, worstTransfer);
    EXPECT_LT(worst, 1e-2) << preset;
    EXPECT_LT(worstTransfer, 1e-4) << preset;
  }
}

// Rays through the tables against the CPU reference (256 double steps, the sun's transmittance
// integrated, Ψ_ms from the CPU table): by day from the ground, at twilight from 10 km, and from
// orbit across the limb. The tables' march (64 steps): single and total within 5 %, the
// transmittance within 1 %. The reference sky pass's march (`--sky reference`, 64 equal steps,
// each integrated in closed form) against the same: single and total within 5 %.
TEST_F(SkyTablesGpu, RaysThroughTheTablesMatchTheCpuReference) {
  const double deg = 3.14159265358979 / 180.0;
  struct Case {
    double altitudeM, viewDeg, sunDeg, azimuthDeg;
  };
  const Case cases[] = {{0.0, 90.0, 60.0, 0.0},      {0.0, 30.0, 20.0, 90.0},       {0.0, 20.0, 10.0, 0.0},
                        {10'000.0, 90.0, -4.0, 0.0}, {10'000.0, 45.0, -4.0, 180.0}, {400'000.0, -19.5, 30.0, 0.0}};
  for (const char* preset : {"earth", "mars"}) {
    const PlanetDescription planet = clearSky(preset);
    SkyTables tables(context(), planet);
    std::vector<SkyTables::RayQuery> queries;
    for (const Case& c : cases) {
      const double mu = std::sin(c.viewDeg * deg), muS = std::sin(c.sunDeg * deg);
      const double nu = mu * muS + std::cos(c.viewDeg * deg) * std::cos(c.sunDeg * deg) * std::cos(c.azimuthDeg * deg);
      queries.push_back({c.altitudeM, mu, muS, nu});
    }
    const std::vector<SkyTables::RayResult> rays = tables.evaluateRays(queries, 64, 64);
    const MultipleScatteringTable table = multipleScatteringTable(tables.atmosphere());
    double worst[4] = {0.0, 0.0, 0.0, 0.0};
    double worstReferenceTotal = 0.0;
    for (size_t i = 0; i < queries.size(); ++i) {
      const SkyTables::RayQuery& q = queries[i];
      const SkySample cpu = skyRadiance(tables.atmosphere(), q.altitudeM, q.mu, q.muS, q.nu, 256, 256, &table);
      const double floor = std::max(1e-3 * std::max({cpu.total.r, cpu.total.g, cpu.total.b}), 1e-12);
      for (int c = 0; c < 3; ++c) {
        const std::string where = std::string(preset) + " case " + std::to_string(i) + " channel " + std::to_string(c);
        const double single = relative(rays[i].single[c], cpu.radiance[c], floor);
        const double total = relative(rays[i].single[c] + rays[i].multiple[c], cpu.total[c], floor);
        const double transmittance = relative(rays[i].transmittance[c], cpu.transmittance[c], 1e-3);
        const double reference = relative(rays[i].reference[c], cpu.radiance[c], floor);
        const double referenceTotal = relative(rays[i].referenceTotal[c], cpu.total[c], floor);
        worstReferenceTotal = std::max(worstReferenceTotal, referenceTotal);
        EXPECT_LT(single, 0.05) << where;
        EXPECT_LT(total, 0.05) << where;
        EXPECT_LT(transmittance, 0.01) << where;
        worst[0] = std::max(worst[0], single);
        worst[1] = std::max(worst[1], total);
        worst[2] = std::max(worst[2], transmittance);
        EXPECT_LT(reference, 0.05) << where;
        EXPECT_LT(referenceTotal, 0.05) << where;
        worst[3] = std::max(worst[3], reference);
      }
    }
    std::printf(
        "%s: rays, GPU tables vs CPU reference (relative): single %.2e, total %.2e, transmittance %.2e; "
        "the reference sky pass's march: single %.2e, total %.2e\n",
        preset, worst[0], worst[1], worst[2], worst[3], worstReferenceTotal);
  }
}

}  // namespace
}  // namespace planet::test

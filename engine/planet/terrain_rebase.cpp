// Compiled without fused multiply-adds like every C++ build of shared GLSL (the top CMakeLists.txt).
#include "planet/terrain_rebase.h"

#include <cmath>

#include "planet/terrain_kernel.h"

namespace planet {
namespace {

constexpr uint32_t kOctaves = gpu::kNoiseMaxOctaves;

}  // namespace

void splitLatticeAnchor(const glm::dvec3& a, glm::vec4& remainder, glm::uvec4& shift) {
  int64_t ix = int64_t(std::floor(a.x));
  const int64_t iy = int64_t(std::floor(a.y));
  const int64_t iz = int64_t(std::floor(a.z));
  int64_t sum = ix + iy + iz;
  int64_t excess = ((sum % 3) + 3) % 3;
  ix -= excess;  // now (ix + iy + iz) is a multiple of 3 and a.x - ix is in [0, 3)
  sum -= excess;
  const int64_t m = sum / 3;
  remainder = glm::vec4(float(a.x - double(ix)), float(a.y - double(iy)), float(a.z - double(iz)), remainder.w);
  // Unsigned wrap-around is intended: both hashes depend on the indices modulo 2^22 or 2^8.
  shift = glm::uvec4(uint32_t(uint64_t(ix + m)), uint32_t(uint64_t(iy + m)), uint32_t(uint64_t(iz + m)), 0u);
}

OctaveTables buildOctaveTables(const PlanetDescription& planet, const glm::dvec3& anchorM) {
  OctaveTables tables;
  tables.anchorM = anchorM;
  tables.remainders.resize(planet.layers.size() * kOctaves);
  tables.shifts.resize(planet.layers.size() * kOctaves);
  for (size_t l = 0; l < planet.layers.size(); ++l) {
    const NoiseLayer& layer = planet.layers[l];
    // Octave i's scale is frequency * L^i with L rounded to float, as the shader's plain walk
    // and the double reference use it.
    const double lacunarity = double(float(layer.noise.lacunarity));
    double scale = layer.frequency;
    if (noise::isGenerator(layer.noise.type)) {
      // Faults and MPD read only octave 0's point, for its direction (noise_generators.glsl):
      // the anchor on the unit sphere as it is, no lattice split, whose remainder in [0, 3) would
      // hold the direction less precisely (a unit vector in float: 6e-8).
      tables.remainders[l * kOctaves] = glm::vec4(glm::vec3(anchorM * scale), float(scale));
      tables.shifts[l * kOctaves] = glm::uvec4(0u);
      continue;
    }
    for (uint32_t i = 0; i < uint32_t(layer.noise.octaves); ++i, scale *= lacunarity) {
      glm::vec4& remainder = tables.remainders[l * kOctaves + i];
      splitLatticeAnchor(anchorM * scale, remainder, tables.shifts[l * kOctaves + i]);
      remainder.w = float(scale);
    }
  }
  return tables;
}

float terrainHeightRebased(const PlanetDescription& planet, const OctaveTables& tables, const glm::vec3& offsetM,
                           double spacingM) {
  // The layer sum of shaders/common/terrain_height.glsl, each layer walking its row of the
  // rebased octave tables: the arithmetic of the shaders' rebased terrain heights.
  const TerrainKernelLayers<float> layers = terrainKernelLayers<float>(planet, spacingM);
  noise::NoiseKernel<float> kernel;
  kernel.octaveRemainders = tables.remainders.data();
  kernel.octaveShifts = tables.shifts.data();
  layers.attach(kernel, true);
  return kernel.terrainHeightSum(float(planet.baseHeightM), float(planet.heightScale), offsetM, 0u);
}

}  // namespace planet

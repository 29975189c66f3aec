// Compiled with -ffp-contract=off like the noise reference (the project-wide rule, top CMakeLists.txt): the band
// noise below is the shader's code compiled as C++.
#include "reference/terrain_surface_cpu.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <thread>
#include <vector>

#include "noise/noise_kernel.h"
#include "planet/terrain_kernel.h"

namespace planet {
namespace {

// common/surface_attributes.glsl, as terrain_vertex_surface.glsl calls it.
glm::vec4 surfaceAttributes(const CpuSurfaceJob& job, const glm::vec3& offsetPlanet, const ClipmapVertex& v) {
  const gpu::FrameUniforms& frame = *job.frame;
  const float radius = frame.camera.y;
  const float spacing = radius * std::sin(v.theta) * (6.2831853f / float(job.mesh->params.numPhi));
  return noise::NoiseKernel<float>().terrainSurfaceAttributes(
      offsetPlanet, radius, glm::vec3(frame.localToPlanet[2]), glm::vec3(frame.refMinusNadir), frame.faceNormal,
      frame.faceAxisA, frame.faceAxisB, job.bandFrequency, spacing, job.regionalWeight);
}

// The height and its gradient at offsetM (terrainHeightRebased's evaluation, with the gradient).
glm::vec4 heightGradient(const CpuSurfaceJob& job, const glm::vec3& offsetM, double spacingM) {
  const PlanetDescription& planet = *job.planet;
  const TerrainKernelLayers<float> layers = terrainKernelLayers<float>(planet, spacingM);
  noise::NoiseKernel<float> kernel;
  kernel.octaveRemainders = job.tables->remainders.data();
  kernel.octaveShifts = job.tables->shifts.data();
  layers.attach(kernel, true);
  return kernel.terrainHeightGradientSum(float(planet.baseHeightM), float(planet.heightScale), offsetM, 0u);
}

void computeVertex(const CpuSurfaceJob& job, uint32_t index, glm::vec4* surface, glm::vec4* normals,
                   glm::vec4* attributes) {
  const ClipmapVertex& v = job.mesh->vertices[index];
  const float s = std::sin(v.theta);
  const float h2 = std::sin(0.5f * v.theta);
  const glm::vec3 offsetLocal =
      job.frame->camera.y * glm::vec3(s * std::cos(v.phi), s * std::sin(v.phi), -2.0f * h2 * h2);
  const glm::vec3 offsetPlanet = glm::mat3(job.frame->localToPlanet) * offsetLocal;
  const glm::vec4 h = heightGradient(job, offsetPlanet, job.ringSpacingM[v.ring]);
  surface[index] = glm::vec4(offsetLocal, h.x);
  normals[index] = glm::vec4(
      surfaceNormalCpu(h, glm::vec3(v.direction), glm::mat3(job.frame->localToPlanet), job.frame->camera.y), 0.0f);
  attributes[index] = surfaceAttributes(job, offsetPlanet, v);
}

}  // namespace

glm::vec3 surfaceNormalCpu(const glm::vec4& heightGradient, const glm::vec3& up, const glm::mat3& localToPlanet,
                           float radiusM) {
  const glm::vec3 gradientLocal = glm::vec3(heightGradient.y, heightGradient.z, heightGradient.w) * localToPlanet;
  const glm::vec3 tangent = gradientLocal - glm::dot(gradientLocal, up) * up;
  return glm::normalize(up - (radiusM / (radiusM + heightGradient.x)) * tangent);
}

void computeSurfaceCpu(const CpuSurfaceJob& job, unsigned threads, glm::vec4* surface, glm::vec4* normals,
                       glm::vec4* attributes) {
  const uint32_t total = job.vertexCount + 1;  // the range, then the pole
  const uint32_t pole = job.mesh->poleVertex();
  auto vertexOf = [&](uint32_t k) { return k == job.vertexCount ? pole : job.firstVertex + k; };
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = std::min<unsigned>(threads, total);
  std::vector<std::exception_ptr> errors(threads);
  auto work = [&](unsigned t) {
    try {
      // Interleaved blocks of 256 vertices: rings differ in cost (octave budgets), so
      // contiguous halves would not balance.
      for (uint32_t block = t * 256u; block < total; block += threads * 256u)
        for (uint32_t k = block; k < std::min(total, block + 256u); ++k)
          computeVertex(job, vertexOf(k), surface, normals, attributes);
    } catch (...) {
      errors[t] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

}  // namespace planet

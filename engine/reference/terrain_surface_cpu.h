// HeightSource::Cpu of the terrain pass (issue 6's comparison): what terrain_heights.comp writes
// for each clipmap vertex (terrain_vertex_surface.glsl), computed on the CPU instead, on several
// threads, for an upload into the same buffers. Heights and their gradients come from the CPU
// reference of the rebased float path (the shader's code compiled as C++: the heights equal
// terrainHeightRebased's), the rest follows terrain_vertex_surface.glsl line by line.
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "planet/clipmap_mesh.h"
#include "planet/planet_description.h"
#include "planet/terrain_rebase.h"
#include "shared/render_params.h"

namespace planet {

struct CpuSurfaceJob {
  const PlanetDescription* planet = nullptr;
  const OctaveTables* tables = nullptr;  // rebased at the frame's anchor
  const ClipmapMesh* mesh = nullptr;
  const gpu::FrameUniforms* frame = nullptr;  // the uniforms the shaders see this frame
  std::span<const double> ringSpacingM;       // per ring and the pole (0: every octave), as the RingBudgets
  float bandFrequency = 0.0f;                 // cycles per metre of the colour-band noise
  float regionalWeight = 0.0f;                // weight of its regional octaves (MaterialDescription::regionalNoise)
  uint32_t firstVertex = 0;                   // vertices firstVertex .. firstVertex + vertexCount − 1, and the pole
  uint32_t vertexCount = 0;
};

// Writes surface[i] (xyz: sea-sphere point − anchor, local frame; w: height), normals[i] (xyz:
// unit normal, local frame, from the height's analytic gradient) and attributes[i]
// (kRenderBindingAttributes) for every vertex of the job, indexed like the mesh. threads = 0:
// one per hardware thread.
void computeSurfaceCpu(const CpuSurfaceJob& job, unsigned threads, glm::vec4* surface, glm::vec4* normals,
                       glm::vec4* attributes);

// surfaceNormal of terrain_vertex_surface.glsl: the unit normal (local frame) of the displaced
// surface at a vertex with sphere normal `up` (local frame), from its height and gradient
// (heightGradient: height, then d/dx, d/dy, d/dz per metre in the planet frame) on the sphere of
// radius radiusM.
glm::vec3 surfaceNormalCpu(const glm::vec4& heightGradient, const glm::vec3& up, const glm::mat3& localToPlanet,
                           float radiusM);

}  // namespace planet

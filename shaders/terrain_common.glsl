// Declarations shared by the terrain pass's shaders: the bindings of shaders/shared/render_params.h.
#ifndef PLANET_TERRAIN_COMMON_GLSL
#define PLANET_TERRAIN_COMMON_GLSL

#include "shared/render_params.h"

layout(std140, set = 0, binding = kRenderBindingFrame) uniform Frame { FrameUniforms frame; };

struct MeshVertex {
  vec4 direction;  // unit direction in the local frame, w = 1
  vec4 polar;      // x: θ, y: φ (radians), z: ring (as uint bits), w: level (as uint bits)
};
layout(std430, set = 0, binding = kRenderBindingMesh) readonly buffer Mesh { MeshVertex mesh[]; };

// The sea's vertices are pulled toward the camera by this fraction of their distance, a few
// float ulps of reversed-Z depth, so that ground just below the surface never shows through it.
const float kWaterTowardCamera = 2.0e-6f;

#endif

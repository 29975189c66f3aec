// Declarations shared by the terrain pass's shaders: the bindings of shaders/shared/render_params.h.
#ifndef PLANET_TERRAIN_COMMON_GLSL
#define PLANET_TERRAIN_COMMON_GLSL

#include "shared/render_params.h"

layout(std140, set = 0, binding = kRenderBindingFrame) uniform Frame { FrameUniforms frame; };
// FrameUniforms again, as RGBA32F texels, for its arrays read at an index that is not a
// compile-time constant (a loop's counter, a pixel's patch level or table entry): lavapipe
// (Mesa 22.3) reads a uniform buffer at a variable offset lane by lane, a bounds-checked scalar
// load per lane and component through memory, and a texel fetch as one vector load per lane. At
// constant indices `frame` is one scalar load for all lanes and stays the way to read it.
layout(set = 0, binding = kRenderBindingFrameTexels) uniform samplerBuffer frameTexels;
// Element i of the array of FrameUniforms that starts at texel `first` (kFrameTexel*).
vec4 frameArray(uint first, uint i) { return texelFetch(frameTexels, int(first + i)); }

struct MeshVertex {
  vec4 direction;  // unit direction in the local frame, w = 1
  vec4 polar;      // x: θ, y: φ (radians), z: ring (as uint bits), w: level (as uint bits)
};
layout(std430, set = 0, binding = kRenderBindingMesh) readonly buffer Mesh { MeshVertex mesh[]; };

// The sea's vertices are pulled toward the camera by this fraction of their distance, a few
// float ulps of reversed-Z depth, so that ground just below the surface never shows through it.
const float kWaterTowardCamera = 2.0e-6f;

#endif

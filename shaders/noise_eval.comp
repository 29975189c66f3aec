#version 450
// Evaluates the noise described by the push constants at a buffer of points (planet noise,
// planet validate, planet bench noise), or the noise with its gradient. One invocation per point.
#extension GL_GOOGLE_include_directive : require

#include "shared/noise_params.h"

layout(local_size_x = kNoiseWorkgroupSize) in;

layout(push_constant) uniform Push { NoiseParams params; };

// The noise type and hash are also specialization constants: the host creates one pipeline
// per (type, hash, output) triple, so the shader compiler removes the branches on them. Lavapipe
// executes both sides of even a uniform branch under a mask, which cost 4x in throughput.
// Everything else (octaves, lacunarity, H, offset, gain, seed) stays a push constant.
layout(constant_id = 0) const uint kSpecNoiseType = 1u;
layout(constant_id = 1) const uint kSpecNoiseHash = 0u;
// 1: write vec4(value, d/dx, d/dy, d/dz) per point (common/noise_gradient.glsl) instead of the value.
layout(constant_id = 2) const uint kSpecGradient = 0u;

layout(std430, set = 0, binding = kNoiseBindingPoints) readonly buffer Points { vec4 points[]; };
layout(std430, set = 0, binding = kNoiseBindingValues) writeonly buffer Values { float values[]; };
// The same binding seen as one vec4 per point (the gradient variant; one 16-byte store).
layout(std430, set = 0, binding = kNoiseBindingValues) writeonly buffer Gradients { vec4 gradients[]; };
layout(std430, set = 0, binding = kNoiseBindingPermutation) readonly buffer Permutation { uint permutation[]; };

#define PERM(i) permutation[i]
// Point evaluation only walks octaves plainly (never rebased).
#define OCTAVE_REMAINDER(layer, i) vec4(0.0f)
#define OCTAVE_SHIFT(layer, i) uvec4(0u)
#include "common/noise.glsl"

void main() {
  uint index = params.firstIndex + gl_GlobalInvocationID.x;
  if (index >= params.count) return;
  vec3 p = points[index].xyz;
  NoiseParams specialized = params;
  specialized.type = kSpecNoiseType;
  specialized.hash = kSpecNoiseHash;
  if (kSpecGradient != 0u)
    gradients[index] = evaluateNoiseGradient(specialized, p);
  else
    values[index] = evaluateNoise(specialized, p);
}

#version 450
// Evaluates the shared ring functions (common/rings.glsl) at a list of queries, so that tests
// can hold the GPU against the CPU reference (engine/reference/ring_density.h). Not used to draw.
#extension GL_GOOGLE_include_directive : require

#include "shared/ring_params.h"

layout(local_size_x = kRingEvalWorkgroupSize) in;

layout(push_constant) uniform Push { RingEvalPush params; };

layout(std430, set = 0, binding = kRingEvalBindingParams) readonly buffer Params { RingParams ring; };
layout(std430, set = 0, binding = kRingEvalBindingQueries) readonly buffer Queries { vec4 queries[]; };
layout(std430, set = 0, binding = kRingEvalBindingResults) writeonly buffer Results { vec4 results[]; };

#include "common/rings.glsl"

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= params.count) return;
  vec4 q = queries[index];
  RingParams p = ring;
  if (params.mode == kRingEvalShadow) {
    results[index] = vec4(ringShadow(q.xyz, params.sun.xyz, p), ringPlanetShadow(q.xyz, params.sun.xyz, p), 0.0f, 0.0f);
  } else if (params.mode == kRingEvalSlant) {
    results[index] = vec4(ringSlantOpacity(q.x, q.y), 0.0f, 0.0f, 0.0f);
  } else {
    results[index] = ringSample(q.x, q.y, p);
  }
}

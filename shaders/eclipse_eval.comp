#version 450
// Evaluates the shared eclipse functions (common/eclipse.glsl) at a list of queries, so that tests
// can hold the GPU against the CPU reference (engine/reference/eclipse.h). Not used to draw.
#extension GL_GOOGLE_include_directive : require

#include "shared/eclipse_params.h"

layout(local_size_x = kEclipseEvalWorkgroupSize) in;

layout(push_constant) uniform Push { EclipseEvalPush params; };

layout(std430, set = 0, binding = kEclipseEvalBindingParams) readonly buffer Params { EclipseParams eclipse; };
layout(std430, set = 0, binding = kEclipseEvalBindingQueries) readonly buffer Queries { vec4 queries[]; };
layout(std430, set = 0, binding = kEclipseEvalBindingResults) writeonly buffer Results { vec4 results[]; };

#include "common/eclipse.glsl"

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= params.count) return;
  vec4 q = queries[index];
  if (params.mode == kEclipseEvalVisible) {
    EclipseParams e = eclipse;
    vec3 refracted;
    float visible = eclipseSunVisibleRefracted(q.xyz, params.sun.xyz, e, refracted);
    results[index] = vec4(visible, refracted);
  } else {
    results[index] = vec4(sunDiscCovered(q.x, q.y), 0.0f, 0.0f, 0.0f);
  }
}

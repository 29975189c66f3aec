#version 450
// Generates the star catalogue once (engine/render/star_pass.h): one invocation per star, the
// model in common/stars.glsl.
#extension GL_GOOGLE_include_directive : require

#include "shared/star_params.h"

layout(local_size_x = kStarWorkgroupSize) in;

layout(push_constant) uniform Push { StarGeneratePush params; };

layout(std430, set = 0, binding = kStarBindingCatalogue) writeonly buffer Catalogue { StarRecord stars[]; };

#include "common/stars.glsl"

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= params.count) return;
  stars[index] = starGenerate(index, params.count, params.seed, params.faintestMagnitude);
}

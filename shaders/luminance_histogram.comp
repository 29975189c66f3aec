#version 450
// Eye adaptation, first dispatch (issue 21, point 4): the luminance histogram of the composed
// HDR frame. Each 16 × 16 group counts its pixels into a histogram in shared memory, then adds
// its non-empty bins to the frame's. Integer counts: the result does not depend on the order
// the groups run in, so the same frame always gives the same histogram.
#extension GL_GOOGLE_include_directive : require

#include "common/definitions.glsl"
#include "shared/exposure_params.h"
#include "common/exposure.glsl"

layout(local_size_x = kExposureWorkgroupSize, local_size_y = kExposureWorkgroupSize) in;

layout(set = 0, binding = kExposureBindingColor, rgba16f) uniform readonly image2D color;
layout(set = 0, binding = kExposureBindingHistogram, std430) buffer Histogram { uint counts[]; };
layout(push_constant) uniform Push { ExposurePush push; };

shared uint groupCounts[kExposureBins];  // one bin per invocation (kExposureBins = 16 × 16)

void main() {
  uint i = gl_LocalInvocationIndex;
  groupCounts[i] = 0u;
  barrier();
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x < int(push.frame.x) && pixel.y < int(push.frame.y)) {
    vec3 c = imageLoad(color, pixel).rgb;
    atomicAdd(groupCounts[exposureBin(exposureLuminance(c.r, c.g, c.b))], 1u);
  }
  barrier();
  uint count = groupCounts[i];
  if (count > 0u) atomicAdd(counts[i], count);
}

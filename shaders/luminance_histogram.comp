#version 450
// Eye adaptation, first dispatch (issue 21, point 4): the luminance histogram of the composed
// HDR frame at half resolution: each invocation takes the mean luminance of a 2 × 2 block of
// pixels (a glint still counts, at a quarter of its pixel's value; the stars do not, and city
// lights count at their physical radiance: alpha gives their shares of the light), which
// quarters the atomic adds that dominate this pass on a CPU device. Each 16 × 16 group counts
// its blocks into a histogram in shared memory, then adds its non-empty bins to the frame's.
// Integer counts: the result does not depend on the order the groups run in, so the same frame
// always gives the same histogram.
#extension GL_GOOGLE_include_directive : require

#include "common/definitions.glsl"
#include "shared/exposure_params.h"
#include "common/exposure.glsl"

layout(local_size_x = kExposureWorkgroupSize, local_size_y = kExposureWorkgroupSize) in;

layout(set = 0, binding = kExposureBindingColor, rgba32f) uniform readonly image2D color;
layout(set = 0, binding = kExposureBindingHistogram, std430) buffer Histogram { uint counts[]; };
layout(push_constant) uniform Push { ExposurePush push; };

shared uint groupCounts[kExposureBins];  // one bin per invocation (kExposureBins = 16 × 16)

void main() {
  uint i = gl_LocalInvocationIndex;
  groupCounts[i] = 0u;
  barrier();
  ivec2 block = ivec2(gl_GlobalInvocationID.xy) * 2;
  ivec2 size = ivec2(push.frame.xy);
  if (block.x < size.x && block.y < size.y) {
    // The pixels of the block inside the frame, in the order the CPU reference adds them.
    float sum = 0.0f, count = 0.0f;
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        ivec2 pixel = block + ivec2(dx, dy);
        if (pixel.x < size.x && pixel.y < size.y) {
          vec4 c = imageLoad(color, pixel);
          sum += exposureSceneLuminance(c.r, c.g, c.b, c.a, push.frame.w);
          count += 1.0f;
        }
      }
    atomicAdd(groupCounts[exposureBin(sum / count)], 1u);
  }
  barrier();
  uint count = groupCounts[i];
  if (count > 0u) atomicAdd(counts[i], count);
}

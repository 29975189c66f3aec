#version 450
// Eye adaptation, second dispatch (issue 21, point 4): from the frame's histogram, the trimmed
// log-average luminance (of the pixels that are not black, those ranked between
// kExposureLowFraction and kExposureHighFraction), the exposure that maps it to the key, and the exposure
// applied: that target outright (planet render), or adapted toward it from the last frame's
// (the viewer). One invocation walks the 256 bins in order, as the CPU reference does
// (engine/render/exposure.cpp): a few microseconds, and no summation order to vary.
#extension GL_GOOGLE_include_directive : require

#include "common/definitions.glsl"
#include "shared/exposure_params.h"
#include "common/exposure.glsl"

layout(local_size_x = 1) in;

layout(set = 0, binding = kExposureBindingHistogram, std430) readonly buffer Histogram { uint counts[]; };
layout(set = 0, binding = kExposureBindingState, std430) buffer State { ExposureState state; };
layout(set = 0, binding = kExposureBindingReport, std430) writeonly buffer Report { ExposureState report; };
layout(push_constant) uniform Push { ExposurePush push; };

void main() {
  float total = 0.0f;
  for (uint bin = 1u; bin < kExposureBins; ++bin) total += float(counts[bin]);  // bin 0: black
  float low = total * kExposureLowFraction;
  float high = total * kExposureHighFraction;
  float below = 0.0f, weight = 0.0f, weightedLog2 = 0.0f;
  for (uint bin = 1u; bin < kExposureBins; ++bin)
    exposureAccumulate(bin, float(counts[bin]), low, high, below, weight, weightedLog2);
  float log2Luminance = weight > 0.0f ? weightedLog2 / weight : kExposureMinLog2;
  float target = exposureForLuminance(log2Luminance);
  float applied = adaptExposure(state.values.x, target, push.frame.z);
  state.values = vec4(applied, target, log2Luminance, weight);
  report.values = state.values;
}

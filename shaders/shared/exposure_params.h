// Eye adaptation (issue 21, point 4): the luminance histogram of the HDR frame and the exposure
// it gives (engine/render/luminance_pass.*, shaders/luminance_histogram.comp and
// shaders/luminance_exposure.comp; the arithmetic in shaders/common/exposure.glsl), shared by
// C++ and GLSL. The reasons for each number are in README.md, "Exposure".
#ifndef PLANET_SHARED_EXPOSURE_PARAMS_H
#define PLANET_SHARED_EXPOSURE_PARAMS_H

#include "shared/gpu_types.h"

GPU_NAMESPACE_BEGIN

// The histogram: bin 0 holds the pixels darker than 2^kExposureMinLog2 (black included); bins
// 1 .. kExposureBins − 1 are kExposureBinsPerStop to a stop from there up, the last one open
// above (the sun's disc).
GPU_CONST uint kExposureBins = 256u;
GPU_CONST float kExposureBinsPerStop = 8.0f;
GPU_CONST float kExposureMinLog2 = -20.0f;    // 1e-6 of the sun's irradiance: darker is black on any exposure
GPU_CONST uint kExposureWorkgroupSize = 16u;  // 16 × 16 blocks of 2 × 2 pixels per histogram group

// The part of the frame the exposure is measured on: black pixels (bin 0: space, the night sky
// between the stars, an airless body's sky) are not measured; of the others, ranked by
// luminance, those between these two fractions are: the darker part goes (deep shadow), and the
// top 2 % (the sun's disc, glints, bright stars). A frame with nothing lit takes the largest
// exposure.
GPU_CONST float kExposureLowFraction = 0.5f;
GPU_CONST float kExposureHighFraction = 0.98f;
// Target: the measured log-average luminance maps to this value before the curve (the tonemap's
// mid-grey: 0.18 through the filmic curve is 0.27 linear, 0.55 sRGB).
GPU_CONST float kExposureKey = 0.18f;
// Clamps on the exposure: the smallest keeps a bright scene (snow at noon) from turning dim; the
// largest keeps a night from being lifted into grey (README.md, "Exposure").
GPU_CONST float kExposureMin = 1.0f;
GPU_CONST float kExposureMax = 64.0f;
// Adaptation time constants of the viewer (seconds): the exposure rises (toward a darker scene)
// slower than it falls (toward a brighter one), as the eye's does.
GPU_CONST float kExposureRiseTimeS = 1.5f;
GPU_CONST float kExposureFallTimeS = 0.4f;

// Bindings of both dispatches (set 0).
GPU_CONST uint kExposureBindingColor = 0u;      // image2D rgba16f: the composed HDR frame (read)
GPU_CONST uint kExposureBindingHistogram = 1u;  // uint[kExposureBins]: pixel counts
GPU_CONST uint kExposureBindingState = 2u;      // ExposureState: the exposure the tonemap applies, carried over frames
GPU_CONST uint kExposureBindingReport = 3u;     // ExposureState: a copy per frame slot, read by the host

struct ExposureState {
  vec4 values;  // x: exposure applied this frame, y: this frame's target exposure, z: log2 of the measured
                // luminance, w: pixels measured (between the two fractions)
};
GPU_ASSERT_SIZE(ExposureState, 16)

struct ExposurePush {
  vec4 frame;  // x: width, y: height (pixels), z: seconds since the last adapted frame (< 0: take the target
               // outright), w: unused
};
GPU_ASSERT_SIZE(ExposurePush, 16)

GPU_NAMESPACE_END

#endif

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
// 2^−32 of the sun's irradiance (3e-5 cd/m², a tenth of the natural night sky's): darker is black on any
// exposure. The last bin opens at 2^0: the sun's disc and glints.
GPU_CONST float kExposureMinLog2 = -32.0f;
GPU_CONST uint kExposureWorkgroupSize = 16u;  // 16 × 16 blocks of 2 × 2 pixels per histogram group

// The part of the frame the exposure is measured on: black pixels (bin 0: space, the night sky
// between the stars, an airless body's sky) are not measured; of the others, ranked by
// luminance, those between these two fractions are: the darker part goes (deep shadow), and the
// top 2 % (the sun's disc, glints, bright stars). A frame with nothing lit takes the largest
// exposure.
GPU_CONST float kExposureLowFraction = 0.5f;
GPU_CONST float kExposureHighFraction = 0.98f;
// Target: the measured log-average luminance maps to this value before the curve (the tonemap's
// mid-grey: 0.18 through the filmic curve is 0.27 linear, 0.55 sRGB) in daylight, from
// kExposureFullKeyCdM2 up. Below, the key falls kExposureKeySlope of a stop for each stop the scene
// is darker, as the eye and a photograph keep a dark scene dark: the sky at the end of civil
// twilight (about 1 cd/m²) 0.6 of a stop lower on the display each stop, reaching black at the
// natural night sky (2e-4 cd/m²; README.md, "Exposure", has the figures).
GPU_CONST float kExposureKey = 0.18f;
GPU_CONST float kExposureFullKeyCdM2 = 1000.0f;
GPU_CONST float kExposureKeySlope = 0.25f;
// The frame's unit in cd/m²: HDR radiance 1 (per steradian, for the sun's irradiance above the
// air of 1) is the sun's illuminance, 1.28e5 lux, spread over a steradian.
GPU_CONST float kExposureSunCdM2 = 1.28e5f;
// Clamps on the exposure: the smallest keeps a bright scene (snow at noon) from turning dim; the
// largest, 2^21, is where the key meets the natural night sky's luminance (2e-4 cd/m²; Earth's
// airglow gives about half of it, common/atmosphere.glsl): a darker frame is not lifted further, and a
// frame with nothing lit takes it.
GPU_CONST float kExposureMin = 1.0f;
GPU_CONST float kExposureMax = 2097152.0f;
// Stars under auto exposure are shown as at exposure 64, whatever the frame's: their drawn flux is
// far above a real star's (so that one shows on a pixel), and a star the eye sees at all
// (common/star_visibility.glsl decides which) is a point of light whatever it has adapted to.
// The HDR frame's alpha tells the measurement and the tonemap which share of a pixel's light is
// the stars' (exposureStarShare): a pixel the last compose wrote holds kExposureComposedAlpha + that
// share; one it did not (outside its region: no air there) holds what was drawn, the stars'
// negated relative flux (stars.frag; all of its light is theirs) or 0 .. 1 on geometry (none).
// A ring drawn after it (the camera's body's, premultiplied over: α + dst α (1 − α)) leaves
// 1 .. 2 where it covers much: the stars seen through it take the frame's exposure.
GPU_CONST float kExposureStarExposure = 64.0f;
GPU_CONST float kExposureComposedAlpha = 2.0f;
// City lights likewise (common/city_lights.glsl): the preset's gain draws them 3·10⁴ times over
// their physical radiance, so that the fixed default exposure (10) shows them as a night
// photograph does; under the exposure a night sky sets (10⁵ .. 2²¹) they blew out white. So under
// auto exposure their share of a pixel's light is shown as at the smaller of the frame's exposure
// and kExposureLightsExposure, and the measurement counts it at its physical radiance
// (ExposurePush::frame.w): the eye adapts to the light around it, and sees a city's lamps, points
// far brighter than the pixel's mean, as bright whatever it adapted to. 64 puts a lit city core
// (60 nW cm⁻² sr⁻¹ times the gain) at 2.3 before the curve: orange with a yellow-white heart, as
// photographs from the air and from the ISS show cities. The terrain writes kExposureLightsAlpha
// plus the lights' share of its pixel's light where they shine (1 elsewhere); each compose passes
// on the share of what it composed. The sea blended over them before a compose loses the mark
// (the compose then writes its own: the pixel takes the frame's exposure); blended after the last
// compose (an airless body's sea, the camera's body's ring) the alpha may read as another mark,
// as it may for the stars.
GPU_CONST float kExposureLightsExposure = 64.0f;
GPU_CONST float kExposureLightsAlpha = 4.0f;
// Adaptation time constants of the viewer (seconds): the exposure rises (toward a darker scene)
// slower than it falls (toward a brighter one), as the eye's does.
GPU_CONST float kExposureRiseTimeS = 1.5f;
GPU_CONST float kExposureFallTimeS = 0.4f;

// Bindings of both dispatches (set 0).
GPU_CONST uint kExposureBindingColor = 0u;      // image2D rgba32f: the composed HDR frame (read)
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
               // outright), w: 1 / the city lights' gain (their drawn light times this is their physical light)
};
GPU_ASSERT_SIZE(ExposurePush, 16)

GPU_NAMESPACE_END

#endif

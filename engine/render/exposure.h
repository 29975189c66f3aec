// Eye adaptation (issue 21, point 4), on the CPU: the reference of what the luminance pass
// computes on the GPU (luminance_pass.h), from the same source (shaders/common/exposure.glsl),
// and the viewer's adaptation step, for tests and for anyone checking a frame's exposure.
//
// The method: a histogram of log2 luminance (8 bins a stop) of the composed HDR frame at half
// resolution (2 × 2 means), less the stars' light, with the city lights' at their physical
// radiance (the shares alpha gives); black
// pixels (below 2^−32: space, the night sky between the stars) are not measured; of the rest,
// the mean log2 luminance of those ranked between 50 % and 98 % (the darker half goes: deep
// shadow; the top 2 %: the sun's disc, glints); the exposure that maps that luminance to the key
// (0.18 in daylight, lower for darker scenes), clamped (kExposureMin, kExposureMax). The reasons
// are in README.md, "Exposure".
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "shared/exposure_params.h"

namespace planet {

using ExposureHistogram = std::array<uint32_t, gpu::kExposureBins>;

// What the luminance pass measured and applied in one frame.
struct ExposureReport {
  double exposure = 0.0;       // applied (the target, or adapted toward it in the viewer)
  double target = 0.0;         // this frame's own exposure
  double log2Luminance = 0.0;  // the trimmed log-average luminance, log2
  double pixels = 0.0;         // pixels it was measured on
};

// The histogram of a width × height HDR frame (rgb linear, alpha which share of the light is the
// stars' or the city lights', shared/exposure_params.h; rows top first), as the GPU bins it: one
// count per 2 × 2 block of pixels (their mean luminance; the blocks at the right and bottom edges
// of an odd size hold the pixels inside the frame). `lightsGain` is the city lights' (the
// preset's `[lights] gain`): their light counts divided by it, at its physical radiance.
ExposureHistogram exposureHistogram(std::span<const glm::vec4> hdr, uint32_t width, uint32_t height,
                                    double lightsGain = 1.0);
// What the measurement multiplies city lights' drawn light by: 1 / their gain (1 for a gain of 0,
// which draws none).
float exposureLightsPhysical(double lightsGain);
// The scale auto exposure gives a pixel of HDR alpha `alpha` before the tonemap's curve, for the
// frame's `exposure`: the stars' and the city lights' shares of it at exposures of their own
// (shaders/common/exposure.glsl, exposureDisplayScale).
double exposureDisplayScale(double exposure, float alpha);
// The trimmed log-average and the exposure for it (no adaptation: exposure == target).
ExposureReport exposureFromHistogram(const ExposureHistogram& histogram);
// One adaptation step of `stepS` seconds from `current` toward `target` (shaders/common/exposure.glsl).
double adaptExposure(double current, double target, double stepS);

}  // namespace planet

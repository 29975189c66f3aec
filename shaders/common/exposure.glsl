// Eye adaptation (issue 21, point 4), written once for GLSL (shaders/luminance_histogram.comp,
// shaders/luminance_exposure.comp) and C++ (engine/render/exposure.cpp, the CPU reference):
// which histogram bin a pixel falls in, how a bin counts toward the trimmed log-average, the
// exposure that puts that average at the key, and the viewer's adaptation toward it. The
// constants are in shared/exposure_params.h. The C++ side provides log2 and exp2 beside the
// builtins of definitions.h.
#ifndef PLANET_COMMON_EXPOSURE_GLSL
#define PLANET_COMMON_EXPOSURE_GLSL

// Rec. 709 luminance of linear RGB (the HDR target's primaries).
real exposureLuminance(real r, real g, real b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

// The share an HDR alpha of mark + share (0 .. 1) holds; 0 for an alpha outside that range.
real exposureMarkedShare(real alpha, real mark) {
  return alpha >= mark && alpha <= mark + 1.0f ? alpha - mark : 0.0f;
}

// The share of a pixel's light that is the stars', from the HDR frame's alpha (shared/
// exposure_params.h says how it is written).
real exposureStarShare(real alpha) {
  if (alpha < 0.0f) return 1.0f;
  return exposureMarkedShare(alpha, kExposureComposedAlpha);
}

// The share of a pixel's light that is city lights', from the same alpha.
real exposureLightsShare(real alpha) { return exposureMarkedShare(alpha, kExposureLightsAlpha); }

// The alpha that marks a pixel whose light is `lightsShare` city lights' (0 .. 1): `otherwise`
// where it has none.
real exposureLightsMark(real lightsShare, real otherwise) {
  return lightsShare > 0.0f ? kExposureLightsAlpha + min(lightsShare, 1.0f) : otherwise;
}

// The luminance the exposure is measured on: the pixel's, less the stars' share of it, with the
// city lights' share at their physical radiance (lightsPhysical: 1 / their gain).
real exposureSceneLuminance(real r, real g, real b, real alpha, real lightsPhysical) {
  real lights = exposureLightsShare(alpha);
  return exposureLuminance(r, g, b) * (1.0f - exposureStarShare(alpha) - lights * (1.0f - lightsPhysical));
}

// The scale auto exposure gives a pixel before the tonemap's curve: the frame's `exposure`, the
// stars' share of its light as at kExposureStarExposure, the city lights' as at the smaller of
// the frame's and kExposureLightsExposure.
real exposureDisplayScale(real exposure, real alpha) {
  real stars = exposureStarShare(alpha);
  real lights = exposureLightsShare(alpha);
  return exposure * (1.0f - stars - lights) + kExposureStarExposure * stars +
         min(exposure, kExposureLightsExposure) * lights;
}

// The histogram bin of a luminance: 0 below 2^kExposureMinLog2 (and for NaN), then
// kExposureBinsPerStop bins a stop, the last one open above.
uint exposureBin(real luminance) {
  if (!(luminance >= exp2(kExposureMinLog2))) return 0u;
  real x = (log2(luminance) - kExposureMinLog2) * kExposureBinsPerStop;
  return uint(min(x, real(kExposureBins - 2u))) + 1u;
}

// log2 of the luminance a bin stands for: its middle (bin 0, black, is not measured).
real exposureBinLog2(uint bin) {
  return kExposureMinLog2 + (real(bin) - 0.5f) / kExposureBinsPerStop;
}

// Adds bin `bin` with `count` pixels to the trimmed average, the bins taken in increasing
// order: `below` is the pixels of the bins before it; only the pixels whose rank lies in
// [low, high) count (a bin that straddles either bound counts in part).
void exposureAccumulate(uint bin, real count, real low, real high, INOUT(real) below, INOUT(real) weight,
                        INOUT(real) weightedLog2) {
  real share = clamp(below + count, low, high) - clamp(below, low, high);
  weight += share;
  weightedLog2 += share * exposureBinLog2(bin);
  below += count;
}

// log2 of the key for a measured luminance 2^log2Luminance (the frame's units): kExposureKey from
// kExposureFullKeyCdM2 up, kExposureKeySlope of a stop lower for each stop below.
real exposureKeyLog2(real log2Luminance) {
  real stopsBelow = max(log2(kExposureFullKeyCdM2 / kExposureSunCdM2) - log2Luminance, 0.0f);
  return log2(kExposureKey) - kExposureKeySlope * stopsBelow;
}

// The exposure that maps the measured luminance 2^log2Luminance to its key, within the clamps.
real exposureForLuminance(real log2Luminance) {
  return clamp(exp2(exposureKeyLog2(log2Luminance) - log2Luminance), kExposureMin, kExposureMax);
}

// The viewer's adaptation: after `stepS` seconds the exposure has moved from `current` toward
// `target` by 1 − e^(−stepS / τ) of the way in stops, τ the rise or fall time (rising: the scene
// got darker). Steps of any size compose: two steps of stepS / 2 land where one of stepS does,
// so the adaptation does not depend on the frame rate. A negative step or no current exposure
// (the first frame) takes the target outright.
real adaptExposure(real current, real target, real stepS) {
  if (!(stepS >= 0.0f) || !(current > 0.0f)) return target;
  real tau = target > current ? kExposureRiseTimeS : kExposureFallTimeS;
  real keep = exp(-stepS / tau);
  return exp2(log2(target) + (log2(current) - log2(target)) * keep);
}

#endif

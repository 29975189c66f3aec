// Whether the eye sees a star against the sky in front of it (issue 21, point 4), written once
// for GLSL (sky.comp's compose fades each star with it) and C++ (engine/render/star_pass.cpp, for
// the tests and `starLimitingMagnitude`). The C++ side provides log2 beside the builtins of
// definitions.h; the constants are in shared/star_params.h.
//
// The threshold is Hecht's law as Schaefer (1990, "Telescopic limiting magnitudes", PASP 102)
// fits Blackwell's (1946) measurements of the naked eye: a point source shows against a
// background of luminance B when its illuminance exceeds I = c1 (1 + sqrt(c2 B))², with B in
// nanolamberts and I in foot-candles; rod vision (c1 = 10^−9.8, c2 = 10^−1.9) below 1500 nL
// (4.8e-3 cd/m²), cone vision (c1 = 10^−8.35, c2 = 10^−5.9) above. It gives magnitude 6.5 under a
// dark sky of 2e-4 cd/m², about 3.4 against the zenith at the end of civil twilight (sun 6° down)
// and no star at all by day. The renderer's stars are far brighter on the display than real ones
// (so that they show at a night's exposure); this decides which of them show, from their
// magnitude and the sky's radiance, whatever the exposure: the eye loses a star against the
// sky's brightness, not against what it has adapted to.
#ifndef PLANET_COMMON_STAR_VISIBILITY_GLSL
#define PLANET_COMMON_STAR_VISIBILITY_GLSL

// The least illuminance (lux) of a point source the eye sees against a sky of HDR luminance
// `skyLuminance` (the frame's units: the sun's irradiance above the air is 1).
real starThresholdLux(real skyLuminance) {
  real nanolamberts = max(skyLuminance, 0.0f) * kStarSunLux / kStarNanolambertCdM2;
  bool rods = nanolamberts < 1500.0f;
  real c1 = rods ? 1.58489e-10f : 4.46684e-9f;  // 10^−9.8, 10^−8.35
  real c2 = rods ? 1.25893e-2f : 1.25893e-6f;   // 10^−1.9, 10^−5.9
  real root = 1.0f + sqrt(c2 * nanolamberts);
  return c1 * root * root * kStarLuxPerFootCandle;
}

// The faintest magnitude the eye sees against a sky of HDR luminance `skyLuminance`.
real starLimitingMagnitude(real skyLuminance) {
  return -2.5f * 0.30103f * log2(starThresholdLux(skyLuminance) / kStarMagnitudeZeroLux);  // −2.5 log10
}

// The share of a star's light that shows: 0 below the threshold, 1 above, over ±0.5 magnitude
// (smoothstep). `relativeFlux` is 10^(−0.4 m) (1 at magnitude 0) as it reaches the eye, after
// the air's transmittance.
real starVisibleShare(real relativeFlux, real skyLuminance) {
  real stops = log2(max(relativeFlux * kStarMagnitudeZeroLux, 1.0e-30f) / starThresholdLux(skyLuminance));
  real t = clamp((stops + kStarFadeStops) / (2.0f * kStarFadeStops), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

#endif

#version 450
// A star's sprite: each pixel gets the part of the star's Gaussian image that falls on its
// square (the Gaussian integrated over the pixel, separably in x and y), added (blend ONE, ONE)
// to the HDR colour target, so the pixels of a star add up to its flux wherever it lies between
// pixel centres. Alpha gets the star's relative flux 10^(−0.4 m), negated, at each of its pixels
// (added up where stars overlap; the target is cleared to 0): the sky's compose fades each star
// by its magnitude against the sky in front of it (common/star_visibility.glsl), and the sign
// tells the stars' light from geometry's (alpha 0 .. 1) to auto exposure where no compose runs
// (shared/exposure_params.h).
#extension GL_GOOGLE_include_directive : require

#include "shared/star_params.h"

layout(location = 0) flat in vec3 inFlux;
layout(location = 1) flat in float inSize;
layout(location = 2) flat in float inSigma;
layout(location = 3) flat in float inRelativeFlux;

layout(location = 0) out vec4 outColor;

// erf(x) to 1.5e-7 (Abramowitz & Stegun 7.1.26).
float erfApprox(float x) {
  float a = abs(x);
  float t = 1.0f / (1.0f + 0.3275911f * a);
  float poly = ((((1.061405429f * t - 1.453152027f) * t + 1.421413741f) * t - 0.284496736f) * t + 0.254829592f) * t;
  float e = 1.0f - poly * exp(-a * a);
  return x < 0.0f ? -e : e;
}

// Share of a unit Gaussian (standard deviation sigma) between d − 0.5 and d + 0.5.
float pixelShare(float d, float sigma) {
  float k = 0.70710678f / sigma;  // 1 / (σ √2)
  return 0.5f * (erfApprox((d + 0.5f) * k) - erfApprox((d - 0.5f) * k));
}

void main() {
  float w = 1.0f;
  if (inSigma > 0.0f) {
    // This pixel's centre relative to the star, in pixels.
    vec2 d = (gl_PointCoord - vec2(0.5f)) * inSize;
    w = pixelShare(d.x, inSigma) * pixelShare(d.y, inSigma);
  }
  outColor = vec4(inFlux * w, -inRelativeFlux);
}

// The colouring schemes of seed 000 (Linda 2007, §4.7; seed digest 000-linda.md §2.2) and seed
// 004's polar caps (Diplomarbeit §4.1.4; digest 004 §3.5), written once in the GLSL/C++ common
// subset (definitions.glsl): terrain.frag colours the ground with them, and
// engine/reference/color_schemes_cpu.cpp compiles them as C++ for the tests.
//
// Every scheme maps a few control variables to a colour by linear interpolation (the seed's
// Table 7) or a Catmull-Rom spline (its Table 8, after Ebert et al.):
//   altitude a      metres above sea level, as a ramp t = clamp(a / snow line, 0, 1) (the seed
//                   normalises by the planet's own altitude range, which a per-pixel shader does
//                   not know; the snow line is the preset's top of the ramp instead)
//   noise n         the colour noise in [-1, 1] (schemeNoise): 3D fBm at the point on the sphere
//   latitude        |latitude| / 90°, 0 at the equator and 1 at the poles
//   slope           the angle between the surface normal and the vertical
// A zone edge is perturbed (the seed's Table 10) by adding perturbation · n to its control
// variable: perturbation × the snow line for heights, perturbation × 20° for latitudes.
//
// Include after noise.glsl (its simplexNoise and kNoiseHashFast); the includer provides
// SchemeParams (shared/scheme_params.h), and in C++ asin and acos.
#ifndef PLANET_COMMON_COLOR_SCHEMES_GLSL
#define PLANET_COMMON_COLOR_SCHEMES_GLSL

#include "common/definitions.glsl"

SHARED_CONST uint kSchemeNoiseSeed = 0x6c8e9cf5u;  // the colour noise's lattice seed (its own octaves)
// The normalised fBm rarely leaves ±0.5; this gain spreads it so that the schemes use their
// whole ramps (measured over the sphere, ColourNoiseIsDeterministicSpreadAndFadesWithThePixel:
// |n| > 0.5 on about 30 % of it, clamped to ±1 on a few per cent).
SHARED_CONST real kSchemeNoiseGain = 2.0f;
SHARED_CONST real kSchemeLatitudePerturbation = 0.22222222f;  // 20° of latitude, in units of 90°

vec3 schemeMix(vec3 a, vec3 b, real t) { return a + (b - a) * t; }

vec3 schemePaletteColor(IN(SchemeParams) s, uint i) {
  return vec3(s.palette[i].x, s.palette[i].y, s.palette[i].z);
}

// The colour noise at unit direction `direction` (planet frame): octave i has
// cellsPerRadius · 2^i cells per planet radius and weight 2^−i (seed 000, Table 4), and fades out
// (toward its mean, 0) where its wavelength comes within four pixels (footprintRadii: the
// pixel's size in planet radii), so it never aliases; the sum is divided by the sum of all the
// weights (~2), scaled by kSchemeNoiseGain and clamped to [-1, 1]. The first two octaves carry
// three quarters of it, so it keeps most of its contrast wherever they show (from orbit too).
real schemeNoise(vec3 direction, real cellsPerRadius, real footprintRadii) {
  real sum = 0.0f;
  real weight = 1.0f;
  real cells = cellsPerRadius;
  for (uint i = 0u; i < kSchemeNoiseOctaves; ++i) {
    real fade = clamp(1.0f / (2.0f * cells * max(footprintRadii, 1e-12f)) - 1.0f, 0.0f, 1.0f);
    if (fade <= 0.0f) break;
    sum += fade * weight * simplexNoise(direction * cells, uvec3(0u, 0u, 0u), kNoiseHashFast, kSchemeNoiseSeed + i);
    weight *= 0.5f;
    cells *= 2.0f;
  }
  // 1 + 1/2 + ... + 1/128
  return clamp(kSchemeNoiseGain * sum / 1.9921875f, -1.0f, 1.0f);
}

// Seed 000's Altitude Based scheme (#1): three colours, piecewise linear over t in [0, 1].
vec3 schemeRamp3(vec3 c0, vec3 c1, vec3 c2, real t) {
  return t < 0.5f ? schemeMix(c0, c1, 2.0f * t) : schemeMix(c1, c2, 2.0f * t - 1.0f);
}

// Four colours (lowlands, highlands, mountains, snowy tops) at t = 0, 1/3, 2/3, 1.
vec3 schemeRamp4(IN(SchemeParams) s, uint first, real t) {
  real x = clamp(t, 0.0f, 1.0f) * 3.0f;
  uint i = uint(min(floor(x), 2.0f));
  return schemeMix(schemePaletteColor(s, first + i), schemePaletteColor(s, first + i + 1u), x - real(i));
}

// A Catmull-Rom spline through the five palette colours from `first` at x = 0, 1/4, 1/2, 3/4, 1
// (seed 000, Table 8; the end knots repeated so the curve passes through all five), clamped to
// [0, 1] where it overshoots.
vec3 schemeSpline5(IN(SchemeParams) s, uint first, real x) {
  real scaled = clamp(x, 0.0f, 1.0f) * 4.0f;
  uint i = uint(min(floor(scaled), 3.0f));
  real u = scaled - real(i);
  vec3 p0 = schemePaletteColor(s, first + (i > 0u ? i - 1u : 0u));
  vec3 p1 = schemePaletteColor(s, first + i);
  vec3 p2 = schemePaletteColor(s, first + i + 1u);
  vec3 p3 = schemePaletteColor(s, first + min(i + 2u, 4u));
  vec3 c = p1 * 2.0f + (p2 - p0) * u + (p0 * 2.0f - p1 * 5.0f + p2 * 4.0f - p3) * (u * u) +
           (p1 * 3.0f - p0 - p2 * 3.0f + p3) * (u * u * u);
  c = c * 0.5f;
  return vec3(clamp(c.x, 0.0f, 1.0f), clamp(c.y, 0.0f, 1.0f), clamp(c.z, 0.0f, 1.0f));
}

// |latitude| / 90° from sin(latitude).
real schemeLatitude(real sinLatitude) { return asin(clamp(abs(sinLatitude), 0.0f, 1.0f)) * 0.63661977f; }

// Ground above sea level (and the sea floor of a dry body) in scheme s.shape.x. altitude: metres
// above sea level; slopeCosine: cos of the slope angle (normal · vertical); noise: schemeNoise;
// edgeM: how many metres of height moon_like's mare shore blends over (the pixel's height change).
vec3 schemeColor(IN(SchemeParams) s, real altitude, real slopeCosine, real sinLatitude, real noise, real edgeM) {
  uint scheme = uint(s.shape.x);
  real snowLine = max(s.shape.y, 1.0f);
  real perturbation = s.shape.z;
  real ramp = clamp(altitude / snowLine, 0.0f, 1.0f);
  real mixNoise = clamp(0.5f + 0.5f * noise, 0.0f, 1.0f);
  vec3 c0 = schemePaletteColor(s, 0u);
  vec3 c1 = schemePaletteColor(s, 1u);
  if (scheme == kSchemeAltitudePerturbed) {
    // #2: the altitude moved by the noise, so the zone edges (the snow line) wander.
    real perturbed = clamp((altitude + perturbation * snowLine * noise) / snowLine, 0.0f, 1.0f);
    return schemeRamp3(c0, c1, schemePaletteColor(s, 2u), perturbed);
  }
  if (scheme == kSchemeNoise) return schemeMix(c0, c1, mixNoise);  // #3: green <-> brown by n in [0, 1]
  if (scheme == kSchemeAltitudeNoise)  // #4: each set of four by altitude, the two blended by n
    return schemeMix(schemeRamp4(s, 0u, ramp), schemeRamp4(s, 4u, ramp), mixNoise);
  if (scheme == kSchemeTurbulence) return schemeMix(c0, c1, abs(noise));  // #5: black -> red by |n|
  if (scheme == kSchemeEarthLike) {
    // #6: splines A and B of the perturbed latitude blended by n, then toward the mountain
    // colours (C and D, blended by n) by altitude.
    real latitude = clamp(schemeLatitude(sinLatitude) + kSchemeLatitudePerturbation * perturbation * noise, 0.0f, 1.0f);
    vec3 zones = schemeMix(schemeSpline5(s, 0u, latitude), schemeSpline5(s, 5u, latitude), mixNoise);
    vec3 mountains = schemeMix(schemePaletteColor(s, 10u), schemePaletteColor(s, 11u), mixNoise);
    return schemeMix(zones, mountains, ramp);
  }
  if (scheme == kSchemeGradient) {
    // #7: flat -> steep, linear in the slope angle up to the rock slope.
    real angle = acos(clamp(slopeCosine, -1.0f, 1.0f));
    return schemeMix(c0, c1, clamp(angle / max(s.shape.w, 1e-3f), 0.0f, 1.0f));
  }
  if (scheme == kSchemeMoonLike) {
    // #8: the seed's water sphere as maria: below sea level two dark greys blended by n, above
    // it brighter greys by altitude; the shore blends over edgeM.
    vec3 mare = schemeMix(c0, c1, mixNoise);
    vec3 land = schemeMix(schemePaletteColor(s, 2u), schemePaletteColor(s, 3u), ramp);
    return schemeMix(mare, land, clamp(0.5f + altitude / max(edgeM, 1e-3f), 0.0f, 1.0f));
  }
  return schemeRamp3(c0, c1, schemePaletteColor(s, 2u), ramp);  // #1 altitude
}

// Seed 004's polar caps: how much of the ground (or sea) is ice, 1 poleward of the caps'
// latitude; the edge moves with the noise (perturbation × 20°, seed 004's proposal of a frayed
// boundary instead of its straight polar circle) and is antialiased over `edgeLatitude` (|latitude|
// / 90° per pixel). 0 without caps.
real schemePolarCap(IN(SchemeParams) s, real sinLatitude, real noise, real edgeLatitude) {
  if (s.noise.y < 0.5f) return 0.0f;
  real capLatitude = s.noise.w * 0.63661977f;
  real latitude = schemeLatitude(sinLatitude) + kSchemeLatitudePerturbation * s.shape.z * noise;
  real edge = max(edgeLatitude, 1e-6f);
  return clamp(0.5f + (latitude - capLatitude) / edge, 0.0f, 1.0f);
}

#endif

// City lights on the night side (issue 14, point 2): where a planet's land is lit at night and
// how brightly, as functions of the point alone (DESIGN.md "Everything per point"), shared by
// terrain.frag and the CPU (engine/reference/city_lights_cpu.cpp compiles it as C++ for tests).
//
// Where people settle (lightsHabitability): low ground (few cities above ~2 km), gentle slopes,
// a mild climate (mean annual temperature above about 0 °C: no lights on ice or tundra) and water
// (moist enough to farm, or a coast or a valley floor: the Nile's ribbon through the desert).
// Coasts and valley floors are settled about twice as densely as the land between (ports,
// rivers). terrain.frag finds them in the relief cube's coarse mip levels: a coast where the
// ground within ~80 km averages below sea level, a valley floor where the ground lies well below
// that average (issue 10's gullies join into valleys; there is no drainage map to follow).
// Which of that land is lit (lightsRadiance): settled regions (noise at ~2,000 km: peopled
// plains and empty ones) times the habitability, times a lognormal factor of metropolitan size,
// give the chance c that a point is lit; cities
// are where an fBm of kLightsCityOctaves octaves (a metropolis down to towns) exceeds the value
// it exceeds with probability c, so a larger chance grows more and larger cities, and a city's
// core is brighter than its suburbs. Octaves narrower than about two pixels fade out and the sum
// is renormalised (its spread, hence the lit share, stays c); once the largest octave is below
// two pixels the pixel shows the expected value, c times the mean brightness of lit ground, so
// from orbit a pixel shows the light it covers on average and nothing sparkles.
// Dusk (lightsDuskFade): lights come on through civil twilight, all of them once the sun is 6°
// below the horizon, none while it is up.
//
// Include after noise.glsl (its simplexNoise and kNoiseHashFast); the includer provides
// LightsParams (shared/lights_params.h), and in C++ log.
#ifndef PLANET_COMMON_CITY_LIGHTS_GLSL
#define PLANET_COMMON_CITY_LIGHTS_GLSL

#include "common/definitions.glsl"

// Regions settled densely or sparsely: one octave this long.
SHARED_CONST real kLightsRegionWavelengthM = 2.0e6f;
// Spread (standard deviation) of one octave of simplexNoise over the sphere, which the cities'
// threshold is set from (measured: CityLightsCpu.CityNoiseSpreadIsTheConstant).
SHARED_CONST real kLightsNoiseSigma = 0.38f;
// Mean brightness (0 .. 1) of lit ground: the core profile below averaged over the lit area
// (measured: CityLightsCpu.FarPixelsShowTheMeanOfTheNearOnes).
SHARED_CONST real kLightsMeanProfile = 0.5f;
// Mean of the streets' brightness factor 0.3 + 0.7 · step(−σ, σ, m) over a symmetric m: 0.65.
SHARED_CONST real kLightsStreetMean = 0.65f;
// sin(−6°): civil twilight's end.
SHARED_CONST real kLightsFullBelowSinElevation = -0.10452846f;

real lightsStep(real edge0, real edge1, real x) {
  real t = clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// 0 with the sun up (sinSunElevation >= 0) .. 1 from 6° below the horizon, never rising as the
// sun rises.
real lightsDuskFade(real sinSunElevation) {
  return 1.0f - lightsStep(kLightsFullBelowSinElevation, 0.0f, sinSunElevation);
}

// How settled land can be, 0 .. 1. altitudeM above sea level; slope = 1 − cos of the slope angle;
// temperatureC the mean annual temperature; moisture 0 (desert) .. 1 (rainforest); coast and
// valley 0 .. 1 (how near a coast, how much of a valley floor).
real lightsHabitability(real altitudeM, real slope, real temperatureC, real moisture, real coast, real valley) {
  real gentle = 1.0f - lightsStep(0.01f, 0.05f, slope);  // 8° .. 18°
  real low = 1.0f - lightsStep(500.0f, 2500.0f, altitudeM);
  real mild = lightsStep(-2.0f, 4.0f, temperatureC);
  real water = max(coast, valley);
  real watered = max(lightsStep(0.15f, 0.4f, moisture), water);
  return gentle * low * mild * watered * (0.45f + 0.55f * water);
}

// The lights' value exceeded with probability `chance` by a normal variable of spread sigma
// (the logistic approximation of the probit: Φ(x) ≈ 1 / (1 + e^(−1.702 x))).
real lightsThreshold(real chance, real sigma) {
  real c = clamp(chance, 1.0e-4f, 0.9999f);
  return sigma * log((1.0f - c) / c) / 1.702f;
}

// Emitted radiance factor (0 .. 1, times LightsParams::radiance) at unit direction `direction`
// (planet frame) of ground with habitability `habitability`, for a pixel footprintRadii planet
// radii wide.
real lightsCover(IN(LightsParams) p, vec3 direction, real habitability, real footprintRadii) {
  if (habitability <= 0.0f || p.radiance.w <= 0.0f) return 0.0f;
  real region = simplexNoise(direction * p.shape.y, uvec3(0u, 0u, 0u), kNoiseHashFast, p.seedMix);
  real settled = lightsStep(-0.35f, 0.35f, region / kLightsNoiseSigma * 0.25f);
  // Metropolitan areas: the chance varies by a lognormal factor at four times the city size (mean
  // 1: e^(3n − 4.5σ²)), so some places grow into large merged cities and others hold only towns,
  // as city sizes spread over orders of magnitude (Zipf's law) rather than all alike.
  real metro = simplexNoise(direction * (0.25f * p.shape.x), uvec3(0u, 0u, 0u), kNoiseHashFast, p.seedMix ^ 0x5bd1e995u);
  real chance = min(p.radiance.w * habitability * (0.15f + 0.85f * settled) *
                        exp(3.0f * metro - 4.5f * kLightsNoiseSigma * kLightsNoiseSigma),
                    0.6f);
  real expected = chance * kLightsMeanProfile * kLightsStreetMean;
  // The cities' shapes: an fBm of the first kLightsCityShapeOctaves octaves, each fading out as
  // it nears two pixels (as schemeNoise), the sum renormalised by the weights that remain. The
  // finer octaves, summed apart, are the districts and streets inside a city: its brightness.
  real shape = 0.0f, shapeWeights = 0.0f;
  real streets = 0.0f, streetWeights = 0.0f;
  real weight = 1.0f;
  real cells = p.shape.x;
  real largest = 0.0f, finest = 0.0f;
  for (uint i = 0u; i < kLightsCityOctaves; ++i) {
    real fade = clamp(1.0f / (2.0f * cells * max(footprintRadii, 1e-12f)) - 1.0f, 0.0f, 1.0f);
    if (i == 0u) largest = fade;
    if (i == kLightsCityShapeOctaves) finest = fade;
    if (fade <= 0.0f) break;
    real n = fade * weight * simplexNoise(direction * cells, uvec3(0u, 0u, 0u), kNoiseHashFast, p.seedMix + 1u + i);
    if (i < kLightsCityShapeOctaves) {
      shape += n;
      shapeWeights += fade * fade * weight * weight;
    } else {
      streets += n;
      streetWeights += fade * fade * weight * weight;
    }
    weight *= 0.65f;  // rougher than 1/2: districts and towns stand out
    cells *= 2.0f;
  }
  if (largest <= 0.0f) return expected;
  real n = shape / sqrt(shapeWeights);
  real t = lightsThreshold(chance, kLightsNoiseSigma);
  real edge = 0.1f * kLightsNoiseSigma;
  real lit = lightsStep(t - edge, t + edge, n);
  // Suburbs at a fifth of the core's brightness, rising steeply to the core one spread above the
  // threshold; the streets dim and brighten it (their mean, kLightsStreetMean, once unresolved).
  real core = lightsStep(t, t + kLightsNoiseSigma, n);
  real profile = 0.2f + 0.8f * core * core;
  real street = 0.3f + 0.7f * lightsStep(-kLightsNoiseSigma, kLightsNoiseSigma,
                                         streetWeights > 0.0f ? streets / sqrt(streetWeights) : 0.0f);
  street = kLightsStreetMean + (street - kLightsStreetMean) * finest;
  return expected + (lit * profile * street - expected) * largest;
}

#endif

// The sun's transmittance from the table (atmosphere_transmittance.comp), with the planet's
// shadow softened over the sun's disc, and the shared atmosphere functions on top of it.
// The includer declares `uniform sampler2D transmittanceTable` first.
#ifndef PLANET_ATMOSPHERE_LOOKUP_GLSL
#define PLANET_ATMOSPHERE_LOOKUP_GLSL

#include "shared/sky_params.h"

vec2 transmittanceUv(AtmosphereParams a, float h, float mu);

vec3 sunTransmittanceTable(AtmosphereParams a, float h, float muS) {
  float R = a.radii.x;
  float hc = max(h, 0.0f);
  float horizon = -sqrt(hc * (2.0f * R + hc)) / (R + hc);  // zenith cosine of the horizon at h
  float visible = smoothstep(-a.radii.z, a.radii.z, muS - horizon);
  if (visible <= 0.0f) return vec3(0.0f);
  return textureLod(transmittanceTable, transmittanceUv(a, hc, muS), 0.0f).rgb * visible;
}

#define SUN_TRANSMITTANCE(a, h, muS) sunTransmittanceTable(a, h, muS)
#include "common/atmosphere.glsl"

#endif

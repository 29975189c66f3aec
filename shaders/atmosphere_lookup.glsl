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

// The sky-view table's texture coordinates (skyViewTexel) of a direction at zenith angle theta,
// for the viewpoint's zenith range (skyViewZenithRange), whose part normal to the vertical is
// viewFlat and the sun's sunFlat (the azimuth between them). Each half of the rows (above and
// below the ground's horizon) is read only from its own texels: the two sides of the horizon are
// the sky and the ground.
vec2 skyViewUv(float theta, vec2 range, vec3 viewFlat, vec3 sunFlat) {
  float v = unitToTexel(skyViewV(theta, range), float(kSkyViewHeight));
  float middle = 0.5f * float(kSkyViewHeight);
  v = theta <= range.y ? min(v, (middle - 0.5f) / float(kSkyViewHeight)) : max(v, (middle + 0.5f) / float(kSkyViewHeight));
  float lengths = length(viewFlat) * length(sunFlat);
  float cosPhi = lengths > 1e-7f ? clamp(dot(viewFlat, sunFlat) / lengths, -1.0f, 1.0f) : 1.0f;
  return vec2(unitToTexel(acos(cosPhi) / kAtmospherePi, float(kSkyViewWidth)), v);
}

// The sky irradiance table (reference/atmosphere_model.h: 16 sun zenith cosines muS from −0.2 to
// 1, 0.08 apart) is read by the terrain, the sea and the clouds, each from its own uniforms:
// skyIrradianceX is where muS falls in it (in entries from the first, negative below it),
// skyIrradianceIndex the entry below that, and skyIrradianceBetween the light from that entry
// and the next. In the first two intervals (the sun 2.3° to 11.5° down) and below the first
// entry the light falls about two stops a degree, and is interpolated, and extrapolated,
// geometrically: linearly, the ground got 3 to 23 times its light in deep twilight (as much as
// the entry above gave it), which auto exposure shows. It fades to none by 18° down, the end of
// astronomical twilight, where no sunlit air is left in sight.
float skyIrradianceX(float muS) { return clamp((muS + 0.2f) / 1.2f, -0.1f, 1.0f) * 15.0f; }
uint skyIrradianceIndex(float x) { return min(uint(max(x, 0.0f)), 14u); }
vec3 skyIrradianceBetween(vec3 below, vec3 above, float x, uint i, float muS) {
  float night = clamp((muS + 0.309f) / 0.109f, 0.0f, 1.0f);
  float f = x - float(i);
  if (i > 1u) return night * mix(below, above, f);
  vec3 low = log2(max(below, vec3(1.0e-30f))), high = log2(max(above, vec3(1.0e-30f)));
  return night * exp2(mix(low, high, f));
}

#endif

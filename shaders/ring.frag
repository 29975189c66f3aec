#version 450
// The ring's pixels (engine/render/ring_pass.h; the model in common/rings.glsl), premultiplied
// for "over" blending into the HDR target.
//
// Position: the pixel's view ray (unprojected from gl_FragCoord) meets the plane z = 0 at
// t = −camera.z / ray.z. That is exact to float precision however close the camera is to the
// plane, where interpolating huge vertex offsets would not be.
//
// Light (kSunIrradiance units, so that an opaque ring of albedo a lit by the sun at cosine μs is
// as bright as ground of albedo a: a/π · E · μs, like terrain.frag):
//   seen from the sun's side:  the particles the view covers (α) reflect a/π · E · μs;
//   seen from the far side:    only light that got through the layer reaches the particles
//                              on that face: a/π · E · μs · (1 − α), so dense bands turn dark
//                              and thin ones glow, as Saturn's unlit rings do;
//   both sides: the body's shadow (sun disc visible fraction) and those of a scene's other
//   bodies (eclipses, common/eclipse.glsl) scale the sunlight, and a fill
//   light of frame.viewport.z · E (as terrain's ambient for airless bodies) is added.
// α is the slant opacity along the view ray (ringSlantOpacity), so a ring seen edge-on is opaque.
//
// Atmospheres (issue 23 point 4; the order in engine/render/renderer.cpp, Renderer::record): the
// ring is drawn after its own body's atmosphere and every farther one were composed over the
// frame, and before the nearer ones. Built with RING_AIR (ring_air.frag) it applies its own
// body's air lying between the camera and the ring point itself: seen through the limb, the ring
// becomes L + T · ring (L the light that stretch of air scatters toward the camera, T its
// transmittance), marched like a sky-view texel's ray. Blended "over" the frame, which already
// holds that air's light along the whole ray, α (L + T · ring) + (1 − α) (L_ray + T_ray · behind)
// is exactly the ring inside the air: the air in front of it over the ring over the rest of the
// ray (L_ray = L + T · L_behind, T_ray = T · T_behind). The ring lies outside the air, so the
// stretch is the whole crossing or nothing; a ring in front of the disc keeps its colour.
// Fragments with α ≥ kRingMinAlpha write their depth, so that the nearer atmospheres composed
// after the ring see it as geometry: their haze and clouds in front of it, no star fade on it.
#extension GL_GOOGLE_include_directive : require

#include "shared/ring_params.h"

layout(set = 0, binding = kRingBindingUniforms) uniform Uniforms { RingUniforms frame; };

#include "common/rings.glsl"

#include "common/eclipse.glsl"

#ifdef RING_AIR
layout(set = 0, binding = kRingBindingTransmittance) uniform sampler2D transmittanceTable;
layout(set = 0, binding = kRingBindingMultipleScattering) uniform sampler2D multipleScatteringTable;
#define MULTIPLE_SCATTERING(a, h, muS) \
  textureLod(multipleScatteringTable, multipleScatteringUv(a, h, muS), 0.0f).rgb
#include "atmosphere_lookup.glsl"

// The ringed body's air between the camera and the point at distance tRing along the unit
// direction dir (body frame): light scattered toward the camera and transmittance.
void airInFront(vec3 dir, float tRing, out vec3 light, out vec3 transmittance) {
  light = vec3(0.0f);
  transmittance = vec3(1.0f);
  AtmosphereParams a = frame.atmosphere;
  if (a.radii.w < 0.5f) return;
  float R = a.radii.x;
  float h = frame.air.x;
  vec3 up = normalize(frame.camera.xyz);
  vec3 sun = frame.sun.xyz;
  float mu = dot(dir, up);
  float muS = dot(sun, up);
  float nu = dot(dir, sun);
  vec2 stretch = atmosphereStretch(a, h, mu, frame.air.y);
  float tEnd = min(stretch.y, tRing);
  if (tEnd <= stretch.x) return;  // the air is behind the ring, or off the ray
  float r = R + h;
  float h0 = altitudeAlong(R, h, mu, stretch.x);
  float mu0 = clamp((r * mu + stretch.x) / (R + h0), -1.0f, 1.0f);
  float muS0 = clamp((r * muS + stretch.x * nu) / (R + h0), -1.0f, 1.0f);
  vec3 single;
  // Quadratic steps from inside the air (its densest part is near the camera), equal from outside.
  uint spacing = h < a.radii.y ? kStepsTowardStart : kStepsEqual;
  scatteringAlong(a, h0, mu0, muS0, nu, tEnd - stretch.x, kRingAirSteps, spacing, single, light, transmittance);
}
#endif

layout(location = 0) out vec4 outColor;

const float kRingPi = 3.14159265f;

void main() {
  vec2 ndc = gl_FragCoord.xy * frame.viewport.xy * 2.0f - 1.0f;
  vec4 nearPoint = frame.clipToRelative * vec4(ndc, 1.0f, 1.0f);  // reversed Z: depth 1 is the near plane
  vec3 ray = nearPoint.xyz / nearPoint.w;
  float t = -frame.camera.z / ray.z;
  vec3 body = frame.camera.xyz + t * ray;
  float u = t > 0.0f ? ringCoordinate(length(body.xy), frame.ring) : -1.0f;
  // How much u changes across this pixel; before any branch (derivatives need uniform control flow).
  float footprint = fwidth(u);
  footprint = footprint < 1.0f ? footprint : 1.0f;  // also NaN: a pixel wider than the ring
  vec4 particles = ringSample(u, footprint, frame.ring);
  vec3 sun = frame.sun.xyz;
  float alpha = ringSlantOpacity(particles.w, ray.z / length(ray));
  float direct = abs(sun.z) * ringPlanetShadow(body, sun, frame.ring) * eclipseSunVisible(t * ray, sun, frame.eclipse);
  if (frame.camera.w < 0.0f) direct *= 1.0f - alpha;  // the unlit face: transmitted light only
  vec3 radiance = particles.rgb / kRingPi * frame.sun.w * (direct + frame.viewport.z);
  // Nothing (a gap, off the annulus, behind the camera): leave colour and depth alone.
  if (!(alpha >= kRingMinAlpha)) discard;
#ifdef RING_AIR
  vec3 light, transmittance;
  airInFront(normalize(ray), t * length(ray), light, transmittance);
  radiance = radiance * transmittance + light;
#endif
  outColor = vec4(radiance * alpha, alpha);
}

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
#extension GL_GOOGLE_include_directive : require

#include "shared/ring_params.h"

layout(set = 0, binding = kRingBindingUniforms) uniform Uniforms { RingUniforms frame; };

#include "common/rings.glsl"

#include "common/eclipse.glsl"

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
  outColor = vec4(radiance * alpha, alpha);
}

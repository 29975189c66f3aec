#version 450
// Water shading (issue 4, point 1): Fresnel reflection of the sky (Schlick, F0 = 0.02), the
// sun's glint off small animated waves, light scattered up from the water body in the
// preset's deep/shallow colours, and transparency that grows toward the coast from the depth
// under the pixel (sea level minus the patch-texture height). Output is premultiplied: the
// blend keeps (1 − α) of the sea floor drawn before.
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"
#include "terrain_surface.glsl"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inUp;
layout(location = 2) in vec4 inAttributes;
layout(location = 3) in float inHeight;
layout(location = 4) in vec3 inToCamera;

layout(location = 0) out vec4 outColor;

void main() {
  vec3 terrainNormal;
  float ground;
  surfaceDetail(inAttributes.xy, inUp, inNormal, inHeight, terrainNormal, ground);
  float depth = frame.planet.x - ground;
  // The coastline follows the patch heights. It is antialiased: the water covers the part of
  // the pixel where the depth, extrapolated over the pixel by its screen derivatives, is
  // positive (a hard cut left stair-steps where a texel spans a few pixels, as near the limb).
  float fwidthDepth = fwidth(depth);
  float coverage = clamp(depth / max(fwidthDepth, 1e-6f) + 0.5f, 0.0f, 1.0f);
  if (coverage <= 0.0f) discard;  // dry land over the whole pixel
  vec3 up = normalize(inUp);
  vec3 toCamera = normalize(inToCamera);
  vec3 sun = frame.sunLocal.xyz;

  // Waves: a few travelling sines in the face plane; the CPU gives each one's phase at the
  // face reference point in double, the pixel adds its small offset (no float at planet scale).
  vec3 axisA = mat3(frame.planetToLocal) * frame.faceAxisA.xyz;
  vec3 axisB = mat3(frame.planetToLocal) * frame.faceAxisB.xyz;
  vec2 offsetM = inAttributes.xy * frame.camera.y;
  vec2 slope = vec2(0.0f);
  // Without patch textures (quality low, --no-patches) there is no face frame and the CPU
  // leaves the waves zero: the sea is then a mirror (normalize(0) would make every pixel NaN).
  uint waveCount = frame.refMinusNadir.w > 0.5f ? kWaterWaveCount : 0u;
  for (uint i = 0u; i < waveCount; ++i) {
    vec4 wave = frame.waves[i];  // xy: wave vector (1/m, face axes), z: phase at the reference, w: amplitude · k
    float phase = wave.z + dot(wave.xy, offsetM);
    slope += wave.w * cos(phase) * normalize(wave.xy);
  }
  // Waves flatten with distance (they are far below a pixel there: keep the mean surface).
  float pixelM = length(fwidth(offsetM));
  slope *= frame.camera.w / (1.0f + pixelM / (0.5f * frame.water.y));
  vec3 normal = normalize(up - slope.x * axisA - slope.y * axisB);

  float cosView = max(dot(normal, toCamera), 0.0f);
  float fresnel = 0.02f + 0.98f * pow(1.0f - cosView, 5.0f);
  float muS = dot(up, sun);
  vec3 sunLight = sunIrradianceAt(frame.planet.x, up);
  vec3 skyLight = skyIrradianceAt(muS);
  // The sky seen in the reflection: its irradiance spread over the hemisphere, brighter low.
  vec3 reflected = reflect(-toCamera, normal);
  vec3 skyRadiance = skyLight / kAtmospherePi * mix(1.6f, 0.7f, clamp(dot(reflected, up), 0.0f, 1.0f));
  // Sun glint: normalised Blinn-Phong lobe.
  vec3 halfway = normalize(sun + toCamera);
  const float kShininess = 600.0f;
  float glint = (kShininess + 8.0f) / (8.0f * kAtmospherePi) * pow(max(dot(normal, halfway), 0.0f), kShininess);
  vec3 specular = fresnel * (skyRadiance + sunLight * glint * step(0.0f, dot(normal, sun)));
  // The water body: shallow colour near the coast, deep colour offshore, lit from above.
  float clarity = frame.water.x;
  vec3 body = mix(frame.colorShallowWater.rgb, frame.colorDeepWater.rgb, smoothstep(0.0f, 6.0f * clarity, depth));
  float iceCap = frame.shading.x;
  float lat = abs(inAttributes.w) + 0.04f * inAttributes.z;
  float ice = smoothstep(iceCap + 0.02f, iceCap + 0.04f, lat);  // sea ice a little poleward of the land caps
  vec3 upwelling = mix(body, frame.colorSnow.rgb, ice) / kAtmospherePi * (sunLight * max(muS, 0.0f) + skyLight);
  // Where the depth changes by more than the clarity across the pixel (the coast from far
  // away), the clear shallow strip is a small part of it: weigh in half the pixel's depth range.
  float opacity = max(1.0f - exp(-(depth + 0.5f * fwidthDepth) / clarity * 3.0f), ice);
  float alpha = fresnel + (1.0f - fresnel) * opacity;
  outColor = coverage * vec4(specular * (1.0f - ice) + (1.0f - fresnel) * opacity * upwelling, alpha);
}

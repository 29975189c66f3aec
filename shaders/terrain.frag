#version 450
// Terrain shading (issue 3, point 8): per-pixel normal and height from the world-anchored
// patch textures where they reach (finest level first, blended across level edges), else the
// vertex normal; colour by altitude, slope, latitude and a noise perturbation of the band
// edges (seed 000 "Earth-like" and "altitude + noise" schemes, seed 001's altitude colour
// map); sun diffuse plus ambient.
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"

layout(set = 0, binding = kRenderBindingPatches) uniform sampler2DArray patches;

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inUp;
layout(location = 2) in vec4 inAttributes;
layout(location = 3) in float inHeight;
layout(location = 4) in vec3 inToCamera;

layout(location = 0) out vec4 outColor;

const uint kSchemeEarth = 0u;
const uint kSchemeAltitude = 1u;
const uint kSchemeMoon = 2u;
const uint kSchemeMars = 3u;

// Normal (local frame) and height at this pixel from the patch levels, chosen like a mip level:
// lod = log2(pixel footprint / finest texel), so detail changes continuously across the screen
// (no rectangles where one level ends). Level floor(lod) and the next are blended by the
// fraction; a level that does not cover the pixel (or is within its outer tenth) hands its
// weight on to coarser ones, and beyond the coarsest the vertex values remain.
void surfaceDetail(out vec3 normal, out float height) {
  vec3 accumulatedNormal = vec3(0.0f);
  float accumulatedHeight = 0.0f;
  float remaining = 1.0f;
  uint levels = uint(frame.refMinusNadir.w);
  vec2 face = inAttributes.xy;
  // Face units per pixel (derivatives taken in uniform control flow, before any branch).
  float footprint = max(length(dFdx(face)), length(dFdy(face)));
  if (levels > 0u) {
    vec4 finest = frame.patchLevels[0];
    float resolution = float(textureSize(patches, 0).x);
    float lod = clamp(log2(max(footprint * finest.y * resolution, 1e-30f)), 0.0f, float(levels - 1u));
    uint first = uint(lod);
    float fraction = lod - float(first);
    for (uint j = first; j < levels && remaining > 0.0f; ++j) {
      vec4 level = frame.patchLevels[j];
      vec2 uv = (face + level.zw) * level.y;
      float edge = min(min(uv.x, 1.0f - uv.x), min(uv.y, 1.0f - uv.y));
      float weight = clamp((edge - 0.02f) / 0.08f, 0.0f, 1.0f);
      if (j == first) weight *= 1.0f - fraction;
      if (weight <= 0.0f) continue;
      vec4 texel = textureLod(patches, vec3(uv, level.x), 0.0f);
      accumulatedNormal += remaining * weight * (mat3(frame.planetToLocal) * texel.xyz);
      accumulatedHeight += remaining * weight * texel.w;
      remaining *= 1.0f - weight;
    }
  }
  normal = normalize(accumulatedNormal + remaining * normalize(inNormal));
  height = accumulatedHeight + remaining * inHeight;
}

vec3 groundColor(float altitude, float slope, float sinLatitude, float jitter) {
  uint scheme = uint(frame.shading.y);
  float beach = frame.planet.z;
  float snowLine = frame.planet.w;
  float iceCap = frame.shading.x;
  float lat = abs(sinLatitude) + 0.04f * jitter;
  if (scheme == kSchemeAltitude) {
    float t = clamp(altitude / max(snowLine, 1.0f), 0.0f, 1.0f);
    return t < 0.5f ? mix(frame.colorLowland.rgb, frame.colorHighland.rgb, 2.0f * t)
                    : mix(frame.colorHighland.rgb, frame.colorSnow.rgb, 2.0f * t - 1.0f);
  }
  if (scheme == kSchemeMoon) {
    // Maria low and dark, highlands bright, fresh rock on steep slopes.
    vec3 c = mix(frame.colorLowland.rgb, frame.colorHighland.rgb,
                 smoothstep(-1500.0f, 1500.0f, altitude + 600.0f * jitter));
    return mix(c, frame.colorCliff.rgb, smoothstep(0.25f, 0.5f, slope));
  }
  vec3 c = mix(frame.colorLowland.rgb, frame.colorHighland.rgb,
               smoothstep(0.1f * snowLine, 0.7f * snowLine, altitude + 250.0f * jitter));
  if (scheme == kSchemeEarth && altitude < beach * (1.0f + 0.6f * jitter)) c = frame.colorBeach.rgb;
  c = mix(c, frame.colorCliff.rgb, smoothstep(0.3f, 0.55f, slope + 0.08f * jitter));
  // The snow line falls toward the poles; snow does not stick to cliffs.
  float snowAltitude = snowLine * (1.0f - 0.6f * lat * lat * lat * lat) + 300.0f * jitter;
  float snow = smoothstep(snowAltitude - 100.0f, snowAltitude + 100.0f, altitude) * (1.0f - smoothstep(0.45f, 0.7f, slope));
  snow = max(snow, smoothstep(iceCap - 0.01f, iceCap + 0.01f, lat));
  return mix(c, frame.colorSnow.rgb, snow);
}

void main() {
  if (frame.shading.z > 0.5f) {  // wireframe debug view
    outColor = vec4(0.2f, 1.0f, 0.4f, 1.0f);
    return;
  }
  vec3 normal;
  float height;
  surfaceDetail(normal, height);
  vec3 up = normalize(inUp);
  float jitter = inAttributes.z;
  float seaLevel = frame.planet.x;
  bool ocean = frame.planet.y > 0.5f;
  vec3 sun = frame.sunLocal.xyz;
  vec3 albedo;
  bool water = ocean && height < seaLevel;
  if (water) {
    float depth = seaLevel - height;
    albedo = mix(frame.colorShallowWater.rgb, frame.colorDeepWater.rgb, smoothstep(0.0f, 200.0f, depth));
    float iceCap = frame.shading.x;
    float lat = abs(inAttributes.w) + 0.04f * jitter;
    float ice = smoothstep(iceCap + 0.02f, iceCap + 0.04f, lat);  // sea ice a little poleward of the land caps
    albedo = mix(albedo, frame.colorSnow.rgb, ice);
    normal = up;
  } else {
    float slope = 1.0f - max(dot(normal, up), 0.0f);
    albedo = groundColor(height - seaLevel, slope, inAttributes.w, jitter);
  }
  // Night side: the sphere's own shadow, softened over a few tenths of a degree of sun angle.
  float daylight = smoothstep(-0.02f, 0.02f, dot(up, sun));
  float diffuse = max(dot(normal, sun), 0.0f) * daylight;
  // Ambient sky light, more on ground that faces the sky (no light on the night side beyond it).
  float sky = frame.shading.w * (0.6f + 0.4f * dot(normal, up)) * (0.3f + 0.7f * daylight);
  vec3 light = albedo * (frame.sunLocal.w * diffuse + sky);
  if (water) {
    // A small sun glint (Blinn-Phong) until the water pass brings Fresnel and sky reflection.
    vec3 toCamera = normalize(inToCamera);
    float glint = pow(max(dot(normal, normalize(sun + toCamera)), 0.0f), 300.0f);
    light += vec3(0.6f) * glint * daylight;
  }
  outColor = vec4(light, 1.0f);
}

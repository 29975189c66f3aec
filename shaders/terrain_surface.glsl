// The per-pixel surface shared by terrain.frag and water.frag: normal and height from the
// world-anchored patch textures (terrain_pass.h), and the lighting both use (sun through the
// atmosphere's transmittance table, sky irradiance by the local sun elevation).
#ifndef PLANET_TERRAIN_SURFACE_GLSL
#define PLANET_TERRAIN_SURFACE_GLSL

layout(set = 0, binding = kRenderBindingPatches) uniform sampler2DArray patches;
layout(set = 0, binding = kRenderBindingTransmittance) uniform sampler2D transmittanceTable;

#include "atmosphere_lookup.glsl"

// Normal (local frame) and height at this pixel from the patch levels, chosen like a mip level:
// lod = log2(pixel footprint / finest texel), so detail changes continuously across the screen
// (no rectangles where one level ends). Level floor(lod) and the next are blended by the
// fraction; a level that does not cover the pixel (or is within its outer tenth) hands its
// weight on to coarser ones, and beyond the coarsest the vertex values remain.
// The levels lie on the camera's cube face, projected from the centre (face coordinates are
// tan of the angle from the face normal): far beyond the face, near the edge of the visible
// hemisphere from orbit, one texel stretches over tens of pixels and the coast turned into
// blocks. There (more than ~65° from the face normal) the patches fade out to the vertex values.
void surfaceDetail(vec2 face, vec3 up, vec3 vertexNormal, float vertexHeight, out vec3 normal, out float height) {
  vec3 accumulatedNormal = vec3(0.0f);
  float accumulatedHeight = 0.0f;
  float remaining = 1.0f;
  uint levels = uint(frame.refMinusNadir.w);
  // Face units per pixel (derivatives taken in uniform control flow, before any branch).
  float footprint = min(length(dFdx(face)), length(dFdy(face)));
  vec3 faceNormal = mat3(frame.planetToLocal) * frame.faceNormal.xyz;
  float onFace = smoothstep(0.35f, 0.45f, dot(normalize(up), faceNormal));
  if (levels > 0u && onFace > 0.0f) {
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
      // Toroidal storage: the level's texel (0, 0) sits at its wrap offset; the sampler repeats.
      vec4 wrap = frame.patchWrap[j >> 1u];
      vec2 stored = uv + ((j & 1u) == 0u ? wrap.xy : wrap.zw);
      vec4 texel = textureLod(patches, vec3(stored, level.x), 0.0f);
      accumulatedNormal += remaining * weight * (mat3(frame.planetToLocal) * texel.xyz);
      accumulatedHeight += remaining * weight * texel.w;
      remaining *= 1.0f - weight;
    }
  }
  accumulatedNormal *= onFace;
  accumulatedHeight *= onFace;
  remaining = 1.0f - onFace * (1.0f - remaining);
  normal = normalize(accumulatedNormal + remaining * normalize(vertexNormal));
  height = accumulatedHeight + remaining * vertexHeight;
}

// Sky irradiance on a horizontal surface for the sun at zenith cosine muS (table on the CPU).
vec3 skyIrradianceAt(float muS) {
  float x = clamp((muS + 0.2f) / 1.2f, 0.0f, 1.0f) * float(kSkyIrradianceSamplesGpu - 1u);
  uint i = min(uint(x), kSkyIrradianceSamplesGpu - 2u);
  return mix(frame.skyIrradiance[i].rgb, frame.skyIrradiance[i + 1u].rgb, x - float(i));
}

// Irradiance from the sun through the air at altitude h with sphere normal `up` (zero on the
// night side, reddened near the terminator).
vec3 sunIrradianceAt(float h, vec3 up) {
  return sunTransmittanceTable(frame.atmosphere, max(h, 0.0f), dot(up, frame.sunLocal.xyz)) * frame.sunLocal.w;
}

#endif

#version 450
// The ground's deferred shading (TerrainSettings::deferredShading): each pixel the G-buffer holds
// ground at (terrain.frag's TERRAIN_GBUFFER variant wrote its TerrainSample) shaded once, by the
// same code as the forward path's fragment shader (terrain_shade.glsl), into the HDR target.
// Hidden ground costs no shading, whatever the depth test did, and on GPUs whose graphics
// pipeline runs on a small part of the chip (the H100 and H200) the shading runs on all of it
// (docs/benchmarks.md, "On a GPU").
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"

layout(local_size_x = kTerrainShadeWorkgroupSize, local_size_y = kTerrainShadeWorkgroupSize) in;
#define TERRAIN_SURFACE_NO_DERIVATIVES
#include "terrain_surface.glsl"

// Any pixel may be sea floor: the G-buffer holds the ground of both of the split's draws.
const bool kSeaFloorPossible = true;
#include "terrain_shade.glsl"

layout(set = 0, binding = kRenderBindingNormalHeight, rgba32f) uniform readonly image2D gNormalHeight;
layout(set = 0, binding = kRenderBindingToCameraPixel, rgba32f) uniform readonly image2D gToCameraPixel;
layout(set = 0, binding = kRenderBindingUpJitter, rgba32f) uniform readonly image2D gUpJitter;
layout(set = 0, binding = kRenderBindingLatitudeFootprint, rgba32f) uniform readonly image2D gLatitudeFootprint;
layout(set = 0, binding = kRenderBindingShadedColor, rgba32f) uniform writeonly image2D color;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(color)))) return;
  vec4 latitudeFootprint = imageLoad(gLatitudeFootprint, pixel);
  if (latitudeFootprint.y < 0.0f) return;  // no ground here (the cleared value)
  vec4 normalHeight = imageLoad(gNormalHeight, pixel);
  vec4 toCameraPixel = imageLoad(gToCameraPixel, pixel);
  vec4 upJitter = imageLoad(gUpJitter, pixel);
  TerrainSample s;
  s.normal = normalHeight.xyz;
  s.height = normalHeight.w;
  s.toCamera = toCameraPixel.xyz;
  s.pixelM = toCameraPixel.w;
  s.up = upJitter.xyz;
  s.jitter = upJitter.w;
  s.sinLatitude = latitudeFootprint.x;
  s.footprintX = latitudeFootprint.y;
  s.footprintY = latitudeFootprint.z;
  s.latitudeEdge = latitudeFootprint.w;
  imageStore(color, pixel, shadeGround(s));
}

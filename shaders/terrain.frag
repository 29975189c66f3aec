#version 450
// Terrain shading (issue 3, point 8; issue 20, points 1 and 5): per-pixel normal and height from
// the world-anchored patch textures where they reach (finest level first, blended across level
// edges), else the vertex normal; then the ground's shading (terrain_shade.glsl) as HDR radiance.
// Ground below sea level is the sea floor; the water pass draws the sea over it.
// The TERRAIN_GBUFFER variant stops before the shading and writes what it needs (TerrainSample)
// into four RGBA32F targets, for terrain_shade.comp to shade each pixel once in a compute pass
// (TerrainSettings::deferredShading).
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"

// The relief cube's lookup: false when no pixel's footprint can reach the size that takes it.
layout(constant_id = 6) const bool kSpecRelief = true;
#define RELIEF_POSSIBLE kSpecRelief
#include "terrain_surface.glsl"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inUp;
layout(location = 2) in vec4 inAttributes;
layout(location = 3) in float inHeight;
layout(location = 4) in vec3 inToCamera;

#ifdef TERRAIN_GBUFFER
// TerrainSample's four texels; the last one's footprintX (never negative) tells ground from the
// cleared background (-1) in the compute pass.
layout(location = 0) out vec4 outNormalHeight;
layout(location = 1) out vec4 outToCameraPixel;
layout(location = 2) out vec4 outUpJitter;
layout(location = 3) out vec4 outLatitudeFootprint;
#else
layout(location = 0) out vec4 outColor;
#endif
#ifdef TERRAIN_EARLY_DEPTH
// The variant for planets with no sea (TerrainPass::createDrawPipeline): nothing to push back, so
// the depth test runs before shading, and with the mesh drawn near to far (clipmap_culling.h)
// hidden ground costs no shading.
layout(early_fragment_tests) in;
#define WRITE_DEPTH(depth)
// No pixel it draws is sea floor: the planet has no sea, or the ground is the split's that lies
// above sea level at every pixel (terrain_split.comp). Without the branch's code, as lavapipe
// would run it for every pixel.
const bool kSeaFloorPossible = false;
#else
const bool kSeaFloorPossible = true;
// With a sea, the shader writes its depth (to push ground under the sea back, main below). On
// lavapipe that moves the depth test after the shader, whatever the layout below says, so every
// hidden fragment is shaded; a full-screen pass that pushed the sea floor back instead (from a
// mark this shader left) cost as much as the early test saved (docs/benchmarks.md, "Early depth
// test"). The layout tells an implementation that may use it that the depth only ever moves
// farther (reversed-Z: smaller).
layout(depth_less) out float gl_FragDepth;
#define WRITE_DEPTH(depth) gl_FragDepth = (depth)
#endif

#ifndef TERRAIN_GBUFFER
#include "terrain_shade.glsl"
#endif

void main() {
  WRITE_DEPTH(gl_FragCoord.z);
#ifndef TERRAIN_GBUFFER
  if (frame.shading.z > 0.5f) {  // wireframe debug view
    outColor = vec4(0.05f, 0.25f, 0.08f, 1.0f);
    return;
  }
#endif
  TerrainSample s;
  surfaceDetail(inAttributes.xy, inUp, inToCamera, inNormal, inHeight, s.normal, s.height);
  s.pixelM = fwidth(s.height);  // before any branch: derivatives need uniform control flow
  s.toCamera = inToCamera;
  s.footprintX = length(dFdx(inToCamera));
  s.footprintY = length(dFdy(inToCamera));
  s.latitudeEdge = fwidth(inAttributes.w) * 0.63661977f;  // |latitude| / 90° per pixel (d asin ≥ d sin)
  s.up = inUp;
  s.jitter = inAttributes.z;
  s.sinLatitude = inAttributes.w;
  // Under water at this pixel, though the triangle may be above sea level: the mesh is coarser
  // than the patch heights, and near a coast it often is. Pushed back to twice its distance, it
  // cannot hide the sea surface in front of it, so the water pass draws the sea here too and the
  // coastline is the patch heights' (the mesh's triangles showed as sandy polygons along the
  // shore). Reversed-Z: half the depth is twice the distance.
  if (kSeaFloorPossible && frame.planet.y > 0.5f && s.height < frame.planet.x && frame.water.z > 0.5f)
    WRITE_DEPTH(0.5f * gl_FragCoord.z);
#ifdef TERRAIN_GBUFFER
  outNormalHeight = vec4(s.normal, s.height);
  outToCameraPixel = vec4(s.toCamera, s.pixelM);
  outUpJitter = vec4(s.up, s.jitter);
  outLatitudeFootprint = vec4(s.sinLatitude, s.footprintX, s.footprintY, s.latitudeEdge);
#else
  outColor = shadeGround(s);
#endif
}

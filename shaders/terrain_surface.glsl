// The per-pixel surface shared by terrain.frag and water.frag: normal and height from the
// world-anchored patch textures (terrain_pass.h), and the lighting both use (sun through the
// atmosphere's transmittance table, sky irradiance by the local sun elevation).
#ifndef PLANET_TERRAIN_SURFACE_GLSL
#define PLANET_TERRAIN_SURFACE_GLSL

layout(set = 0, binding = kRenderBindingPatches) uniform sampler2DArray patches;
layout(set = 0, binding = kRenderBindingTransmittance) uniform sampler2D transmittanceTable;
layout(set = 0, binding = kRenderBindingRelief) uniform samplerCube reliefCube;

#include "atmosphere_lookup.glsl"
#include "common/rings.glsl"
#include "shared/relief_params.h"

// Whether some pixel can take the relief cube (TerrainPass::shadingFor): a specialization
// constant where the includer declares one (terrain.frag), as lavapipe runs the lookup whatever
// its weight.
#ifndef RELIEF_POSSIBLE
#define RELIEF_POSSIBLE true
#endif

// What the shading needs of a ground pixel: the surface (surfaceDetail below) and the derivatives
// terrain.frag took of it, in the local frame. The G-buffer's four RGBA32F texels hold it in this
// order (terrain.frag, terrain_shade.comp).
struct TerrainSample {
  vec3 normal;         // unit surface normal
  float height;        // m above the radius sphere
  vec3 toCamera;       // from the pixel's ground point to the camera, m
  float pixelM;        // the height's change across the pixel (fwidth), m
  vec3 up;             // the sphere normal as interpolated (not normalized)
  float jitter;        // the vertices' band noise
  float sinLatitude;   // sin(latitude)
  float footprintX;    // the ground point's move across one pixel along x, m
  float footprintY;    // along y, m
  float latitudeEdge;  // |latitude| / 90° across the pixel
};

// surfaceDetail takes derivatives, which a compute shader (terrain_shade.comp) has not.
#ifndef TERRAIN_SURFACE_NO_DERIVATIVES
// Normal (local frame) and height at this pixel from the patch levels, chosen like a mip level:
// lod = log2(pixel footprint / finest texel), so detail changes continuously across the screen
// (no rectangles where one level ends). Level floor(lod) and the next are blended by the
// fraction; a level that does not cover the pixel (or is within its outer tenth) hands its
// weight on to coarser ones, as does one built over several frames where it holds nothing yet.
// The levels lie on the camera's cube face, projected from the centre (face coordinates are
// tan of the angle from the face normal): far beyond the face, near the edge of the visible
// hemisphere from orbit, one texel stretches over tens of pixels and the coast turned into
// blocks. There (more than ~65° from the face normal) the patches fade out.
// What the patches leave goes to the relief cube (relief_cube.h: the whole planet at a fixed
// spacing, mipmapped) where its texels are at most ~4 pixels wide across the line of sight (the
// pixel's distance times the angle it spans, the footprint no tilt of the ground lengthens, so
// that TerrainPass::shadingFor can bound it for a frame from the farthest drawn ground and leave
// the lookup out where no pixel can take it), else to the vertex values:
// from orbit, beyond the face and at quality `low`, the coast follows the cube's texels instead
// of the mesh's triangles, hundreds of km wide near the limb; near the camera, where the cube is
// far coarser than a pixel, the vertices (every octave the ring can show) stay.
void surfaceDetail(vec2 face, vec3 up, vec3 toCamera, vec3 vertexNormal, float vertexHeight, out vec3 normal,
                   out float height) {
  vec3 accumulatedNormal = vec3(0.0f);
  float accumulatedHeight = 0.0f;
  float remaining = 1.0f;
  uint levels = uint(frame.refMinusNadir.w);
  // Face units per pixel, and the sphere's angle per pixel (radians; up is the unit sphere
  // normal), both from derivatives taken in uniform control flow, before any branch.
  float footprint = min(length(dFdx(face)), length(dFdy(face)));
  vec3 unitUp = normalize(up);
  float angleX = length(dFdx(unitUp));
  float angleY = length(dFdy(unitUp));
  vec3 ray = normalize(toCamera);
  float across = length(toCamera) * min(length(dFdx(ray)), length(dFdy(ray))) / frame.camera.y;
  vec3 faceNormal = mat3(frame.planetToLocal) * frame.faceNormal.xyz;
  float onFace = smoothstep(0.35f, 0.45f, dot(unitUp, faceNormal));
  if (levels > 0u && onFace > 0.0f) {
    vec4 finest = frame.patchLevels[0];
    float resolution = float(textureSize(patches, 0).x);
    float lod = clamp(log2(max(footprint * finest.y * resolution, 1e-30f)), 0.0f, float(levels - 1u));
    uint first = uint(lod);
    float fraction = lod - float(first);
    // The levels' weights first, from the level tables alone; then two texture reads, the first
    // two levels that have weight, the second taking the weight of any after it (a third level
    // shares a pixel only near the edge of one built over several frames). On lavapipe a loop
    // runs for as many turns as its slowest lane, and a read was most of a turn.
    vec3 storedA = vec3(0.0f), storedB = vec3(0.0f);
    float shareA = 0.0f, shareB = 0.0f;
    for (uint j = first; j < levels && remaining > 0.0f; ++j) {
      vec4 level = frameArray(kFrameTexelPatchLevels, j);
      vec2 uv = (face + level.zw) * level.y;
      vec4 bounds = frameArray(kFrameTexelPatchBounds, j);  // what the layer holds (a level built over frames)
      float edge = min(min(uv.x - bounds.x, bounds.z - uv.x), min(uv.y - bounds.y, bounds.w - uv.y));
      // A level whose build waits for a later frame has layer −1 (PatchTextures::plan).
      float weight = level.x < 0.0f ? 0.0f : clamp((edge - 0.02f) / 0.08f, 0.0f, 1.0f);
      if (j == first) weight *= 1.0f - fraction;
      if (weight <= 0.0f) continue;
      // Toroidal storage: the level's texel (0, 0) sits at its wrap offset; the sampler repeats.
      vec4 wrap = frameArray(kFrameTexelPatchWrap, j >> 1u);
      vec3 stored = vec3(uv + ((j & 1u) == 0u ? wrap.xy : wrap.zw), level.x);
      float share = remaining * weight;
      if (shareA == 0.0f) {
        storedA = stored;
        shareA = share;
      } else {
        if (shareB == 0.0f) storedB = stored;
        shareB += share;
      }
      remaining *= 1.0f - weight;
    }
    // A read without weight counts for nothing, whatever the texel holds (a layer not yet built).
    vec4 texelA = shareA > 0.0f ? textureLod(patches, storedA, 0.0f) : vec4(0.0f);
    vec4 texelB = shareB > 0.0f ? textureLod(patches, storedB, 0.0f) : vec4(0.0f);
    accumulatedNormal =
        shareA * (mat3(frame.planetToLocal) * texelA.xyz) + shareB * (mat3(frame.planetToLocal) * texelB.xyz);
    accumulatedHeight = shareA * texelA.w + shareB * texelB.w;
  }
  accumulatedNormal *= onFace;
  accumulatedHeight *= onFace;
  remaining = 1.0f - onFace * (1.0f - remaining);
  // The relief cube: texels 2 / size radians wide at a face's centre; its weight from the
  // pixel's extent across the line of sight, its mip level from the larger of the pixel's two
  // extents on the sphere (softer along a grazing view, never aliased).
  uint reliefSize = uint(textureSize(reliefCube, 0).x);
  float texelAngle = 2.0f / float(reliefSize);
  float pixelsPerTexel = texelAngle / max(across, 1e-30f);
  float relief = RELIEF_POSSIBLE && reliefSize > kReliefStandInSize
                     ? remaining * (1.0f - smoothstep(4.0f, 8.0f, pixelsPerTexel))
                     : 0.0f;
  if (relief > 0.0f) {
    float reliefLod = max(log2(max(angleX, angleY) / texelAngle), 0.0f);
    vec4 texel = textureLod(reliefCube, mat3(frame.localToPlanet) * unitUp, reliefLod);
    accumulatedNormal += relief * normalize(mat3(frame.planetToLocal) * texel.xyz);
    accumulatedHeight += relief * texel.w;
    remaining -= relief;
  }
  normal = normalize(accumulatedNormal + remaining * normalize(vertexNormal));
  height = accumulatedHeight + remaining * vertexHeight;
}

#endif  // TERRAIN_SURFACE_NO_DERIVATIVES

// Sky irradiance on a horizontal surface for the sun at zenith cosine muS (table on the CPU;
// atmosphere_lookup.glsl, skyIrradianceBetween). The table starts with the sun 11.5° below the
// horizon (muS −0.2); deeper, it falls on to none at 18° below (muS −0.31): held at its first
// entry, it lit every night side as if at −11.5°.
vec3 skyIrradianceAt(float muS) {
  float x = skyIrradianceX(muS);
  uint i = skyIrradianceIndex(x);
  vec3 below = frameArray(kFrameTexelSkyIrradiance, i).rgb;
  vec3 above = frameArray(kFrameTexelSkyIrradiance, i + 1u).rgb;
  return skyIrradianceBetween(below, above, x, i, muS);
}

// Irradiance from the sun through the air at altitude h with sphere normal `up` (zero on the
// night side, reddened near the terminator).
vec3 sunIrradianceAt(float h, vec3 up) {
  return sunTransmittanceTable(frame.atmosphere, max(h, 0.0f), dot(up, frame.sunLocal.xyz)) * frame.sunLocal.w;
}

// The share of the sun's light that the body's rings let through to the surface point
// `toCamera` from the camera (local frame, as the vertex shaders' outToCamera); 1 without rings.
float surfaceRingShadow(vec3 toCamera) {
  if (!(frame.cameraPlanet.w > 0.5f)) return 1.0f;
  mat3 localToPlanet = mat3(frame.localToPlanet);
  vec3 pointPlanet = frame.cameraPlanet.xyz - localToPlanet * toCamera;
  return ringShadow(pointPlanet, localToPlanet * frame.sunLocal.xyz, frame.ring);
}

#endif

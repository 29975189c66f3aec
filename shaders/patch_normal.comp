#version 450
// Patch textures, pass 2 (engine/render/patch_textures.h): the unit outward normal of every
// texel of one region of a level from central differences of the surface points P = (R + h)·p
// of its four neighbours, written with the height as (normal, height) into the level's array
// layer, where its face index puts it (toroidal storage, shared/patch_params.h).
#extension GL_GOOGLE_include_directive : require

#include "shared/patch_params.h"

layout(local_size_x = kPatchWorkgroupSize, local_size_y = kPatchWorkgroupSize) in;

layout(std430, set = 0, binding = kPatchBindingLevel) readonly buffer Level {
  PatchLevelParams level;
  PatchTile tiles[];
};
layout(std430, set = 0, binding = kPatchBindingHeights) readonly buffer Heights { float heights[]; };
layout(set = 0, binding = kPatchBindingImage, rgba32f) writeonly uniform image2DArray patches;

void main() {
  uvec2 id = gl_GlobalInvocationID.xy;
  if (id.x >= level.regionWidth || id.y >= level.regionHeight) return;
  uint side = level.regionWidth + 2u;
  uint centre = (id.y + 1u) * side + id.x + 1u;
  float h = heights[centre];
  float hl = heights[centre - 1u];
  float hr = heights[centre + 1u];
  float hd = heights[centre - side];
  float hu = heights[centre + side];
  // Directions as offsets d = p − c from the anchor c of this texel's tile (small and accurate,
  // shared/patch_params.h), so that the result, too, depends only on where the texel lies.
  uint tileIndex;
  int dx, dy;
  patchTileOf(level, id + uvec2(1u), tileIndex, dx, dy);
  PatchTile tile = tiles[tileIndex];
  vec3 axisA = level.axisA.xyz;
  vec3 axisB = level.axisB.xyz;
  vec3 dl = patchDirectionOffset(axisA, axisB, level.texelSize, tile, dx - 1, dy);
  vec3 dr = patchDirectionOffset(axisA, axisB, level.texelSize, tile, dx + 1, dy);
  vec3 dd = patchDirectionOffset(axisA, axisB, level.texelSize, tile, dx, dy - 1);
  vec3 du = patchDirectionOffset(axisA, axisB, level.texelSize, tile, dx, dy + 1);
  // P_r − P_l = (R + h_r)(d_r − d_l) + (h_r − h_l)(c + d_l): differences of small offsets and
  // of heights only, so no float position of size R swallows the texel spacing.
  vec3 c = tile.anchor.xyz;
  float r = level.radiusM;
  precise vec3 alongA = (r + hr) * (dr - dl) + (hr - hl) * (c + dl);
  precise vec3 alongB = (r + hu) * (du - dd) + (hu - hd) * (c + dd);
  // A × B = N, so the cross product of the +a and +b tangents points outward.
  vec3 normal = normalize(cross(alongA, alongB));
  uvec2 stored = (id + uvec2(level.storeOffsetA, level.storeOffsetB)) % level.resolution;
  imageStore(patches, ivec3(ivec2(stored), int(level.imageLayer)), vec4(normal, h));
}

#version 450
// Vertex normals of the clipmap from its neighbours' positions (after terrain_heights.comp):
// the cross product of the differences along θ (ring k−1 minus ring k+1, outward) and along φ
// (index i+1 minus i−1). At the rim and at the range's inner edge the difference is one-sided.
// The pole takes four vertices of poleNeighbourRing at φ = 0, π/2, π, 3π/2.
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"

layout(local_size_x = kTerrainComputeWorkgroupSize) in;
layout(push_constant) uniform Push { TerrainComputePush push; };

layout(std430, set = 0, binding = kRenderBindingSurface) readonly buffer Surface { vec4 surface[]; };
layout(std430, set = 0, binding = kRenderBindingNormals) writeonly buffer Normals { vec4 normals[]; };

// The displaced position of a vertex relative to the anchor (local frame).
vec3 position(uint index) {
  vec4 s = surface[index];
  return s.xyz + s.w * mesh[index].direction.xyz;
}

void main() {
  uint invocation = gl_GlobalInvocationID.x;
  if (invocation > push.vertexCount) return;
  uint n = push.numPhi;
  uint pole = push.ringCount * n;
  vec3 normal;
  if (invocation == push.vertexCount) {
    uint base = push.poleNeighbourRing * n;
    vec3 p0 = position(base);
    vec3 p1 = position(base + n / 4u);
    vec3 p2 = position(base + n / 2u);
    vec3 p3 = position(base + (3u * n) / 4u);
    normal = cross(p0 - p2, p1 - p3);
    normals[pole] = vec4(normalize(normal), 0.0f);
    return;
  }
  uint index = push.firstVertex + invocation;
  uint ring = index / n;
  uint i = index - ring * n;
  // Outward along θ: the outer neighbour (or this vertex at the edge of the rings that have
  // heights, push.firstRing..lastRing) minus the inner one (the pole after the mesh's last ring).
  uint outer = ring > push.firstRing ? index - n : index;
  uint inner = ring < push.lastRing ? index + n : (ring + 1u == push.ringCount ? pole : index);
  uint next = ring * n + (i + 1u == n ? 0u : i + 1u);
  uint previous = ring * n + (i == 0u ? n - 1u : i - 1u);
  normal = cross(position(outer) - position(inner), position(next) - position(previous));
  normals[index] = vec4(normalize(normal), 0.0f);
}

#version 450
// The culled mesh's triangles split by whether their ground can be sea floor (issue 21, point 7;
// TerrainPass::recordCompute). The sea floor is pushed back in depth by terrain.frag so that the
// water pass draws the sea over it, and a shader that writes depth has its depth test after
// shading on lavapipe: every hidden fragment of the ground was shaded. A triangle whose lowest
// vertex lies far enough above sea level that no pixel of it can be under the sea is drawn by the
// early-depth variant, which skips hidden ground; the rest as before.
//
// A pixel's height (terrain_surface.glsl) is the patch levels', the relief cube's or the
// vertices' interpolation. None strays from the triangle's vertices by more than the terrain can
// rise or fall across the triangle, bounded here by push.slope times its longest edge plus
// push.marginM (kSplitSlope and kSplitMarginM, terrain_pass.cpp); the relief cube's averages,
// which can reach far lower, are read only where a pixel spans kilometres, and triangles there
// are wider still. Same index positions in both lists, the other list's triangle collapsed to
// one point (drawn as nothing), so each stays near to far.
layout(local_size_x = 64) in;

layout(set = 0, binding = 0) readonly buffer Culled { uint culled[]; };
// xyz: sea-sphere point − anchor (local frame), w: height above the radius sphere (m).
layout(set = 0, binding = 1) readonly buffer Surface { vec4 surface[]; };
layout(set = 0, binding = 2) writeonly buffer Dry { uint dry[]; };
layout(set = 0, binding = 3) writeonly buffer Rest { uint rest[]; };

layout(push_constant) uniform Push {
  uint triangleCount;
  float seaLevelM;
  float slope;    // rise per metre of edge that the margin allows
  float marginM;  // plus this
} push;

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (t >= push.triangleCount) return;
  uint i0 = culled[3u * t], i1 = culled[3u * t + 1u], i2 = culled[3u * t + 2u];
  vec4 a = surface[i0], b = surface[i1], c = surface[i2];
  float longest = max(max(distance(a.xyz, b.xyz), distance(b.xyz, c.xyz)), distance(c.xyz, a.xyz));
  float lowest = min(min(a.w, b.w), c.w);
  bool land = lowest - push.slope * longest - push.marginM >= push.seaLevelM;
  uint none = culled[0];  // a vertex the frame evaluated: the collapsed triangles stay finite
  dry[3u * t] = land ? i0 : none;
  dry[3u * t + 1u] = land ? i1 : none;
  dry[3u * t + 2u] = land ? i2 : none;
  rest[3u * t] = land ? none : i0;
  rest[3u * t + 1u] = land ? none : i1;
  rest[3u * t + 2u] = land ? none : i2;
}

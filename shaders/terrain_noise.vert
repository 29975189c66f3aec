#version 450
// Terrain vertices that evaluate their own heights (HeightSource::VertexShader): seed 002's
// design, every drawn vertex runs the planet's noise stack in the vertex shader on every draw,
// with the same mesh, octave budgets and functions as terrain_heights.comp, so that
// `planet bench --compare` measures the design and nothing else. To shade like the compute
// path it also needs the normal, which terrain_normals.comp takes from the four neighbours'
// positions: here the shader evaluates those four as well (five noise stacks per vertex).
// Outputs are those of terrain.vert.
#extension GL_GOOGLE_include_directive : require

#include "terrain_vertex_surface.glsl"

layout(location = 0) out vec3 outNormal;      // local frame
layout(location = 1) out vec3 outUp;          // sphere normal (local frame)
layout(location = 2) out vec4 outAttributes;  // face Δa, Δb, band noise, sin(latitude)
layout(location = 3) out float outHeight;     // metres above the radius sphere
layout(location = 4) out vec3 outToCamera;    // local frame, metres

// The vertex itself (k = 0) and the four neighbours whose positions give its normal in
// terrain_normals.comp (k = 1..4, so that the normal is cross(p1 − p2, p3 − p4)). push.firstRing
// and push.lastRing are the rings the compute path gives heights (one beyond the drawn ones).
void stencil(uint index, out uint points[5]) {
  uint n = push.numPhi;
  uint pole = push.ringCount * n;
  points[0] = index;
  if (index == pole) {
    uint base = push.poleNeighbourRing * n;
    points[1] = base;
    points[2] = base + n / 2u;
    points[3] = base + n / 4u;
    points[4] = base + (3u * n) / 4u;
    return;
  }
  uint ring = index / n;
  uint i = index - ring * n;
  points[1] = ring > push.firstRing ? index - n : index;                                        // outer
  points[2] = ring < push.lastRing ? index + n : (ring + 1u == push.ringCount ? pole : index);  // inner
  points[3] = ring * n + (i + 1u == n ? 0u : i + 1u);                                          // next
  points[4] = ring * n + (i == 0u ? n - 1u : i - 1u);                                          // previous
}

void main() {
  uint index = uint(gl_VertexIndex);
  uint points[5];
  stencil(index, points);
  // One loop over the five points rather than five calls: the driver inlines every call, and
  // five copies of the noise stack made lavapipe's LLVM compile of the shader take tens of
  // seconds (and it recompiles vertex shaders on some draws).
  vec3 positions[5];
  vec3 offsetLocal = vec3(0.0f);
  vec3 offsetPlanet = vec3(0.0f);
  float height = 0.0f;
  for (uint k = 0u; k < 5u; ++k) {
    MeshVertex p = mesh[points[k]];
    vec3 local = surfaceOffsetLocal(p);
    vec3 planet = mat3(frame.localToPlanet) * local;
    float h = surfaceHeight(planet, floatBitsToUint(p.polar.z));
    positions[k] = local + h * p.direction.xyz;
    if (k == 0u) {
      offsetLocal = local;
      offsetPlanet = planet;
      height = h;
    }
  }
  vec3 up = mesh[index].direction.xyz;
  bool ocean = frame.planet.y > 0.5f;
  float shown = ocean ? max(height, frame.planet.x) : height;
  vec3 position = offsetLocal + shown * up - vec3(0.0f, 0.0f, frame.camera.x);
  gl_Position = frame.viewProjection * vec4(position, 1.0f);
  outNormal = normalize(cross(positions[1] - positions[2], positions[3] - positions[4]));
  outUp = up;
  outAttributes = surfaceAttributes(offsetPlanet);
  outHeight = height;
  outToCamera = -position;
}

#version 450
// Terrain vertices that evaluate their own heights (HeightSource::VertexShader): seed 002's
// design, every drawn vertex runs the planet's noise stack in the vertex shader on every draw,
// with the same mesh, octave budgets and functions as terrain_heights.comp, so that
// `planet bench --compare` measures the design and nothing else. The normal comes from the
// stack's analytic gradient as there: one evaluation per vertex.
// Outputs are those of terrain.vert.
#extension GL_GOOGLE_include_directive : require

#include "terrain_vertex_surface.glsl"

layout(location = 0) out vec3 outNormal;      // local frame
layout(location = 1) out vec3 outUp;          // sphere normal (local frame)
layout(location = 2) out vec4 outAttributes;  // face Δa, Δb, band noise, sin(latitude)
layout(location = 3) out float outHeight;     // metres above the radius sphere
layout(location = 4) out vec3 outToCamera;    // local frame, metres

void main() {
  uint index = uint(gl_VertexIndex);
  MeshVertex v = mesh[index];
  vec3 offsetLocal = surfaceOffsetLocal(v);
  vec3 offsetPlanet = mat3(frame.localToPlanet) * offsetLocal;
  vec4 heightGradient = surfaceHeightGradient(offsetPlanet, floatBitsToUint(v.polar.z));
  float height = heightGradient.x;
  vec3 up = v.direction.xyz;
  bool ocean = frame.planet.y > 0.5f;
  float shown = ocean ? max(height, frame.planet.x) : height;
  vec3 position = offsetLocal + shown * up - vec3(0.0f, 0.0f, frame.camera.x);
  gl_Position = frame.viewProjection * vec4(position, 1.0f);
  outNormal = surfaceNormal(heightGradient, up);
  outUp = up;
  outAttributes = surfaceAttributes(offsetPlanet, v);
  outHeight = height;
  outToCamera = -position;
}

#version 450
// Terrain vertices that evaluate their own heights (HeightSource::VertexShader): seed 002's
// design, every drawn vertex runs the planet's noise stack in the vertex shader on every draw,
// with the same mesh, octave budgets, functions and specialization on the planet's layers as
// terrain_heights.comp, so that `planet bench --compare` measures the design and nothing else.
// The normal comes from the stack's analytic gradient as there: one evaluation per vertex.
// The sea is the same shader specialized with kNoiseVertexWater: that design has no vertex
// buffers to share between the two draws, so the sea's vertices evaluate the stack again (its
// fragments need the ground's height and normal, as water.vert passes them).
// Outputs are those of terrain.vert (and water.vert).
#extension GL_GOOGLE_include_directive : require

#include "terrain_layer_specialization.glsl"
#define TERRAIN_SPECIALIZED_LAYERS
#define TERRAIN_TABLE_BLOCK gl_InstanceIndex  // 0: one instance, the first
#include "terrain_vertex_surface.glsl"

// After the layers' constants (shared/terrain_params.h): 1 draws the sea, 0 the ground.
layout(constant_id = kTerrainSpecCount) const uint kNoiseVertexWater = 0u;

layout(location = 0) out vec3 outNormal;      // local frame
layout(location = 1) out vec3 outUp;          // sphere normal (local frame)
layout(location = 2) out vec4 outAttributes;  // face Δa, Δb, band noise, sin(latitude)
layout(location = 3) out float outHeight;     // metres above the radius sphere (the ground's)
layout(location = 4) out vec3 outToCamera;    // local frame, metres

void main() {
  uint index = uint(gl_VertexIndex);
  MeshVertex v = mesh[index];
  vec3 offsetLocal = surfaceOffsetLocal(v);
  vec3 offsetPlanet = mat3(frame.localToPlanet) * offsetLocal;
  vec4 attributes = surfaceAttributes(offsetPlanet, v);
  float height;
  vec3 normal;
  vertexSurface(offsetPlanet, v, attributes, height, normal);
  vec3 up = v.direction.xyz;
  bool ocean = frame.planet.y > 0.5f;
  float shown = kNoiseVertexWater != 0u ? frame.planet.x : ocean ? max(height, frame.planet.x) : height;
  vec3 position = offsetLocal + shown * up - vec3(0.0f, 0.0f, frame.camera.x);
  float towardCamera = kNoiseVertexWater != 0u ? kWaterTowardCamera : 0.0f;
  gl_Position = frame.viewProjection * vec4(position * (1.0f - towardCamera), 1.0f);
  outNormal = normal;
  outUp = up;
  outAttributes = attributes;
  outHeight = height;
  outToCamera = -position;
}

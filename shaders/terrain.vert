#version 450
// Terrain vertices: everything was computed by terrain_heights.comp (heights and normals);
// this only places the vertex relative to the camera (local frame, float offsets from the
// anchor) and projects it. Below sea level the ground is drawn at the water surface (the ocean
// colour comes from the fragment shader until the water pass exists).
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"

layout(std430, set = 0, binding = kRenderBindingSurface) readonly buffer Surface { vec4 surface[]; };
layout(std430, set = 0, binding = kRenderBindingNormals) readonly buffer Normals { vec4 normals[]; };
layout(std430, set = 0, binding = kRenderBindingAttributes) readonly buffer Attributes { vec4 attributes[]; };

layout(location = 0) out vec3 outNormal;      // local frame
layout(location = 1) out vec3 outUp;          // sphere normal (local frame)
layout(location = 2) out vec4 outAttributes;  // face Δa, Δb, band noise, sin(latitude)
layout(location = 3) out float outHeight;     // metres above the radius sphere
layout(location = 4) out vec3 outToCamera;    // local frame, metres

void main() {
  uint index = uint(gl_VertexIndex);
  vec4 s = surface[index];
  vec3 up = mesh[index].direction.xyz;
  float height = s.w;
  bool ocean = frame.planet.y > 0.5f;
  float shown = ocean ? max(height, frame.planet.x) : height;
  vec3 position = s.xyz + shown * up - vec3(0.0f, 0.0f, frame.camera.x);
  gl_Position = frame.viewProjection * vec4(position, 1.0f);
  outNormal = normals[index].xyz;
  outUp = up;
  outAttributes = attributes[index];
  outHeight = height;
  outToCamera = -position;
}

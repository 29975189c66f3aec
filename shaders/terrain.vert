#version 450
// Terrain vertices: everything was computed by terrain_heights.comp (heights and normals);
// this only places the vertex relative to the camera (local frame, float offsets from the
// anchor) and projects it. Below sea level the ground is drawn at the water surface (the ocean
// colour comes from the fragment shader until the water pass exists).
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"

// The vertex's values, from the buffers the height pass wrote (TerrainPass::bindDrawState).
layout(location = 0) in vec4 inSurface;     // xyz: sea-sphere point − anchor (local), w: height (m)
layout(location = 1) in vec4 inDirection;   // the mesh vertex's unit direction (local), w = 1
layout(location = 2) in vec4 inNormal;      // xyz: unit normal (local)
layout(location = 3) in vec4 inAttributes;  // face Δa, Δb, band noise, sin(latitude)

layout(location = 0) out vec3 outNormal;      // local frame
layout(location = 1) out vec3 outUp;          // sphere normal (local frame)
layout(location = 2) out vec4 outAttributes;  // face Δa, Δb, band noise, sin(latitude)
layout(location = 3) out float outHeight;     // metres above the radius sphere
layout(location = 4) out vec3 outToCamera;    // local frame, metres

void main() {
  vec4 s = inSurface;
  vec3 up = inDirection.xyz;
  float height = s.w;
  bool ocean = frame.planet.y > 0.5f;
  float shown = ocean ? max(height, frame.planet.x) : height;
  vec3 position = s.xyz + shown * up - vec3(0.0f, 0.0f, frame.camera.x);
  gl_Position = frame.viewProjection * vec4(position, 1.0f);
  outNormal = inNormal.xyz;
  outUp = up;
  outAttributes = inAttributes;
  outHeight = height;
  outToCamera = -position;
}

#version 450
// The water sphere (issue 4, point 1): the clipmap mesh again, placed at sea level. Sharing the
// terrain's vertices makes the coastline the exact intersection of two surfaces interpolated
// over the same triangles; the fragment shader refines it per pixel from the patch heights.
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"

// The vertex's values, from the buffers the height pass wrote (TerrainPass::bindDrawState).
layout(location = 0) in vec4 inSurface;     // xyz: sea-sphere point − anchor (local), w: height (m)
layout(location = 1) in vec4 inDirection;   // the mesh vertex's unit direction (local), w = 1
layout(location = 2) in vec4 inNormal;      // xyz: unit normal (local)
layout(location = 3) in vec4 inAttributes;  // face Δa, Δb, band noise, sin(latitude)

layout(location = 0) out vec3 outNormal;      // terrain normal (local frame), for the patch fallback
layout(location = 1) out vec3 outUp;          // sphere normal (local frame)
layout(location = 2) out vec4 outAttributes;  // face Δa, Δb, band noise, sin(latitude)
layout(location = 3) out float outHeight;     // terrain height at the vertex (m)
layout(location = 4) out vec3 outToCamera;    // local frame, metres

void main() {
  vec4 s = inSurface;
  vec3 up = inDirection.xyz;
  vec3 position = s.xyz + frame.planet.x * up - vec3(0.0f, 0.0f, frame.camera.x);
  gl_Position = frame.viewProjection * vec4(position * (1.0f - kWaterTowardCamera), 1.0f);
  outNormal = inNormal.xyz;
  outUp = up;
  outAttributes = inAttributes;
  outHeight = s.w;
  outToCamera = -position;
}

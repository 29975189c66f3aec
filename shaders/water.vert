#version 450
// The water sphere (issue 4, point 1): the clipmap mesh again, placed at sea level. Sharing the
// terrain's vertices makes the coastline the exact intersection of two surfaces interpolated
// over the same triangles; the fragment shader refines it per pixel from the patch heights.
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"

layout(std430, set = 0, binding = kRenderBindingSurface) readonly buffer Surface { vec4 surface[]; };
layout(std430, set = 0, binding = kRenderBindingNormals) readonly buffer Normals { vec4 normals[]; };
layout(std430, set = 0, binding = kRenderBindingAttributes) readonly buffer Attributes { vec4 attributes[]; };

layout(location = 0) out vec3 outNormal;      // terrain normal (local frame), for the patch fallback
layout(location = 1) out vec3 outUp;          // sphere normal (local frame)
layout(location = 2) out vec4 outAttributes;  // face Δa, Δb, band noise, sin(latitude)
layout(location = 3) out float outHeight;     // terrain height at the vertex (m)
layout(location = 4) out vec3 outToCamera;    // local frame, metres

void main() {
  uint index = uint(gl_VertexIndex);
  vec4 s = surface[index];
  vec3 up = mesh[index].direction.xyz;
  vec3 position = s.xyz + frame.planet.x * up - vec3(0.0f, 0.0f, frame.camera.x);
  gl_Position = frame.viewProjection * vec4(position * (1.0f - kWaterTowardCamera), 1.0f);
  outNormal = normals[index].xyz;
  outUp = up;
  outAttributes = attributes[index];
  outHeight = s.w;
  outToCamera = -position;
}

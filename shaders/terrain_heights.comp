#version 450
// Heights of the clipmap vertices this frame (issue 3, "Heights by compute"): for every vertex
// of the drawn ring range (plus one ring on each side for the normals, plus the pole) it
// evaluates the planet's noise stack through the rebased octave tables, limited to the
// octaves its ring's spacing can show (RingBudget), and stores the vertex's position as an
// offset from the anchor in the local frame. See shaders/shared/render_params.h for frames;
// the per-vertex functions are in terrain_surface.glsl.
#extension GL_GOOGLE_include_directive : require

#include "terrain_vertex_surface.glsl"

layout(local_size_x = kTerrainComputeWorkgroupSize) in;

layout(std430, set = 0, binding = kRenderBindingSurface) writeonly buffer Surface { vec4 surface[]; };
layout(std430, set = 0, binding = kRenderBindingAttributes) writeonly buffer Attributes { vec4 attributes[]; };

void main() {
  uint invocation = gl_GlobalInvocationID.x;
  if (invocation > push.vertexCount) return;
  // The last invocation handles the pole (vertex ringCount · numPhi).
  uint index = invocation == push.vertexCount ? push.ringCount * push.numPhi : push.firstVertex + invocation;
  MeshVertex v = mesh[index];
  vec3 offsetLocal = surfaceOffsetLocal(v);
  vec3 offsetPlanet = mat3(frame.localToPlanet) * offsetLocal;
  surface[index] = vec4(offsetLocal, surfaceHeight(offsetPlanet, floatBitsToUint(v.polar.z)));
  attributes[index] = surfaceAttributes(offsetPlanet);
}

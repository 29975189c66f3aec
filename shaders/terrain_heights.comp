#version 450
// Heights and normals of the clipmap vertices this frame (issue 3, "Heights by compute"): for
// every vertex the culled mesh draws (issue 12: the cells of the drawn rings that the view
// frustum can show, clipmap_culling.h, and the pole) it evaluates
// the planet's noise stack through the rebased octave tables, limited to the octaves its ring's
// spacing can show (RingBudget), and stores the vertex's position as an offset from the anchor
// in the local frame, and its normal from the stack's analytic gradient (issue 19: one
// evaluation, where a normals pass over the neighbours' positions needed them all first).
// See shaders/shared/render_params.h for frames; the per-vertex functions are in
// terrain_vertex_surface.glsl.
// The layers' count, types and hashes are specialization constants (one pipeline per planet),
// so that lavapipe, which runs every side of a branch, evaluates only each layer's own fractal.
#extension GL_GOOGLE_include_directive : require

#include "terrain_layer_specialization.glsl"
#define TERRAIN_SPECIALIZED_LAYERS
#define TERRAIN_TABLE_BLOCK gl_WorkGroupID.z  // 0: the dispatch is one-dimensional
#include "terrain_vertex_surface.glsl"

layout(local_size_x = kTerrainComputeWorkgroupSize) in;

layout(std430, set = 0, binding = kRenderBindingSurface) writeonly buffer Surface { vec4 surface[]; };
layout(std430, set = 0, binding = kRenderBindingNormals) writeonly buffer Normals { vec4 normals[]; };
layout(std430, set = 0, binding = kRenderBindingAttributes) writeonly buffer Attributes { vec4 attributes[]; };

// The vertices to evaluate, as runs of at most a workgroup (TerrainPass::writeCulledMesh): the
// culled mesh's, ring by ring, the pole last.
layout(std430, set = 0, binding = kRenderBindingChunks) readonly buffer Chunks { uvec2 chunks[]; };

void main() {
  // No early return: lavapipe turns loads with uniform addresses (layer parameters, octave
  // tables) into one scalar load only outside control flow. Invocations past their chunk's end
  // redo its last vertex and store nothing.
  uvec2 chunk = chunks[gl_WorkGroupID.x];
  uint local = gl_LocalInvocationID.x;
  bool inRange = local < chunk.y;
  uint index = chunk.x + min(local, chunk.y - 1u);
  MeshVertex v = mesh[index];
  vec3 offsetLocal = surfaceOffsetLocal(v);
  vec3 offsetPlanet = mat3(frame.localToPlanet) * offsetLocal;
  vec4 attributeValue = surfaceAttributes(offsetPlanet, v);
  float height;
  vec3 normal;
  vertexSurface(offsetPlanet, v, attributeValue, height, normal);
  vec4 surfaceValue = vec4(offsetLocal, height);
  vec4 normalValue = vec4(normal, 0.0f);
  if (inRange) {
    surface[index] = surfaceValue;
    normals[index] = normalValue;
    attributes[index] = attributeValue;
  }
}

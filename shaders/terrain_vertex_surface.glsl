// The terrain surface at one clipmap vertex: its point on the sea sphere, its height from the
// planet's noise stack (rebased octave tables, octaves limited by its ring's RingBudget) and
// its shading attributes. Written once for the two GPU height sources of the terrain pass:
// terrain_heights.comp (HeightSource::Compute, the design) and terrain_noise.vert
// (HeightSource::VertexShader, seed 002's design, kept for `planet bench --compare`).
// The includer declares nothing of its own before this file (but the specialization constants
// of terrain_layer_specialization.glsl, see surfaceHeight, and TERRAIN_TABLE_BLOCK, see the
// octave tables); `push` is the frame's TerrainComputePush in both.
#ifndef PLANET_TERRAIN_VERTEX_SURFACE_GLSL
#define PLANET_TERRAIN_VERTEX_SURFACE_GLSL

#include "terrain_common.glsl"

layout(push_constant) uniform Push { TerrainComputePush push; };

// The rebased octave tables, read at every octave of every layer: uniform buffers, each reached
// through an array of one at TERRAIN_TABLE_BLOCK, which the includer defines as 0 in a way the
// compiler cannot fold (gl_WorkGroupID.z of a one-dimensional dispatch, gl_InstanceIndex of a
// draw of one instance). On lavapipe a storage buffer read inside a loop costs a bounds-checked
// scalar load per lane and component (measured: 14 of the height pass's 35 ms at 640×360), a
// uniform buffer's a load per lane in registers; a constant block index would let lavapipe
// compile the tables, which change every frame, into the shader (sky_uniforms.glsl says more).
layout(std140, set = 0, binding = kRenderBindingRemainders) uniform Remainders {
  vec4 values[kTerrainMaxLayers * kNoiseMaxOctaves];
} remainderTables[1];
layout(std140, set = 0, binding = kRenderBindingShifts) uniform Shifts {
  uvec4 values[kTerrainMaxLayers * kNoiseMaxOctaves];
} shiftTables[1];
// The layers' parameters, likewise: read in the layers' loops over their curves' knots. (TerrainLayer
// has the same layout in std140 as in std430: all its members align to 16 bytes or pack within one.)
layout(std140, set = 0, binding = kRenderBindingLayers) uniform Layers {
  TerrainLayer values[kTerrainMaxLayers];
} layerTables[1];
layout(std430, set = 0, binding = kRenderBindingPermutations) readonly buffer Permutations { uint permutations[]; };
layout(std430, set = 0, binding = kRenderBindingBudgets) readonly buffer Budgets { RingBudget budgets[]; };

// The patch textures (patch_textures.h): texel = (unit normal, planet frame; height, m).
layout(set = 0, binding = kRenderBindingPatches) uniform sampler2DArray patches;

uint gPermutationBase = 0u;
// False for a vertex whose surface comes from the patch textures (vertexSurface): its layers are
// evaluated with no octaves (on lavapipe an octave loop ends as soon as all its lanes are done).
bool gEvaluateNoise = true;
#define PERM(i) permutations[gPermutationBase + (i)]
#define OCTAVE_REMAINDER(layer, i) remainderTables[TERRAIN_TABLE_BLOCK].values[(layer) * kNoiseMaxOctaves + (i)]
#define OCTAVE_SHIFT(layer, i) shiftTables[TERRAIN_TABLE_BLOCK].values[(layer) * kNoiseMaxOctaves + (i)]
#include "common/noise.glsl"

// Sea-sphere point of a mesh vertex minus the anchor, local frame: R (sinθ cosφ, sinθ sinφ,
// cosθ − 1), with cosθ − 1 = −2 sin²(θ/2) so that it does not cancel near the pole.
vec3 surfaceOffsetLocal(MeshVertex v) {
  float theta = v.polar.x;
  float phi = v.polar.y;
  float s = sin(theta);
  float h2 = sin(0.5f * theta);
  return frame.camera.y * vec3(s * cos(phi), s * sin(phi), -2.0f * h2 * h2);
}

// Layer l's noise at the point `offsetPlanet` (planet frame, metres from the anchor), with the
// octaves of ring `ring`'s RingBudget, or none where `needed` is false (its mask is 0; its
// amplitude not applied). An includer that defines
// TERRAIN_SPECIALIZED_LAYERS (and includes terrain_layer_specialization.glsl first) gets the
// layers' count, types and hashes from specialization constants; otherwise from the buffer.
float layerNoise(uint l, vec3 offsetPlanet, uint ring, bool needed);
// The same with its gradient with respect to offsetPlanet (per metre, planet frame).
vec4 layerNoiseGradient(uint l, vec3 offsetPlanet, uint ring, bool needed);
#ifdef TERRAIN_SPECIALIZED_LAYERS
#define TERRAIN_UNROLLED_LAYERS
#define TERRAIN_LAYER_COUNT kSpecLayerCount
#else
#define TERRAIN_LAYER_COUNT push.layerCount
#endif
#define TERRAIN_LAYER_NOISE(l, p, ring, needed) layerNoise(l, p, ring, needed)
#define TERRAIN_LAYER_NOISE_GRADIENT(l, p, ring, needed) layerNoiseGradient(l, p, ring, needed)
#define TERRAIN_LAYER(l) layerTables[TERRAIN_TABLE_BLOCK].values[l]
#define TERRAIN_LAYER_AMPLITUDE(l) TERRAIN_LAYER(l).amplitudeM
#include "common/terrain_height.glsl"
#include "common/surface_attributes.glsl"

// Layer l's noise parameters with ring `ring`'s octaves (none where not needed); selects its
// permutation table.
NoiseParams layerParams(uint l, uint ring, bool needed) {
  gPermutationBase = l * kNoisePermutationSize;
#ifdef TERRAIN_SPECIALIZED_LAYERS
  uint type = specLayerType(l);
  uint hash = specLayerHash(l);
#else
  uint type = TERRAIN_LAYER(l).noise.type;
  uint hash = TERRAIN_LAYER(l).noise.hash;
#endif
  uint octaves = needed && gEvaluateNoise ? budgets[ring].octaves[l] : 0u;
  return terrainLayerParams(TERRAIN_LAYER(l).noise, type, hash, octaves, budgets[ring].lastOctaveWeight[l]);
}

float layerNoise(uint l, vec3 offsetPlanet, uint ring, bool needed) {
  return rebasedLayerNoise(layerParams(l, ring, needed), l, offsetPlanet);
}

vec4 layerNoiseGradient(uint l, vec3 offsetPlanet, uint ring, bool needed) {
  return rebasedLayerNoiseGradient(layerParams(l, ring, needed), l, offsetPlanet);
}

// Height in metres above the radius sphere at the point `offsetPlanet` (planet frame, metres
// from the anchor), with the octaves of ring `ring`.
float surfaceHeight(vec3 offsetPlanet, uint ring) {
  return terrainHeightSum(push.baseHeightM, push.heightScale, offsetPlanet, ring);
}

// The height and its gradient (per metre, planet frame) at `offsetPlanet`, with the octaves of
// ring `ring`: the height bit-identical to surfaceHeight's.
vec4 surfaceHeightGradient(vec3 offsetPlanet, uint ring) {
  return terrainHeightGradientSum(push.baseHeightM, push.heightScale, offsetPlanet, ring);
}

// The unit normal (local frame) of the displaced surface r = (R + h) up at a vertex with sphere
// normal `up` (local frame), from h and its gradient g at the sea-sphere point (planet frame):
// h varies over the sphere of radius R, so a step R dθ moves r by (R + h) dθ sideways and by
// R g_t dθ up, g_t the part of g tangent to the sphere; n ∝ up − R / (R + h) · g_t. The same
// formula on the CPU (reference/terrain_surface_cpu.cpp).
vec3 surfaceNormal(vec4 heightGradient, vec3 up) {
  // Precise: the compute and the vertex-shader sources must shade alike, and without it the
  // compiler may fuse these differently in the two stages.
  // Planet to local: the transpose of the rotation localToPlanet.
  PRECISE vec3 gradientLocal = gradientOf(heightGradient) * mat3(frame.localToPlanet);
  PRECISE vec3 tangent = gradientLocal - dot(gradientLocal, up) * up;
  float radius = frame.camera.y;
  PRECISE float tilt = radius / (radius + heightGradient.x);
  PRECISE vec3 normal = up - tilt * tangent;
  return normalize(normal);
}

// The spacing of mesh vertex v: its ring's circumference over the vertices per ring (CPU: the same).
float vertexSpacingM(MeshVertex v) { return frame.camera.y * sin(v.polar.x) * (6.2831853f / float(push.numPhi)); }

// The patch texel (normal in the planet frame, height) at face offset `face` (attributes.xy)
// from the level whose texels are no wider than `spacingM`, the vertex spacing (the coarsest
// such: its texels carry the octaves of a spacing between half the vertex's and the vertex's),
// the finest where even its texels are wider; false where that level's layer does not hold the
// vertex (and one texel inside, for the bilinear filter), where even the coarsest level's texels
// are under half the spacing, or there are no levels. A texel's width
// is at most R·Δ (Δ its size in face units: the gnomonic projection only shrinks it).
bool patchTexelAt(vec2 face, float spacingM, out vec4 texel) {
  texel = vec4(0.0f);
  uint levels = uint(frame.refMinusNadir.w);
  if (levels == 0u) return false;
  float resolution = float(textureSize(patches, 0).x);
  float finestTexelM = frame.camera.y / (frame.patchLevels[0].y * resolution);
  float coarser = floor(log2(max(spacingM / finestTexelM, 1.0f)));
  // Past the coarsest level's reach its texels carry octaves far finer than the vertices could
  // sample without aliasing: the noise, band-limited to the ring, takes over.
  bool fine = coarser < float(levels);
  uint j = uint(min(coarser, float(levels - 1u)));
  vec4 level = frameArray(kFrameTexelPatchLevels, j);
  vec2 uv = (face + level.zw) * level.y;
  vec4 bounds = frameArray(kFrameTexelPatchBounds, j) + vec4(1.0f, 1.0f, -1.0f, -1.0f) / resolution;
  bool held = fine && level.x >= 0.0f && all(greaterThanEqual(uv, bounds.xy)) && all(lessThanEqual(uv, bounds.zw));
  vec4 wrap = frameArray(kFrameTexelPatchWrap, j >> 1u);
  vec2 stored = uv + ((j & 1u) == 0u ? wrap.xy : wrap.zw);
  texel = textureLod(patches, vec3(stored, max(level.x, 0.0f)), 0.0f);
  return held;
}

// Height (m above the radius sphere) and normal (local frame) of mesh vertex v at `offsetPlanet`,
// with its attributes (surfaceAttributes): from the patch textures where a level fine enough
// holds the vertex (patchTexelAt: the same terrain, evaluated once per texel, fixed to the
// planet), else from the noise stack with its ring's octaves. Near the camera, where the
// vertices are densest and need the most octaves, the patches hold them all.
void vertexSurface(vec3 offsetPlanet, MeshVertex v, vec4 attributes, out float height, out vec3 normal) {
  vec4 texel;
  bool fromPatch = patchTexelAt(attributes.xy, vertexSpacingM(v), texel);
  gEvaluateNoise = !fromPatch;
  vec4 heightGradient = surfaceHeightGradient(offsetPlanet, floatBitsToUint(v.polar.z));
  gEvaluateNoise = true;
  height = fromPatch ? texel.w : heightGradient.x;
  normal = fromPatch ? normalize(mat3(frame.planetToLocal) * texel.xyz) : surfaceNormal(heightGradient, v.direction.xyz);
}

// Shading attributes at `offsetPlanet` of mesh vertex v (common/surface_attributes.glsl).
vec4 surfaceAttributes(vec3 offsetPlanet, MeshVertex v) {
  return terrainSurfaceAttributes(offsetPlanet, frame.camera.y, frame.localToPlanet[2].xyz, frame.refMinusNadir.xyz,
                                  frame.faceNormal, frame.faceAxisA, frame.faceAxisB, push.bandFrequency,
                                  vertexSpacingM(v), push.regionalWeight);
}

#endif

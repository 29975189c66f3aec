// The terrain surface at one clipmap vertex: its point on the sea sphere, its height from the
// planet's noise stack (rebased octave tables, octaves limited by its ring's RingBudget) and
// its shading attributes. Written once for the two GPU height sources of the terrain pass:
// terrain_heights.comp (HeightSource::Compute, the design) and terrain_noise.vert
// (HeightSource::VertexShader, seed 002's design, kept for `planet bench --compare`).
// The includer declares nothing of its own before this file (but the specialization constants
// of terrain_layer_specialization.glsl, see surfaceHeight); `push` is the frame's
// TerrainComputePush in both.
#ifndef PLANET_TERRAIN_VERTEX_SURFACE_GLSL
#define PLANET_TERRAIN_VERTEX_SURFACE_GLSL

#include "terrain_common.glsl"

layout(push_constant) uniform Push { TerrainComputePush push; };

layout(std430, set = 0, binding = kRenderBindingLayers) readonly buffer Layers { TerrainLayer layers[]; };
layout(std430, set = 0, binding = kRenderBindingRemainders) readonly buffer Remainders { vec4 remainders[]; };
layout(std430, set = 0, binding = kRenderBindingShifts) readonly buffer Shifts { uvec4 shifts[]; };
layout(std430, set = 0, binding = kRenderBindingPermutations) readonly buffer Permutations { uint permutations[]; };
layout(std430, set = 0, binding = kRenderBindingBudgets) readonly buffer Budgets { RingBudget budgets[]; };

uint gPermutationBase = 0u;
#define PERM(i) permutations[gPermutationBase + (i)]
#define OCTAVE_REMAINDER(layer, i) remainders[(layer) * kNoiseMaxOctaves + (i)]
#define OCTAVE_SHIFT(layer, i) shifts[(layer) * kNoiseMaxOctaves + (i)]
#include "common/noise.glsl"

// Face-coordinate offset of a direction from the patch reference point c (DESIGN.md precision
// rule): with δ = d − c small, a − a_c = (δ·A (c·N) − (c·A) δ·N) / ((c·N)(c·N + δ·N)), every
// term a product of small numbers, so the float result keeps its relative precision.
vec2 faceOffset(vec3 delta) {
  float cN = frame.faceNormal.w;
  float dN = dot(delta, frame.faceNormal.xyz);
  float denominator = cN * (cN + dN);
  if (cN + dN <= 0.05f) return vec2(1e30f);  // far round the planet: outside every patch
  float da = dot(delta, frame.faceAxisA.xyz) * cN - frame.faceAxisA.w * dN;
  float db = dot(delta, frame.faceAxisB.xyz) * cN - frame.faceAxisB.w * dN;
  return vec2(da, db) / denominator;
}

// Sea-sphere point of a mesh vertex minus the anchor, local frame: R (sinθ cosφ, sinθ sinφ,
// cosθ − 1), with cosθ − 1 = −2 sin²(θ/2) so that it does not cancel near the pole.
vec3 surfaceOffsetLocal(MeshVertex v) {
  float theta = v.polar.x;
  float phi = v.polar.y;
  float s = sin(theta);
  float h2 = sin(0.5f * theta);
  return frame.camera.y * vec3(s * cos(phi), s * sin(phi), -2.0f * h2 * h2);
}

// Layer l's noise at the point `offsetPlanet` (planet frame, metres from the anchor) as fractal
// `type` with lattice hash `hash`, with the octaves of `budget` (its amplitude not applied).
float layerNoise(uint l, uint type, uint hash, vec3 offsetPlanet, RingBudget budget) {
  gPermutationBase = l * kNoisePermutationSize;
  NoiseParams params = layers[l].noise;
  params.type = type;
  params.hash = hash;
  params.octaves = budget.octaves[l];
  params.lastOctaveWeight = budget.lastOctaveWeight[l];
  OctaveWalk walk;
  walk.q = vec3(0.0f);
  walk.lacunarity = params.lacunarity;
  walk.offset = offsetPlanet;
  walk.layer = l;
  walk.octave = 0u;
  walk.rebased = 1u;
  return fractalNoise(params, walk);
}

// Height in metres above the radius sphere at the point `offsetPlanet` (planet frame, metres
// from the anchor), with the octaves of ring `ring`. An includer that defines
// TERRAIN_SPECIALIZED_LAYERS (and includes terrain_layer_specialization.glsl first) gets the
// layers' count, types and hashes from specialization constants; otherwise from the buffer.
float surfaceHeight(vec3 offsetPlanet, uint ring) {
  RingBudget budget = budgets[ring];
  precise float sum = push.baseHeightM;
#ifdef TERRAIN_SPECIALIZED_LAYERS
  // The layers in order, as terrainHeightM sums them; the constant conditions fold away.
  if (kSpecLayerCount > 0u) sum += layers[0].amplitudeM * layerNoise(0u, kSpecType0, kSpecHash0, offsetPlanet, budget);
  if (kSpecLayerCount > 1u) sum += layers[1].amplitudeM * layerNoise(1u, kSpecType1, kSpecHash1, offsetPlanet, budget);
  if (kSpecLayerCount > 2u) sum += layers[2].amplitudeM * layerNoise(2u, kSpecType2, kSpecHash2, offsetPlanet, budget);
  if (kSpecLayerCount > 3u) sum += layers[3].amplitudeM * layerNoise(3u, kSpecType3, kSpecHash3, offsetPlanet, budget);
  if (kSpecLayerCount > 4u) sum += layers[4].amplitudeM * layerNoise(4u, kSpecType4, kSpecHash4, offsetPlanet, budget);
  if (kSpecLayerCount > 5u) sum += layers[5].amplitudeM * layerNoise(5u, kSpecType5, kSpecHash5, offsetPlanet, budget);
  if (kSpecLayerCount > 6u) sum += layers[6].amplitudeM * layerNoise(6u, kSpecType6, kSpecHash6, offsetPlanet, budget);
  if (kSpecLayerCount > 7u) sum += layers[7].amplitudeM * layerNoise(7u, kSpecType7, kSpecHash7, offsetPlanet, budget);
#else
  for (uint l = 0u; l < push.layerCount; ++l)
    sum += layers[l].amplitudeM * layerNoise(l, layers[l].noise.type, layers[l].noise.hash, offsetPlanet, budget);
#endif
  return push.heightScale * sum;
}

// Displaced position of mesh vertex `index` minus the anchor, local frame (what
// terrain_normals.comp reads back from the surface buffer).
vec3 surfacePosition(uint index) {
  MeshVertex v = mesh[index];
  vec3 offsetLocal = surfaceOffsetLocal(v);
  float height = surfaceHeight(mat3(frame.localToPlanet) * offsetLocal, floatBitsToUint(v.polar.z));
  return offsetLocal + height * v.direction.xyz;
}

// Shading attributes at `offsetPlanet`: face Δa, Δb of the patch textures, colour noise,
// sin(latitude) (layout of kRenderBindingAttributes).
vec4 surfaceAttributes(vec3 offsetPlanet) {
  float radius = frame.camera.y;
  // Planet-frame direction, good to float precision (colour and latitude only).
  vec3 nadir = frame.localToPlanet[2].xyz;
  vec3 directionPlanet = nadir + offsetPlanet / radius;
  // Colour noise: four fBm octaves from bandWavelengthM down (tens of km to a few km). It frays
  // the colour-band edges and picks the vegetation (terrain.frag); float is enough here.
  NoiseParams band;
  band.type = kNoiseFbm;
  band.octaves = 4u;
  band.hash = kNoiseHashFast;
  band.seedMix = 0x5bd1e995u;
  band.lacunarity = 2.0f;
  band.octaveWeight = 0.5f;
  band.offset = 0.0f;
  band.gain = 0.0f;
  band.count = 0u;
  band.firstIndex = 0u;
  band.lastOctaveWeight = 1.0f;
  band.pad2 = 0u;
  float bandNoise = evaluateFbm(band, directionPlanet * (radius * push.bandFrequency));
  vec2 face = faceOffset(offsetPlanet / radius - frame.refMinusNadir.xyz);
  return vec4(face, bandNoise, normalize(directionPlanet).z);
}

#endif

#version 450
// Heights of the clipmap vertices this frame (issue 3, "Heights by compute"): for every vertex
// of the drawn ring range (plus one ring on each side for the normals, plus the pole) it
// evaluates the planet's noise stack through the rebased octave tables, limited to the
// octaves its ring's spacing can show (RingBudget), and stores the vertex's position as an
// offset from the anchor in the local frame. See shaders/shared/render_params.h for frames.
#extension GL_GOOGLE_include_directive : require

#include "terrain_common.glsl"

layout(local_size_x = kTerrainComputeWorkgroupSize) in;
layout(push_constant) uniform Push { TerrainComputePush push; };

layout(std430, set = 0, binding = kRenderBindingSurface) writeonly buffer Surface { vec4 surface[]; };
layout(std430, set = 0, binding = kRenderBindingAttributes) writeonly buffer Attributes { vec4 attributes[]; };
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

void main() {
  uint invocation = gl_GlobalInvocationID.x;
  if (invocation > push.vertexCount) return;
  // The last invocation handles the pole (vertex ringCount · numPhi).
  uint index = invocation == push.vertexCount ? push.ringCount * push.numPhi : push.firstVertex + invocation;
  MeshVertex v = mesh[index];
  float theta = v.polar.x;
  float phi = v.polar.y;
  uint ring = floatBitsToUint(v.polar.z);
  float radius = frame.camera.y;

  // Sea-sphere point minus anchor, local frame: R (sinθ cosφ, sinθ sinφ, cosθ − 1), with
  // cosθ − 1 = −2 sin²(θ/2) so that it does not cancel near the pole.
  float s = sin(theta);
  float h2 = sin(0.5f * theta);
  vec3 offsetLocal = radius * vec3(s * cos(phi), s * sin(phi), -2.0f * h2 * h2);
  vec3 offsetPlanet = mat3(frame.localToPlanet) * offsetLocal;

  RingBudget budget = budgets[ring];
  precise float sum = push.baseHeightM;
  for (uint l = 0u; l < push.layerCount; ++l) {
    gPermutationBase = l * kNoisePermutationSize;
    NoiseParams params = layers[l].noise;
    params.octaves = budget.octaves[l];
    params.lastOctaveWeight = budget.lastOctaveWeight[l];
    OctaveWalk walk;
    walk.q = vec3(0.0f);
    walk.lacunarity = params.lacunarity;
    walk.offset = offsetPlanet;
    walk.layer = l;
    walk.octave = 0u;
    walk.rebased = 1u;
    sum += layers[l].amplitudeM * fractalNoise(params, walk);
  }
  float height = push.heightScale * sum;
  surface[index] = vec4(offsetLocal, height);

  // Planet-frame direction, good to float precision (colour and latitude only).
  vec3 nadir = frame.localToPlanet[2].xyz;
  vec3 directionPlanet = nadir + offsetPlanet / radius;
  // Colour-band noise: one plain simplex octave over a few km, enough to fray band edges.
  NoiseParams band;
  band.type = kNoiseSimplex;
  band.octaves = 1u;
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
  float bandNoise = evaluateNoise(band, directionPlanet * (radius * push.bandFrequency));
  vec2 face = faceOffset(offsetPlanet / radius - frame.refMinusNadir.xyz);
  attributes[index] = vec4(face, bandNoise, normalize(directionPlanet).z);
}

#version 450
// The relief cube (engine/render/relief_cube.h): for every texel of a cube map over the whole
// planet, the terrain height and the displaced surface's normal (planet frame) at the texel's
// direction, from the planet's layers limited to the octaves the texel spacing can show. Built
// once per planet. The layers walk their octaves plainly from the point on the radius sphere, as
// the double reference does (terrain_height.cpp): in float that point is good to ~0.5 m, far
// below the ~20 km texels, and no octave the budget keeps is fine enough to see it.
#extension GL_GOOGLE_include_directive : require

#include "shared/relief_params.h"

layout(local_size_x = kReliefWorkgroupSize, local_size_y = kReliefWorkgroupSize) in;

// The planet's layer count, types and hashes: one pipeline per planet.
#include "terrain_layer_specialization.glsl"

layout(push_constant) uniform Push { ReliefPush push; };
layout(set = 0, binding = kReliefBindingImage, rgba16f) uniform writeonly image2DArray relief;
layout(std430, set = 0, binding = kReliefBindingLayers) readonly buffer Layers { TerrainLayer layers[]; };
layout(std430, set = 0, binding = kReliefBindingPermutations) readonly buffer Permutations { uint permutations[]; };

uint gPermutationBase = 0u;
#define PERM(i) permutations[gPermutationBase + (i)]
// Plain walks only (never rebased).
#define OCTAVE_REMAINDER(layer, i) vec4(0.0f)
#define OCTAVE_SHIFT(layer, i) uvec4(0u)
#include "common/noise.glsl"

// Layer l's noise and its gradient (per metre) at the planet-frame point p (metres), with the
// cube's octave budget, or none where its mask is 0 (not needed).
vec4 layerNoiseGradient(uint l, vec3 p, bool needed);
#define TERRAIN_UNROLLED_LAYERS
#define TERRAIN_LAYER_COUNT kSpecLayerCount
#define TERRAIN_LAYER_NOISE(l, p, context, needed) layerNoiseGradient(l, p, needed).x
#define TERRAIN_LAYER_NOISE_GRADIENT(l, p, context, needed) layerNoiseGradient(l, p, needed)
#define TERRAIN_LAYER(l) layers[l]
#define TERRAIN_LAYER_AMPLITUDE(l) layers[l].amplitudeM
#include "common/terrain_height.glsl"

vec4 layerNoiseGradient(uint l, vec3 p, bool needed) {
  gPermutationBase = l * kNoisePermutationSize;
  uint octaves = needed ? push.budget.octaves[l] : 0u;
  NoiseParams params = terrainLayerParams(layers[l].noise, specLayerType(l), specLayerHash(l), octaves,
                                          push.budget.lastOctaveWeight[l]);
  float frequency = push.frequency[l / 4u][l % 4u];
  vec4 noise = evaluateNoiseGradient(params, p * frequency);
  return withGradient(noise.x, gradientOf(noise) * frequency);
}

// The direction through texel coordinates st in [0, 1]² of cube face `face`, in Vulkan's face
// order and orientation (+x, −x, +y, −y, +z, −z), as clouds_cover.comp.
vec3 cubeDirection(uint face, vec2 st) {
  float sc = 2.0f * st.x - 1.0f;
  float tc = 2.0f * st.y - 1.0f;
  if (face == 0u) return vec3(1.0f, -tc, -sc);
  if (face == 1u) return vec3(-1.0f, -tc, sc);
  if (face == 2u) return vec3(sc, 1.0f, tc);
  if (face == 3u) return vec3(sc, -1.0f, -tc);
  if (face == 4u) return vec3(sc, -tc, 1.0f);
  return vec3(-sc, -tc, -1.0f);
}

void main() {
  // No early return (lavapipe: uniform loads stay scalar only outside control flow); the
  // invocations past the face's edge (none for sizes that are multiples of 8) store nothing.
  uvec3 id = gl_GlobalInvocationID;
  bool inside = id.x < push.size && id.y < push.size;
  vec3 up = normalize(cubeDirection(id.z, (vec2(id.xy) + 0.5f) / float(push.size)));
  vec3 p = push.radiusM * up;
  vec4 hg = terrainHeightGradientSum(push.baseHeightM, push.heightScale, p, 0u);
  // The displaced surface's normal, as terrain_vertex_surface.glsl's surfaceNormal: the part of
  // the height's gradient along the sphere tilts it by R / (R + h).
  vec3 gradient = gradientOf(hg);
  vec3 tangent = gradient - dot(gradient, up) * up;
  vec3 normal = normalize(up - push.radiusM / (push.radiusM + hg.x) * tangent);
  if (inside) imageStore(relief, ivec3(id), vec4(normal, hg.x));
}

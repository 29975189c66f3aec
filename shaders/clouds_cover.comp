#version 450
// Cloud cover (seed 001 §4.4): three independent 3D fBm images over the sphere, one per
// channel of a cube map, generated once. The sky pass cross-fades them over time with the
// weights of seed 001's eq. 4.2 and shapes the result with Elias's cover function (eq. 4.1).
#extension GL_GOOGLE_include_directive : require

#include "shared/noise_params.h"
#include "shared/sky_params.h"

layout(local_size_x = kSkyWorkgroupSize, local_size_y = kSkyWorkgroupSize) in;
layout(push_constant) uniform Push {
  NoiseParams noise;  // fBm with the preset's octaves; seedMix is recomputed per channel
  vec4 shape;         // x: radius · frequency (noise units per unit direction), y: face size (texels), z: seed (uint bits), w: 1 / Σ octave weights
};
layout(set = 0, binding = 0, rgba8) uniform writeonly image2DArray cover;

#define PERM(i) 0u  // the fast hash only
#define OCTAVE_REMAINDER(layer, i) vec4(0.0f)
#define OCTAVE_SHIFT(layer, i) uvec4(0u)
#include "common/noise.glsl"

// The direction through texel (s, t) of cube face `face`, in Vulkan's face order and
// orientation (+x, −x, +y, −y, +z, −z; the spec's cube map face selection, inverted).
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
  uint size = uint(shape.y);
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= size || id.y >= size) return;
  vec3 direction = normalize(cubeDirection(id.z, (vec2(id.xy) + 0.5f) / float(size)));
  vec3 p = direction * shape.x;
  vec3 value;
  for (uint c = 0u; c < 3u; ++c) {
    NoiseParams params = noise;
    params.seedMix = noiseSeedMix(floatBitsToUint(shape.z) + c * 7919u);
    params.hash = kNoiseHashFast;  // PERM is 0 here: the compiler drops the reference hash
    // fBm is about ±0.6 of its weight sum: map it to [0, 1] around 0.5.
    value[c] = clamp(0.5f + 0.8f * evaluateFbm(params, p) * shape.w, 0.0f, 1.0f);
  }
  imageStore(cover, ivec3(id), vec4(value, 1.0f));
}

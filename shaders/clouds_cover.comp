#version 450
// Cloud cover (seed 001 §4.4, issue 20 point 4): three cloud density images over the sphere, one
// per channel of a cube map, generated once per planet; the sky pass cross-fades them over time
// with the weights of seed 001's eq. 4.2. Each image is 3D fBm shaped into weather:
// - the fBm is sampled where the air at the texel came from: the point is carried back through
//   the cyclones (a twist about each centre that decays outward, so the noise winds into spiral
//   arms, counter-clockwise in the north and clockwise in the south, as low-pressure systems
//   turn), then through the zonal winds (each latitude circle turned by how far its wind
//   carried it: easterly trades, the westerly jet, polar easterlies; their shear draws the noise
//   out into fronts and streets), then through a smooth fBm displacement (Quilez's domain
//   warping) that bends everything into swirls;
// - Elias's cover function (seed 001 eq. 4.1) d = 1 − S^max(0, v − (1 − coverage)) turns it into
//   density, with v raised in the cyclones and by latitude: the ITCZ near 5° N, the storm tracks
//   at 50–60° and the polar cloud, and lowered over the dry subtropics near 25°.
// The largest octaves and the weather are the same in the three images, so the cross-fade
// changes the small clouds while the weather systems persist. Storing density (not v) lets the
// mip levels average what the sky pass draws: a far pixel sees the mean cloudiness of its
// footprint instead of an aliased speck.
#extension GL_GOOGLE_include_directive : require

#include "shared/noise_params.h"
#include "shared/sky_params.h"

layout(local_size_x = kSkyWorkgroupSize, local_size_y = kSkyWorkgroupSize) in;
layout(push_constant) uniform Push {
  NoiseParams noise;  // fBm with the preset's octaves; seedMix and octaves are set per use
};
layout(set = 0, binding = 0, rgba8) uniform writeonly image2DArray cover;
layout(std430, set = 0, binding = 1) readonly buffer Weather { CloudWeather weather; };

#define PERM(i) 0u  // the fast hash only
#define OCTAVE_REMAINDER(layer, i) vec4(0.0f)
#define OCTAVE_SHIFT(layer, i) uvec4(0u)
#include "common/noise.glsl"

const float kPi = 3.14159265f;

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

// v rotated by `angle` about the unit axis (Rodrigues).
vec3 rotateAbout(vec3 v, vec3 axis, float angle) {
  float c = cos(angle), s = sin(angle);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.0f - c));
}

NoiseParams fbmParams(uint seed, uint octaves) {
  NoiseParams params = noise;
  params.seedMix = noiseSeedMix(seed);
  params.hash = kNoiseHashFast;  // PERM is 0 here: the compiler drops the reference hash
  params.octaves = octaves;
  params.lastOctaveWeight = 1.0f;
  return params;
}

// Zonal wind over its peak, by latitude: easterly trades peaking near 15°, the westerly jet
// near 45°, polar easterlies near 75° (−sin 6|φ|, the three-cell circulation).
float zonalWind(float latitude) { return -sin(6.0f * abs(latitude)); }

void main() {
  uint size = uint(weather.shape.y);
  uvec3 id = gl_GlobalInvocationID;
  if (id.x >= size || id.y >= size) return;
  vec3 direction = normalize(cubeDirection(id.z, (vec2(id.xy) + 0.5f) / float(size)));
  uint seed = floatBitsToUint(weather.shape.z);

  // Cyclones: carried back through each twist (the last one applied first), and their cover.
  vec3 p = direction;
  float boost = 0.0f;
  uint vortexCount = uint(weather.cover.w);
  for (uint k = 0u; k < vortexCount; ++k) {
    CloudVortex vortex = weather.vortices[k];
    vec3 centre = vortex.centre.xyz;
    float reach = acos(clamp(dot(direction, centre), -1.0f, 1.0f)) / vortex.centre.w;
    if (reach > 3.0f) continue;
    float falloff = exp(-reach * reach);
    p = rotateAbout(p, centre, -vortex.shape.x * falloff);
    float eye = vortex.shape.z > 0.0f ? smoothstep(0.5f * vortex.shape.z, vortex.shape.z, reach) : 1.0f;
    boost += vortex.shape.y * falloff * eye;
  }
  // Zonal winds: the latitude circle through p came from further west (or east); the jets
  // meander with a slow noise so that the fronts they draw are not parallel to latitude lines.
  float latitude = asin(clamp(p.z, -1.0f, 1.0f));
  NoiseParams slow = fbmParams(seed + 31u, 2u);
  float meander = weather.flow.z * evaluateFbm(slow, p * 3.0f);
  float shift = weather.flow.x * zonalWind(latitude + meander) / max(cos(latitude), 0.25f);
  p = rotateAbout(p, vec3(0.0f, 0.0f, 1.0f), -shift);
  // Domain warping: a smooth displacement bends the field into swirls.
  vec3 warp = vec3(evaluateFbm(fbmParams(seed + 101u, 3u), p * weather.flow.w),
                   evaluateFbm(fbmParams(seed + 202u, 3u), p * weather.flow.w),
                   evaluateFbm(fbmParams(seed + 303u, 3u), p * weather.flow.w));
  p = normalize(p + weather.flow.y * warp);

  // Climate by latitude of the texel (not of the warped point): ITCZ a little north of the
  // equator, dry subtropics, storm tracks, polar cloud; in units of v.
  float lat = asin(clamp(direction.z, -1.0f, 1.0f)) * (180.0f / kPi);
  float absLat = abs(lat);
  float climate = 0.16f * exp(-((lat - 5.0f) / 7.0f) * ((lat - 5.0f) / 7.0f)) -
                  0.05f * exp(-((absLat - 24.0f) / 9.0f) * ((absLat - 24.0f) / 9.0f)) +
                  0.12f * exp(-((absLat - 57.0f) / 11.0f) * ((absLat - 57.0f) / 11.0f));
  float bias = weather.cover.z * climate + boost;

  // fBm: the shared large octaves, then each image's own finer ones (octave i at p·L^i with
  // weight L^(−iH), the same sum as one fBm of all octaves).
  vec3 q = p * weather.shape.x;
  uint octaves = noise.octaves;
  uint sharedOctaves = min(octaves, kCloudSharedOctaves);
  float large = evaluateFbm(fbmParams(seed, sharedOctaves), q);
  float scale = 1.0f, weight = 1.0f;
  for (uint i = 0u; i < sharedOctaves; ++i) {
    scale *= noise.lacunarity;
    weight *= noise.octaveWeight;
  }
  vec3 density;
  for (uint c = 0u; c < 3u; ++c) {
    float fine = octaves > sharedOctaves ? evaluateFbm(fbmParams(seed + 1u + c * 7919u, octaves - sharedOctaves), q * scale) : 0.0f;
    // fBm is about ±0.6 of its weight sum: map it to [0, 1] around 0.5.
    float v = 0.5f + 0.8f * (large + weight * fine) * weather.shape.w + bias;
    density[c] = 1.0f - exp(-weather.cover.y * max(0.0f, v - (1.0f - weather.cover.x)));
  }
  imageStore(cover, ivec3(id), vec4(density, 1.0f));
}

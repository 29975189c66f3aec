// Per-pixel ground noise (issue 20, points 1 and 5): octaves of simplex noise on a lattice fixed
// to the planet, evaluated per pixel down to the pixel's footprint. The coarse octaves (2.5 km and
// 625 m) fray the edges of the materials below the vertex spacing; the fine ones (4 m to 1.6 cm)
// are the ground's detail: a height field whose analytic gradient tilts the normal, and albedo
// variation (whose fields also fray the edges at their scales, terrain.frag). Each octave costs
// every pixel that shows it one noise evaluation, hence lacunarities of 4 and 3 (issue 20,
// point 7: the render pass may grow by at most a quarter). Used by terrain.frag through terrain_material.glsl.
//
// Precision (DESIGN.md "Earth-scale precision"): a fragment knows its position only as a small
// float offset from the mesh's anchor (the radius-sphere point below the camera); its
// planet-frame position is far too large for a float to hold centimetres. So every frame the CPU
// splits anchor · frequency_i, in double, into an integer lattice shift (coordinates summing to
// a multiple of 3, so the simplex skew stays integral) and a remainder in [0, 3) × [0, 1)²
// (TerrainPass::writeUniforms, FrameUniforms::groundOctaves and groundShifts), and the pixel
// samples octave i at remainder_i + offset · frequency_i. An octave is evaluated only where the
// pixel footprint is below half its wavelength, i.e. within about a thousand wavelengths of the
// camera, so offset · frequency stays below ~10³ cells and the sample is good to ~10⁻⁴ of a
// cell: the lattice stays on the planet when the anchor moves with the camera, and nothing is
// quantised at planet radius. The shift is stored modulo 2²² (the fast hash's lattice mask),
// which a float holds exactly.
#ifndef PLANET_TERRAIN_DETAIL_GLSL
#define PLANET_TERRAIN_DETAIL_GLSL

// The ground noise uses only the fast hash and no rebased walk of noise.glsl.
#define PERM(i) 0u
#define OCTAVE_REMAINDER(layer, i) frameArray(kFrameTexelGroundOctaves, i)
#define OCTAVE_SHIFT(layer, i) uvec4(frameArray(kFrameTexelGroundShifts, i))
#define NOISE_NO_CRATERS
#include "common/noise.glsl"

// An includer's specialization constant: false in frames where no pixel's footprint is below
// half the detail's longest wavelength, so that every octave's fade is 0 and groundDetail returns
// zeros (TerrainPass::shadingFor); the code is then left out.
#ifndef GROUND_DETAIL_POSSIBLE
#define GROUND_DETAIL_POSSIBLE true
#endif

const uint kGroundSeedBiome = 0x2c1b3c6du;   // the coarse octaves' lattice seed
const uint kGroundSeedDetail = 0x297a2d39u;  // the fine octaves'

// How much of an octave of wavelength λ a pixel of footprint f shows: all of it from λ = 4 f
// down, none from λ = 2 f (its cells would be two pixels wide and alias into shimmer).
float octaveFade(float wavelengthM, float footprintM) {
  return clamp(wavelengthM / (2.0f * footprintM) - 1.0f, 0.0f, 1.0f);
}

// Octave i's lattice point and shift at `offsetPlanet` (planet frame, metres from the anchor).
vec3 groundOctavePoint(uint i, vec3 offsetPlanet, out uvec3 shift) {
  vec4 r = frameArray(kFrameTexelGroundOctaves, i);
  shift = uvec3(frameArray(kFrameTexelGroundShifts, i).xyz);
  return r.xyz + offsetPlanet * r.w;
}

// The coarse octaves (2.5 km and 625 m, a lacunarity of 4: fraying needs fewer octaves than relief,
// and each costs every pixel): the fBm that the per-vertex band noise (40 .. 5 km, attributes.z)
// continues, weights 0.3 per octave from 0.06 (where the band noise's weights end), faded out
// by the footprint. About [-0.1, 0.1]: it frays edges, it does not place them.
float groundBiomeNoise(vec3 offsetPlanet, float footprintM) {
  float sum = 0.0f;
  float weight = 0.0625f;
  for (uint i = 0u; i < kGroundBiomeOctavesGpu; ++i) {
    float fade = octaveFade(1.0f / frameArray(kFrameTexelGroundOctaves, i).w, footprintM);
    if (fade <= 0.0f) break;
    uvec3 shift;
    vec3 q = groundOctavePoint(i, offsetPlanet, shift);
    sum += fade * weight * simplexWrapped(q, shift, kNoiseHashFast, kGroundSeedBiome);
    weight *= 0.3f;
  }
  return sum;
}

// The fine octaves at a pixel: relief slope and albedo fields.
struct GroundDetail {
  vec3 slope;      // gradient of the detail height field (planet frame, m/m) at one unit of relief
  float albedo;    // luminance field, about [-1, 1] (even octaves)
  float hue;       // a second field for colour variation, about [-1, 1] (odd octaves)
  float stones;    // 0 .. 1: where stones lie (thresholded mid octaves, antialiased)
};

// The height field is self-similar (each octave's amplitude proportional to its wavelength, so
// every octave adds the same slope): octave i's height is 0.055 λ_i N_i, whose gradient is
// 0.055 ∇_q N_i per metre (q = p · f_i, λ_i f_i = 1). |∇_q N| is about 3 on average, so each
// octave adds a slope of ~0.16 and the six visible near the camera ~0.4 (rms, at relief 1).
GroundDetail groundDetail(vec3 offsetPlanet, float footprintM) {
  GroundDetail d;
  d.slope = vec3(0.0f);
  d.albedo = 0.0f;
  d.hue = 0.0f;
  d.stones = 0.0f;
  if (!GROUND_DETAIL_POSSIBLE) return d;
  for (uint i = kGroundBiomeOctavesGpu; i < kGroundOctavesGpu; ++i) {
    float frequency = frameArray(kFrameTexelGroundOctaves, i).w;
    float fade = octaveFade(1.0f / frequency, footprintM);
    if (fade <= 0.0f) break;
    uvec3 shift;
    vec3 q = groundOctavePoint(i, offsetPlanet, shift);
    vec4 n = simplexWrappedGradient(q, shift, kNoiseHashFast, kGroundSeedDetail + i);
    d.slope += (fade * 0.055f) * gradientOf(n);
    uint k = i - kGroundBiomeOctavesGpu;
    if ((k & 1u) == 0u)
      d.albedo += fade * 0.6f * n.x;
    else
      d.hue += fade * 0.6f * n.x;
    // Stones: the top of octaves 1 .. 3 (wavelengths 133 .. 15 cm), each a patch of stones a
    // third of its wavelength across. The edge is as soft as the noise's change across a pixel.
    if (k >= 1u && k <= 3u) {
      float blur = 0.05f + length(gradientOf(n)) * frequency * footprintM;
      d.stones += fade * smoothstep(0.45f - blur, 0.45f + blur, n.x);
    }
  }
  d.stones = min(d.stones, 1.0f);
  return d;
}

#endif

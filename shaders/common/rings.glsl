// Planetary rings, written once in the common subset of GLSL 4.50 and C++: included by ring.frag
// (the ring itself), ring_eval.comp (tests) and any shader that darkens a body by the ring's
// shadow (ringShadow), and by engine/reference/ring_density.cpp (the CPU reference).
//
// Seed 001 §4.5 (Algorithm 3): the ring coordinate u is 0 at the inner radius and 1 at the outer;
// the opacity is 10 octaves of 1D Perlin noise of u, starting at frequency 2 and amplitude 20,
// each octave 2.1 times the frequency and half the amplitude of the one before, averaged over
// the octaves, mapped by 0.5 + 0.5 · x and cubed (clamped to [0, 1] first: the sum can leave
// [−1, 1]). The paper's per-ring offset `no` becomes a seeded lattice hash plus a fractional
// offset per octave. Added here: octaves finer than the pixel (or the sun's penumbra) fade out,
// a few gaps (Cassini-like) at seeded radii, a fade at both edges, and a second noise that
// mixes the two colours.
//
// Rules (STYLE.md): `real` for every float, .x/.y/.z instead of swizzles, an `f` suffix on
// every literal, explicit conversions, unsigned integer hashing, PRECISE on float
// intermediates, IN() for structs passed in. The noise core (ringNoise .. ringSample) uses
// only + − × ÷, floor, clamp, max and abs, so lavapipe and the CPU agree bit for bit; the slant
// opacity needs pow and the shadows sqrt, which other GPUs may round differently (a few ULP).
//
// Types, qualifiers and builtins: definitions.glsl (C++: definitions.h); the includer provides
// RingParams (shared/ring_params.h).
#ifndef PLANET_COMMON_RINGS_GLSL
#define PLANET_COMMON_RINGS_GLSL

#include "common/definitions.glsl"
#include "common/hash.glsl"

// --- Hashing and 1D gradient noise ------------------------------------------------------------

SHARED_CONST real kRingUnit24 = 5.96046448e-08f;  // 2^−24
SHARED_CONST uint kRingColourOctaves = 7u;  // of the colour noise: frequencies 5 .. 5 · 2.2^6 ≈ 570

// The gradient (slope) of lattice point i: the hash's top 24 bits as a number in [−1, 1), exact in float.
real ringGradient(int i, uint salt) {
  uint h = lowbias32(uint(i) ^ salt);
  PRECISE real g = real(h >> 8u) * (2.0f * kRingUnit24) - 1.0f;
  return g;
}

// 1D Perlin (gradient) noise (Perlin 2002, "Improving Noise": quintic fade): 0 at every lattice
// point, with the hashed slope there, scaled by 2 to the usual [−1, 1] range (the raw
// interpolation reaches ±0.5). x must be finite and below 2^31.
real ringNoise(real x, uint salt) {
  real cell = floor(x);
  PRECISE real f = x - cell;
  int i = int(cell);
  real g0 = ringGradient(i, salt);
  real g1 = ringGradient(i + 1, salt);
  PRECISE real fade = f * f * f * (f * (f * 6.0f - 15.0f) + 10.0f);
  PRECISE real a = g0 * f;
  PRECISE real b = g1 * (f - 1.0f);
  PRECISE real n = a + fade * (b - a);
  return 2.0f * n;
}

// GLSL's smoothstep, spelled out so that both compilers round it the same way.
real ringSmoothstep(real edge0, real edge1, real x) {
  PRECISE real t = clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  PRECISE real s = t * t * (3.0f - 2.0f * t);
  return s;
}

// An octave whose lattice cells span 4 pixels or more counts fully; at 2 pixels or fewer it would
// alias and is left out (its mean is 0). `footprint`: how much u changes across a pixel.
real ringOctaveWeight(real frequency, real footprint) {
  return 1.0f - ringSmoothstep(0.25f, 0.5f, frequency * footprint);
}

// --- The ring's opacity and colour -------------------------------------------------------------

// Algorithm 3 of seed 001 (see the top of this file), for u in [0, 1].
real ringNoiseOpacity(real u, real footprint, IN(RingParams) ring) {
  PRECISE real sum = 0.0f;
  PRECISE real frequency = 2.0f;
  PRECISE real amplitude = 20.0f;
  for (uint k = 0u; k < ring.octaves; ++k) {
    uint salt = lowbias32(ring.seedMix + k);  // each octave its own lattice
    // The paper's `no`: a fractional offset of 0 .. 64 cells, so that the octaves' lattice
    // points (where each is 0) do not line up at u = 0.
    PRECISE real offset = real(salt >> 8u) * (64.0f * kRingUnit24);
    real weight = ringOctaveWeight(frequency, footprint);
    if (weight <= 0.0f) break;  // and every finer octave: adding their zeros changes no bit
    PRECISE real x = offset + frequency * u;
    PRECISE real term = amplitude * weight * ringNoise(x, salt);
    sum = sum + term;
    amplitude = amplitude * 0.5f;
    frequency = frequency * 2.1f;
  }
  PRECISE real alpha = clamp(0.5f + 0.5f * (sum / real(ring.octaves)), 0.0f, 1.0f);
  PRECISE real cubed = alpha * alpha * alpha;
  return cubed;
}

// The share of the opacity the gaps leave at u: each gap removes `depth` of it within its half
// width, with soft walls (at least a pixel wide, so that a narrow gap seen from afar does not alias).
real ringGapFactor(real u, real footprint, IN(RingParams) ring) {
  PRECISE real factor = 1.0f;
  for (uint g = 0u; g < ring.gapCount; ++g) {
    vec4 gap = ring.gaps[g];
    real soft = max(0.3f * gap.y, footprint);
    PRECISE real inside = 1.0f - ringSmoothstep(gap.y - soft, gap.y + soft, abs(u - gap.x));
    factor = factor * (1.0f - gap.z * inside);
  }
  return factor;
}

// How much of the second colour (ring.variation) the particles at u have: a noise of its own
// lattice, so that colour and opacity bands do not coincide, and rougher than the opacity's
// (gain 0.7 instead of 0.5) so that the many narrow ringlets real rings show appear in colour
// where Algorithm 3's opacity is smooth.
real ringColourMix(real u, real footprint, IN(RingParams) ring) {
  PRECISE real sum = 0.0f;
  PRECISE real frequency = 5.0f;
  PRECISE real amplitude = 1.0f;
  for (uint k = 0u; k < kRingColourOctaves; ++k) {
    uint salt = lowbias32((ring.seedMix ^ 0x68e31da4u) + k);
    PRECISE real offset = real(salt >> 8u) * (64.0f * kRingUnit24);
    real weight = ringOctaveWeight(frequency, footprint);
    if (weight <= 0.0f) break;
    PRECISE real x = offset + frequency * u;
    PRECISE real term = amplitude * weight * ringNoise(x, salt);
    sum = sum + term;
    amplitude = amplitude * 0.7f;
    frequency = frequency * 2.2f;
  }
  return ringSmoothstep(-0.6f, 0.6f, sum);
}

// The ring at coordinate u seen perpendicularly: rgb the particles' albedo, a the opacity in
// [0, 1] (0 outside 0 < u < 1, fading to 0 at both edges). `footprint` is how much u changes
// across a pixel (0: every octave).
vec4 ringSample(real u, real footprint, IN(RingParams) ring) {
  if (!(u > 0.0f && u < 1.0f)) return vec4(0.0f, 0.0f, 0.0f, 0.0f);  // also NaN
  real fade = max(kRingEdgeFade, footprint);
  PRECISE real edges = ringSmoothstep(0.0f, fade, u) * ringSmoothstep(0.0f, fade, 1.0f - u);
  PRECISE real alpha = ringNoiseOpacity(u, footprint, ring) * ringGapFactor(u, footprint, ring) * edges * ring.colour.w;
  real t = ringColourMix(u, footprint, ring);
  PRECISE real r = ring.colour.x + t * (ring.variation.x - ring.colour.x);
  PRECISE real g = ring.colour.y + t * (ring.variation.y - ring.colour.y);
  PRECISE real b = ring.colour.z + t * (ring.variation.z - ring.colour.z);
  return vec4(r, g, b, clamp(alpha, 0.0f, 1.0f));
}

// The ring coordinate of body-frame radius r (metres).
real ringCoordinate(real r, IN(RingParams) ring) {
  PRECISE real u = (r - ring.radii.x) * ring.radii.z;
  return u;
}

// The opacity of a ring of perpendicular opacity alpha along a path at `cosine` to its normal:
// the particles cover 1 − (1 − alpha)^(1/|cosine|) of the view (the layer's optical depth grows
// as 1/|cosine|), so a ring seen at a grazing angle is more opaque than seen from above.
real ringSlantOpacity(real alpha, real cosine) {
  real mu = max(abs(cosine), kRingMinSlantCosine);
  return 1.0f - pow(1.0f - alpha, 1.0f / mu);
}

// --- Shadows --------------------------------------------------------------------------------------

// The fraction of sunlight that reaches a body-frame point after passing the ring (1 = no ring
// in the way): the sun ray from the point meets the plane z = 0 ahead of it only when point and
// sun lie on opposite sides. The sun's disc blurs the shadow: seen from the point it covers 2ρt
// of the plane across the ray (ρ the sun's angular radius, t the distance), more along a
// slanted ray, and the finer octaves fade within that penumbra.
real ringShadow(vec3 pointBody, vec3 sunBody, IN(RingParams) ring) {
  if (!(pointBody.z * sunBody.z < 0.0f)) return 1.0f;
  PRECISE real t = -pointBody.z / sunBody.z;
  PRECISE real x = pointBody.x + t * sunBody.x;
  PRECISE real y = pointBody.y + t * sunBody.y;
  PRECISE real r = sqrt(x * x + y * y);
  PRECISE real penumbra = 2.0f * ring.variation.w * t * ring.radii.z / max(abs(sunBody.z), 0.1f);
  real alpha = ringSample(ringCoordinate(r, ring), penumbra, ring).w;
  return 1.0f - ringSlantOpacity(alpha, sunBody.z);
}

// The visible fraction of the sun's disc at a body-frame point, with the sphere of radius
// ring.radii.w (the body the ring circles) in the way: 1 when the sun ray passes the sphere
// by more than the penumbra ρ·d (ρ the sun's angular radius, d the distance to the point of
// closest approach), 0 when it passes that much below the surface, smooth in between.
real ringPlanetShadow(vec3 pointBody, vec3 sunBody, IN(RingParams) ring) {
  PRECISE real along = -(pointBody.x * sunBody.x + pointBody.y * sunBody.y + pointBody.z * sunBody.z);
  if (!(along > 0.0f)) return 1.0f;  // the ray toward the sun leads away from the body
  PRECISE real cx = pointBody.x + along * sunBody.x;
  PRECISE real cy = pointBody.y + along * sunBody.y;
  PRECISE real cz = pointBody.z + along * sunBody.z;
  PRECISE real miss = sqrt(cx * cx + cy * cy + cz * cz) - ring.radii.w;
  real penumbra = max(along * ring.variation.w, 1.0f);
  return ringSmoothstep(-penumbra, penumbra, miss);
}

#endif

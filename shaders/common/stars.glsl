// The star catalogue, written once in the common subset of GLSL 4.50 and C++: included by
// stars.comp (one invocation per star) and by engine/reference/star_kernel.h (the CPU reference).
//
// Rules (STYLE.md): .x/.y/.z instead of swizzles, an `f` suffix on every literal, explicit
// conversions, unsigned integer hashing only, PRECISE on every float intermediate (no fused
// multiply-add on either side). No sin/cos/exp/log builtin either: their GPU and C library
// versions round differently, so the few transcendental steps (log2 for the magnitude law, exp2
// for the flux, sin/cos for the azimuth) are polynomials below, built from + − × ÷, sqrt,
// floor and ldexp only. IEEE-754 rounds those exactly, so the GPU catalogue equals the CPU one
// bit for bit on lavapipe (and within a few ULP where a GPU's division or sqrt is not exact).
// Every polynomial is accurate to ~1e-7 relative, far below what a picture of stars can show.
//
// Types, qualifiers and builtins: definitions.glsl (C++: definitions.h); the includer provides
// StarRecord (shared/star_params.h).
#ifndef PLANET_COMMON_STARS_GLSL
#define PLANET_COMMON_STARS_GLSL

#include "common/definitions.glsl"
#include "common/hash.glsl"

// --- Random numbers -------------------------------------------------------------------------

// The top 24 bits of h as a float in [0, 1 − 2^−24], exactly (every value is a float).
SHARED_CONST float kStarInvTwoPow24 = 5.96046448e-08f;  // 2^−24
float starUnit(uint h) { return float(h >> 8u) * kStarInvTwoPow24; }

// --- Polynomial log2, exp2, sin/cos -------------------------------------------------------------

SHARED_CONST float kStarSqrt2 = 1.41421354f;
SHARED_CONST float kStarTwoOverLn2 = 2.88539004f;
SHARED_CONST float kStarLn2 = 0.693147182f;

// log2(k · 2^−24) for an integer 1 ≤ k ≤ 2^24, i.e. of every value (starUnit + 2^−24) takes.
// k = f · 2^e with f in [√2/2, √2], and ln f = 2 atanh t, t = (f − 1)/(f + 1), |t| ≤ 0.172:
// the series t + t³/3 + ... + t⁹/9 leaves out less than 1e-9.
float starLog2Unit(uint k) {
  int e = findMSB(k);
  PRECISE float f = ldexp(float(k), -e);  // [1, 2), exact
  if (f > kStarSqrt2) {
    f = f * 0.5f;  // exact
    e = e + 1;
  }
  PRECISE float t = (f - 1.0f) / (f + 1.0f);
  PRECISE float t2 = t * t;
  // 1/9, 1/7, 1/5, 1/3 rounded to float.
  PRECISE float series = ((((0.111111112f * t2 + 0.142857149f) * t2 + 0.200000003f) * t2 + 0.333333343f) * t2 + 1.0f);
  PRECISE float lnF = series * t;
  PRECISE float result = float(e - 24) + lnF * kStarTwoOverLn2;
  return result;
}

// 2^y for −126 < y < 127: 2^floor(y) (exact, ldexp) times e^x, x = frac(y)·ln 2 in [0, ln 2),
// by its Taylor series to x⁹ (the rest is below 8e-9).
float starExp2(float y) {
  PRECISE float n = floor(y);
  PRECISE float x = (y - n) * kStarLn2;
  // 1/9!, 1/8!, ..., 1/2! rounded to float.
  PRECISE float p = 2.75573188e-06f * x + 2.48015876e-05f;
  p = p * x + 0.000198412701f;
  p = p * x + 0.00138888892f;
  p = p * x + 0.00833333377f;
  p = p * x + 0.0416666679f;
  p = p * x + 0.166666672f;
  p = p * x + 0.5f;
  p = p * x + 1.0f;
  p = p * x + 1.0f;
  return ldexp(p, int(n));
}

// (cos, sin) of the angle a·π/2 for a in [0, 1): nested Taylor series to θ¹⁴ and θ¹³ (the rest
// is below 7e-10 at θ = π/2).
SHARED_CONST float kStarHalfPi = 1.57079637f;
vec2 starCosSinQuarter(float a) {
  PRECISE float theta = a * kStarHalfPi;
  PRECISE float t2 = theta * theta;
  // sin θ = θ (1 − θ²/(2·3) (1 − θ²/(4·5) (1 − ... (1 − θ²/(12·13)))))
  PRECISE float s = 1.0f - t2 * 0.00641025649f;  // 1/156
  s = 1.0f - t2 * 0.0090909088f * s;             // 1/110
  s = 1.0f - t2 * 0.013888889f * s;              // 1/72
  s = 1.0f - t2 * 0.0238095243f * s;             // 1/42
  s = 1.0f - t2 * 0.0500000007f * s;             // 1/20
  s = 1.0f - t2 * 0.166666672f * s;              // 1/6
  s = theta * s;
  // cos θ = 1 − θ²/(1·2) (1 − θ²/(3·4) (1 − ... (1 − θ²/(13·14))))
  PRECISE float c = 1.0f - t2 * 0.00549450563f;  // 1/182
  c = 1.0f - t2 * 0.0075757578f * c;             // 1/132
  c = 1.0f - t2 * 0.0111111114f * c;             // 1/90
  c = 1.0f - t2 * 0.0178571437f * c;             // 1/56
  c = 1.0f - t2 * 0.0333333351f * c;             // 1/30
  c = 1.0f - t2 * 0.0833333358f * c;             // 1/12
  c = 1.0f - t2 * 0.5f * c;                      // 1/2
  return vec2(c, s);
}

// --- The star model -------------------------------------------------------------------------

// The tile of star `index` in a catalogue of `count` (shared/star_params.h): tile t holds the
// indices i with t · count ≤ i · kStarTileCount < (t + 1) · count, an equal share (± 1) of
// stars, in order. The product stays below 2^32 for count ≤ kStarMaxCount.
uint starTileOf(uint index, uint count) { return (index * kStarTileCount) / count; }

// Direction: sphere point picking by Archimedes' hat-box theorem: z uniform in [−1, 1] and the
// azimuth uniform give a uniform density on the sphere (a normalised cube point would not).
// Both are drawn within the star's tile (z in its band, the azimuth in its sector), so every
// star is uniform over the sphere and the catalogue a stratified sample of it.
SHARED_CONST uint kStarSectorsPerQuadrant = kStarTileSectors / 4u;
vec3 starDirection(uint tile, uint hz, uint hAzimuth) {
  uint band = tile / kStarTileSectors;
  uint sector = tile - band * kStarTileSectors;
  PRECISE float v = (float(band) + starUnit(hz)) / float(kStarTileBands);  // [0, 1), ÷ 2^k exact
  PRECISE float z = 1.0f - 2.0f * v;
  PRECISE float rho = sqrt(max((1.0f - z) * (1.0f + z), 0.0f));
  uint quadrant = sector / kStarSectorsPerQuadrant;
  uint inQuadrant = sector - quadrant * kStarSectorsPerQuadrant;
  PRECISE float a = (float(inQuadrant) + starUnit(hAzimuth)) / float(kStarSectorsPerQuadrant);
  vec2 cs = starCosSinQuarter(a);
  // Rotation by quadrant · 90°: exact sign flips and swaps.
  float c = cs.x;
  float s = cs.y;
  if (quadrant == 1u) {
    c = -cs.y;
    s = cs.x;
  } else if (quadrant == 2u) {
    c = -cs.x;
    s = -cs.y;
  } else if (quadrant == 3u) {
    c = cs.y;
    s = -cs.x;
  }
  PRECISE float x = rho * c;
  PRECISE float y = rho * s;
  return vec3(x, y, z);
}

// Apparent visual magnitude. Whole-sky star counts grow by a factor of about 10^0.5 per
// magnitude over the naked-eye range: N(< m) ≈ 9,000 · 10^(0.5 (m − 6.5)) gives the ~9,100
// stars of the Yale Bright Star Catalogue (Hoffleit & Warren 1991, complete to V = 6.5), about
// 16 stars brighter than m = 1 and 5 brighter than m = 0 (the real sky has 16 and 4; tables of
// such counts: Allen's Astrophysical Quantities, 4th ed., Cox 2000). Fainter than the eye sees,
// real counts grow more slowly; the law is meant for m ≲ 8. A catalogue of `count` stars to
// `faintest` follows N(< m) = count · 10^(0.5 (m − faintest)): m = faintest + 2 log10(u) for u
// uniform in (0, 1], the inverse of that distribution; the brightest are clamped at −1.5.
SHARED_CONST float kStarTwoLog10Of2 = 0.60206002f;  // 2 log10(2): 2 log10(u) = this · log2(u)
float starMagnitude(uint h, float faintestMagnitude) {
  PRECISE float m = faintestMagnitude + kStarTwoLog10Of2 * starLog2Unit((h >> 8u) + 1u);
  return max(m, -1.5f);  // kStarBrightestMagnitude
}

// Relative flux 10^(−0.4 m) = 2^(−0.4 log2(10) m): 1 at magnitude 0, Pogson's ratio 100^(1/5)
// per magnitude.
SHARED_CONST float kStarPogsonLog2 = 1.32877123f;  // 0.4 log2(10)
float starFlux(float magnitude) {
  PRECISE float y = -kStarPogsonLog2 * magnitude;
  return starExp2(y);
}

// Effective temperature: a simple model, not a catalogue fit. The reciprocal temperature
// r = 1000 K / T is uniform between 1000/25000 and 1000/3000 (the colour of a black body
// changes about evenly in r, the "mired" scale), so the density in T falls as T^−2: most stars
// are cool (median 5,360 K; 28 % below 4,000 K) and one in five is a blue-white star above
// 10,000 K.
SHARED_CONST float kStarMinReciprocalT = 0.0399999991f;  // 1000 / kStarMaxTemperatureK
SHARED_CONST float kStarReciprocalTRange = 0.293333322f;  // 1000 / kStarMinTemperatureK − the above
float starReciprocalTemperature(uint h) {
  PRECISE float r = kStarMinReciprocalT + kStarReciprocalTRange * starUnit(h);
  return r;
}

// Linear sRGB colour of a black body at r = 1000 K / T, scaled to luminance Y = 1 (before the
// clamp of negative components, which only the coolest stars would have). The chromaticity is
// Kang et al.'s cubic fit of the Planckian locus in CIE 1931 xy ("Design of advanced color
// temperature control system for HDTV applications", J. Korean Phys. Soc. 41 (2002), valid for
// 1,667–25,000 K, within ~1e-3 in x and y), written in r so it needs no division; then xyY with
// Y = 1 to XYZ, and XYZ to linear sRGB (IEC 61966-2-1, D65 white: a 6,500 K star is white).
vec3 starColor(float r) {
  PRECISE float x;
  PRECISE float y;
  if (r >= 0.25f) {  // T ≤ 4,000 K
    x = ((-0.2661239f * r - 0.2343589f) * r + 0.8776956f) * r + 0.179910f;
    y = ((-0.9549476f * x - 1.37418593f) * x + 2.09137015f) * x - 0.16748867f;
  } else {
    x = ((-3.0258469f * r + 2.1070379f) * r + 0.2226347f) * r + 0.240390f;
    y = ((3.0817580f * x - 5.87338670f) * x + 3.75112997f) * x - 0.37001483f;
  }
  PRECISE float bigX = x / y;
  PRECISE float bigZ = (1.0f - x - y) / y;
  PRECISE float red = 3.2406f * bigX - 1.5372f - 0.4986f * bigZ;
  PRECISE float green = -0.9689f * bigX + 1.8758f + 0.0415f * bigZ;
  PRECISE float blue = 0.0557f * bigX - 0.2040f + 1.0570f * bigZ;
  return vec3(max(red, 0.0f), max(green, 0.0f), max(blue, 0.0f));
}

// Star `index` of the catalogue of `count` stars of `seed`. Four hashes per star, chained from
// one that mixes the index and the seed. Both are hashed before they are added, so that two
// seeds give unrelated catalogues instead of the same stars at shifted indices, and the seed is
// offset first (by 2^32 / φ) so that star i of seed s is not star s of seed i.
StarRecord starGenerate(uint index, uint count, uint seed, float faintestMagnitude) {
  uint h0 = pcgHash(pcgHash(index) + pcgHash(seed ^ 0x9e3779b9u));
  uint h1 = pcgHash(h0);
  uint h2 = pcgHash(h1);
  uint h3 = pcgHash(h2);
  vec3 direction = starDirection(starTileOf(index, count), h0, h1);
  float magnitude = starMagnitude(h2, faintestMagnitude);
  float r = starReciprocalTemperature(h3);
  PRECISE float temperature = 1000.0f / r;
  vec3 rgb = starColor(r);
  PRECISE float flux = starFlux(magnitude);
  StarRecord star;
  star.direction = vec4(direction, magnitude);
  star.color = vec4(rgb * flux, temperature);
  return star;
}

// Sprite diameter in pixels (before the view's pixel scale): 1 px at magnitude 4 and fainter,
// growing by 0.4 px per magnitude to 3 px at −1. The star's Gaussian has σ = diameter / 4
// (shared/star_params.h), so its centre pixel gets flux · erf(√2 / diameter)² at most, which
// still falls with magnitude everywhere (the flux falls by 0.92 in ln per magnitude, the
// spreading costs at most 0.29): a brighter star is both larger and brighter.
float starSpriteDiameter(float magnitude) {
  PRECISE float d = 1.0f + 0.4f * (4.0f - magnitude);
  return clamp(d, 1.0f, 3.0f);
}

#endif

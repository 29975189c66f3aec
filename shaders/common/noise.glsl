// 3D simplex noise and its fractals, written once in the common subset of GLSL 4.50 and C++.
//
// This file is compiled twice: as GLSL by glslang (included by compute shaders) and as C++
// inside engine/noise/noise_kernel.h, which is the CPU reference (float and double). The rules
// of the common subset and the types, qualifiers and builtins are definitions.glsl's (C++:
// definitions.h); no sin/cos/exp/pow in the noise. The includer provides PERM(i) (the
// reference permutation table), OCTAVE_REMAINDER and OCTAVE_SHIFT (the rebased octave tables,
// see OctaveWalk).
#ifndef PLANET_COMMON_NOISE_GLSL
#define PLANET_COMMON_NOISE_GLSL

#include "common/definitions.glsl"
#include "common/hash.glsl"

// The lean variant of the shaders specialized on a planet's layers (NOISE_NO_CRATERS,
// shaders/CMakeLists.txt) serves planets with neither crater nor erosion layers
// (planet_gpu_data.h, needsFullNoiseShaders), so it leaves the erosion fractals out too.
#if defined(NOISE_NO_CRATERS) && !defined(NOISE_NO_EROSION)
#define NOISE_NO_EROSION
#endif
// ... and the generators of seeds 000 and 004 (faults, mpd, mpd_ico: noise_generators.glsl).
#if defined(NOISE_NO_CRATERS) && !defined(NOISE_NO_GENERATORS)
#define NOISE_NO_GENERATORS
#endif

// Simplex skew and unskew factors for 3D (Gustavson 2005): F3 = 1/3, G3 = 1/6.
SHARED_CONST real kSkew3 = real(1.0f) / real(3.0f);
SHARED_CONST real kUnskew3 = real(1.0f) / real(6.0f);
// Squared kernel radius: a corner contributes (0.5 - r^2)^4. At 0.5 the kernel has vanished
// before the point can leave the simplices around its corner, so the noise is continuous.
// Gustavson's 2005 code uses 0.6, whose kernels are cut off where the point changes simplex:
// jumps of up to 5e-3 across every simplex face. The planes x = y, y = z and x = z through the
// origin are faces at every octave, so the jumps add up there: terrain seams of decimetres
// along such great circles and of metres where they meet (the poles, and latitude 0 at
// longitudes 0, ±90, 180).
SHARED_CONST real kKernelRadius2 = real(0.5f);
// Final scale that maps the sum of four kernels to about [-1, 1]: the largest |N| found by a
// search is 0.013007 before scaling, so 75 gives 0.976 (the 0.6 kernel's 32 gave 0.977).
SHARED_CONST real kNoiseScale = real(75.0f);

// Both hashes depend only on the lattice indices modulo 2^22 (the fast hash masks them, the
// reference table repeats every 256), so the noise repeats every P = 3 * 2^22 units along each
// axis. Two bounds keep every float finite and every conversion defined, for any finite input:
// - an input point is wrapped once into [-P/2, P/2] (exact, i.e. unchanged, for |x| < P/2), so
//   32 octaves of lacunarity <= 8 stay below 1.3e35 and cannot overflow;
// - lattice cells are clamped to +-2^29 before conversion to int. Beyond that an octave's
//   kernels are all out of range and it contributes 0; a float that large cannot resolve a
//   lattice cell anyway.
SHARED_CONST uint kLatticeMask = 0x3fffffu;
SHARED_CONST real kDomainPeriod = real(12582912.0f);
SHARED_CONST real kInvDomainPeriod = real(1.0f) / real(12582912.0f);
SHARED_CONST real kCellLimit = real(536870912.0f);

// Mixes a user seed into 32 well-spread bits (once per evaluation, on the CPU).
uint noiseSeedMix(uint seed) { return lowbias32(seed ^ 0x9e3779b9u); }

// Reference hash: Perlin's nested permutation lookup, as in Gustavson's reference code.
uint referenceGradient(uint i, uint j, uint k) {
  return PERM((i & 255u) + PERM((j & 255u) + PERM(k & 255u))) % 12u;
}

// Fast hash, axis term: a different odd multiplier per axis makes neighbouring cells differ
// in many bits. The mask makes the hash, and so the noise, periodic (see kLatticeMask).
SHARED_CONST uint kHashAxisX = 0x8da6b343u;
SHARED_CONST uint kHashAxisY = 0xd8163841u;
SHARED_CONST uint kHashAxisZ = 0xcb1ab31fu;
uint hashAxis(uint index, uint multiplier) { return (index & kLatticeMask) * multiplier; }

// Fast hash, final mix of seedMix + the three axis terms into a gradient index in [0, 12):
// one multiply-xorshift round spreads the bits (pure ALU, no memory access), then the top 16
// bits are scaled to [0, 12), cheaper than a modulo.
uint fastGradient(uint h) {
  h ^= h >> 16u;
  h *= 0x7feb352du;
  h ^= h >> 15u;
  return ((h >> 16u) * 12u) >> 16u;
}

// Gradient index in [0, 12) of lattice point (i, j, k).
uint latticeGradient(uint i, uint j, uint k, uint hashKind, uint seedMix) {
  if (hashKind == kNoiseHashReference) return referenceGradient(i, j, k);
  return fastGradient(seedMix + hashAxis(i, kHashAxisX) + hashAxis(j, kHashAxisY) + hashAxis(k, kHashAxisZ));
}

// Dot product of gradient g with (x, y, z). The 12 gradients are the cube-edge midpoints in
// Gustavson's order: (±1,±1,0) for g < 4, (±1,0,±1) for g < 8, (0,±1,±1) otherwise; bit 0
// negates the first non-zero component, bit 1 the second. Selected arithmetically, no table.
real gradientDot(uint g, real x, real y, real z) {
  PRECISE real u = g < 8u ? x : y;
  PRECISE real v = g < 4u ? y : z;
  return ((g & 1u) != 0u ? -u : u) + ((g & 2u) != 0u ? -v : v);
}

// One corner's kernel: (0.5 - r^2)^4 * (gradient . offset), zero outside the radius.
real cornerContribution(uint g, real x, real y, real z) {
  PRECISE real t = kKernelRadius2 - x * x - y * y - z * z;
  t = max(t, real(0.0f));
  t = t * t;
  // Named and precise, as the results below: `precise` reaches only the operations of the
  // function that assigns to a precise variable, so an unnamed return value's multiply may be
  // fused with the caller's add once a driver inlines the call. That would explain why the value
  // variants were 66-91 % bit-identical on an H200 where the gradient variants, written so, were
  // all (not yet run there again).
  PRECISE real contribution = t * t * gradientDot(g, x, y, z);
  return contribution;
}

// Any finite point wrapped into [-P/2, P/2]. The clamp only acts where float rounding left a
// remainder beyond the period (|x| > 2^24 * P).
real wrapDomain(real x) {
  PRECISE real wrapped = x - kDomainPeriod * roundEven(x * kInvDomainPeriod);
  return clamp(wrapped, -kDomainPeriod, kDomainPeriod);
}

vec3 wrapPoint(vec3 p) { return vec3(wrapDomain(p.x), wrapDomain(p.y), wrapDomain(p.z)); }

// The simplex around p (a point derived from a wrapped point): p's offsets d0..d3 from its four
// corners and their gradient indices g. simplexWrapped and simplexWrappedGradient both start here,
// so the value and the value with gradient pick the same corners and gradients.
void simplexCorners(vec3 p, uvec3 shift, uint hashKind, uint seedMix, OUT(vec3) d0, OUT(vec3) d1, OUT(vec3) d2,
                    OUT(vec3) d3, OUT(uvec4) g) {
  PRECISE real x = p.x;
  PRECISE real y = p.y;
  PRECISE real z = p.z;

  // Skew into the cubic lattice and find the cell.
  PRECISE real s = (x + y + z) * kSkew3;
  int ci = int(clamp(floor(x + s), -kCellLimit, kCellLimit));
  int cj = int(clamp(floor(y + s), -kCellLimit, kCellLimit));
  int ck = int(clamp(floor(z + s), -kCellLimit, kCellLimit));
  // Unskew the cell origin back and take the offset from it.
  PRECISE real t = real(ci + cj + ck) * kUnskew3;
  PRECISE real x0 = x - (real(ci) - t);
  PRECISE real y0 = y - (real(cj) - t);
  PRECISE real z0 = z - (real(ck) - t);

  // Which of the six simplices of the cube: rank the offset's components, with Gustavson's
  // tie-breaking (>=) so the reference hash reproduces his values exactly.
  bool xy = x0 >= y0;
  bool yz = y0 >= z0;
  bool xz = x0 >= z0;
  uint i1 = uint(xy && xz);
  uint j1 = uint(!xy && yz);
  uint k1 = uint(!xz && !yz);
  uint i2 = uint(xy || xz);
  uint j2 = uint(!xy || yz);
  uint k2 = uint(!(xz && yz));

  PRECISE real x1 = x0 - real(i1) + kUnskew3;
  PRECISE real y1 = y0 - real(j1) + kUnskew3;
  PRECISE real z1 = z0 - real(k1) + kUnskew3;
  PRECISE real x2 = x0 - real(i2) + real(2.0f) * kUnskew3;
  PRECISE real y2 = y0 - real(j2) + real(2.0f) * kUnskew3;
  PRECISE real z2 = z0 - real(k2) + real(2.0f) * kUnskew3;
  PRECISE real x3 = x0 - real(1.0f) + real(3.0f) * kUnskew3;
  PRECISE real y3 = y0 - real(1.0f) + real(3.0f) * kUnskew3;
  PRECISE real z3 = z0 - real(1.0f) + real(3.0f) * kUnskew3;

  uint i = uint(ci) + shift.x;
  uint j = uint(cj) + shift.y;
  uint k = uint(ck) + shift.z;
  uint g0, g1, g2, g3;
  if (hashKind == kNoiseHashReference) {
    g0 = referenceGradient(i, j, k);
    g1 = referenceGradient(i + i1, j + j1, k + k1);
    g2 = referenceGradient(i + i2, j + j2, k + k2);
    g3 = referenceGradient(i + 1u, j + 1u, k + 1u);
  } else {
    // The corners share their axis terms: six multiplies instead of twelve
    // (same values as latticeGradient; the seed rides on the x terms).
    uint x0h = seedMix + hashAxis(i, kHashAxisX), x1h = seedMix + hashAxis(i + 1u, kHashAxisX);
    uint y0h = hashAxis(j, kHashAxisY), y1h = hashAxis(j + 1u, kHashAxisY);
    uint z0h = hashAxis(k, kHashAxisZ), z1h = hashAxis(k + 1u, kHashAxisZ);
    g0 = fastGradient(x0h + y0h + z0h);
    g1 = fastGradient((i1 != 0u ? x1h : x0h) + (j1 != 0u ? y1h : y0h) + (k1 != 0u ? z1h : z0h));
    g2 = fastGradient((i2 != 0u ? x1h : x0h) + (j2 != 0u ? y1h : y0h) + (k2 != 0u ? z1h : z0h));
    g3 = fastGradient(x1h + y1h + z1h);
  }
  d0 = vec3(x0, y0, z0);
  d1 = vec3(x1, y1, z1);
  d2 = vec3(x2, y2, z2);
  d3 = vec3(x3, y3, z3);
  g = uvec4(g0, g1, g2, g3);
}

// N(p) for a p derived from a wrapped point (wrapPoint, then scaled by at most 8^31).
real simplexWrapped(vec3 p, uvec3 shift, uint hashKind, uint seedMix) {
  vec3 d0, d1, d2, d3;
  uvec4 g;
  simplexCorners(p, shift, hashKind, seedMix, d0, d1, d2, d3, g);
  PRECISE real n0 = cornerContribution(g.x, d0.x, d0.y, d0.z);
  PRECISE real n1 = cornerContribution(g.y, d1.x, d1.y, d1.z);
  PRECISE real n2 = cornerContribution(g.z, d2.x, d2.y, d2.z);
  PRECISE real n3 = cornerContribution(g.w, d3.x, d3.y, d3.z);
  PRECISE real sum = n0 + n1 + n2 + n3;
  PRECISE real scaled = kNoiseScale * sum;
  return scaled;
}

real simplexNoise(vec3 p, uvec3 shift, uint hashKind, uint seedMix) {
  return simplexWrapped(wrapPoint(p), shift, hashKind, seedMix);
}

// Where each octave is sampled. Plain: q_0 = wrapPoint(p), q_i = q_(i-1) * L, no lattice
// shift. Rebased (Earth-scale terrain, DESIGN.md "Earth-scale precision"): the CPU splits the
// anchor's position in octave i's units, in double, into an integer lattice shift (coordinates
// summing to a multiple of 3, so the simplex skew stays integral) and a small float remainder;
// the sample is then remainder_i + offset * scale_i, where offset = sample - anchor in metres
// stays small near the camera. OCTAVE_REMAINDER(layer, i) gives (remainder, scale) and
// OCTAVE_SHIFT(layer, i) the shift (as uvec4); the includer defines both.
struct OctaveWalk {
  vec3 q;           // plain: the next octave's point
  real lacunarity;  // plain: L
  vec3 offset;      // rebased: sample minus anchor, in metres
  uint layer;       // rebased: row of the octave tables
  uint octave;      // the next octave to sample
  uint rebased;     // 0: plain, 1: rebased
};

OctaveWalk plainWalk(IN(NoiseParams) params, vec3 p) {
  OctaveWalk walk;
  walk.q = wrapPoint(p);
  walk.lacunarity = real(params.lacunarity);
  walk.offset = vec3(real(0.0f));
  walk.layer = 0u;
  walk.octave = 0u;
  walk.rebased = 0u;
  return walk;
}

// The walk's next octave as a point q and the simplex lattice shift that goes with it (the
// octave's sample is q + shift in lattice units), then advances the walk.
void nextOctavePoint(INOUT(OctaveWalk) walk, OUT(vec3) q, OUT(uvec3) shift) {
  if (walk.rebased != 0u) {
    vec4 rs = OCTAVE_REMAINDER(walk.layer, walk.octave);
    uvec4 s = OCTAVE_SHIFT(walk.layer, walk.octave);
    PRECISE vec3 r = vec3(rs.x + walk.offset.x * rs.w, rs.y + walk.offset.y * rs.w, rs.z + walk.offset.z * rs.w);
    q = r;
    shift = uvec3(s.x, s.y, s.z);
  } else {
    q = walk.q;
    shift = uvec3(0u);
    walk.q = walk.q * walk.lacunarity;
  }
  walk.octave += 1u;
}

// N at the walk's next octave, then advances the walk.
real nextOctave(INOUT(OctaveWalk) walk, IN(NoiseParams) params) {
  vec3 q;
  uvec3 shift;
  nextOctavePoint(walk, q, shift);
  return simplexWrapped(q, shift, params.hash, params.seedMix);
}

// The fractals below follow the formulas of issue 2 (Musgrave's definitions as given in
// seed 002 §4.9-4.10): octave i samples p * L^i (through the walk) with weight w_i = L^(-i*H).
//
// Octave fade: every fractal is a running value updated once per octave, so "the last octave
// at a fraction f" is the value before it plus f times what it added (fadeLast). A renderer
// limits each sample to the octaves its spacing can show and fades the last one in with
// params.lastOctaveWeight, so the value changes continuously with the spacing (no popping).
// At weight 1 the result is exactly the unfaded one.
real fadeLast(IN(NoiseParams) params, real before, real after) {
  if (params.lastOctaveWeight >= real(1.0f)) return after;
  PRECISE real faded = before + (after - before) * real(params.lastOctaveWeight);
  return faded;
}

// fBm: sum of N(p_i) * w_i.
real fbmNoise(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE real sum = real(0.0f);
  PRECISE real before = real(0.0f);
  PRECISE real w = real(1.0f);
  for (uint i = 0u; i < params.octaves; ++i) {
    before = sum;
    sum += nextOctave(walk, params) * w;
    w *= real(params.octaveWeight);
  }
  return fadeLast(params, before, sum);
}

// Ridged multifractal: s_0 = (offset - |N(p_0)|)^2; each next octave is weighted by the
// previous one's signal times gain (clamped to [0, 1]), so ridges stay sharp and valleys smooth.
real ridgedNoise(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE real offset = real(params.offset);
  PRECISE real signal = offset - abs(nextOctave(walk, params));
  signal = signal * signal;
  PRECISE real result = signal;
  PRECISE real before = real(0.0f);
  PRECISE real w = real(1.0f);
  for (uint i = 1u; i < params.octaves; ++i) {
    w *= real(params.octaveWeight);
    PRECISE real weight = clamp(signal * real(params.gain), real(0.0f), real(1.0f));
    signal = offset - abs(nextOctave(walk, params));
    signal = signal * signal * weight;
    before = result;
    result += signal * w;
  }
  return fadeLast(params, before, result);
}

// Hybrid multifractal: smooth low areas, rough peaks; each octave is weighted by the running
// product of the previous signals.
real hybridNoise(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE real offset = real(params.offset);
  PRECISE real result = nextOctave(walk, params) + offset;
  PRECISE real before = real(0.0f);
  PRECISE real weight = result;
  PRECISE real w = real(1.0f);
  for (uint i = 1u; i < params.octaves; ++i) {
    w *= real(params.octaveWeight);
    weight = clamp(weight, real(0.0f), real(1.0f));
    PRECISE real signal = (nextOctave(walk, params) + offset) * w;
    before = result;
    result += weight * signal;
    weight *= signal;
  }
  return fadeLast(params, before, result);
}

// Heterogeneous terrain: each octave is scaled by the value so far, so heights vary in
// roughness with altitude.
real heteroNoise(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE real offset = real(params.offset);
  PRECISE real value = offset + nextOctave(walk, params);
  PRECISE real before = real(0.0f);
  PRECISE real w = real(1.0f);
  for (uint i = 1u; i < params.octaves; ++i) {
    w *= real(params.octaveWeight);
    before = value;
    value += (nextOctave(walk, params) + offset) * w * value;
  }
  return fadeLast(params, before, value);
}

// Multiplicative cascade: product of (N(p_i) + offset). Seed 002's amplitude division cancels
// out, so H has no effect here. Faded, the last factor is 1 + f * (N + offset - 1).
real cascadeNoise(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE real value = real(1.0f);
  PRECISE real before = real(1.0f);
  for (uint i = 0u; i < params.octaves; ++i) {
    before = value;
    value *= nextOctave(walk, params) + real(params.offset);
  }
  return fadeLast(params, before, value);
}

// Craters (seed 000 §3.1.9, after Linda 2007 §4.6.2: bowl, raised rim, ejecta, perturbed zones;
// here as a lattice fractal so that it needs no crater list and works at any scale).
//
// Octave i is one size class. Its sample q (the same walk as the other types, so rebasing and
// octave limiting work unchanged) lies in a unit cubic lattice; each cell holds a crater with
// probability kCraterPresence, its centre jittered inside the cell and its radius r a hashed
// fraction of kCraterRadiusMax cells. A crater reaches E = kCraterReach radii (rim at 1, ejecta
// to E), E·r·(1 + eps) with the rim perturbation below. Bound: the centre keeps a margin
// m = max(0, E·r·(1 + eps) - 1/2) from its cell's faces, and q lies within 1/2 of its nearest
// lattice corner c; a cell outside the 2x2x2 around c is, along some axis, at least 1/2 away
// from q, so its centre is at least 1/2 + m >= the crater's reach away. So those eight cells hold
// every crater that touches q (m stays below 1/2: E·rMax·1.5 = 0.675 < 1).
//
// Profile, for x = (distance / r')^2 (no square root), rim height R = kCraterRim relative to a
// floor depth of 1:
//   bowl   x <= 1:  R - (1 + R)·(1 - x)^2           (parabolic floor, -1 at the centre)
//   ejecta x >= 1:  R·(1 - u)^3·(1 + 3u), u = (x - 1) / (E^2 - 1), 0 from u = 1 on
// Both are R with zero slope at the rim and the ejecta ends with zero slope, so the height and
// its slope are continuous (no rings in the normals). A crater adds r / rMax times this
// (depth in proportion to size within the octave; the largest craters of octave 0 have floor
// depth 1), octave i weighted by w_i = L^(-iH): the depth of a crater of diameter D grows as
// D^H (H = 1: geometrically similar craters; H < 1: small craters relatively deeper, as the
// simple craters of the Moon are compared with its shallow large basins).
//
// Size distribution: octave i has L^(3i) cells per unit volume; the craters a surface cuts are
// those within their reach of it, a slab of thickness ~L^(-i), so L^(2i) per unit area, with
// diameters D_i ~ L^(-i). The cumulative count N(>D) per area = sum over i with D_i > D of
// L^(2i) ~ D^(-2): many small, few large, the equilibrium slope of lunar crater counts. (The
// surface cuts each crater's ball at a random height, so apparent sizes and depths also vary
// within an octave, like fresh and degraded craters.)
//
// Perturbation (params.offset = eps, in [0, 0.5]): r' = r·(1 + eps·n) and the rim height
// R·(1 + eps·n), with n a simplex value at twice the octave's frequency, so rims are neither
// circles nor level. Both hashes work: the cell values come from the integer hash (fast) or from
// the seed-shuffled permutation table (reference; craters then repeat every 256 cells).
SHARED_CONST real kCraterPresence = real(0.8f);   // fraction of cells that hold a crater
SHARED_CONST real kCraterRadiusMax = real(0.3f);   // largest radius, in cells
SHARED_CONST real kCraterRadiusMin = real(0.5f);   // smallest radius as a fraction of the largest
SHARED_CONST real kCraterRim = real(0.3f);         // rim height over the surroundings / floor depth
SHARED_CONST real kCraterReach = real(1.5f);       // ejecta reach in radii (E)
// 1 / (E^2 - 1), written out: a folded constant expression might round differently in glslang.
SHARED_CONST real kCraterInvEjectaSpan = real(0.8f);
SHARED_CONST real kCraterMaxPerturbation = real(0.5f);
SHARED_CONST real kInv65536 = real(1.0f) / real(65536.0f);

// 32 random bits of cell (i, j, k), from the layer's hash.
uint craterCellHash(uint i, uint j, uint k, uint hashKind, uint seedMix) {
  if (hashKind == kNoiseHashReference) {
    // Three permutation chains, the axes rotated, give 24 bits; the mix spreads them.
    uint b0 = PERM((i & 255u) + PERM((j & 255u) + PERM(k & 255u)));
    uint b1 = PERM((j & 255u) + PERM((k & 255u) + PERM(i & 255u)));
    uint b2 = PERM((k & 255u) + PERM((i & 255u) + PERM(j & 255u)));
    return lowbias32(b0 | (b1 << 8u) | (b2 << 16u));
  }
  return lowbias32(seedMix + hashAxis(i, kHashAxisX) + hashAxis(j, kHashAxisY) + hashAxis(k, kHashAxisZ));
}

// The cubic lattice's integer shift from a walk's simplex shift. The CPU's shift is
// I + m·(1,1,1) for the anchor's integer part I, whose coordinates sum to 3m (OctaveWalk); the
// shift's coordinates then sum to 6m, so m = sum/6 modulo 2^31 (halve, then multiply by the
// inverse of 3 modulo 2^32). I modulo 2^31 is all either hash uses (2^22 and 2^8).
uvec3 craterCellShift(uvec3 shift) {
  uint m = ((shift.x + shift.y + shift.z) >> 1u) * 0xaaaaaaabu;
  return uvec3(shift.x - m, shift.y - m, shift.z - m);
}

// Profile of one crater at x = (distance / r')^2, rim height rim (see above).
real craterProfile(real x, real rim) {
  if (x <= real(1.0f)) {
    PRECISE real t = real(1.0f) - x;
    PRECISE real bowl = rim - (real(1.0f) + rim) * t * t;
    return bowl;
  }
  PRECISE real u = min((x - real(1.0f)) * kCraterInvEjectaSpan, real(1.0f));
  PRECISE real s = real(1.0f) - u;
  PRECISE real ejecta = rim * s * s * s * (real(1.0f) + real(3.0f) * u);
  return ejecta;
}

// One octave of craters at point q (cell lattice shifted by `cells`), perturbation n.
real craterOctave(vec3 q, uvec3 cells, real eps, real n, uint hashKind, uint seedMix) {
  // Nearest lattice corner c and q relative to it, in [-1/2, 1/2].
  int cx = int(clamp(floor(q.x + real(0.5f)), -kCellLimit, kCellLimit));
  int cy = int(clamp(floor(q.y + real(0.5f)), -kCellLimit, kCellLimit));
  int cz = int(clamp(floor(q.z + real(0.5f)), -kCellLimit, kCellLimit));
  PRECISE real fx = q.x - real(cx);
  PRECISE real fy = q.y - real(cy);
  PRECISE real fz = q.z - real(cz);
  PRECISE real grow = real(1.0f) + eps;
  PRECISE real radiusScale = real(1.0f) + eps * n;
  PRECISE real rim = kCraterRim * radiusScale;
  PRECISE real sum = real(0.0f);
  for (uint cell = 0u; cell < 8u; ++cell) {
    // Cell (c + a) for a in {-1, 0}^3, its corner at a relative to c.
    int ax = int(cell & 1u) - 1;
    int ay = int((cell >> 1u) & 1u) - 1;
    int az = int((cell >> 2u) & 1u) - 1;
    uint h = craterCellHash(uint(cx + ax) + cells.x, uint(cy + ay) + cells.y, uint(cz + az) + cells.z, hashKind,
                            seedMix);
    uint h2 = lowbias32(h);
    if (real(h2 & 0xffffu) * kInv65536 >= kCraterPresence) continue;
    // size = r / rMax in [kCraterRadiusMin, 1): the crater's depth scale.
    PRECISE real size = kCraterRadiusMin + (real(1.0f) - kCraterRadiusMin) * real(h2 >> 16u) * kInv65536;
    PRECISE real r = kCraterRadiusMax * size;
    PRECISE real reach = kCraterReach * r * grow;
    PRECISE real margin = max(reach - real(0.5f), real(0.0f));
    PRECISE real span = real(1.0f) - real(2.0f) * margin;
    PRECISE real dx = fx - (real(ax) + margin + span * real(h >> 16u) * kInv65536);
    PRECISE real dy = fy - (real(ay) + margin + span * real(h & 0xffffu) * kInv65536);
    PRECISE real dz = fz - (real(az) + margin + span * real(lowbias32(h2) >> 16u) * kInv65536);
    PRECISE real distance2 = dx * dx + dy * dy + dz * dz;
    if (distance2 >= reach * reach) continue;
    PRECISE real rp = r * radiusScale;
    PRECISE real x = distance2 / (rp * rp);
    sum += size * craterProfile(x, rim);
  }
  return sum;
}

// Crater fractal: sum over octaves of w_i · craterOctave at octave i's point (see above).
real cratersNoise(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE real eps = clamp(real(params.offset), real(0.0f), kCraterMaxPerturbation);
  PRECISE real sum = real(0.0f);
  PRECISE real before = real(0.0f);
  PRECISE real w = real(1.0f);
  for (uint i = 0u; i < params.octaves; ++i) {
    vec3 q;
    uvec3 shift;
    nextOctavePoint(walk, q, shift);
    // Twice the frequency: the point 2q with twice the shift (its coordinates still sum to a
    // multiple of 3, so the simplex skew stays integral).
    PRECISE vec3 q2 = q * real(2.0f);
    real n = simplexWrapped(q2, shift * 2u, params.hash, params.seedMix);
    before = sum;
    sum += craterOctave(q, craterCellShift(shift), eps, n, params.hash, params.seedMix) * w;
    w *= real(params.octaveWeight);
  }
  return fadeLast(params, before, sum);
}

// The same functions with their analytic gradients (value and gradient together), and the
// erosion fractals (noise_erosion.glsl, included there), which need them.
#include "common/noise_gradient.glsl"

// The fractal of type params.type along `walk` (a simplex type samples one octave). A shader
// compiled with NOISE_NO_CRATERS leaves the crater fractal out (a craters layer then reads as
// simplex), one compiled with NOISE_NO_EROSION the damped and eroded fractals (the same), one
// compiled with NOISE_NO_GENERATORS faults, mpd and mpd_ico (the same):
// lavapipe inlines every branch here before specialization constants fold them away, so a shader
// specialized on other layers would still pay for compiling that code.
real fractalNoise(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  if (params.type == kNoiseFbm) return fbmNoise(params, walk);
  if (params.type == kNoiseRidged) return ridgedNoise(params, walk);
  if (params.type == kNoiseHybrid) return hybridNoise(params, walk);
  if (params.type == kNoiseHetero) return heteroNoise(params, walk);
  if (params.type == kNoiseCascade) return cascadeNoise(params, walk);
#ifndef NOISE_NO_CRATERS
  if (params.type == kNoiseCraters) return cratersNoise(params, walk);
#endif
#ifndef NOISE_NO_EROSION
  if (params.type == kNoiseDamped) return dampedNoise(params, walk);
  if (params.type == kNoiseEroded) return erodedNoise(params, walk);
#endif
#ifndef NOISE_NO_GENERATORS
  // Their value is the value part of the value with gradient (the gradient is dead code here).
  if (params.type == kNoiseFaults) return faultsNoiseGradient(params, walk).x;
  if (params.type == kNoiseMpd || params.type == kNoiseMpdIco) return mpdNoiseGradient(params, walk).x;
#endif
  return nextOctave(walk, params);
}

// The noise of type params.type at p.
real evaluateNoise(IN(NoiseParams) params, vec3 p) {
  OctaveWalk walk = plainWalk(params, p);
  return fractalNoise(params, walk);
}

// fBm at p whatever params.type says (equal to evaluateNoise of an fBm): for shaders that use no
// other type (clouds, colour noise), so that the other fractals never enter their code.
real evaluateFbm(IN(NoiseParams) params, vec3 p) {
  OctaveWalk walk = plainWalk(params, p);
  return fbmNoise(params, walk);
}

#endif

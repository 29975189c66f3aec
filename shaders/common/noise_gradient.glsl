// Noise with analytic derivatives: simplex noise and every fractal of noise.glsl together with its
// gradient, written once in the common subset of GLSL 4.50 and C++ (definitions.glsl). Included
// at the end of noise.glsl, so every includer of the noise (engine/noise/noise_kernel.h, the
// shaders) has both; uses noise.glsl's simplexCorners, OctaveWalk and crater functions.
//
// Why analytic: a normal or a slope from neighbour evaluations costs three more evaluations
// and a step to choose; the derivative of the formulas costs a fraction of one evaluation and
// is exact to rounding at every scale.
#ifndef PLANET_COMMON_NOISE_GRADIENT_GLSL
#define PLANET_COMMON_NOISE_GRADIENT_GLSL

// Value and gradient: the functions named *Gradient below return vec4(value, d/dx, d/dy, d/dz),
// the gradient with respect to their input point. The value is computed with the operations of
// the plain function in its order, so it is bit-identical to it; the gradient is the exact
// derivative of the formulas (not a difference), so it is as smooth as the noise itself.
// Where a formula has a kink (|N| in ridged, a clamp, a min) the gradient is the one-sided
// derivative of the branch the value took.

// The gradient part of a value with gradient.
vec3 gradientOf(vec4 valueGradient) { return vec3(valueGradient.y, valueGradient.z, valueGradient.w); }

vec4 withGradient(real value, vec3 gradient) { return vec4(value, gradient.x, gradient.y, gradient.z); }

// Gradient g of gradientDot as a vector: gradientDot(g, x, y, z) = dot(gradientVector(g), (x, y, z)).
vec3 gradientVector(uint g) {
  real u = (g & 1u) != 0u ? real(-1.0f) : real(1.0f);
  real v = (g & 2u) != 0u ? real(-1.0f) : real(1.0f);
  if (g < 4u) return vec3(u, v, real(0.0f));
  if (g < 8u) return vec3(u, real(0.0f), v);
  return vec3(real(0.0f), u, v);
}

// cornerContribution and its gradient. With t = 0.5 - r^2 and d = (x, y, z), the kernel
// t^4 (g . d) has the gradient t^4 g - 8 t^3 (g . d) d; outside the radius (t clamped to 0)
// both vanish, and the kernel's t^3 makes the gradient continuous at the radius.
vec4 cornerContributionGradient(uint g, real x, real y, real z) {
  PRECISE real t = kKernelRadius2 - x * x - y * y - z * z;
  t = max(t, real(0.0f));
  PRECISE real t2 = t * t;
  PRECISE real t4 = t2 * t2;
  PRECISE real along = gradientDot(g, x, y, z);
  PRECISE real value = t4 * along;
  PRECISE real radial = real(-8.0f) * (t2 * t) * along;
  vec3 gv = gradientVector(g);
  PRECISE real dx = t4 * gv.x + radial * x;
  PRECISE real dy = t4 * gv.y + radial * y;
  PRECISE real dz = t4 * gv.z + radial * z;
  return vec4(value, dx, dy, dz);
}

// simplexWrapped with its gradient with respect to p (the offsets from the corners move with
// p one to one: the cell is constant inside a simplex).
vec4 simplexWrappedGradient(vec3 p, uvec3 shift, uint hashKind, uint seedMix) {
  vec3 d0, d1, d2, d3;
  uvec4 g;
  simplexCorners(p, shift, hashKind, seedMix, d0, d1, d2, d3, g);
  PRECISE vec4 n0 = cornerContributionGradient(g.x, d0.x, d0.y, d0.z);
  PRECISE vec4 n1 = cornerContributionGradient(g.y, d1.x, d1.y, d1.z);
  PRECISE vec4 n2 = cornerContributionGradient(g.z, d2.x, d2.y, d2.z);
  PRECISE vec4 n3 = cornerContributionGradient(g.w, d3.x, d3.y, d3.z);
  PRECISE vec4 sum = n0 + n1 + n2 + n3;
  PRECISE vec4 scaled = kNoiseScale * sum;
  return scaled;
}

// simplexNoise with its gradient (the wrap is a translation: it leaves the gradient alone).
vec4 simplexNoiseGradient(vec3 p, uvec3 shift, uint hashKind, uint seedMix) {
  return simplexWrappedGradient(wrapPoint(p), shift, hashKind, seedMix);
}

// ---- The fractals with their gradients ----
// Each mirrors its value function above line for line (so the value is bit-identical) and
// carries the gradient beside it by the product and chain rules. The gradient is with respect
// to the walk's input: the plain walk's p, or the rebased walk's offset in metres.

// d(octave sample)/d(walk input) of the walk's next octave; call it before nextOctavePoint.
// Plain: octave i samples wrapPoint(p)·L^i, so L^i, which the caller keeps as the running
// product `plainScale` (1 at octave 0, times L after each octave: the same products as the
// walk's points). Rebased: octave i samples remainder_i + offset·scale_i, so scale_i.
real octaveChainScale(IN(OctaveWalk) walk, real plainScale) {
  if (walk.rebased != 0u) return real(OCTAVE_REMAINDER(walk.layer, walk.octave).w);
  return plainScale;
}

// nextOctave with its gradient with respect to the walk's input; advances plainScale with the walk.
vec4 nextOctaveGradient(INOUT(OctaveWalk) walk, IN(NoiseParams) params, INOUT(real) plainScale) {
  real scale = octaveChainScale(walk, plainScale);
  vec3 q;
  uvec3 shift;
  nextOctavePoint(walk, q, shift);
  plainScale = plainScale * walk.lacunarity;
  vec4 n = simplexWrappedGradient(q, shift, params.hash, params.seedMix);
  PRECISE vec3 gradient = gradientOf(n) * scale;
  return withGradient(n.x, gradient);
}

// fadeLast of a value with gradient: the same blend of both.
vec4 fadeLastGradient(IN(NoiseParams) params, vec4 before, vec4 after) {
  if (params.lastOctaveWeight >= real(1.0f)) return after;
  PRECISE vec4 faded = before + (after - before) * real(params.lastOctaveWeight);
  return faded;
}

// Derivative factor of clamp(x, 0, 1) on the branch it takes: 1 on [0, 1] (where GLSL's
// min/max return x itself), 0 outside.
real clampUnitSlope(real x) { return (x < real(0.0f) || x > real(1.0f)) ? real(0.0f) : real(1.0f); }

// d(offset - |N|) / dN on the branch abs takes (N < 0: -N, else N): +1 or -1.
real ridgeSlope(real n) { return n < real(0.0f) ? real(1.0f) : real(-1.0f); }

vec4 fbmNoiseGradient(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE vec4 sum = vec4(real(0.0f));
  PRECISE vec4 before = vec4(real(0.0f));
  PRECISE real w = real(1.0f);
  real plainScale = real(1.0f);
  for (uint i = 0u; i < params.octaves; ++i) {
    before = sum;
    sum += nextOctaveGradient(walk, params, plainScale) * w;
    w *= real(params.octaveWeight);
  }
  return fadeLastGradient(params, before, sum);
}

// Ridged: s = offset - |N|, signal = s^2 · weight with weight = clamp(previous signal · gain, 0, 1).
vec4 ridgedNoiseGradient(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE real offset = real(params.offset);
  real plainScale = real(1.0f);
  vec4 n = nextOctaveGradient(walk, params, plainScale);
  PRECISE real s = offset - abs(n.x);
  PRECISE vec3 ds = gradientOf(n) * ridgeSlope(n.x);
  PRECISE real signal = s * s;
  PRECISE vec3 dsignal = ds * (real(2.0f) * s);
  PRECISE real result = signal;
  PRECISE vec3 dresult = dsignal;
  PRECISE real before = real(0.0f);
  PRECISE vec3 dbefore = vec3(real(0.0f));
  PRECISE real w = real(1.0f);
  for (uint i = 1u; i < params.octaves; ++i) {
    w *= real(params.octaveWeight);
    PRECISE real raw = signal * real(params.gain);
    PRECISE real weight = clamp(raw, real(0.0f), real(1.0f));
    PRECISE vec3 dweight = dsignal * (real(params.gain) * clampUnitSlope(raw));
    n = nextOctaveGradient(walk, params, plainScale);
    s = offset - abs(n.x);
    ds = gradientOf(n) * ridgeSlope(n.x);
    signal = s * s * weight;
    dsignal = ds * (real(2.0f) * s * weight) + dweight * (s * s);
    before = result;
    dbefore = dresult;
    result += signal * w;
    dresult += dsignal * w;
  }
  return fadeLastGradient(params, withGradient(before, dbefore), withGradient(result, dresult));
}

vec4 hybridNoiseGradient(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE real offset = real(params.offset);
  real plainScale = real(1.0f);
  vec4 n = nextOctaveGradient(walk, params, plainScale);
  PRECISE real result = n.x + offset;
  PRECISE vec3 dresult = gradientOf(n);
  PRECISE real before = real(0.0f);
  PRECISE vec3 dbefore = vec3(real(0.0f));
  PRECISE real weight = result;
  PRECISE vec3 dweight = dresult;
  PRECISE real w = real(1.0f);
  for (uint i = 1u; i < params.octaves; ++i) {
    w *= real(params.octaveWeight);
    dweight = dweight * clampUnitSlope(weight);
    weight = clamp(weight, real(0.0f), real(1.0f));
    n = nextOctaveGradient(walk, params, plainScale);
    PRECISE real signal = (n.x + offset) * w;
    PRECISE vec3 dsignal = gradientOf(n) * w;
    before = result;
    dbefore = dresult;
    result += weight * signal;
    dresult += dweight * signal + dsignal * weight;
    dweight = dweight * signal + dsignal * weight;
    weight *= signal;
  }
  return fadeLastGradient(params, withGradient(before, dbefore), withGradient(result, dresult));
}

vec4 heteroNoiseGradient(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE real offset = real(params.offset);
  real plainScale = real(1.0f);
  vec4 n = nextOctaveGradient(walk, params, plainScale);
  PRECISE real value = offset + n.x;
  PRECISE vec3 dvalue = gradientOf(n);
  PRECISE real before = real(0.0f);
  PRECISE vec3 dbefore = vec3(real(0.0f));
  PRECISE real w = real(1.0f);
  for (uint i = 1u; i < params.octaves; ++i) {
    w *= real(params.octaveWeight);
    before = value;
    dbefore = dvalue;
    n = nextOctaveGradient(walk, params, plainScale);
    // value += a · value with a = (N + offset) · w.
    PRECISE real a = (n.x + offset) * w;
    dvalue = dvalue + gradientOf(n) * (w * value) + dvalue * a;
    value += a * value;
  }
  return fadeLastGradient(params, withGradient(before, dbefore), withGradient(value, dvalue));
}

vec4 cascadeNoiseGradient(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE real value = real(1.0f);
  PRECISE vec3 dvalue = vec3(real(0.0f));
  PRECISE real before = real(1.0f);
  PRECISE vec3 dbefore = vec3(real(0.0f));
  real plainScale = real(1.0f);
  for (uint i = 0u; i < params.octaves; ++i) {
    before = value;
    dbefore = dvalue;
    vec4 n = nextOctaveGradient(walk, params, plainScale);
    PRECISE real factor = n.x + real(params.offset);
    dvalue = dvalue * factor + gradientOf(n) * value;
    value *= factor;
  }
  return fadeLastGradient(params, withGradient(before, dbefore), withGradient(value, dvalue));
}

// craterProfile as vec3(P, dP/dx, dP/drim). Bowl: dP/dx = 2(1 + R)(1 - x); ejecta:
// dP/du = -12·R·(1 - u)^2·u, zero where min() has clamped u to 1 (where P and its slope vanish).
vec3 craterProfileGradient(real x, real rim) {
  if (x <= real(1.0f)) {
    PRECISE real t = real(1.0f) - x;
    PRECISE real bowl = rim - (real(1.0f) + rim) * t * t;
    PRECISE real dx = real(2.0f) * (real(1.0f) + rim) * t;
    PRECISE real drim = real(1.0f) - t * t;
    return vec3(bowl, dx, drim);
  }
  PRECISE real raw = (x - real(1.0f)) * kCraterInvEjectaSpan;
  PRECISE real u = min(raw, real(1.0f));
  PRECISE real s = real(1.0f) - u;
  PRECISE real ejecta = rim * s * s * s * (real(1.0f) + real(3.0f) * u);
  PRECISE real dx = raw > real(1.0f) ? real(0.0f) : real(-12.0f) * rim * s * s * u * kCraterInvEjectaSpan;
  PRECISE real drim = s * s * s * (real(1.0f) + real(3.0f) * u);
  return vec3(ejecta, dx, drim);
}

// craterOctave with its gradient with respect to q; dn is the gradient of the perturbation n.
// Per crater, with d = q - centre (the centre is fixed in its cell), r' = r·(1 + eps·n) and
// R' = R·(1 + eps·n): x = |d|^2 / r'^2 has the gradient 2d / r'^2 - 2x·r·eps·dn / r'.
vec4 craterOctaveGradient(vec3 q, uvec3 cells, real eps, real n, vec3 dn, uint hashKind, uint seedMix) {
  int cx = int(clamp(floor(q.x + real(0.5f)), -kCellLimit, kCellLimit));
  int cy = int(clamp(floor(q.y + real(0.5f)), -kCellLimit, kCellLimit));
  int cz = int(clamp(floor(q.z + real(0.5f)), -kCellLimit, kCellLimit));
  PRECISE real fx = q.x - real(cx);
  PRECISE real fy = q.y - real(cy);
  PRECISE real fz = q.z - real(cz);
  PRECISE real grow = real(1.0f) + eps;
  PRECISE real radiusScale = real(1.0f) + eps * n;
  PRECISE real rim = kCraterRim * radiusScale;
  PRECISE vec3 drim = dn * (kCraterRim * eps);
  PRECISE real sum = real(0.0f);
  PRECISE vec3 dsum = vec3(real(0.0f));
  for (uint cell = 0u; cell < 8u; ++cell) {
    int ax = int(cell & 1u) - 1;
    int ay = int((cell >> 1u) & 1u) - 1;
    int az = int((cell >> 2u) & 1u) - 1;
    uint h = craterCellHash(uint(cx + ax) + cells.x, uint(cy + ay) + cells.y, uint(cz + az) + cells.z, hashKind,
                            seedMix);
    uint h2 = lowbias32(h);
    if (real(h2 & 0xffffu) * kInv65536 >= kCraterPresence) continue;
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
    PRECISE real rp2 = rp * rp;
    PRECISE real x = distance2 / rp2;
    vec3 profile = craterProfileGradient(x, rim);
    PRECISE vec3 dxq = vec3(dx, dy, dz) * (real(2.0f) / rp2) - dn * (real(2.0f) * x * r * eps / rp);
    sum += size * profile.x;
    dsum += (dxq * profile.y + drim * profile.z) * size;
  }
  return withGradient(sum, dsum);
}

// cratersNoise with its gradient. The perturbation n = N(2q) has the gradient 2·N'(2q) in q.
vec4 cratersNoiseGradient(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  PRECISE real eps = clamp(real(params.offset), real(0.0f), kCraterMaxPerturbation);
  PRECISE real sum = real(0.0f);
  PRECISE vec3 dsum = vec3(real(0.0f));
  PRECISE real before = real(0.0f);
  PRECISE vec3 dbefore = vec3(real(0.0f));
  PRECISE real w = real(1.0f);
  real plainScale = real(1.0f);
  for (uint i = 0u; i < params.octaves; ++i) {
    real scale = octaveChainScale(walk, plainScale);
    vec3 q;
    uvec3 shift;
    nextOctavePoint(walk, q, shift);
    plainScale = plainScale * walk.lacunarity;
    PRECISE vec3 q2 = q * real(2.0f);
    vec4 n = simplexWrappedGradient(q2, shift * 2u, params.hash, params.seedMix);
    PRECISE vec3 dn = gradientOf(n) * real(2.0f);
    vec4 c = craterOctaveGradient(q, craterCellShift(shift), eps, n.x, dn, params.hash, params.seedMix);
    before = sum;
    dbefore = dsum;
    sum += c.x * w;
    dsum += gradientOf(c) * (w * scale);
    w *= real(params.octaveWeight);
  }
  return fadeLastGradient(params, withGradient(before, dbefore), withGradient(sum, dsum));
}

// The erosion fractals (damped, eroded), value and gradient.
#include "common/noise_erosion.glsl"

// The generators of seeds 000 and 004 (faults, mpd, mpd_ico), value with gradient.
#ifndef NOISE_NO_GENERATORS
#include "common/noise_generators.glsl"
#endif

// fractalNoise with its gradient, vec4(value, d/dx, d/dy, d/dz), with respect to the walk's
// input (plain: p; rebased: the offset in metres, for a terrain's slope). The value is
// bit-identical to fractalNoise's. NOISE_NO_CRATERS, NOISE_NO_EROSION and NOISE_NO_GENERATORS as there.
vec4 fractalNoiseGradient(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  if (params.type == kNoiseFbm) return fbmNoiseGradient(params, walk);
  if (params.type == kNoiseRidged) return ridgedNoiseGradient(params, walk);
  if (params.type == kNoiseHybrid) return hybridNoiseGradient(params, walk);
  if (params.type == kNoiseHetero) return heteroNoiseGradient(params, walk);
  if (params.type == kNoiseCascade) return cascadeNoiseGradient(params, walk);
#ifndef NOISE_NO_CRATERS
  if (params.type == kNoiseCraters) return cratersNoiseGradient(params, walk);
#endif
#ifndef NOISE_NO_EROSION
  if (params.type == kNoiseDamped) return dampedNoiseGradient(params, walk);
  if (params.type == kNoiseEroded) return erodedNoiseGradient(params, walk);
#endif
#ifndef NOISE_NO_GENERATORS
  if (params.type == kNoiseFaults) return faultsNoiseGradient(params, walk);
  if (params.type == kNoiseMpd || params.type == kNoiseMpdIco) return mpdNoiseGradient(params, walk);
#endif
  real plainScale = real(1.0f);
  return nextOctaveGradient(walk, params, plainScale);
}

// evaluateNoise with its gradient with respect to p: vec4(value, d/dx, d/dy, d/dz).
vec4 evaluateNoiseGradient(IN(NoiseParams) params, vec3 p) {
  OctaveWalk walk = plainWalk(params, p);
  return fractalNoiseGradient(params, walk);
}

#endif

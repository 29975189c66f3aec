// The generators of seeds 000 and 004 as functions of position (issue 22): random faults and
// midpoint displacement on the octahedron and on the icosahedron, each as a value with its
// gradient, written once in the common subset of GLSL 4.50 and C++ (definitions.glsl). Included
// by noise_gradient.glsl before its dispatch; the value functions of noise.glsl's dispatch take
// the value part (the gradient work is dead code there and the compilers drop it).
//
// Both seeds ran these on a mesh refined on the CPU. Here every point is evaluated on its own,
// from its direction only (the distance from the domain's origin does not matter), so they run
// in the same passes as the fractals, at every LOD, and agree across patch borders.
//
// Direction: a layer samples planet-frame p·frequency, so the direction of the walk's octave-0
// point is the point's direction on the planet (the rebased walk's anchor split is undone, as in
// noise_erosion.glsl). In float that direction is good to about 6e-8 (0.4 m on an Earth-sized
// planet), which bounds the finest fault transition and the finest useful MPD level (README).
//
// Both hash with the integer hash of hash.glsl whatever params.hash says: their randomness is one
// value per fault or per mesh vertex, not a lattice gradient.
#ifndef PLANET_COMMON_NOISE_GENERATORS_GLSL
#define PLANET_COMMON_NOISE_GENERATORS_GLSL

// Vector algebra: dot3 and cross3 of noise_erosion.glsl (included before this file by
// noise_gradient.glsl), written out so that both compilers round alike.

// The walk's octave-0 point (plain: the wrapped input; rebased: the anchor's integer part plus
// remainder plus offset, see erosionUp) and, in chainScale, d(point)/d(walk input): 1 plain, the
// octave-0 scale (per metre) rebased.
vec3 generatorPoint(IN(OctaveWalk) walk, OUT(real) chainScale) {
  chainScale = real(1.0f);
  if (walk.rebased == 0u) return walk.q;
  vec4 rs = OCTAVE_REMAINDER(walk.layer, 0u);
  uvec4 s = OCTAVE_SHIFT(walk.layer, 0u);
  int m = int(s.x + s.y + s.z) / 6;
  PRECISE vec3 r = vec3(rs.x + walk.offset.x * rs.w, rs.y + walk.offset.y * rs.w, rs.z + walk.offset.z * rs.w);
  PRECISE vec3 absolute = r + vec3(real(int(s.x) - m), real(int(s.y) - m), real(int(s.z) - m));
  chainScale = real(rs.w);
  return absolute;
}

// ---- Random faults (seed 000 §1.2, Table 1) ----
//
// params.elements great circles (planes through the origin). Fault i's plane normal and step
// come from a hash of (seed, i) alone, so the faults are the same at every point: the point sums
// +r_i on the side its normal points to and -r_i on the other, r_i uniform in (0, 1] (the seed's
// "R = random value in [0 .. Amp]"; the layer's amplitude is Amp). With a transition width
// w = params.offset > 0, the step is the cubic (3t - t^3)/2 of t = d / w, d the sine of the
// point's angular distance from the circle (so w is in radians, to 1 % below 0.25), clamped to
// +-1: continuous in value and slope, so the steps can be refined (a finer mesh samples the same
// smooth ramp) where the seed's sign steps could not. w = 0 keeps the seed's sharp steps.

// Fault i's unit plane normal (xyz) and step r_i (w). The normal is uniform on the sphere:
// z uniform in [-1, 1] (Archimedes), the azimuth from a quarter-turn polynomial, so that no
// sin/cos of either compiler enters.
vec4 faultPlane(uint i, uint seedMix) {
  uint h1 = lowbias32(seedMix + i * 0x9e3779b9u);
  uint h2 = lowbias32(h1 ^ 0x5851f42du);
  PRECISE real z = (real(h1 >> 8u) + real(0.5f)) * real(1.0f / 8388608.0f) - real(1.0f);
  // Quadrant from the top 2 bits of h2, the angle within it from the next 14.
  uint quadrant = h2 >> 30u;
  PRECISE real x = (real((h2 >> 16u) & 0x3fffu) + real(0.5f)) * real(9.58737992e-5f);
  PRECISE real x2 = x * x;
  // Taylor series to x^9 / x^10 on [0, pi/2]: errors below 4e-6, which only tilts the plane a
  // little (both sides compute the same polynomial).
  PRECISE real sine =
      x * (real(1.0f) - x2 * (real(0.166666667f) -
                              x2 * (real(8.33333333e-3f) - x2 * (real(1.98412698e-4f) - x2 * real(2.75573192e-6f)))));
  PRECISE real cosine =
      real(1.0f) -
      x2 * (real(0.5f) - x2 * (real(4.16666667e-2f) -
                               x2 * (real(1.38888889e-3f) - x2 * (real(2.48015873e-5f) - x2 * real(2.75573192e-7f)))));
  real c = cosine;
  real s = sine;
  if (quadrant == 1u) {
    c = -sine;
    s = cosine;
  } else if (quadrant == 2u) {
    c = -cosine;
    s = -sine;
  } else if (quadrant == 3u) {
    c = sine;
    s = -cosine;
  }
  PRECISE real ring = sqrt(max(real(1.0f) - z * z, real(0.0f)));
  PRECISE real step = (real(h2 & 0xffffu) + real(1.0f)) * real(1.0f / 65536.0f);
  PRECISE vec4 plane = vec4(ring * c, ring * s, z, step);
  return plane;
}

// Sum of the faults at the walk's point, with its gradient with respect to the walk's input.
// O(params.elements) per point; no fault where params.octaves is 0 (a masked-out layer).
vec4 faultsNoiseGradient(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  real chainScale;
  vec3 p = generatorPoint(walk, chainScale);
  uint count = params.octaves == 0u ? 0u : params.elements;
  PRECISE real width = max(real(params.offset), real(0.0f));
  PRECISE real inverseWidth = width > real(0.0f) ? real(1.0f) / width : real(0.0f);
  PRECISE real length2 = dot3(p, p);
  PRECISE real inverseLength = length2 > real(0.0f) ? real(1.0f) / sqrt(length2) : real(0.0f);
  PRECISE vec3 up = p * inverseLength;
  PRECISE real sum = real(0.0f);
  PRECISE vec3 gradient = vec3(real(0.0f));
  for (uint i = 0u; i < count; ++i) {
    vec4 plane = faultPlane(i, params.seedMix);
    vec3 normal = vec3(plane.x, plane.y, plane.z);
    PRECISE real d = dot3(normal, up);
    if (width > real(0.0f)) {
      PRECISE real t = d * inverseWidth;
      if (t >= real(1.0f)) {
        sum += plane.w;
      } else if (t <= real(-1.0f)) {
        sum -= plane.w;
      } else {
        PRECISE real ramp = t * (real(3.0f) - t * t) * real(0.5f);
        sum += plane.w * ramp;
        // d(ramp)/dt = 1.5 (1 - t^2); dt/dp = (normal - d up) / (width |p|).
        PRECISE real slope = plane.w * real(1.5f) * (real(1.0f) - t * t) * inverseWidth;
        gradient += (normal - up * d) * slope;
      }
    } else {
      sum += d >= real(0.0f) ? plane.w : -plane.w;
    }
  }
  PRECISE vec3 scaled = gradient * (inverseLength * chainScale);
  return withGradient(sum, scaled);
}

// ---- Midpoint displacement (seed 000 §1.3-1.4 on the octahedron, seed 004 §3.3 on the
// icosahedron) ----
//
// The mesh of the seeds, descended per point: the base face whose central projection holds the
// point, then at each level the one of its four children (corners and edge midpoints) that holds
// it, to params.octaves levels. Vertex values: a base vertex gets v_0 = u; a midpoint created at
// level l gets the mean of its edge's two ends plus u · w^l (w = params.octaveWeight = 2^-H;
// seed 000: H = 1), where u in [-1, 1) is a hash of the vertex's identity and level. The value at
// the point is the barycentric interpolation of the finest triangle's corner values, so the
// surface is continuous and values at a level's vertices never change with finer levels.
//
// Identity without cracks: the face is subdivided as a flat triangle (its lattice at level l is
// the integer barycentric coordinates summing to 2^l) and projected centrally onto the sphere.
// A vertex's key is sum_k f(base vertex k) · coordinate_k (f a fixed odd hash per base vertex,
// arithmetic modulo 2^32): a point on a base edge has coordinate 0 on the third vertex, so both
// faces of the edge compute the same key, and the central projection of a point on the edge
// hits the same place on it from either face's plane. Level-1 midpoints are the seeds'
// normalize(A + B); deeper ones sit at the central projection of the flat lattice, within a
// fraction of a cell of the seeds' repeated normalisation (the same topology and hashing rule).
// Multifractal (params.elements = 1, seed 000 Table 3): each offset is further multiplied by
// k · mean(parents), k = params.gain.
//
// The finest level is faded in by params.lastOctaveWeight (its offsets scaled), which is exactly
// the blend of the surfaces with and without it (a linear function's midpoints lie on it).

// Base vertex ids: the octahedron's are 2·axis + (negative ? 1 : 0) (+x, -x, +y, -y, +z, -z);
// the icosahedron's 4·k + (s1 < 0 ? 2 : 0) + (s2 < 0 ? 1 : 0) for the vertex that is
// (0, s1·a, s2·b) with its coordinates rotated k times, (x, y, z) -> (z, x, y).
SHARED_CONST real kIcoShort = real(0.525731112f);  // a = 1 / sqrt(1 + phi^2)
SHARED_CONST real kIcoLong = real(0.850650808f);   // b = phi · a
SHARED_CONST real kPhi = real(1.61803399f);
SHARED_CONST real kInvPhi = real(0.618033989f);

vec3 mpdBaseVertex(uint solid, uint id) {
  if (solid == kNoiseMpd) {
    real sign = (id & 1u) != 0u ? real(-1.0f) : real(1.0f);
    uint axis = id >> 1u;
    return vec3(axis == 0u ? sign : real(0.0f), axis == 1u ? sign : real(0.0f), axis == 2u ? sign : real(0.0f));
  }
  real u = (id & 2u) != 0u ? -kIcoShort : kIcoShort;
  real v = (id & 1u) != 0u ? -kIcoLong : kIcoLong;
  uint k = id >> 2u;
  if (k == 0u) return vec3(real(0.0f), u, v);
  if (k == 1u) return vec3(v, real(0.0f), u);
  return vec3(u, v, real(0.0f));
}

uint icoVertexId(uint k, bool negative1, bool negative2) {
  return 4u * k + (negative1 ? 2u : 0u) + (negative2 ? 1u : 0u);
}

// The base face whose plane the ray through p meets first (for a solid whose faces are all at
// one distance from the centre, the face of largest n·p): its three vertex ids.
uvec3 mpdBaseFace(uint solid, vec3 p) {
  bool nx = p.x < real(0.0f);
  bool ny = p.y < real(0.0f);
  bool nz = p.z < real(0.0f);
  if (solid == kNoiseMpd) return uvec3(nx ? 1u : 0u, ny ? 3u : 2u, nz ? 5u : 4u);
  // Icosahedron: its face normals are the dodecahedron's vertices, (+-1, +-1, +-1) and the
  // rotations of (0, +-1/phi, +-phi), all of length sqrt(3); the one nearest p wins.
  real ax = abs(p.x);
  real ay = abs(p.y);
  real az = abs(p.z);
  PRECISE real octant = ax + ay + az;
  PRECISE real zeroY = ax * kInvPhi + az * kPhi;
  PRECISE real zeroZ = ax * kPhi + ay * kInvPhi;
  PRECISE real zeroX = ay * kPhi + az * kInvPhi;
  if (octant >= zeroY && octant >= zeroZ && octant >= zeroX)
    return uvec3(icoVertexId(0u, ny, nz), icoVertexId(1u, nz, nx), icoVertexId(2u, nx, ny));
  if (zeroY >= zeroZ && zeroY >= zeroX)
    return uvec3(icoVertexId(0u, false, nz), icoVertexId(0u, true, nz), icoVertexId(1u, nz, nx));
  if (zeroZ >= zeroX) return uvec3(icoVertexId(1u, false, nx), icoVertexId(1u, true, nx), icoVertexId(2u, nx, ny));
  return uvec3(icoVertexId(2u, false, ny), icoVertexId(2u, true, ny), icoVertexId(0u, ny, nz));
}

// A base vertex's odd key multiplier (fixed, the same for every seed).
uint mpdVertexKey(uint id) { return lowbias32(id * 0x2545f491u + 0x68e31da4u) | 1u; }

// u in [-1, 1) of the vertex with key `key` created at `level`.
real mpdOffset(uint key, uint level, uint seedMix) {
  uint h = lowbias32(key + seedMix + level * 0x9e3779b9u);
  return real(h >> 8u) * real(1.0f / 8388608.0f) - real(1.0f);
}

// The value a new midpoint gets: the mean of its ends plus its offset at level weight `weight`.
real mpdMidpoint(real h0, real h1, uint key, uint level, real weight, bool multifractal, real k, uint seedMix) {
  PRECISE real mean = (h0 + h1) * real(0.5f);
  PRECISE real offset = mpdOffset(key, level, seedMix) * weight;
  if (multifractal) offset = offset * (mean * k);
  PRECISE real value = mean + offset;
  return value;
}

// Midpoint displacement of solid params.type (kNoiseMpd: octahedron, kNoiseMpdIco: icosahedron)
// at the walk's point, with its gradient with respect to the walk's input.
vec4 mpdNoiseGradient(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  real chainScale;
  vec3 p = generatorPoint(walk, chainScale);
  uint solid = params.type;
  uvec3 ids = mpdBaseFace(solid, p);
  vec3 a = mpdBaseVertex(solid, ids.x);
  vec3 b = mpdBaseVertex(solid, ids.y);
  vec3 c = mpdBaseVertex(solid, ids.z);
  // Barycentric coordinates of p's central projection onto the face's plane: p = la·a + lb·b +
  // lc·c scaled, la ∝ p·(b × c) (the common determinant cancels in the ratio).
  vec3 da = cross3(b, c);
  vec3 db = cross3(c, a);
  vec3 dc = cross3(a, b);
  // (Half the faces are listed clockwise: then all three are negative, and so is their sum.)
  PRECISE real la = dot3(p, da);
  PRECISE real lb = dot3(p, db);
  PRECISE real lc = dot3(p, dc);
  PRECISE real total = la + lb + lc;
  if (!(abs(total) > real(1e-30f))) total = real(1e-30f);  // p = 0 only
  // The descent carries the weights times |total| (u_k = w_k · t), so that it needs no division:
  // Vulkan rounds +, - and * correctly but lets a division be 2.5 ulp off, and the descent
  // doubles a weight's error with every level, so a GPU that divided differently would pick a
  // neighbouring finest triangle near its edges (another slope: `planet validate` on NVIDIA).
  // With only +, - and * the same triangle is chosen on every driver. Two weights are carried,
  // the third is t minus them: carried separately, their sum's rounding would double with every
  // level (2^24 · 6e-8 = 1 at level 24). A point a rounding outside its face (the face choice and
  // the weights round differently) is clamped onto it.
  PRECISE real t = abs(total);
  PRECISE real u0 = max(total < real(0.0f) ? -la : la, real(0.0f));
  PRECISE real u1 = max(total < real(0.0f) ? -lb : lb, real(0.0f));

  // The current triangle: its corners' keys and values, and p's barycentric weights in it (slot k
  // of each child keeps weight ±2 w_k + const, see below).
  uint k0 = mpdVertexKey(ids.x);
  uint k1 = mpdVertexKey(ids.y);
  uint k2 = mpdVertexKey(ids.z);
  PRECISE real h0 = mpdOffset(k0, 0u, params.seedMix);
  PRECISE real h1 = mpdOffset(k1, 0u, params.seedMix);
  PRECISE real h2 = mpdOffset(k2, 0u, params.seedMix);
  bool multifractal = params.elements != 0u;
  real k = real(params.gain);
  PRECISE real weight = real(1.0f);
  PRECISE real orientation = real(1.0f);  // d(final weights)/d(base weights) = orientation · 2^levels
  PRECISE real scale = real(1.0f);
  for (uint level = 1u; level <= params.octaves; ++level) {
    weight *= real(params.octaveWeight);
    PRECISE real levelWeight = weight;
    if (level == params.octaves) levelWeight = weight * real(params.lastOctaveWeight);
    // The corners' keys at this level are twice their keys at the one before (every lattice
    // coordinate doubles); a midpoint's is the sum of its ends'.
    uint m01 = k0 + k1;
    uint m12 = k1 + k2;
    uint m20 = k2 + k0;
    real v01 = mpdMidpoint(h0, h1, m01, level, levelWeight, multifractal, k, params.seedMix);
    real v12 = mpdMidpoint(h1, h2, m12, level, levelWeight, multifractal, k, params.seedMix);
    real v20 = mpdMidpoint(h2, h0, m20, level, levelWeight, multifractal, k, params.seedMix);
    k0 = k0 * 2u;
    k1 = k1 * 2u;
    k2 = k2 * 2u;
    scale = scale * real(2.0f);
    PRECISE real u2 = t - u0 - u1;
    if (real(2.0f) * u0 >= t) {
      // Corner child at corner 0: (c0, m01, m20), weights (2 w0 - 1, 2 w1, 2 w2).
      k1 = m01;
      k2 = m20;
      h1 = v01;
      h2 = v20;
      u0 = real(2.0f) * u0 - t;
      u1 = real(2.0f) * u1;
    } else if (real(2.0f) * u1 >= t) {
      k0 = m01;
      k2 = m12;
      h0 = v01;
      h2 = v12;
      u0 = real(2.0f) * u0;
      u1 = real(2.0f) * u1 - t;
    } else if (real(2.0f) * u2 >= t) {
      k0 = m20;
      k1 = m12;
      h0 = v20;
      h1 = v12;
      u0 = real(2.0f) * u0;
      u1 = real(2.0f) * u1;
    } else {
      // Middle child (m12, m20, m01): p = sum w_k c_k = (1 - 2 w0) m12 + (1 - 2 w1) m20 + (1 - 2 w2) m01.
      k0 = m12;
      k1 = m20;
      k2 = m01;
      h0 = v12;
      h1 = v20;
      h2 = v01;
      u0 = t - real(2.0f) * u0;
      u1 = t - real(2.0f) * u1;
      orientation = -orientation;
    }
  }
  PRECISE real w0 = u0 / t;
  PRECISE real w1 = u1 / t;
  PRECISE real w2 = real(1.0f) - w0 - w1;
  PRECISE real value = h0 * w0 + h1 * w1 + h2 * w2;

  // Gradient: value = sum h_k w_k with w_k = orientation · 2^levels · (base weight k) + const, and
  // d(base weight k)/dp = (d_k - w_k sum_j d_j) / total for the unclamped weights. The three
  // weights' gradients sum to zero, so the gradient is g0 (h0 - h2) + g1 (h1 - h2): written as
  // sum g_k h_k it would cancel the corners' common height, ~1, to leave their differences,
  // ~2^-levels·H, and a rounding of the g_k (a GPU's division) would grow by the ratio.
  PRECISE vec3 dsum = da + db + dc;
  PRECISE real base0 = la / total;
  PRECISE real base1 = lb / total;
  PRECISE vec3 g0 = (da - dsum * base0) / total;
  PRECISE vec3 g1 = (db - dsum * base1) / total;
  PRECISE real rise0 = h0 - h2;
  PRECISE real rise1 = h1 - h2;
  PRECISE vec3 gradient = (g0 * rise0 + g1 * rise1) * (orientation * scale * chainScale);
  return withGradient(value, gradient);
}

#endif

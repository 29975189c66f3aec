// Erosion-like relief evaluated per point (issue 19 point 2): two fractals whose octaves react to
// the slope of the octaves before them, each as a value and as a value with its exact gradient,
// written once in the common subset of GLSL 4.50 and C++ (definitions.glsl). Included by
// noise_gradient.glsl before its dispatch; uses noise.glsl's simplex corners and octave walk and
// noise_gradient.glsl's simplex gradient and chain scales.
//
// Nothing here needs neighbours or a simulation pass, so both run wherever a fractal runs: per
// vertex and per texel, at any octave budget, the same on both sides of a patch border.
//
// Which way is down. A terrain samples its noise on a sphere about the noise domain's origin
// (a layer samples planet-frame p·frequency; the rebased walk's anchor split is undone for
// octave 0 below), and what a viewer calls slope is the gradient's part along that sphere: the
// part along the radius is how the noise would change with altitude, which nobody sees. So the
// slope here is the tangential gradient cross(up, G), up = the point's direction from the origin.
// Elsewhere (planet noise on arbitrary points) the types stay continuous and deterministic, with
// "up" still the direction from the origin.
//
// Exact gradients. Both types are functions of a gradient accumulated along the octaves, so their
// derivatives need second derivatives of what came before: the simplex Hessian below, and for
// `eroded` the Jacobian of its flow field carried from scale to scale. The values need first
// derivatives only. Measured on lavapipe, 8 octaves (README, "The noise"): values 1.3x (damped)
// and 1.5x (eroded) fBm's, values with gradients 1.5x and 2.5x fBm's.
#ifndef PLANET_COMMON_NOISE_EROSION_GLSL
#define PLANET_COMMON_NOISE_EROSION_GLSL

// ---- Small vector algebra, written out so that both compilers round alike ----

real dot3(vec3 a, vec3 b) {
  PRECISE real d = a.x * b.x + a.y * b.y + a.z * b.z;
  return d;
}

vec3 cross3(vec3 a, vec3 b) {
  PRECISE vec3 c = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  return c;
}

// A 3x3 matrix by rows: row i is the gradient of component i (a Jacobian's layout).
struct ErosionRows {
  vec3 x;
  vec3 y;
  vec3 z;
};

ErosionRows rowsOf(vec3 x, vec3 y, vec3 z) {
  ErosionRows m;
  m.x = x;
  m.y = y;
  m.z = z;
  return m;
}

ErosionRows rowsZero() { return rowsOf(vec3(real(0.0f)), vec3(real(0.0f)), vec3(real(0.0f))); }

// m·v.
vec3 rowsTimes(IN(ErosionRows) m, vec3 v) { return vec3(dot3(m.x, v), dot3(m.y, v), dot3(m.z, v)); }

// transpose(m)·v.
vec3 rowsTransposeTimes(IN(ErosionRows) m, vec3 v) {
  PRECISE vec3 r = m.x * v.x + m.y * v.y + m.z * v.z;
  return r;
}

// a·b (rows of a times the matrix b).
ErosionRows rowsProduct(IN(ErosionRows) a, IN(ErosionRows) b) {
  return rowsOf(rowsTransposeTimes(b, a.x), rowsTransposeTimes(b, a.y), rowsTransposeTimes(b, a.z));
}

// a + b·s.
ErosionRows rowsAddScaled(IN(ErosionRows) a, IN(ErosionRows) b, real s) {
  PRECISE vec3 x = a.x + b.x * s;
  PRECISE vec3 y = a.y + b.y * s;
  PRECISE vec3 z = a.z + b.z * s;
  return rowsOf(x, y, z);
}

// ---- The simplex Hessian ----

// Hessian of cornerContribution t^4 (a . d), t = 0.5 - |d|^2, a the corner's gradient:
// -8 t^3 (a d^T + d a^T) + 48 t^2 (a . d) d d^T - 8 t^3 (a . d) I, continuous where t reaches 0.
ErosionRows cornerContributionHessian(uint g, vec3 d) {
  PRECISE real t = kKernelRadius2 - d.x * d.x - d.y * d.y - d.z * d.z;
  t = max(t, real(0.0f));
  PRECISE real t2 = t * t;
  PRECISE real along = gradientDot(g, d.x, d.y, d.z);
  PRECISE real c1 = real(-8.0f) * t2 * t;
  PRECISE real c2 = real(48.0f) * t2 * along;
  PRECISE real c3 = c1 * along;
  vec3 a = gradientVector(g);
  PRECISE vec3 x = (a * d.x + d * a.x) * c1 + d * (c2 * d.x) + vec3(c3, real(0.0f), real(0.0f));
  PRECISE vec3 y = (a * d.y + d * a.y) * c1 + d * (c2 * d.y) + vec3(real(0.0f), c3, real(0.0f));
  PRECISE vec3 z = (a * d.z + d * a.z) * c1 + d * (c2 * d.z) + vec3(real(0.0f), real(0.0f), c3);
  return rowsOf(x, y, z);
}

// simplexWrappedGradient (bit for bit) and the Hessian with respect to p.
vec4 simplexWrappedHessian(vec3 p, uvec3 shift, uint hashKind, uint seedMix, OUT(ErosionRows) hessian) {
  vec3 d0, d1, d2, d3;
  uvec4 g;
  simplexCorners(p, shift, hashKind, seedMix, d0, d1, d2, d3, g);
  PRECISE vec4 n0 = cornerContributionGradient(g.x, d0.x, d0.y, d0.z);
  PRECISE vec4 n1 = cornerContributionGradient(g.y, d1.x, d1.y, d1.z);
  PRECISE vec4 n2 = cornerContributionGradient(g.z, d2.x, d2.y, d2.z);
  PRECISE vec4 n3 = cornerContributionGradient(g.w, d3.x, d3.y, d3.z);
  PRECISE vec4 sum = n0 + n1 + n2 + n3;
  PRECISE vec4 scaled = kNoiseScale * sum;
  ErosionRows h = cornerContributionHessian(g.x, d0);
  h = rowsAddScaled(h, cornerContributionHessian(g.y, d1), real(1.0f));
  h = rowsAddScaled(h, cornerContributionHessian(g.z, d2), real(1.0f));
  h = rowsAddScaled(h, cornerContributionHessian(g.w, d3), real(1.0f));
  hessian = rowsAddScaled(rowsZero(), h, kNoiseScale);
  return scaled;
}

// ---- Up ----

// The walk's octave-0 point relative to the noise domain's origin, as vec4(up, 1 / distance):
// plain, the wrapped input itself; rebased, the anchor's integer part (the CPU's shift is
// I + m·(1,1,1) with I's coordinates summing to 3m, so the shift's sum is 6m) plus the
// remainder and the offset. Call it before the walk moves. At the origin itself up is +z.
vec4 erosionUp(IN(OctaveWalk) walk) {
  vec3 p = walk.q;
  if (walk.rebased != 0u) {
    vec4 rs = OCTAVE_REMAINDER(walk.layer, 0u);
    uvec4 s = OCTAVE_SHIFT(walk.layer, 0u);
    int m = int(s.x + s.y + s.z) / 6;
    PRECISE vec3 r = vec3(rs.x + walk.offset.x * rs.w, rs.y + walk.offset.y * rs.w, rs.z + walk.offset.z * rs.w);
    PRECISE vec3 absolute = r + vec3(real(int(s.x) - m), real(int(s.y) - m), real(int(s.z) - m));
    p = absolute;
  }
  PRECISE real radius2 = dot3(p, p);
  if (!(radius2 > real(0.0f))) return vec4(real(0.0f), real(0.0f), real(1.0f), real(0.0f));
  PRECISE real radius = sqrt(radius2);
  PRECISE vec3 up = vec3(p.x / radius, p.y / radius, p.z / radius);
  PRECISE real inverse = real(1.0f) / radius;
  return vec4(up.x, up.y, up.z, inverse);
}

// d(up)/d(point) = (I - up up^T) / distance.
ErosionRows erosionUpJacobian(vec4 up) {
  vec3 n = vec3(up.x, up.y, up.z);
  PRECISE vec3 x = (vec3(real(1.0f), real(0.0f), real(0.0f)) - n * n.x) * up.w;
  PRECISE vec3 y = (vec3(real(0.0f), real(1.0f), real(0.0f)) - n * n.y) * up.w;
  PRECISE vec3 z = (vec3(real(0.0f), real(0.0f), real(1.0f)) - n * n.z) * up.w;
  return rowsOf(x, y, z);
}

// d(cross(n, G)) given the Jacobians of n (dn) and of G (dg): row i of d(n_j G_k - n_k G_j) is
// G_k·dn_j + n_j·dg_k - G_j·dn_k - n_k·dg_j.
ErosionRows crossJacobian(vec3 n, IN(ErosionRows) dn, vec3 g, IN(ErosionRows) dg) {
  PRECISE vec3 x = dn.y * g.z + dg.z * n.y - dn.z * g.y - dg.y * n.z;
  PRECISE vec3 y = dn.z * g.x + dg.x * n.z - dn.x * g.z - dg.z * n.x;
  PRECISE vec3 z = dn.x * g.y + dg.y * n.x - dn.y * g.x - dg.x * n.y;
  return rowsOf(x, y, z);
}

// ---- damped: derivative-damped fBm ----
//
// After Inigo Quilez, "More noise" (2008): fBm whose octave i is divided by 1 + k·|S_i|^2, S_i
// the slope of octaves 0..i-1 (the tangential gradient of their sum, in octave-0 lattice units
// so that it does not depend on the planet's radius or on metres). Where the ground is already
// steep the detail fades, where it is flat (plains, crests, valley floors) it stays: slopes come
// out smooth and crests rough, as water and gravity leave them. k = params.gain / 16 (0: fBm, bit
// for bit): one octave's slope along a sphere is 2.4 on average, so with the default gain 2 an
// octave keeps half its height where the octaves before it slope by 2.8 (a few octaves' worth),
// and the fade saturates as k grows (NoiseErosion.DampedSmoothsSteepGround...: 0.08 of fBm's fine
// roughness on the steepest tenth, 0.8 on the flattest). offset is unused. Unlike Quilez's form
// the octave's own slope does not damp it, so the first octave is the fBm's.
SHARED_CONST real kDampedSlopeScale = real(0.0625f);

real dampedNoise(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  vec4 up = erosionUp(walk);
  vec3 n = vec3(up.x, up.y, up.z);
  real scale0 = octaveChainScale(walk, real(1.0f));
  PRECISE real k = real(params.gain) * kDampedSlopeScale;
  PRECISE real sum = real(0.0f);
  PRECISE real before = real(0.0f);
  PRECISE vec3 slope = vec3(real(0.0f));  // gradient of the sum so far, octave-0 units
  PRECISE real w = real(1.0f);
  real plainScale = real(1.0f);
  for (uint i = 0u; i < params.octaves; ++i) {
    PRECISE real ratio = octaveChainScale(walk, plainScale) / scale0;
    vec3 q;
    uvec3 shift;
    nextOctavePoint(walk, q, shift);
    plainScale = plainScale * walk.lacunarity;
    vec4 noise = simplexWrappedGradient(q, shift, params.hash, params.seedMix);
    vec3 across = cross3(n, slope);
    PRECISE real damp = real(1.0f) + k * dot3(across, across);
    before = sum;
    sum += noise.x * w / damp;
    slope += gradientOf(noise) * (w * ratio);
    w *= real(params.octaveWeight);
  }
  return fadeLast(params, before, sum);
}

// dampedNoise with its gradient. With c = cross(up, S) and J the Hessian of the sum so far,
// d|c|^2/du = 2 (J S - (up . S)(J up + d(up)/du · S)), since |c|^2 = |S|^2 - (up . S)^2.
vec4 dampedNoiseGradient(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  vec4 up = erosionUp(walk);
  vec3 n = vec3(up.x, up.y, up.z);
  ErosionRows dn = erosionUpJacobian(up);
  real scale0 = octaveChainScale(walk, real(1.0f));
  PRECISE real k = real(params.gain) * kDampedSlopeScale;
  PRECISE real sum = real(0.0f);
  PRECISE vec3 dsum = vec3(real(0.0f));  // with respect to the walk's input
  PRECISE real before = real(0.0f);
  PRECISE vec3 dbefore = vec3(real(0.0f));
  PRECISE vec3 slope = vec3(real(0.0f));
  ErosionRows hessian = rowsZero();  // of the sum so far, octave-0 units
  PRECISE real w = real(1.0f);
  real plainScale = real(1.0f);
  for (uint i = 0u; i < params.octaves; ++i) {
    real scale = octaveChainScale(walk, plainScale);
    PRECISE real ratio = scale / scale0;
    vec3 q;
    uvec3 shift;
    nextOctavePoint(walk, q, shift);
    plainScale = plainScale * walk.lacunarity;
    ErosionRows h;
    vec4 noise = simplexWrappedHessian(q, shift, params.hash, params.seedMix, h);
    vec3 across = cross3(n, slope);
    PRECISE real damp = real(1.0f) + k * dot3(across, across);
    PRECISE real along = dot3(n, slope);
    PRECISE vec3 dacross2 =
        (rowsTimes(hessian, slope) - (rowsTimes(hessian, n) + rowsTimes(dn, slope)) * along) * real(2.0f);
    PRECISE real valueWeight = noise.x * w * k * scale0 / (damp * damp);
    before = sum;
    dbefore = dsum;
    sum += noise.x * w / damp;
    dsum += gradientOf(noise) * scale * w / damp - dacross2 * valueWeight;
    slope += gradientOf(noise) * (w * ratio);
    hessian = rowsAddScaled(hessian, h, w * ratio * ratio);
    w *= real(params.octaveWeight);
  }
  return fadeLastGradient(params, withGradient(before, dbefore), withGradient(sum, dsum));
}

// ---- eroded: gullies carved down the slope at several scales ----
//
// After Rune Skovbo Johansen's erosion filter (2023), which builds on Clay John's "Eroded
// terrain noise" (2018) and Fewes' (2023): a base fBm, then at each finer scale a stripe pattern
// whose crests run down the slope of the height so far, blended over the lattice cells around
// the point. The stripes' troughs are gullies. Each scale's stripes follow the slope including
// the gullies of the coarser scales, so the fine gullies run down the walls of the coarse ones
// and join them: branching valleys that drain into each other, as on eroded slopes.
//
// Octave i < B (B = floor(offset), at least 1) is the base: simplex with the fBm's weight w_i.
// Octave i >= B adds gullies, a_i · P_i, with
//   P_i = sum_k K_k wave(L d_k . v + phase_k) / sum_k K_k,   a_i = gain · kGullyDepth · w_i · F · walls,
// over the four corners k of the simplex around the previous octave's point q_(i-1), with offsets
// d_k = q_(i-1) - corner_k and kernels K_k = max(0.5 - |d_k|^2, 0)^3 (normalised: a partition of
// unity, continuous in value, slope and curvature, as the kernels vanish at the simplex's faces);
// phase_k = g_k / 12 from the corner's lattice hash (either hash). The cells are an octave
// coarser than the stripes (L of them per cell), so a gully runs straight for a cell or two before
// its neighbour's stripes, of another phase, take over; on cells of their own octave they were
// dashes. v = c / sqrt(|c|^2 + eps_i^2), c = cross(up, G) the slope of the height so far along
// the sphere turned a quarter (G: its gradient in octave-0 units): the crests run down the slope,
// one stripe per lattice unit of octave i where it is steep and wider where it is gentle, never
// finer (so the octave budget's wavelength rule holds as for fBm). eps_i is half the slope the
// octaves so far have on average (their weights and frequencies alone, no position): where the
// slope vanishes the stripes would swing round at any rate, faster than their own spacing (and
// the value would vary finer than its octaves); this widens them there. The depth grows with the
// slope, F = |c|^2 / (|c|^2 + kGullySlope^2), no gullies on flat ground, and walls = 1 - P_(i-1)^2
// fades them on the crests and floors of the previous scale's gullies, where its walls meet and
// the slope turns over (and where the valley floors of the real thing are smooth).
//
// G is the base's gradient plus, per gully scale, the gradient of its stripes with the
// direction and the depth held fixed (Johansen's; the slope a gully wall adds), so the next
// scale's stripes run down the walls. The value's exact gradient also differentiates the
// direction and the depth, which needs the Jacobian of G: the base's Hessian plus each scale's
// Hessian and its change with the direction and the depth, carried along (erodedNoiseGradient).
SHARED_CONST real kGullyDepth = real(0.2f);        // stripe amplitude per unit of gain, times w_i
SHARED_CONST real kGullySlope = real(1.0f);        // slope (octave-0 units) of half the full depth
SHARED_CONST real kGullySlopeSoft2 = real(0.25f);  // (eps_i / the octaves' mean slope)^2
SHARED_CONST real kBaseSlope2 = real(6.0f);        // mean square slope of N along a sphere (2.4^2)
SHARED_CONST real kStripeSlope2 = real(10.0f);     // about that of P per unit of L·|v| (wave' alone: 19.5)
SHARED_CONST real kGullyPhaseStep = real(1.0f) / real(12.0f);

// The number of base octaves: floor(offset), at least 1 and at most `octaves`.
uint erodedBaseOctaves(IN(NoiseParams) params) {
  PRECISE real b = clamp(floor(real(params.offset)), real(1.0f), real(kNoiseMaxOctaves));
  return min(uint(b), params.octaves);
}

// The stripe profile, period 1: vec3(wave, d/dphase, d2/dphase2). With t = phase - round(phase)
// in [-1/2, 1/2], wave = 2 (1 - 4 t^2)^2 - 1: crests (t = 0) at 1, troughs (t = ±1/2) at -1 and
// twice as sharp as the crests (V-shaped gully floors, rounded ridges). A polynomial (no cos),
// continuous with its first two derivatives across the troughs, where the period wraps.
vec3 gullyWave(real phase) {
  PRECISE real t = phase - floor(phase + real(0.5f));
  PRECISE real t2 = t * t;
  PRECISE real u = real(1.0f) - real(4.0f) * t2;
  PRECISE real wave = real(2.0f) * u * u - real(1.0f);
  PRECISE real slope = real(-32.0f) * t * u;
  PRECISE real curvature = real(384.0f) * t2 - real(32.0f);
  return vec3(wave, slope, curvature);
}

// One corner's share of the stripes: the kernel sum S and its gradient, and the weighted stripes
// T and their gradient (direction v fixed), accumulated.
void gullyCorner(vec3 d, uint g, vec3 v, INOUT(real) s, INOUT(vec3) ds, INOUT(real) t, INOUT(vec3) dt) {
  PRECISE real r = kKernelRadius2 - d.x * d.x - d.y * d.y - d.z * d.z;
  r = max(r, real(0.0f));
  PRECISE real r2 = r * r;
  PRECISE real kernel = r2 * r;
  PRECISE vec3 dkernel = d * (real(-6.0f) * r2);
  PRECISE real phase = dot3(d, v) + real(g) * kGullyPhaseStep;
  vec3 wave = gullyWave(phase);
  // Through precise locals: a parameter cannot be declared precise.
  PRECISE real s1 = s + kernel;
  PRECISE vec3 ds1 = ds + dkernel;
  PRECISE real t1 = t + kernel * wave.x;
  PRECISE vec3 dt1 = dt + dkernel * wave.x + v * (kernel * wave.y);
  s = s1;
  ds = ds1;
  t = t1;
  dt = dt1;
}

// The stripe pattern P at q along v and its gradient in q: vec4(P, dP/dq). 0 where no corner
// reaches (only past the lattice clamp of noise.glsl, where every octave is 0 anyway).
vec4 gullyPattern(vec3 q, uvec3 shift, vec3 v, uint hashKind, uint seedMix) {
  vec3 d0, d1, d2, d3;
  uvec4 g;
  simplexCorners(q, shift, hashKind, seedMix, d0, d1, d2, d3, g);
  PRECISE real s = real(0.0f);
  PRECISE vec3 ds = vec3(real(0.0f));
  PRECISE real t = real(0.0f);
  PRECISE vec3 dt = vec3(real(0.0f));
  gullyCorner(d0, g.x, v, s, ds, t, dt);
  gullyCorner(d1, g.y, v, s, ds, t, dt);
  gullyCorner(d2, g.z, v, s, ds, t, dt);
  gullyCorner(d3, g.w, v, s, ds, t, dt);
  if (!(s > real(0.0f))) return vec4(real(0.0f));
  PRECISE real pattern = t / s;
  PRECISE vec3 dpattern = (dt - ds * pattern) / s;
  return withGradient(pattern, dpattern);
}

// The stripe direction v and the depth factor F of a gully scale, from the tangential slope
// c = cross(up, G): vec4(v, F).
vec4 gullyDirection(vec3 c, real soft2) {
  PRECISE real c2 = dot3(c, c);
  PRECISE real norm = sqrt(c2 + soft2);
  PRECISE vec3 v = vec3(c.x / norm, c.y / norm, c.z / norm);
  PRECISE real depth = c2 / (c2 + kGullySlope * kGullySlope);
  return vec4(v.x, v.y, v.z, depth);
}

real erodedNoise(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  vec4 up = erosionUp(walk);
  vec3 n = vec3(up.x, up.y, up.z);
  real scale0 = octaveChainScale(walk, real(1.0f));
  uint baseOctaves = erodedBaseOctaves(params);
  PRECISE real height = real(0.0f);
  PRECISE real before = real(0.0f);
  PRECISE vec3 slope = vec3(real(0.0f));  // G: the flow gradient, octave-0 units
  PRECISE real w = real(1.0f);
  real plainScale = real(1.0f);
  // The previous octave's point: a gully scale's cells.
  vec3 cellQ = vec3(real(0.0f));
  uvec3 cellShift = uvec3(0u);
  real cellRatio = real(1.0f);
  PRECISE real walls = real(1.0f);  // 1 - P^2 of the previous gully scale: 0 on its floors and crests
  PRECISE real expected2 = real(0.0f);  // the expected square slope so far
  for (uint i = 0u; i < baseOctaves; ++i) {
    PRECISE real ratio = octaveChainScale(walk, plainScale) / scale0;
    vec3 q;
    uvec3 shift;
    nextOctavePoint(walk, q, shift);
    plainScale = plainScale * walk.lacunarity;
    vec4 noise = simplexWrappedGradient(q, shift, params.hash, params.seedMix);
    before = height;
    height += noise.x * w;
    slope += gradientOf(noise) * (w * ratio);
    expected2 += (w * ratio) * (w * ratio) * kBaseSlope2;
    w *= real(params.octaveWeight);
    cellQ = q;
    cellShift = shift;
    cellRatio = ratio;
  }
  for (uint i = baseOctaves; i < params.octaves; ++i) {
    PRECISE real ratio = octaveChainScale(walk, plainScale) / scale0;
    vec3 q;
    uvec3 shift;
    nextOctavePoint(walk, q, shift);
    plainScale = plainScale * walk.lacunarity;
    PRECISE real soft2 = kGullySlopeSoft2 * expected2;
    vec4 direction = gullyDirection(cross3(n, slope), soft2);
    PRECISE vec3 stripes = vec3(direction.x, direction.y, direction.z) * walk.lacunarity;
    vec4 pattern = gullyPattern(cellQ, cellShift, stripes, params.hash, params.seedMix);
    PRECISE real amplitude = real(params.gain) * kGullyDepth * w;
    PRECISE real depth = amplitude * direction.w * walls;
    walls = real(1.0f) - pattern.x * pattern.x;
    expected2 += (amplitude * cellRatio * walk.lacunarity) * (amplitude * cellRatio * walk.lacunarity) * kStripeSlope2;
    before = height;
    height += depth * pattern.x;
    slope += gradientOf(pattern) * (depth * cellRatio);
    w *= real(params.octaveWeight);
    cellQ = q;
    cellShift = shift;
    cellRatio = ratio;
  }
  return fadeLast(params, before, height);
}

// gullyPattern with its second derivatives: the Hessian in q (direction fixed), dP/dv, and the
// mixed derivatives d(dP/dq)/dv (row i: the gradient in v of dP/dq_i).
struct GullyPatternDerivatives {
  vec4 value;           // gullyPattern's vec4(P, dP/dq), bit for bit
  vec3 dv;              // dP/dv
  ErosionRows hessian;  // d2P/dq2
  ErosionRows mixed;    // d(dP/dq)/dv
};

GullyPatternDerivatives gullyPatternDerivatives(vec3 q, uvec3 shift, vec3 v, uint hashKind, uint seedMix) {
  vec3 d[4];
  uvec4 g;
  simplexCorners(q, shift, hashKind, seedMix, d[0], d[1], d[2], d[3], g);
  uint gs[4];
  gs[0] = g.x;
  gs[1] = g.y;
  gs[2] = g.z;
  gs[3] = g.w;
  PRECISE real s = real(0.0f);
  PRECISE vec3 ds = vec3(real(0.0f));
  PRECISE real t = real(0.0f);
  PRECISE vec3 dt = vec3(real(0.0f));
  PRECISE vec3 tv = vec3(real(0.0f));  // dT/dv
  ErosionRows hs = rowsZero();         // d2S/dq2
  ErosionRows ht = rowsZero();         // d2T/dq2
  ErosionRows mt = rowsZero();         // d(dT/dq)/dv
  for (uint k = 0u; k < 4u; ++k) {
    vec3 dk = d[k];
    gullyCorner(dk, gs[k], v, s, ds, t, dt);
    // The corner's kernel and stripe again (the same operations as in gullyCorner).
    PRECISE real r = kKernelRadius2 - dk.x * dk.x - dk.y * dk.y - dk.z * dk.z;
    r = max(r, real(0.0f));
    PRECISE real r2 = r * r;
    PRECISE real kernel = r2 * r;
    PRECISE vec3 dkernel = dk * (real(-6.0f) * r2);
    PRECISE real phase = dot3(dk, v) + real(gs[k]) * kGullyPhaseStep;
    vec3 wave = gullyWave(phase);
    // d2K/dq2 = 24 r d d^T - 6 r^2 I.
    PRECISE real c24 = real(24.0f) * r;
    PRECISE real c6 = real(-6.0f) * r2;
    PRECISE vec3 hkx = dk * (c24 * dk.x) + vec3(c6, real(0.0f), real(0.0f));
    PRECISE vec3 hky = dk * (c24 * dk.y) + vec3(real(0.0f), c6, real(0.0f));
    PRECISE vec3 hkz = dk * (c24 * dk.z) + vec3(real(0.0f), real(0.0f), c6);
    ErosionRows hk = rowsOf(hkx, hky, hkz);
    hs = rowsAddScaled(hs, hk, real(1.0f));
    // d2(K W)/dq2 = W d2K + W' (dK v^T + v dK^T) + K W'' v v^T.
    PRECISE real kw2 = kernel * wave.z;
    PRECISE vec3 htx = (v * dkernel.x + dkernel * v.x) * wave.y + v * (kw2 * v.x);
    PRECISE vec3 hty = (v * dkernel.y + dkernel * v.y) * wave.y + v * (kw2 * v.y);
    PRECISE vec3 htz = (v * dkernel.z + dkernel * v.z) * wave.y + v * (kw2 * v.z);
    ht = rowsAddScaled(ht, hk, wave.x);
    ht = rowsAddScaled(ht, rowsOf(htx, hty, htz), real(1.0f));
    // d(K W)/dv = K W' d; d(d(K W)/dq_i)/dv = (dK_i W' + v_i K W'') d + K W' e_i.
    PRECISE real kw1 = kernel * wave.y;
    tv += dk * kw1;
    PRECISE vec3 mtx = dk * (dkernel.x * wave.y + v.x * kw2) + vec3(kw1, real(0.0f), real(0.0f));
    PRECISE vec3 mty = dk * (dkernel.y * wave.y + v.y * kw2) + vec3(real(0.0f), kw1, real(0.0f));
    PRECISE vec3 mtz = dk * (dkernel.z * wave.y + v.z * kw2) + vec3(real(0.0f), real(0.0f), kw1);
    mt = rowsAddScaled(mt, rowsOf(mtx, mty, mtz), real(1.0f));
  }
  GullyPatternDerivatives result;
  result.value = vec4(real(0.0f));
  result.dv = vec3(real(0.0f));
  result.hessian = rowsZero();
  result.mixed = rowsZero();
  if (!(s > real(0.0f))) return result;
  PRECISE real pattern = t / s;
  PRECISE vec3 dpattern = (dt - ds * pattern) / s;
  result.value = withGradient(pattern, dpattern);
  PRECISE vec3 pv = tv / s;
  result.dv = pv;
  // S P = T: S d2P = d2T - P d2S - (dP dS^T + dS dP^T); d(dP/dq_i)/dv = (d(dT/dq_i)/dv - dS_i dP/dv) / S.
  PRECISE real inverse = real(1.0f) / s;
  PRECISE real minusPattern = -pattern;
  ErosionRows hp = rowsAddScaled(ht, hs, minusPattern);
  PRECISE vec3 sx = dpattern * ds.x + ds * dpattern.x;
  PRECISE vec3 sy = dpattern * ds.y + ds * dpattern.y;
  PRECISE vec3 sz = dpattern * ds.z + ds * dpattern.z;
  hp = rowsAddScaled(hp, rowsOf(sx, sy, sz), real(-1.0f));
  result.hessian = rowsAddScaled(rowsZero(), hp, inverse);
  PRECISE vec3 px = pv * ds.x;
  PRECISE vec3 py = pv * ds.y;
  PRECISE vec3 pz = pv * ds.z;
  ErosionRows mp = rowsAddScaled(mt, rowsOf(px, py, pz), real(-1.0f));
  result.mixed = rowsAddScaled(rowsZero(), mp, inverse);
  return result;
}

// erodedNoise with its gradient. Per gully scale, with c = cross(up, G), v = c·m,
// m = (|c|^2 + eps^2)^(-1/2), F = |c|^2 / (|c|^2 + kGullySlope^2) and a = A·F:
//   d(a P)/du = a (ratio dP/dq + (dv/du)^T dP/dv) + P da/du,
//   dv/du = m dc/du - (m^3 / 2) c (d|c|^2/du)^T,  d|c|^2/du = 2 (dc/du)^T c,
//   dF/du = kGullySlope^2 / (|c|^2 + kGullySlope^2)^2 · d|c|^2/du,
// and the flow gradient's Jacobian grows by d(a ratio dP/dq)/du
//   = ratio (dP/dq (da/du)^T + a (ratio d2P/dq2 + (d(dP/dq)/dv) dv/du)).
vec4 erodedNoiseGradient(IN(NoiseParams) params, INOUT(OctaveWalk) walk) {
  vec4 up = erosionUp(walk);
  vec3 n = vec3(up.x, up.y, up.z);
  ErosionRows dn = erosionUpJacobian(up);
  real scale0 = octaveChainScale(walk, real(1.0f));
  uint baseOctaves = erodedBaseOctaves(params);
  PRECISE real height = real(0.0f);
  PRECISE vec3 dheight = vec3(real(0.0f));  // octave-0 units until the end
  PRECISE real before = real(0.0f);
  PRECISE vec3 dbefore = vec3(real(0.0f));
  PRECISE vec3 slope = vec3(real(0.0f));
  ErosionRows flow = rowsZero();  // d(slope)/du
  PRECISE real w = real(1.0f);
  real plainScale = real(1.0f);
  vec3 cellQ = vec3(real(0.0f));
  uvec3 cellShift = uvec3(0u);
  real cellRatio = real(1.0f);
  PRECISE real walls = real(1.0f);
  PRECISE vec3 dwalls = vec3(real(0.0f));
  PRECISE real expected2 = real(0.0f);
  for (uint i = 0u; i < baseOctaves; ++i) {
    PRECISE real ratio = octaveChainScale(walk, plainScale) / scale0;
    vec3 q;
    uvec3 shift;
    nextOctavePoint(walk, q, shift);
    plainScale = plainScale * walk.lacunarity;
    ErosionRows h;
    vec4 noise = simplexWrappedHessian(q, shift, params.hash, params.seedMix, h);
    before = height;
    dbefore = dheight;
    height += noise.x * w;
    dheight += gradientOf(noise) * (w * ratio);
    slope += gradientOf(noise) * (w * ratio);
    expected2 += (w * ratio) * (w * ratio) * kBaseSlope2;
    flow = rowsAddScaled(flow, h, w * ratio * ratio);
    w *= real(params.octaveWeight);
    cellQ = q;
    cellShift = shift;
    cellRatio = ratio;
  }
  for (uint i = baseOctaves; i < params.octaves; ++i) {
    PRECISE real ratio = octaveChainScale(walk, plainScale) / scale0;
    vec3 q;
    uvec3 shift;
    nextOctavePoint(walk, q, shift);
    plainScale = plainScale * walk.lacunarity;
    vec3 c = cross3(n, slope);
    PRECISE real soft2 = kGullySlopeSoft2 * expected2;
    vec4 direction = gullyDirection(c, soft2);
    PRECISE vec3 stripes = vec3(direction.x, direction.y, direction.z) * walk.lacunarity;
    GullyPatternDerivatives pattern = gullyPatternDerivatives(cellQ, cellShift, stripes, params.hash, params.seedMix);
    PRECISE real amplitude = real(params.gain) * kGullyDepth * w;
    PRECISE real depth = amplitude * direction.w * walls;
    // The stripes' and the depth's derivatives.
    ErosionRows dc = crossJacobian(n, dn, slope, flow);
    PRECISE vec3 dc2 = rowsTransposeTimes(dc, c) * real(2.0f);
    PRECISE real c2 = dot3(c, c);
    PRECISE real norm2 = c2 + soft2;
    PRECISE real m = walk.lacunarity / sqrt(norm2);
    PRECISE real m3 = m / norm2 * real(0.5f);
    PRECISE vec3 dsx = dc.x * m - dc2 * (c.x * m3);
    PRECISE vec3 dsy = dc.y * m - dc2 * (c.y * m3);
    PRECISE vec3 dsz = dc.z * m - dc2 * (c.z * m3);
    ErosionRows dstripes = rowsOf(dsx, dsy, dsz);
    PRECISE real soft = c2 + kGullySlope * kGullySlope;
    PRECISE vec3 ddepth = (dc2 * (kGullySlope * kGullySlope / (soft * soft) * walls) + dwalls * direction.w) * amplitude;
    vec3 dpattern = gradientOf(pattern.value);
    // The pattern's whole derivative (through q and through the stripes).
    PRECISE vec3 dfull = dpattern * cellRatio + rowsTransposeTimes(dstripes, pattern.dv);
    walls = real(1.0f) - pattern.value.x * pattern.value.x;
    dwalls = dfull * (real(-2.0f) * pattern.value.x);
    expected2 += (amplitude * cellRatio * walk.lacunarity) * (amplitude * cellRatio * walk.lacunarity) * kStripeSlope2;
    before = height;
    dbefore = dheight;
    height += depth * pattern.value.x;
    dheight += dfull * depth + ddepth * pattern.value.x;
    // The flow field's Jacobian (from the slope before this scale), then the slope.
    ErosionRows dgully = rowsAddScaled(rowsProduct(pattern.mixed, dstripes), pattern.hessian, cellRatio);
    dgully = rowsAddScaled(rowsZero(), dgully, depth);
    PRECISE vec3 gx = ddepth * dpattern.x;
    PRECISE vec3 gy = ddepth * dpattern.y;
    PRECISE vec3 gz = ddepth * dpattern.z;
    dgully = rowsAddScaled(dgully, rowsOf(gx, gy, gz), real(1.0f));
    flow = rowsAddScaled(flow, dgully, cellRatio);
    slope += dpattern * (depth * cellRatio);
    w *= real(params.octaveWeight);
    cellQ = q;
    cellShift = shift;
    cellRatio = ratio;
  }
  PRECISE vec3 inputBefore = dbefore * scale0;
  PRECISE vec3 inputAfter = dheight * scale0;
  return fadeLastGradient(params, withGradient(before, inputBefore), withGradient(height, inputAfter));
}

#endif

// The terrain height of a planet, its noise stack shaped and summed (README, "Planets"):
//   value_l = curve_l(noise_l(p)) · mask_l(value of an earlier layer)
//   height  = heightScale · (baseHeight + Σ_l amplitude_l · value_l),
// written once for every place that evaluates it: the double reference (terrainHeightM,
// engine/planet/terrain_height.cpp), the rebased float path (terrainHeightRebased,
// engine/planet/terrain_rebase.cpp, and so the CPU height source), and the shaders
// terrain_heights.comp and terrain_noise.vert (through terrain_vertex_surface.glsl),
// patch_height.comp and terrain_points.comp. Common subset: definitions.glsl; include it after
// noise.glsl and shared/terrain_params.h (C++: noise_kernel.h does).
//
// The includer defines, before including:
//   TERRAIN_LAYER_COUNT                 the number of layers (at most kTerrainMaxLayers)
//   TERRAIN_LAYER_NOISE(l, p, context, needed)  layer l's noise value at p, through
//                                       terrainLayerParams and rebasedLayerNoise below (or
//                                       evaluateNoise for the double reference); `context` is
//                                       what terrainHeightSum was given (the mesh: the ring).
//                                       Where `needed` is false the layer's mask is 0 there, so
//                                       its value does not matter: evaluate it with no octaves
//                                       (any finite value will do)
//   TERRAIN_LAYER(l)                    layer l's TerrainLayer (its curves and mask are read)
//   TERRAIN_LAYER_AMPLITUDE(l)          its amplitude in the evaluation's precision
// and, for terrainHeightGradientSum (compiled only where it is defined):
//   TERRAIN_LAYER_NOISE_GRADIENT(l, p, context, needed)  TERRAIN_LAYER_NOISE with its gradient with
//                                       respect to p, vec4(value, d/dx, d/dy, d/dz), the value
//                                       bit-identical to TERRAIN_LAYER_NOISE's
// and TERRAIN_UNROLLED_LAYERS where layer indices must be constants: a shader specialized on the
// layers' types and hashes (terrain_layer_specialization.glsl) names a layer's type by its
// index, and with constant indices its compiler folds each layer's branches away.
#ifndef PLANET_COMMON_TERRAIN_HEIGHT_GLSL
#define PLANET_COMMON_TERRAIN_HEIGHT_GLSL

#include "common/definitions.glsl"

// A layer's noise parameters as one evaluation uses them: its fractal type and lattice hash
// (specialized shaders pass constants), limited to `octaves`, the last one weighted
// `lastOctaveWeight` (the octave budget of the point's spacing, planet/octave_budget.h).
NoiseParams terrainLayerParams(NoiseParams params, uint type, uint hash, uint octaves, float lastOctaveWeight) {
  params.type = type;
  params.hash = hash;
  params.octaves = octaves;
  params.lastOctaveWeight = lastOctaveWeight;
  return params;
}

// Layer `layer`'s fractal at `offset` (metres from the anchor of the rebased octave tables,
// planet frame), walking row `layer` of the tables (DESIGN.md, "Earth-scale precision").
real rebasedLayerNoise(IN(NoiseParams) params, uint layer, vec3 offset) {
  OctaveWalk walk;
  walk.q = vec3(real(0.0f));
  walk.lacunarity = real(params.lacunarity);
  walk.offset = offset;
  walk.layer = layer;
  walk.octave = 0u;
  walk.rebased = 1u;
  return fractalNoise(params, walk);
}

// rebasedLayerNoise with its gradient with respect to the offset (per metre, planet frame).
vec4 rebasedLayerNoiseGradient(IN(NoiseParams) params, uint layer, vec3 offset) {
  OctaveWalk walk;
  walk.q = vec3(real(0.0f));
  walk.lacunarity = real(params.lacunarity);
  walk.offset = offset;
  walk.layer = layer;
  walk.octave = 0u;
  walk.rebased = 1u;
  return fractalNoiseGradient(params, walk);
}

// The knot of layer l's curve (`count` knots from knots[first]) that starts x's segment: the
// last one at or below x, never the last knot (x inside the knots; the callers take the ends).
uint terrainCurveSegment(uint l, uint first, uint count, real x) {
  uint segment = first;
  for (uint k = 1u; k + 1u < count; ++k)
    if (x >= real(TERRAIN_LAYER(l).knots[first + k].x)) segment = first + k;
  return segment;
}

// The Hermite segment from knot a to knot b at t in [0, 1] (width = b.x − a.x).
real terrainHermite(vec4 a, vec4 b, real t, real width) {
  PRECISE real t2 = t * t;
  PRECISE real t3 = t2 * t;
  PRECISE real rise = real(3.0f) * t2 - real(2.0f) * t3;  // h01; h00 = 1 - h01
  PRECISE real startSlope = (t3 - real(2.0f) * t2 + t) * width;
  PRECISE real endSlope = (t3 - t2) * width;
  PRECISE real y = a.y * (real(1.0f) - rise) + b.y * rise + a.z * startSlope + b.z * endSlope;
  return y;
}

// Monotone cubic Hermite curve through `count` knots of layer l from knots[first] (shared/
// terrain_params.h), at x; its end values outside the knots. Continuous in value and slope, so a
// curve leaves no crease in the terrain's shading along the level sets of the noise.
real terrainCurve(uint l, uint first, uint count, real x) {
  vec4 a = vec4(TERRAIN_LAYER(l).knots[first]);
  if (x <= a.x) return a.y;
  vec4 last = vec4(TERRAIN_LAYER(l).knots[first + count - 1u]);
  if (x >= last.x) return last.y;
  uint segment = terrainCurveSegment(l, first, count, x);
  a = vec4(TERRAIN_LAYER(l).knots[segment]);
  vec4 b = vec4(TERRAIN_LAYER(l).knots[segment + 1u]);
  // A division, not a stored reciprocal: t must be 1 exactly at the next knot, or the value
  // would step there by the reciprocal's rounding times the segment's rise.
  PRECISE real width = b.x - a.x;
  PRECISE real t = (x - a.x) / width;
  return terrainHermite(a, b, t, width);
}

// terrainCurve and its slope dy/dx: vec2(y, dy/dx), y as terrainCurve computes it (bit-identical),
// the slope the derivative of the same Hermite basis (0 outside the knots, where the curve is flat).
vec2 terrainCurveWithSlope(uint l, uint first, uint count, real x) {
  vec4 a = vec4(TERRAIN_LAYER(l).knots[first]);
  if (x <= a.x) return vec2(a.y, real(0.0f));
  vec4 last = vec4(TERRAIN_LAYER(l).knots[first + count - 1u]);
  if (x >= last.x) return vec2(last.y, real(0.0f));
  uint segment = terrainCurveSegment(l, first, count, x);
  a = vec4(TERRAIN_LAYER(l).knots[segment]);
  vec4 b = vec4(TERRAIN_LAYER(l).knots[segment + 1u]);
  PRECISE real width = b.x - a.x;
  PRECISE real t = (x - a.x) / width;
  PRECISE real t2 = t * t;
  // d/dx = (d/dt) / width: the rise's 6t − 6t² carries the knots' difference over the width, the
  // tangent terms' width cancels.
  PRECISE real riseSlope = real(6.0f) * (t - t2) / width;
  PRECISE real startTangent = real(3.0f) * t2 - real(4.0f) * t + real(1.0f);
  PRECISE real endTangent = real(3.0f) * t2 - real(2.0f) * t;
  PRECISE real slope = (b.y - a.y) * riseSlope + a.z * startTangent + b.z * endTangent;
  return vec2(terrainHermite(a, b, t, width), slope);
}

// Layer l's mask from the value of the layer that masks it, through the mask curve; 1 where no
// layer masks it.
real terrainLayerMask(uint l, real maskSource) {
  if (TERRAIN_LAYER(l).maskLayer == kTerrainNoMask) return real(1.0f);
  if (TERRAIN_LAYER(l).maskKnots == 0u) return maskSource;
  return terrainCurve(l, kTerrainCurveKnots, TERRAIN_LAYER(l).maskKnots, maskSource);
}

// Layer l's value from its noise value and its mask (terrainLayerMask): the transfer curve, then
// the mask.
real terrainLayerValue(uint l, real noiseValue, real mask) {
  PRECISE real value = noiseValue;
  if (TERRAIN_LAYER(l).curveKnots > 0u) value = terrainCurve(l, 0u, TERRAIN_LAYER(l).curveKnots, value);
  if (TERRAIN_LAYER(l).maskLayer != kTerrainNoMask) value = value * mask;
  return value;
}

// Runs STEP(l) for each layer l in order: with constant indices where the includer asks for
// them (TERRAIN_UNROLLED_LAYERS), else in a loop.
#ifdef TERRAIN_UNROLLED_LAYERS
#define TERRAIN_FOR_EACH_LAYER(STEP)          \
  if (TERRAIN_LAYER_COUNT > 0u) STEP(0u)      \
  if (TERRAIN_LAYER_COUNT > 1u) STEP(1u)      \
  if (TERRAIN_LAYER_COUNT > 2u) STEP(2u)      \
  if (TERRAIN_LAYER_COUNT > 3u) STEP(3u)      \
  if (TERRAIN_LAYER_COUNT > 4u) STEP(4u)      \
  if (TERRAIN_LAYER_COUNT > 5u) STEP(5u)      \
  if (TERRAIN_LAYER_COUNT > 6u) STEP(6u)      \
  if (TERRAIN_LAYER_COUNT > 7u) STEP(7u)
#else
#define TERRAIN_FOR_EACH_LAYER(STEP) \
  for (uint l = 0u; l < TERRAIN_LAYER_COUNT; ++l) STEP(l)
#endif

// One layer of terrainHeightSum: its value kept for the layers it masks, its term added. A mask
// layer is always an earlier one (the parser's rule); any other index reads this layer's 0.
// Where the mask is exactly 0 the layer adds nothing whatever its noise, so the noise is
// evaluated with no octaves there: most of a planet for masked mountains, and on lavapipe an
// octave loop ends as soon as all its lanes are done. The value is then 0 (or −0) as before.
#define TERRAIN_HEIGHT_STEP(l)                                                                        \
  {                                                                                                   \
    uint source = TERRAIN_LAYER(l).maskLayer < (l) ? TERRAIN_LAYER(l).maskLayer : (l);                 \
    PRECISE real mask = terrainLayerMask(l, values[source]);                                          \
    bool needed = mask != real(0.0f);                                                                 \
    values[l] = terrainLayerValue(l, TERRAIN_LAYER_NOISE(l, p, context, needed), mask);               \
    sum += TERRAIN_LAYER_AMPLITUDE(l) * values[l];                                                    \
  }

// The height at p: the layers in order, each term added to the base as it comes, then scaled.
real terrainHeightSum(real baseHeight, real heightScale, vec3 p, uint context) {
  PRECISE real sum = baseHeight;
  real values[kTerrainMaxLayers];
  for (uint i = 0u; i < kTerrainMaxLayers; ++i) values[i] = real(0.0f);
  TERRAIN_FOR_EACH_LAYER(TERRAIN_HEIGHT_STEP)
  return heightScale * sum;
}

#undef TERRAIN_HEIGHT_STEP

#ifdef TERRAIN_LAYER_NOISE_GRADIENT
// terrainLayerMask with its gradient, from the mask source's (a value with its gradient).
vec4 terrainLayerMaskGradient(uint l, vec4 maskSource) {
  if (TERRAIN_LAYER(l).maskLayer == kTerrainNoMask) return withGradient(real(1.0f), vec3(real(0.0f)));
  if (TERRAIN_LAYER(l).maskKnots == 0u) return maskSource;
  vec2 curve = terrainCurveWithSlope(l, kTerrainCurveKnots, TERRAIN_LAYER(l).maskKnots, maskSource.x);
  PRECISE vec3 gradient = gradientOf(maskSource) * curve.y;
  return withGradient(curve.x, gradient);
}

// terrainLayerValue with its gradient, from the noise's and the mask's (values with gradients):
// for value = c(n) · m, grad = c'(n) grad n · m + c(n) · grad m. The value with
// terrainLayerValue's operations (bit-identical).
vec4 terrainLayerValueGradient(uint l, vec4 noiseValue, vec4 mask) {
  PRECISE real value = noiseValue.x;
  PRECISE vec3 gradient = gradientOf(noiseValue);
  if (TERRAIN_LAYER(l).curveKnots > 0u) {
    vec2 curve = terrainCurveWithSlope(l, 0u, TERRAIN_LAYER(l).curveKnots, value);
    value = curve.x;
    gradient = gradient * curve.y;
  }
  if (TERRAIN_LAYER(l).maskLayer != kTerrainNoMask) {
    gradient = gradient * mask.x + gradientOf(mask) * value;
    value = value * mask.x;
  }
  return withGradient(value, gradient);
}

// One layer of terrainHeightGradientSum: TERRAIN_HEIGHT_STEP with each value's gradient beside it.
// Where the mask is 0 the noise is skipped as there: the value is the same, and the gradient too
// but where a mask crosses 0 with a slope (c(n) · grad m then depends on the noise; a set of
// measure zero, where the normal is that of the point beside it).
#define TERRAIN_HEIGHT_GRADIENT_STEP(l)                                                                  \
  {                                                                                                      \
    uint source = TERRAIN_LAYER(l).maskLayer < (l) ? TERRAIN_LAYER(l).maskLayer : (l);                    \
    vec4 mask = terrainLayerMaskGradient(l, values[source]);                                             \
    bool needed = mask.x != real(0.0f);                                                                  \
    vec4 noise = TERRAIN_LAYER_NOISE_GRADIENT(l, p, context, needed);                                    \
    values[l] = terrainLayerValueGradient(l, noise, mask);                                               \
    sum += TERRAIN_LAYER_AMPLITUDE(l) * values[l].x;                                                     \
    gradient += gradientOf(values[l]) * real(TERRAIN_LAYER_AMPLITUDE(l));                                \
  }

// terrainHeightSum with its gradient with respect to p: vec4(height, dh/dp), the height
// bit-identical to terrainHeightSum's (the same operations in the same order). One evaluation
// of the stack gives a vertex its normal, where differences of neighbours took four more.
vec4 terrainHeightGradientSum(real baseHeight, real heightScale, vec3 p, uint context) {
  PRECISE real sum = baseHeight;
  PRECISE vec3 gradient = vec3(real(0.0f));
  vec4 values[kTerrainMaxLayers];
  for (uint i = 0u; i < kTerrainMaxLayers; ++i) values[i] = vec4(real(0.0f));
  TERRAIN_FOR_EACH_LAYER(TERRAIN_HEIGHT_GRADIENT_STEP)
  PRECISE vec3 scaled = gradient * heightScale;
  return withGradient(heightScale * sum, scaled);
}

#undef TERRAIN_HEIGHT_GRADIENT_STEP
#endif

#undef TERRAIN_FOR_EACH_LAYER

#endif

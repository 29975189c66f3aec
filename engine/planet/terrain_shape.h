// The shaping of a planet's layers as the height evaluations read it (shared/terrain_params.h,
// shaders/common/terrain_height.glsl): each layer's curves turned into spline knots and its
// mask into a layer index, built on the CPU in double so that the GPU and every CPU path read
// the same floats.
//
// A hypsometry curve (NoiseLayer::hypsometry) names area fractions, not noise values: the knot
// of fraction F sits at the F-quantile of the layer's noise over the whole sphere, measured at
// kHypsometrySamples points of a Fibonacci lattice in double with every octave. The map from
// noise to value then gives the layer (nearly) the named hypsometry whatever its seed, which a
// fixed curve cannot: a few continents' worth of low-frequency noise covers a different share of
// the sphere at every seed.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "planet/planet_description.h"
#include "shared/terrain_params.h"

namespace planet {

inline constexpr size_t kHypsometrySamples = 65536;

// Layer l of `planet` as the GPU and the C++ kernels read it: its noise parameters (every
// octave), amplitude, curve knots and mask. Throws planet::Error for a mask that names no
// earlier layer. A hypsometry's quantiles are computed once per distinct layer and kept.
gpu::TerrainLayer terrainLayerShape(const PlanetDescription& planet, size_t l);

// The noise values of `layer` on the sphere of radius `radiusM` below which the fractions
// `fractions` (each in [0, 1]) of the area lie (the quantiles behind a hypsometry).
std::vector<double> noiseQuantiles(const NoiseLayer& layer, double radiusM, std::span<const double> fractions);

// Knots of the monotone cubic through `points` (x strictly increasing) into `knots` (as many):
// Fritsch–Carlson slopes, zero at both ends so that the curve meets its constant ends smoothly.
void curveKnots(std::span<const CurvePoint> points, gpu::vec4* knots);

// The index of the earlier layer that layer l's mask names. Throws planet::Error when none does.
size_t maskIndex(const PlanetDescription& planet, size_t l);

// Bounds of a layer's mask factor (1 without a mask) and of its value (its curve's largest |y|,
// else 2 for the noise, times the mask's bound): what the height bounds assume a layer can add.
double layerMaskBound(const PlanetDescription& planet, size_t l);
double layerValueBound(const PlanetDescription& planet, size_t l);

}  // namespace planet

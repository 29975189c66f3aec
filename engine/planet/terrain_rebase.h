// Earth-scale precision for the terrain noise (DESIGN.md, "Earth-scale precision").
//
// A float holds a point of an Earth-sized planet to about 0.5 m, and octave 20 of the detail
// noise needs centimetres. So, per frame, the CPU takes an anchor point near the camera and,
// in double, splits the anchor's position in every octave's noise units into an integer
// lattice shift and a small float remainder (OctaveWalk in shaders/common/noise.glsl). The GPU
// then evaluates each sample from its small float offset to the anchor. This file builds those
// tables and evaluates the float path on the CPU, exactly as the shader will (NoiseKernel<float>
// is the shader code compiled as C++).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "planet/planet_description.h"

namespace planet {

struct OctaveTables {
  glm::dvec3 anchorM{0.0};            // anchor on the radius sphere, planet frame, metres
  std::vector<glm::vec4> remainders;  // per layer, kNoiseMaxOctaves rows: xyz remainder, w scale (1/m)
  std::vector<glm::uvec4> shifts;     // per layer, kNoiseMaxOctaves rows: lattice shift (xyz)
};

// Splits `a` (a point in octave units) into an integer vector whose coordinates sum to a multiple
// of 3 and a remainder in [0, 3) x [0, 1)^2 (remainder.xyz; w untouched), and gives the simplex
// lattice shift of that integer vector (shift.xyz): skewing adds the integer (I.x + I.y + I.z) / 3
// to every axis, so the lattice moves exactly. Wraps modulo 2^32: both hashes depend on the indices
// modulo 2^22 or 2^8.
void splitLatticeAnchor(const glm::dvec3& a, glm::vec4& remainder, glm::uvec4& shift);

// Tables for every layer of `planet` around `anchorM` (a point on the radius sphere).
OctaveTables buildOctaveTables(const PlanetDescription& planet, const glm::dvec3& anchorM);

// Height in metres, computed in float along the rebased path, at the point of the radius sphere
// that lies `offsetM` from the anchor (offsetM = sample - anchor, planet frame). spacingM limits
// the octaves as in terrainHeightM (0: all of them).
float terrainHeightRebased(const PlanetDescription& planet, const OctaveTables& tables, const glm::vec3& offsetM,
                           double spacingM = 0.0);

}  // namespace planet

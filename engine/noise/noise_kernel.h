// The CPU reference of the noise: shaders/common/noise.glsl compiled as C++.
//
// The GLSL functions become member functions of NoiseKernel<real>, so one source yields the
// float reference (bit-identical to the GPU on lavapipe) and a double-precision one (the
// accuracy reference for Earth-scale tests). The translation units that instantiate it are
// compiled with -ffp-contract=off (never -ffast-math) so that no multiply-add is fused.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "shared/noise_params.h"

namespace planet::noise {
namespace kernel_detail {

using namespace planet::gpu;

template <typename Real>
struct NoiseKernel {
  using real = Real;
  using vec3 = glm::vec<3, Real, glm::defaultp>;
  using uvec3 = glm::uvec3;
  using vec4 = glm::vec<4, Real, glm::defaultp>;
  using uvec4 = glm::uvec4;
  using uint = std::uint32_t;

  // The reference hash's 512-entry permutation table (permutationTable()); unused by the fast hash.
  const uint* permutation = nullptr;
  // Rebased octave tables (OctaveWalk), kNoiseMaxOctaves entries per layer; unused by plain walks.
  const glm::vec4* octaveRemainders = nullptr;
  const glm::uvec4* octaveShifts = nullptr;

  // The GLSL builtins the shared code uses, for exactly this precision (no silent promotion
  // of float to double through a C library overload).
  static real floor(real x) { return std::floor(x); }
  static real abs(real x) { return std::fabs(x); }
  static real roundEven(real x) { return std::nearbyint(x); }  // default rounding: ties to even
  static real max(real x, real y) { return x < y ? y : x; }    // GLSL 4.50 definitions
  static real min(real x, real y) { return y < x ? y : x; }
  static real clamp(real x, real lo, real hi) { return min(max(x, lo), hi); }

#define IN(T) const T&
#define OUT(T) T&
#define INOUT(T) T&
#define OCTAVE_REMAINDER(layer, i) vec4(octaveRemainders[(layer)*kNoiseMaxOctaves + (i)])
#define OCTAVE_SHIFT(layer, i) octaveShifts[(layer)*kNoiseMaxOctaves + (i)]
#define NOISE_CONST static constexpr
#define PRECISE  // C++: this file is compiled with -ffp-contract=off
#define PERM(i) permutation[i]
#include "common/noise.glsl"
#undef IN
#undef OUT
#undef INOUT
#undef OCTAVE_REMAINDER
#undef OCTAVE_SHIFT
#undef NOISE_CONST
#undef PRECISE
#undef PERM
};

}  // namespace kernel_detail

using kernel_detail::NoiseKernel;

}  // namespace planet::noise

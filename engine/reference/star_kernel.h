// The CPU reference of the star catalogue: shaders/common/stars.glsl compiled as C++.
//
// The GLSL functions become static member functions of StarKernel. Translation units that
// include this are compiled with -ffp-contract=off (never -ffast-math) so that no multiply-add
// is fused and the results equal the GPU's bit for bit (engine/CMakeLists.txt, tests/CMakeLists.txt).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "shared/star_params.h"

namespace planet::stars {
namespace kernel_detail {

using namespace planet::gpu;

struct StarKernel {
  using uint = std::uint32_t;
  using vec2 = glm::vec2;
  using vec3 = glm::vec3;
  using vec4 = glm::vec4;

  // The GLSL builtins the shared code uses, in float (no silent promotion to double).
  static float floor(float x) { return std::floor(x); }
  static float sqrt(float x) { return std::sqrt(x); }
  static float ldexp(float x, int e) { return std::ldexp(x, e); }
  static float max(float x, float y) { return x < y ? y : x; }  // GLSL 4.50 definitions
  static float min(float x, float y) { return y < x ? y : x; }
  static float clamp(float x, float lo, float hi) { return min(max(x, lo), hi); }
  static int findMSB(uint x) { return x == 0u ? -1 : 31 - std::countl_zero(x); }

#define STAR_CONST static constexpr
#define PRECISE  // C++: compiled with -ffp-contract=off
#include "common/stars.glsl"
#undef STAR_CONST
#undef PRECISE
};

}  // namespace kernel_detail

using kernel_detail::StarKernel;

}  // namespace planet::stars

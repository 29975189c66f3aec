// The C++ half of the contract between GLSL and C++ for the shared files of shaders/common (the
// GLSL half is definitions.glsl beside it, which names the rules). A CPU reference is such a
// file included inside a struct, so that its functions become member functions:
//
//   template <typename Real> struct MyKernel {
//     PLANET_GLSL_KERNEL(Real)       // real, the vector types and the GLSL builtins
//   #include "common/my_shared_file.glsl"
//   };
//
// and the translation unit is compiled without fused multiply-adds (the project-wide rule in
// the top CMakeLists.txt).
#pragma once

#ifndef __cplusplus
#error "definitions.h is the C++ half of the contract; GLSL includes definitions.glsl"
#endif

#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

// Parameters passed by reference, and the qualifiers the GLSL side spells `precise` and `const`.
#define IN(T) const T&
#define OUT(T) T&
#define INOUT(T) T&
#define PRECISE  // C++: no contraction anyway (-ffp-contract=off)
#define SHARED_CONST static constexpr

// The types of the common subset for precision Real, and the GLSL builtins the shared files
// use, as static members for exactly that precision: a call never promotes float to double
// through a C library overload, and max/min/clamp follow GLSL 4.50's definitions.
#define PLANET_GLSL_KERNEL(Real)                                                             \
  using real = Real;                                                                         \
  using uint = std::uint32_t;                                                                \
  using vec2 = glm::vec<2, Real, glm::defaultp>;                                             \
  using vec3 = glm::vec<3, Real, glm::defaultp>;                                             \
  using vec4 = glm::vec<4, Real, glm::defaultp>;                                             \
  using uvec3 = glm::uvec3;                                                                  \
  using uvec4 = glm::uvec4;                                                                  \
  static real floor(real x) { return std::floor(x); }                                        \
  static real abs(real x) { return std::fabs(x); }                                           \
  static real roundEven(real x) { return std::nearbyint(x); } /* default rounding: to even */ \
  static real max(real x, real y) { return x < y ? y : x; }                                  \
  static real min(real x, real y) { return y < x ? y : x; }                                  \
  static real clamp(real x, real lo, real hi) { return min(max(x, lo), hi); }                \
  static real sqrt(real x) { return std::sqrt(x); }                                          \
  static real exp(real x) { return std::exp(x); }                                            \
  static real pow(real x, real y) { return std::pow(x, y); }                                 \
  static real ldexp(real x, int e) { return std::ldexp(x, e); }                              \
  static int findMSB(uint x) { return x == 0u ? -1 : 31 - std::countl_zero(x); }

// Lets one header declare structs and constants for both GLSL and C++.
// Rules for shared structs (STYLE.md): only vec4/mat4/uint/int/float members, explicit
// padding to 16 bytes, and GPU_ASSERT_SIZE(T, bytes) after each struct (no semicolon: GLSL
// rejects an empty declaration) so that C++ checks the size.
#ifndef PLANET_SHARED_GPU_TYPES_H
#define PLANET_SHARED_GPU_TYPES_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
#define GPU_NAMESPACE_BEGIN namespace planet::gpu { using uint = std::uint32_t; using vec4 = glm::vec4; using mat4 = glm::mat4;
#define GPU_NAMESPACE_END }
#define GPU_CONST inline constexpr
#define GPU_ASSERT_SIZE(T, bytes) static_assert(sizeof(T) == (bytes), #T " must keep its GLSL std430 size");
#else
#define GPU_NAMESPACE_BEGIN
#define GPU_NAMESPACE_END
#define GPU_CONST const
#define GPU_ASSERT_SIZE(T, bytes)
#endif

#endif

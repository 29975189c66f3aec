// The CPU reference of the star catalogue: shaders/common/stars.glsl compiled as C++.
//
// The GLSL functions become static member functions of StarKernel. Translation units that
// include this are compiled with -ffp-contract=off (never -ffast-math) so that no multiply-add
// is fused and the results equal the GPU's bit for bit (the project-wide rule, top CMakeLists.txt).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "common/definitions.h"
#include "shared/star_params.h"

namespace planet::stars {
namespace kernel_detail {

using namespace planet::gpu;

struct StarKernel {
  PLANET_GLSL_KERNEL(float)
#include "common/stars.glsl"
};

}  // namespace kernel_detail

using kernel_detail::StarKernel;

}  // namespace planet::stars

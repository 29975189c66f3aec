// Compiled with -ffp-contract=off (engine/CMakeLists.txt): the reference must round exactly like
// the GLSL it is compiled from.
#include "render/star_catalogue.h"

#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "render/star_kernel.h"

namespace planet {

uint32_t realisticStarCount(float faintestMagnitude) {
  return uint32_t(std::lround(9000.0 * std::pow(10.0, 0.5 * (double(faintestMagnitude) - 6.5))));
}

void validateStarSettings(const StarSettings& settings) {
  if (settings.count == 0 || settings.count > gpu::kStarMaxCount)
    throw Error(fmt::format("star count {} is outside 1..{}", settings.count, gpu::kStarMaxCount));
  if (!(settings.faintestMagnitude >= kStarMinFaintestMagnitude &&
        settings.faintestMagnitude <= kStarMaxFaintestMagnitude))
    throw Error(fmt::format("faintest star magnitude {} is outside [{}, {}]", settings.faintestMagnitude,
                            kStarMinFaintestMagnitude, kStarMaxFaintestMagnitude));
  if (!(settings.brightness > 0.0f && settings.brightness <= kStarMaxBrightness))
    throw Error(fmt::format("star brightness {} is outside (0, {}]", settings.brightness, kStarMaxBrightness));
}

std::vector<gpu::StarRecord> starCatalogueCpu(const StarSettings& settings) {
  validateStarSettings(settings);
  std::vector<gpu::StarRecord> catalogue(settings.count);
  stars::StarKernel kernel;
  for (uint32_t i = 0; i < settings.count; ++i)
    catalogue[i] = kernel.starGenerate(i, settings.seed, settings.faintestMagnitude);
  return catalogue;
}

}  // namespace planet

#include "reference/sunlight.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace planet {

Sunlight sunlightAtDistance(double distanceM) {
  if (!(std::isfinite(distanceM) && distanceM > 0.0))
    throw Error(fmt::format("distance from the sun must be a number > 0 m, got {}", distanceM));
  Sunlight sun;
  if (distanceM == kAstronomicalUnitM) return sun;  // the presets' values, not a rounding of them
  const double ratio = kAstronomicalUnitM / distanceM;
  sun.irradianceScale = ratio * ratio;
  const double sine = std::min(std::sin(kSunAngularRadiusRad) * ratio, std::sin(kMaxSunAngularRadiusRad));
  sun.angularRadiusRad = std::asin(sine);
  return sun;
}

}  // namespace planet

// Sunlight by distance from the sun (issue 23, point 3). A planet preset is lit as if it were
// 1 au from the sun: irradiance gpu::kSunIrradiance and a disc of kSunAngularRadiusRad. In a
// scene, where the sun sits at the origin, a body at distance d gets the irradiance of the
// inverse-square law, E = E(1 au) · (1 au / d)², and sees a disc of angular radius
// asin(sin(θ(1 au)) · 1 au / d), the disc of a sphere of fixed radius seen from d. The disc's
// radiance, E / (π θ²) in the small-angle limit, is then the same at every distance, as a
// surface's radiance is.
#pragma once

#include "planet/scene_description.h"
#include "reference/atmosphere_model.h"

namespace planet {

// Near the sun the disc would fill the sky; the shaders' disc and penumbra terms assume a small
// one. Reached within 0.030 au of the sun (the sun's photosphere, which no orbit may enter,
// is at 0.0047 au).
inline constexpr double kMaxSunAngularRadiusRad = 0.25;

struct Sunlight {
  double irradianceScale = 1.0;                    // of gpu::kSunIrradiance: (1 au / d)²
  double angularRadiusRad = kSunAngularRadiusRad;  // of the disc, at most kMaxSunAngularRadiusRad
};

// The sunlight at distanceM from the sun's centre; exactly the presets' values at
// kAstronomicalUnitM. Throws planet::Error for a distance that is not a finite number > 0.
Sunlight sunlightAtDistance(double distanceM);

}  // namespace planet

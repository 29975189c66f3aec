// Eclipses (issue 23, point 1): shaders/common/eclipse.glsl compiled as C++ (the reference the
// tests hold the shaders' function against, and in double for scene geometry), and the per-frame
// occluder block the passes upload. The model is described at the top of eclipse.glsl.
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "planet/scene_description.h"
#include "shared/eclipse_params.h"

namespace planet {

// A sphere that may hide the sun: its centre relative to the camera, in the receiving body's
// frame (metres), its radius, and the sunlight its air bends into its shadow
// (refractedIntoShadow).
struct Occluder {
  glm::dvec3 centreM{0.0};
  double radiusM = 0.0;
  glm::dvec3 refracted{0.0};
};

// The share of the sun's irradiance (per channel) that a body's air bends into its shadow, per
// share of the sun the body covers: 0 without air. A crude model, not a ray trace: sunlight
// passing the limb within one Rayleigh scale height H of the ground is bent by about the angle
// that carries it into the umbra (on Earth twice the horizontal refraction, ~1.2 degrees), and
// that ring, of area 2πR·H, spreads what the air lets through along the tangent path,
// T(H, horizontal)², over the shadow's cross-section πR²: 2H/R · T². Earth's: ~(6, 0.7, 0.03)·10⁻⁴,
// red, as the Moon in Earth's umbra is (some 10⁻⁴ of its full brightness).
glm::dvec3 refractedIntoShadow(const PlanetDescription& planet);

// The block the shaders read: each occluder's centre turned into the pass's frame by `toFrame`
// (body frame → the pass's frame), and the sun's angular radius. Throws planet::Error for more
// than gpu::kEclipseMaxOccluders occluders or a radius that is not a finite number >= 0.
gpu::EclipseParams eclipseGpuParams(std::span<const Occluder> occluders, const glm::dmat3& toFrame,
                                    double sunAngularRadiusRad);

// eclipse.glsl's functions in float, exactly as the shaders evaluate them.
float sunDiscCoveredCpu(float k, float s);
float occluderSunVisibleCpu(const glm::vec3& toOccluder, float radius, const glm::vec3& sun, float sunRadius);
float eclipseSunVisibleCpu(const glm::vec3& fromCamera, const glm::vec3& sun, const gpu::EclipseParams& eclipse);
float eclipseSunVisibleRefractedCpu(const glm::vec3& fromCamera, const glm::vec3& sun,
                                    const gpu::EclipseParams& eclipse, glm::vec3& refracted);

// The same functions in double.
double sunDiscCovered(double k, double s);
double occluderSunVisible(const glm::dvec3& toOccluder, double radius, const glm::dvec3& sun, double sunRadius);

// The share of the sun's disc seen from a scene-frame point on or above body `receiver`, past
// every other body of the scene at `states` (sceneStateAt), with the sun at the origin and its
// disc as large as reference/sunlight.h makes it at the point's distance. In double.
double sceneSunVisible(const SceneDescription& scene, const std::vector<BodyState>& states, size_t receiver,
                       const glm::dvec3& pointSceneM);

}  // namespace planet

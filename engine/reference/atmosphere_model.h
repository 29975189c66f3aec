// The atmosphere on the CPU (issue 4, point 2): the coefficients the shaders get, and the CPU
// reference of shaders/common/atmosphere.glsl (the same source compiled as C++, in double),
// used to check the GPU's transmittance and multiple-scattering tables, to integrate the sky's
// irradiance, and by `planet sky`.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "planet/planet_description.h"
#include "shared/sky_params.h"

namespace planet {

// The sun's angular radius as drawn (the real sun's 0.267° is under 3 pixels in a 60° view;
// this is a little larger so that it reads as a disc).
inline constexpr double kSunAngularRadiusRad = 0.0075;

// The description's atmosphere as the shaders read it (zero coefficients when it has none,
// so that every transmittance is 1).
gpu::AtmosphereParams makeAtmosphereParams(const PlanetDescription& planet);
// The preset's airglow (all 0 without one), for the compose's uniforms and airglowAlong.
gpu::AirglowParams makeAirglowParams(const PlanetDescription& planet);
// The airglow along a ray from altitude h (zenith cosine mu) up to distance tEnd, in double
// (common/atmosphere.glsl, airglowAlong): the part in front of the air seen from above the
// shell, and the rest, which the air along the ray dims.
struct AirglowLight {
  glm::dvec3 nearLight{0.0};
  glm::dvec3 farLight{0.0};
};
AirglowLight airglowAlong(const gpu::AirglowParams& airglow, double radiusM, double altitudeM, double mu, double tEndM);

// Transmittance from altitude h (m above the radius) along zenith cosine mu to the top of the
// atmosphere, by `steps` midpoint steps in double; the planet is not an obstacle here.
glm::dvec3 transmittanceToTop(const gpu::AtmosphereParams& atmosphere, double altitudeM, double mu,
                              uint32_t steps = 4096);

// A row-major table of width × height texels read as the GPU's linear sampler with clamp-to-edge
// reads it: (u, v) in [0, 1], texel centres at (i + 0.5) / size.
glm::dvec3 sampleBilinear(const std::vector<glm::dvec3>& table, uint32_t width, uint32_t height, double u, double v);

// Transmittance from altitude h along zenith cosine mu over the first `distanceM` metres of the
// ray, by `steps` midpoint steps in double; past the ground the air keeps its density there.
glm::dvec3 transmittanceAlong(const gpu::AtmosphereParams& atmosphere, double altitudeM, double mu, double distanceM,
                              uint32_t steps = 4096);

// The unit coordinates (x by distance, y by zenith cosine) of the camera's transmittance table
// (shaders/common/atmosphere.glsl, cameraTransmittanceUnit) for distance t along a ray of zenith
// cosine mu, a ground horizon of zenith cosine muHorizon and a table out to farthestM.
glm::dvec2 cameraTransmittanceUnit(double mu, double distanceM, double muHorizon, double farthestM);

// The altitude (x) and zenith cosine (y) that transmittance-table coordinates (u, v) in [0, 1]
// stand for (the table's parameterisation, shaders/common/atmosphere.glsl).
glm::dvec2 transmittanceTexelAltitudeMu(const gpu::AtmosphereParams& atmosphere, double u, double v);

// Single-scattered sky radiance (per the params' sun irradiance) seen from altitude h looking
// along zenith cosine mu, with the sun at zenith cosine muS and view-sun cosine nu, over the
// whole ray (to the top of the atmosphere, or to the ground where the ray meets it).
// With a multiple-scattering table, `total` adds the light scattered two or more times along the
// same samples (σ_s · Ψ_ms from the table); without one it is the single-scattered radiance.
struct MultipleScatteringTable;
struct SkySample {
  glm::dvec3 radiance;       // single scattering
  glm::dvec3 transmittance;  // along the ray, to where it leaves the atmosphere or meets the ground
  glm::dvec3 total;          // single and multiple scattering
};
SkySample skyRadiance(const gpu::AtmosphereParams& atmosphere, double altitudeM, double mu, double muS, double nu,
                      uint32_t steps = 256, uint32_t sunSteps = 256,
                      const MultipleScatteringTable* multipleScattering = nullptr);

// The multiple-scattering table (Hillaire 2020, §5.5; shaders/common/atmosphere.glsl) in double:
// Ψ_ms and f_ms at every texel of the GPU's table (kMultiScatteringSize², row-major, rows of
// altitude, columns of sun zenith cosine). The sun's transmittance comes from a double
// transmittance table of the GPU's size and steps, read as the GPU reads its own (bilinear, the
// planet's shadow softened over the sun's disc), so that the GPU table can be compared with it.
struct MultipleScatteringTable {
  std::vector<glm::dvec3> psi;       // Ψ_ms: radiance per steradian per unit sun irradiance
  std::vector<glm::dvec3> transfer;  // f_ms: the share of isotropic light one more scattering returns
  // The double transmittance table it was built with (the GPU's size and steps; empty without air).
  std::vector<glm::dvec3> transmittance;
  // Ψ_ms at altitude h for a sun at zenith cosine muS, bilinear between texel centres (clamped
  // at the edges) as the GPU's sampler reads the table.
  glm::dvec3 sample(const gpu::AtmosphereParams& atmosphere, double altitudeM, double muS) const;
};
MultipleScatteringTable multipleScatteringTable(const gpu::AtmosphereParams& atmosphere);

// The altitude (x) and sun zenith cosine (y) that multiple-scattering table coordinates (u, v)
// in [0, 1] stand for.
glm::dvec2 multipleScatteringTexelAltitudeMuS(const gpu::AtmosphereParams& atmosphere, double u, double v);

// Ψ_ms and f_ms at one point with the sun's transmittance integrated directly (`sunSteps`
// midpoint steps, the planet's shadow sharp): a check of the table's way of getting it.
struct MultipleScatteringPoint {
  glm::dvec3 psi;
  glm::dvec3 transfer;
};
MultipleScatteringPoint multipleScatteringAt(const gpu::AtmosphereParams& atmosphere, double altitudeM, double muS,
                                             uint32_t sunSteps = 512);

// The sky-view table (Hillaire 2020, §5.3; shaders/sky_view.comp) in double, for a viewpoint at
// altitude h over the ground sphere at hGround and a sun at zenith cosine muS: kSkyViewWidth ×
// kSkyViewHeight texels, row-major, each the total sky radiance along its direction (the GPU's
// steps, the sun's transmittance and Ψ_ms read from `multipleScattering`'s double tables as the
// GPU reads its own).
std::vector<glm::dvec3> skyViewTable(const gpu::AtmosphereParams& atmosphere, double altitudeM, double groundM,
                                     double muS, const MultipleScatteringTable& multipleScattering);

// Irradiance from the sky on a horizontal surface at the ground, for the sun at zenith
// cosine muS: the hemisphere integral of skyRadiance · cos θ (no ground bounce).
glm::dvec3 skyIrradiance(const gpu::AtmosphereParams& atmosphere, double muS);

// skyIrradiance at kSkyIrradianceSamples sun cosines from -0.2 to 1 (the terrain's ambient
// light interpolates them by each point's own sun elevation).
inline constexpr int kSkyIrradianceSamples = 16;
inline constexpr double kSkyIrradianceMinMuS = -0.2;
std::array<glm::vec4, kSkyIrradianceSamples> skyIrradianceTable(const gpu::AtmosphereParams& atmosphere);

}  // namespace planet

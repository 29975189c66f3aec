// Rings in the haze (issue 23, point 4): the ringed giant with its air (giant.toml
// [atmosphere]) on lavapipe, at 160–200 pixels a side. A ring in front of the disc keeps its
// colour when the giant gets its air; a ring seen through the limb is dimmed by exactly the
// transmittance of the grazing path (the CPU reference's); the limb's haze falls off with the
// air's scale height, and the sky-view table draws it as the reference march does. Writes the
// views to the test output folder (tonemapped PNGs) for looking at.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image_file.h"
#include "gpu_fixture.h"
#include "planet/scene_description.h"
#include "planet/terrain_height.h"
#include "reference/atmosphere_model.h"
#include "reference/ring_density.h"
#include "render/renderer.h"

namespace planet::test {
namespace {

using RingHaze = GpuTest;

// The giant of the built-in system at 1 au, its rings as there (system.toml).
const char* kGiantScene = R"([scene]
name = "ringed giant"
[[body]]
name = "G"
preset = "giant"
[body.orbit]
semi_major_axis_m = 1.496e11
period_s = 1e12
mean_anomaly_deg = 90
[body.spin]
tilt_deg = 26.7
[body.rings]
inner_radius_m = 7.45e7
outer_radius_m = 1.368e8
seed = 7
colour = [0.62, 0.53, 0.40]
colour_variation = [0.40, 0.36, 0.32]
octaves = 10
gaps = 2
)";

double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// A camera in the giant's body frame, and the pixels' rays in that frame.
struct GiantCamera {
  glm::dvec3 eye{0.0};
  glm::dvec3 forward{0.0, 0.0, -1.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  RenderSettings settings;

  glm::dvec3 ray(uint32_t x, uint32_t y) const {
    const glm::dvec3 right = glm::cross(forward, up);
    const double tanHalf = std::tan(0.5 * settings.fovYDeg * std::numbers::pi / 180.0);
    const double aspect = double(settings.width) / double(settings.height);
    const double ndcX = (x + 0.5) / settings.width * 2.0 - 1.0;
    const double ndcY = 1.0 - (y + 0.5) / settings.height * 2.0;
    return glm::normalize(forward + ndcX * tanHalf * aspect * right + ndcY * tanHalf * up);
  }
};

GiantCamera lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& upHint, uint32_t width,
                   uint32_t height, double fovYDeg) {
  GiantCamera camera;
  camera.eye = eye;
  camera.forward = glm::normalize(target - eye);
  camera.up = glm::normalize(upHint - glm::dot(upHint, camera.forward) * camera.forward);
  camera.settings.width = width;
  camera.settings.height = height;
  camera.settings.fovYDeg = fovYDeg;
  return camera;
}

struct Scene {
  SceneDescription description = parseSceneDescription(kGiantScene, "ring-haze.toml");
  std::vector<BodyState> states = sceneStateAt(description, 0.0);
  glm::dmat3 toBody = glm::transpose(states[0].bodyToScene);
  glm::dvec3 sunBody = glm::normalize(toBody * -states[0].positionM);  // the sun at the scene's origin
  double radius = description.bodies[0].planet.radiusM;
};

// The HDR frame of the giant with or without its air and its rings.
// `hazeScale` multiplies the haze's scattering and absorption.
std::vector<glm::vec4> renderGiant(vk::Context& context, const Scene& scene, const GiantCamera& camera, bool air,
                                   bool rings, SkyMode mode = SkyMode::Tables, const char* picture = nullptr,
                                   double hazeScale = 1.0) {
  SceneDescription description = scene.description;
  AtmosphereDescription& atmosphere = description.bodies[0].planet.atmosphere;
  atmosphere.enabled = air;
  atmosphere.mieScattering *= hazeScale;
  atmosphere.mieAbsorption *= hazeScale;
  if (!rings) description.bodies[0].rings.reset();
  RenderSettings settings = camera.settings;
  settings.sky.mode = mode;
  Renderer renderer(context, description, settings);
  SceneView view;
  view.camera.position = scene.states[0].positionM + scene.states[0].bodyToScene * camera.eye;
  view.camera.forward = scene.states[0].bodyToScene * camera.forward;
  view.camera.up = scene.states[0].bodyToScene * camera.up;
  view.bodies = sceneBodyViews(scene.states);
  RenderResult result = renderer.renderScene(view, true);
  if (picture) writePng((testOutputDir() / picture).string(), result.image);
  return std::move(result.hdr);
}

glm::dvec3 at(const std::vector<glm::vec4>& hdr, const GiantCamera& camera, uint32_t x, uint32_t y) {
  const glm::vec4& texel = hdr[size_t(y) * camera.settings.width + x];
  return {texel.r, texel.g, texel.b};
}

// Where a ray from the eye meets the ring plane (distance, radius), or distance -1.
glm::dvec2 ringHit(const glm::dvec3& eye, const glm::dvec3& dir) {
  if (dir.z == 0.0) return {-1.0, 0.0};
  const double t = -eye.z / dir.z;
  if (t <= 0.0) return {-1.0, 0.0};
  const glm::dvec3 p = eye + t * dir;
  return {t, std::hypot(p.x, p.y)};
}

// The ray's closest approach to the giant's centre: distance along the ray and altitude above
// the radius sphere (negative: the ray meets the sphere).
glm::dvec2 closestApproach(const glm::dvec3& eye, const glm::dvec3& dir, double radius) {
  const double t = -glm::dot(eye, dir);
  return {t, glm::length(eye + t * dir) - radius};
}

// From 20 degrees below the ring plane (the sun is 27 degrees above it) on the sun's side: the
// near half of the rings, seen from their unlit face, crosses the northern half of the disc,
// where the rings cast no shadow (the disc behind them is the disc without them), with the
// giant's haze made 100 times thicker (optical depth ~7: the disc turns to haze).
// Drawn after the giant's compose pass, a ring over the disc is the ring over the hazed disc,
// P = ring + (1 − α) D, so the air changes the pixel by (1 − α) times its change to the disc
// alone: P_air − P_bare = (1 − α) (D_air − D_bare), with α the ring's opacity there (the CPU
// reference's, at the pixel's footprint). The old order (the rings drawn before the compose pass)
// hazed the ring as the disc behind it, P = T · P_bare + L, and lost most of its light. The
// tolerance, 8 % of the disc's change plus 3 % of the pixel, covers the reference's opacity at a
// footprint estimated from the neighbouring pixels (the shader's fwidth) and half floats.
TEST_F(RingHaze, ARingInFrontOfTheDiscIsNotHazedByTheAirBehindIt) {
  const Scene scene;
  const glm::dvec3 sunFlat = glm::normalize(glm::dvec3(scene.sunBody.x, scene.sunBody.y, 0.0));
  const double elevation = -20.0 * std::numbers::pi / 180.0;
  const glm::dvec3 eye = 3.0e8 * (std::cos(elevation) * sunFlat + std::sin(elevation) * glm::dvec3(0.0, 0.0, 1.0));
  const GiantCamera camera = lookAt(eye, glm::dvec3(0.0), {0.0, 0.0, 1.0}, 200, 120, 36.0);
  const double thick = 100.0;
  const std::vector<glm::vec4> airRings =
      renderGiant(context(), scene, camera, true, true, SkyMode::Tables, "ring_haze_front.png", thick);
  const std::vector<glm::vec4> bareRings = renderGiant(context(), scene, camera, false, true);
  const std::vector<glm::vec4> airDisc =
      renderGiant(context(), scene, camera, true, false, SkyMode::Tables, nullptr, thick);
  const std::vector<glm::vec4> bareDisc = renderGiant(context(), scene, camera, false, false);

  const gpu::RingParams ring = ringGpuParams(*scene.description.bodies[0].rings, scene.radius, kSunAngularRadiusRad);
  auto coordinate = [&](uint32_t x, uint32_t y) {
    const glm::dvec2 hit = ringHit(eye, camera.ray(x, y));
    return hit.x > 0.0 ? ringCoordinateCpu(ring, hit.y) : -1.0;
  };
  int checked = 0, failed = 0, inFront = 0, inside = 0;
  double maxAlpha = 0.0;
  double worst = 0.0;
  double airChange = 0.0;
  for (uint32_t y = 1; y + 1 < camera.settings.height; ++y)
    for (uint32_t x = 1; x + 1 < camera.settings.width; ++x) {
      const glm::dvec3 dir = camera.ray(x, y);
      const glm::dvec2 hit = ringHit(eye, dir);
      const glm::dvec2 closest = closestApproach(eye, dir, scene.radius);
      // In front of the disc, clear of its edge (the terrain's few km and the limb's air).
      if (hit.x <= 0.0 || closest.y > -2.0e6 || hit.x > closest.x) continue;
      ++inFront;
      const double u = coordinate(x, y);
      if (!(u > 0.02 && u < 0.98)) continue;
      ++inside;
      const double footprint = std::abs(coordinate(x + 1, y) - coordinate(x - 1, y)) / 2.0 +
                               std::abs(coordinate(x, y + 1) - coordinate(x, y - 1)) / 2.0;
      const float alpha =
          ringSlantOpacityCpu(ringOpacityCpu(ring, float(u), float(std::min(footprint, 1.0))), float(std::abs(dir.z)));
      maxAlpha = std::max(maxAlpha, double(alpha));
      if (alpha < 0.3f) continue;
      const glm::dvec3 withAir = at(airRings, camera, x, y), without = at(bareRings, camera, x, y);
      const glm::dvec3 bareDiscColour = at(bareDisc, camera, x, y);
      const glm::dvec3 discChange = at(airDisc, camera, x, y) - bareDiscColour;
      // Each channel (the haze changes the disc's colour more than its luminance).
      bool off = false;
      for (int c = 0; c < 3; ++c) {
        const double allowed = 0.08 * std::abs(discChange[c]) + 0.03 * without[c];
        const double difference = std::abs(withAir[c] - without[c] - (1.0 - alpha) * discChange[c]);
        off = off || difference > allowed;
        worst = std::max(worst, difference / std::max(without[c], 1e-6));
      }
      airChange += std::max({std::abs(discChange.x) / std::max(bareDiscColour.x, 1e-6),
                             std::abs(discChange.y) / std::max(bareDiscColour.y, 1e-6),
                             std::abs(discChange.z) / std::max(bareDiscColour.z, 1e-6)});
      ++checked;
      failed += off ? 1 : 0;
    }
  ASSERT_GT(checked, 200) << "the view should put dense ring in front of the disc (" << inFront
                          << " ring pixels in front, " << inside << " inside the annulus, densest " << maxAlpha << ")";
  // The air must matter on the disc itself, or the comparison shows nothing (the largest
  // relative change of a channel, averaged).
  EXPECT_GT(airChange / checked, 0.3) << "the air should change the disc behind the ring";
  EXPECT_LE(failed, checked / 20) << failed << " of " << checked
                                  << " ring pixels in front of the disc off ring + (1 - alpha) disc (worst by "
                                  << worst * 100.0 << " % of the pixel)";
}

// Seen past the limb, the ring behind the giant shows through its air as through a filter: the
// ring's share of a pixel (the frame with the ring less the frame without it) with air is the
// share without air times the transmittance of the grazing path, which the CPU reference gives
// in closed form: T(h)² with T(h) the transmittance from the tangent point at altitude h to the
// top along the horizontal (transmittanceToTop). That holds exactly when the ring's own haze
// (ring_air.frag) matches the compose pass's sky behind it; the tables and the ring's march
// agree to a few per cent of the limb's light, hence the tolerance of 0.06 in transmittance.
// Deep in the limb the ring vanishes (T < 0.05), above the top of the air it is untouched.
TEST_F(RingHaze, ARingBehindTheLimbIsDimmedByTheGrazingPathsTransmittance) {
  const Scene scene;
  // The camera 3e8 m away at 90 degrees from the sun's azimuth (the ring behind the limb is
  // lit), raised until its ray to the ring point at radius 1.05e8 m on the far side grazes the
  // sphere at 300 km: the middle of the picture.
  const glm::dvec3 sunFlat = glm::normalize(glm::dvec3(scene.sunBody.x, scene.sunBody.y, 0.0));
  const glm::dvec3 side = glm::cross(glm::dvec3(0.0, 0.0, 1.0), sunFlat);
  const glm::dvec3 target = -1.05e8 * side;
  auto eyeAt = [&](double elevation) {
    return 3.0e8 * (std::cos(elevation) * side + std::sin(elevation) * glm::dvec3(0.0, 0.0, 1.0));
  };
  double low = 0.0, high = 0.5 * std::numbers::pi;
  for (int i = 0; i < 60; ++i) {
    const double middle = 0.5 * (low + high);
    const glm::dvec3 eye = eyeAt(middle);
    const double altitude = closestApproach(eye, glm::normalize(target - eye), scene.radius).y;
    (altitude < 3.0e5 ? low : high) = middle;
  }
  const glm::dvec3 eye = eyeAt(0.5 * (low + high));
  const GiantCamera camera = lookAt(eye, target, {0.0, 0.0, 1.0}, 160, 160, 0.6);
  const std::vector<glm::vec4> airRings =
      renderGiant(context(), scene, camera, true, true, SkyMode::Tables, "ring_haze_limb.png");
  const std::vector<glm::vec4> airSky = renderGiant(context(), scene, camera, true, false);
  const std::vector<glm::vec4> bareRings = renderGiant(context(), scene, camera, false, true);
  const std::vector<glm::vec4> bareSky = renderGiant(context(), scene, camera, false, false);

  const gpu::AtmosphereParams air = makeAtmosphereParams(scene.description.bodies[0].planet);
  int checked = 0, failed = 0, hidden = 0, deep = 0, clear = 0, above = 0;
  double worst = 0.0;
  for (uint32_t y = 0; y < camera.settings.height; ++y)
    for (uint32_t x = 0; x < camera.settings.width; ++x) {
      const glm::dvec3 dir = camera.ray(x, y);
      const glm::dvec2 closest = closestApproach(eye, dir, scene.radius);
      const glm::dvec2 hit = ringHit(eye, dir);
      if (closest.y < 2.0e4 || hit.x <= closest.x) continue;  // the disc, or the ring in front
      const double ringWithout = luminance(at(bareRings, camera, x, y) - at(bareSky, camera, x, y));
      if (ringWithout < 0.02 * luminance(at(bareRings, camera, x, y)) + 1e-4) continue;  // a gap
      const double ringWith = luminance(at(airRings, camera, x, y) - at(airSky, camera, x, y));
      const glm::dvec3 t = transmittanceToTop(air, closest.y, 0.0);
      const double expected = luminance(t * t);
      const double measured = ringWith / ringWithout;
      worst = std::max(worst, std::abs(measured - expected));
      ++checked;
      failed += std::abs(measured - expected) > 0.06 ? 1 : 0;
      if (expected < 0.05) {
        ++deep;
        hidden += measured < 0.1 ? 1 : 0;
      }
      if (closest.y > air.radii.y) {
        ++above;
        clear += std::abs(measured - 1.0) < 0.02 ? 1 : 0;
      }
    }
  ASSERT_GT(checked, 1000) << "the ring should be seen past the limb";
  EXPECT_LE(failed, checked / 50) << failed << " of " << checked
                                  << " ring pixels past the limb off the grazing transmittance (worst by " << worst
                                  << ")";
  ASSERT_GT(deep, 50);
  ASSERT_GT(above, 50);
  EXPECT_EQ(hidden, deep) << "deep in the limb the ring should vanish into the haze";
  EXPECT_EQ(clear, above) << "above the air the ring should be as without it";
}

// The giant's sunlit limb from 3e8 m, the sun 90 degrees off the view: past the edge of the
// disc the haze's light falls off with the tangent altitude h, and where the grazing path is
// optically thin (τ < 0.15 above ~200 km with giant.toml's air) as the single scattering of a
// thin path predicts: the sum over the gas and the haze of β · phase(90°) · e^(−h/H) · sqrt(2πRH)
// (each layer's density at the lowest point times the length of path it spans). A fit of
// ln L over 200–420 km must give the scale height of that prediction within 15 % (the sky-view
// table's rows are ~20 km apart near the top of the air: linear interpolation of the
// exponential between them errs by ~2 %; the sun's light along the path dims a little). The
// tables' limb must also match the reference march's (`--sky reference`) within 10 % over the
// whole haze (the table's parameterisation at a 5.8e7 m radius and a 500 km shell, from 3e8 m).
TEST_F(RingHaze, TheLimbHazeFallsOffWithTheScaleHeight) {
  const Scene scene;
  // Sun from the side of the view (the limb lit at 90 degrees of phase), the limb point toward it.
  const glm::dvec3 sun = scene.sunBody;
  const glm::dvec3 pole{0.0, 0.0, 1.0};
  const glm::dvec3 across = glm::normalize(glm::cross(pole, sun));
  const glm::dvec3 eye = 3.0e8 * across;
  const glm::dvec3 towardSun = glm::normalize(sun - glm::dot(sun, across) * across);
  const double d = glm::length(eye);
  const glm::dvec3 limb = scene.radius * scene.radius / d * (eye / d) +
                          scene.radius * std::sqrt(1.0 - std::pow(scene.radius / d, 2.0)) * towardSun;
  const GiantCamera camera = lookAt(eye, limb, towardSun, 120, 160, 0.6);
  const std::vector<glm::vec4> tables =
      renderGiant(context(), scene, camera, true, false, SkyMode::Tables, "ring_haze_giant_limb.png");
  const std::vector<glm::vec4> reference = renderGiant(context(), scene, camera, true, false, SkyMode::Reference);

  // Each column crosses the limb; the middle one is the profile.
  const uint32_t x = camera.settings.width / 2;
  std::vector<std::pair<double, double>> profile;  // (tangent altitude, luminance) past the edge
  int compared = 0, mismatched = 0;
  double previous = -1.0;
  int rises = 0;
  for (uint32_t y = 0; y < camera.settings.height; ++y) {
    const glm::dvec2 closest = closestApproach(eye, camera.ray(x, y), scene.radius);
    if (closest.y < 3.0e4 || closest.y > 4.8e5) continue;
    const double light = luminance(at(tables, camera, x, y));
    const double marched = luminance(at(reference, camera, x, y));
    ++compared;
    mismatched += std::abs(light - marched) > 0.1 * marched + 1e-5 ? 1 : 0;
    profile.emplace_back(closest.y, light);
  }
  std::sort(profile.begin(), profile.end());
  for (const auto& [altitude, light] : profile) {
    if (altitude > 2.5e5 && previous >= 0.0 && light > previous * 1.02) ++rises;
    if (altitude > 2.5e5) previous = light;
  }
  // The thin path's light, predicted (luminance of the per-channel sum; the factors common to
  // both layers left out).
  const AtmosphereDescription& air = scene.description.bodies[0].planet.atmosphere;
  const double rayleighPhase = 3.0 / (16.0 * std::numbers::pi);
  const double g = air.mieG.y;
  const double miePhase = 3.0 / (8.0 * std::numbers::pi) * (1.0 - g * g) / (2.0 + g * g) / std::pow(1.0 + g * g, 1.5);
  auto predicted = [&](double h) {
    const glm::dvec3 gas = air.rayleighScattering * rayleighPhase * std::exp(-h / air.rayleighScaleHeightM) *
                           std::sqrt(air.rayleighScaleHeightM);
    const glm::dvec3 haze =
        air.mieScattering * miePhase * std::exp(-h / air.mieScaleHeightM) * std::sqrt(air.mieScaleHeightM);
    return luminance(gas + haze);
  };
  // Least squares of ln L against h over the thin part: the measured profile and the prediction.
  auto fitScaleHeight = [&](auto light) {
    double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (const auto& sample : profile) {
      const double h = sample.first, l = light(sample);
      if (h < 2.0e5 || h > 4.2e5 || !(l > 0.0)) continue;
      n += 1.0;
      sx += h;
      sy += std::log(l);
      sxx += h * h;
      sxy += h * std::log(l);
    }
    EXPECT_GE(n, 8.0) << "the profile should sample the thin haze";
    return -(n * sxx - sx * sx) / (n * sxy - sx * sy);
  };
  const double measured = fitScaleHeight([](const std::pair<double, double>& s) { return s.second; });
  const double expected = fitScaleHeight([&](const std::pair<double, double>& s) { return predicted(s.first); });
  EXPECT_NEAR(measured, expected, 0.15 * expected) << "the limb's haze should fall off as the air's density";
  EXPECT_EQ(rises, 0) << "above 250 km the haze should only fade outward";
  EXPECT_LE(mismatched, compared / 20) << mismatched << " of " << compared
                                       << " limb pixels differ from the reference march by more than 10 %";
}

// The built-in system from 10 km above Terra's ground (its air, no clouds), the giant and its
// rings in the afternoon sky (as system_5_terra_ground). Terra's atmosphere is nearer than the rings and is composed
// after them: they write depth, so Terra's compose pass sees them as geometry past its air and puts the air in front of
// them, the same light as the sky around plus the transmittance of the ray. The rings' share of a pixel (the frame with
// them less the frame without) is then the share without Terra's air times that transmittance (the CPU reference's,
// from 10 km along the ray to the top). Before, the rings were faded out with the stars behind a bright sky. The median
// over the ring's pixels must be within 0.05 of the reference (stars behind a thin part of the ring are not faded with
// it, and a ring pixel's own edges blend with the sky).
TEST_F(RingHaze, RingsInADaytimeSkyAreSeenThroughItsAir) {
  SceneDescription system = resolveScene("system");
  system.bodies.pop_back();  // the Moon, out of the picture (one body less to build)
  const size_t giant = 0, terra = 1;
  // Terra's radius and air over the giant preset's two smooth layers (heights within ±5 km):
  // the ground is not what this looks at, and earth's terrain shaders take most of a minute
  // to build four times on lavapipe.
  {
    PlanetDescription plain = system.bodies[giant].planet;
    const PlanetDescription& earth = system.bodies[terra].planet;
    plain.name = "Terra";
    plain.radiusM = earth.radiusM;
    plain.atmosphere = earth.atmosphere;
    plain.stars = earth.stars;
    system.bodies[terra].planet = plain;
  }
  const double timeS = 66500.0;
  const std::vector<BodyState> states = sceneStateAt(system, timeS);
  const PlanetDescription& world = system.bodies[terra].planet;
  const glm::dvec3 upTerra = directionFromLatLon(5.0, 172.0);
  const double altitude = 1.0e4;
  SceneView view;
  view.camera.position = states[terra].positionM + states[terra].bodyToScene * (upTerra * (world.radiusM + altitude));
  view.camera.forward = glm::normalize(states[giant].positionM - view.camera.position);
  const glm::dvec3 up = states[terra].bodyToScene * upTerra;
  view.camera.up = glm::normalize(up - glm::dot(up, view.camera.forward) * view.camera.forward);
  view.bodies = sceneBodyViews(states);
  view.timeS = timeS;
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.fovYDeg = 20.0;
  settings.terrain.patches = false;  // the ground is not what this looks at
  auto render = [&](bool air, bool rings, const char* picture = nullptr) {
    SceneDescription scene = system;
    scene.bodies[terra].planet.atmosphere.enabled = air;
    if (!rings) scene.bodies[giant].rings.reset();
    Renderer renderer(context(), scene, settings);
    RenderResult result = renderer.renderScene(view, true);
    if (picture) writePng((testOutputDir() / picture).string(), result.image);
    return std::move(result.hdr);
  };
  const std::vector<glm::vec4> airRings = render(true, true, "ring_haze_terra_sky.png");
  const std::vector<glm::vec4> airSky = render(true, false);
  const std::vector<glm::vec4> bareRings = render(false, true);
  const std::vector<glm::vec4> bareSky = render(false, false);

  const glm::dmat3 toGiant = glm::transpose(states[giant].bodyToScene);
  const glm::dvec3 eye = toGiant * (view.camera.position - states[giant].positionM);
  const double giantRadius = system.bodies[giant].planet.radiusM;
  const gpu::RingParams ring = ringGpuParams(*system.bodies[giant].rings, giantRadius, kSunAngularRadiusRad);
  const gpu::AtmosphereParams air = makeAtmosphereParams(world);
  const glm::dvec3 right = glm::cross(view.camera.forward, view.camera.up);
  const double tanHalf = std::tan(0.5 * settings.fovYDeg * std::numbers::pi / 180.0);
  std::vector<double> offsets;
  auto pixel = [&](const std::vector<glm::vec4>& hdr, uint32_t x, uint32_t y) {
    const glm::vec4& t = hdr[size_t(y) * settings.width + x];
    return glm::dvec3(t.r, t.g, t.b);
  };
  for (uint32_t y = 0; y < settings.height; ++y)
    for (uint32_t x = 0; x < settings.width; ++x) {
      const double ndcX = (x + 0.5) / settings.width * 2.0 - 1.0, ndcY = 1.0 - (y + 0.5) / settings.height * 2.0;
      const glm::dvec3 dir =
          glm::normalize(view.camera.forward + ndcX * tanHalf * settings.width / settings.height * right +
                         ndcY * tanHalf * view.camera.up);
      const glm::dvec3 dirGiant = toGiant * dir;
      const glm::dvec2 hit = ringHit(eye, dirGiant);
      if (hit.x <= 0.0) continue;
      const glm::dvec2 closest = closestApproach(eye, dirGiant, giantRadius);
      if (closest.y < 1.0e6 && hit.x > closest.x) continue;  // behind the giant or its limb
      const double u = ringCoordinateCpu(ring, hit.y);
      if (!(u > 0.05 && u < 0.95)) continue;
      if (ringSlantOpacityCpu(ringOpacityCpu(ring, float(u), 0.01f), float(std::abs(dirGiant.z))) < 0.3f) continue;
      const double without = luminance(pixel(bareRings, x, y) - pixel(bareSky, x, y));
      if (!(without > 0.0)) continue;
      const double with = luminance(pixel(airRings, x, y) - pixel(airSky, x, y));
      const glm::dvec3 t = transmittanceToTop(air, altitude, glm::dot(dir, up));
      offsets.push_back(with / without - luminance(t));
    }
  ASSERT_GT(offsets.size(), 100u) << "the rings should fill part of the view";
  std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
  EXPECT_NEAR(offsets[offsets.size() / 2], 0.0, 0.05)
      << "the rings' light through Terra's air should be their light times its transmittance";
}

}  // namespace
}  // namespace planet::test

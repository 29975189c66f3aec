// Scenes of several bodies on lavapipe (issue 8, points 1-3 and 6): camera-relative rendering
// far from the origin, bodies hiding each other through one depth buffer, a far body's
// atmosphere composed without a second sun, and the built-in system's picture.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image_file.h"
#include "gpu_fixture.h"
#include "planet/scene_description.h"
#include "reference/atmosphere_model.h"
#include "render/renderer.h"
#include "reference/ring_density.h"
#include "reference/sunlight.h"

namespace planet::test {
namespace {

using SceneRender = GpuTest;

RenderSettings smallSettings() {
  RenderSettings settings;
  settings.width = 320;
  settings.height = 180;
  return settings;
}

glm::dvec3 pixel(const Rgba8Image& image, uint32_t x, uint32_t y) {
  const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
  return {double(p[0]), double(p[1]), double(p[2])};
}

// A scene from TOML text (the presets are the built-in ones).
SceneDescription sceneFrom(const std::string& text) { return parseSceneDescription(text, "test-scene.toml"); }

// The camera at `local` in body `body`'s frame, at time t, as the scene sees it.
SceneView viewFrom(const SceneDescription& scene, double timeS, size_t body, const CameraBasis& local) {
  const std::vector<BodyState> states = sceneStateAt(scene, timeS);
  SceneView view;
  const BodyState& on = states[body];
  view.camera = cameraToScene(on.positionM, on.bodyToScene, local);
  view.bodies = sceneBodyViews(states);
  view.timeS = timeS;
  return view;
}

std::string moonAt(double semiMajorAxisM) {
  return "[scene]\nname = \"far\"\n[[body]]\nname = \"M\"\npreset = \"moon\"\n[body.orbit]\nsemi_major_axis_m = " +
         std::to_string(semiMajorAxisM) + "\nperiod_s = 1e9\nmean_anomaly_deg = 30\n[body.spin]\ntilt_deg = 10\n";
}

// The same body, camera and sun, once 1e9 m and once 1.5e11 m (1 au) from the scene's origin:
// positions reach the GPU relative to the camera, so the pictures agree to rounding. A float
// position at 1 au would be off by ~8 km, and the ground would jitter by whole pixels. The near
// body's sun is (1.5e11 / 1e9)² times brighter (reference/sunlight.h): its sun intensity is
// turned down by that factor, so that the two are lit alike.
TEST_F(SceneRender, ABodyFarFromTheOriginLooksAsItDoesNearIt) {
  CameraPose pose;
  pose.latitudeDeg = 20.0;
  pose.longitudeDeg = -30.0;
  pose.altitudeM = 300.0;
  pose.headingDeg = 60.0;
  pose.pitchDeg = -20.0;
  Rgba8Image images[2];
  int i = 0;
  for (double axis : {1.0e9, 1.5e11}) {
    const SceneDescription scene = sceneFrom(moonAt(axis));
    RenderSettings settings = smallSettings();
    settings.terrain.sunIntensity = (axis / 1.5e11) * (axis / 1.5e11);
    Renderer renderer(context(), scene, settings);
    const CameraBasis local = cameraBasis(pose, scene.bodies[0].planet.radiusM);
    images[i++] = renderer.renderScene(viewFrom(scene, 0.0, 0, local)).image;
  }
  // The sun is where it was: the ground is lit, and the two pictures are the same to a level.
  double lit = 0.0;
  int differing = 0, maxDifference = 0;
  for (size_t k = 0; k < images[0].pixels.size(); ++k) {
    const int d = std::abs(int(images[0].pixels[k]) - int(images[1].pixels[k]));
    maxDifference = std::max(maxDifference, d);
    differing += d > 1 ? 1 : 0;
    lit += images[0].pixels[k];
  }
  EXPECT_GT(lit / double(images[0].pixels.size()), 10.0) << "the ground should be sunlit";
  EXPECT_LE(differing, int(images[0].pixels.size() / 1000)) << "max difference " << maxDifference;
  EXPECT_LE(maxDifference, 8);
}

// Sunlight by distance (issue 23, point 3): the same airless moon, camera and sun direction at
// 1 au and at 2 au from the sun. The renderer gives the shaders a quarter of the irradiance and
// half the disc, and the ground (all of the frame, looking down) is a quarter as bright in
// linear HDR: every light on an airless body, the sun and the fill, is proportional to it.
TEST_F(SceneRender, ABodyTwiceAsFarFromTheSunGetsAQuarterOfTheLight) {
  // moonAt's body stands at 30° on its orbit: the sun is overhead near latitude 0, longitude
  // -150 of its frame; here it is about 30° from the zenith.
  CameraPose pose;
  pose.latitudeDeg = 5.0;
  pose.longitudeDeg = -120.0;
  pose.altitudeM = 3000.0;
  pose.pitchDeg = -70.0;  // the top edge 40 degrees below the horizon: ground only
  RenderSettings settings;
  settings.width = 96;
  settings.height = 54;
  double irradiance[2], disc[2], ground[2];
  int k = 0;
  for (double axis : {kAstronomicalUnitM, 2.0 * kAstronomicalUnitM}) {
    const SceneDescription scene = sceneFrom(moonAt(axis));
    Renderer renderer(context(), scene, settings);
    const CameraBasis local = cameraBasis(pose, scene.bodies[0].planet.radiusM);
    const RenderResult result = renderer.renderScene(viewFrom(scene, 0.0, 0, local), true);
    irradiance[k] = result.terrain.sunIrradiance;
    disc[k] = result.terrain.sunAngularRadiusRad;
    double sum = 0.0;
    for (const glm::vec4& texel : result.hdr) sum += double(texel.r) + double(texel.g) + double(texel.b);
    ground[k] = sum / double(result.hdr.size());
    ++k;
  }
  EXPECT_NEAR(irradiance[0], gpu::kSunIrradiance, 1e-6) << "the preset's sun at 1 au";
  EXPECT_NEAR(irradiance[1] / irradiance[0], 0.25, 1e-6);
  EXPECT_NEAR(disc[0], kSunAngularRadiusRad, 1e-9);
  EXPECT_NEAR(disc[1] / disc[0], 0.5, 1e-5);
  ASSERT_GT(ground[0], 0.01) << "the ground should be sunlit";
  // Half-float HDR rounds each value by at most 2^-11 relative; the mean over 5,184 pixels far less.
  EXPECT_NEAR(ground[1] / ground[0], 0.25, 0.25 * 1e-3);
}

// A moon between the camera and a ringed giant, with the sun behind the camera: one depth
// buffer for bodies 2e8 m apart, so the moon covers the middle and the giant's rings show
// around it; the moon is drawn with the giant's near plane choice not cutting it.
TEST_F(SceneRender, ANearerBodyHidesAFartherOneAndTheRingsShowAroundIt) {
  const SceneDescription scene = sceneFrom(R"([scene]
name = "pair"
[[body]]
name = "G"
preset = "giant"
[body.orbit]
semi_major_axis_m = 1e11
period_s = 1e10
[body.spin]
tilt_deg = 30
[body.rings]
inner_radius_m = 7.45e7
outer_radius_m = 1.368e8
[[body]]
name = "M"
preset = "moon"
parent = "G"
[body.orbit]
semi_major_axis_m = 2e8
period_s = 1e8
inclination_deg = 40
ascending_node_deg = 90
mean_anomaly_deg = 90
)");
  ASSERT_TRUE(scene.bodies[0].rings.has_value());
  Renderer renderer(context(), scene, smallSettings());
  const std::vector<BodyState> states = sceneStateAt(scene, 0.0);
  // The moon 2e8 m from the giant, 40 degrees out of the reference plane (the rings open by 34
  // degrees seen along that line); the camera 6e6 m beyond it, the sun 40 degrees off its back.
  const glm::dvec3 toGiant = glm::normalize(states[0].positionM - states[1].positionM);
  SceneView view;
  view.camera.position = states[1].positionM - 6.0e6 * toGiant;
  view.camera.forward = toGiant;
  view.camera.up = glm::dvec3(0.0, 0.0, 1.0);
  view.bodies = sceneBodyViews(states);
  const RenderResult result = renderer.renderScene(view);
  EXPECT_EQ(renderer.primaryBody(), 1u);
  const Rgba8Image& image = result.image;
  // Middle: the moon's sunlit grey (no warm tint of the giant or its rings).
  const glm::dvec3 middle = pixel(image, 160, 90);
  EXPECT_GT(middle.x, 20.0);
  EXPECT_LT(std::abs(middle.x - middle.z), 0.2 * middle.x + 4.0) << middle.x << " " << middle.z;
  // Beyond the moon's limb (16.8 degrees from the middle): the rings' warm light.
  const double pixelsPerRadian = 90.0 / std::tan(0.5 * 60.0 * 3.14159265358979 / 180.0);
  int warm = 0;
  for (int y = 0; y < 180; ++y)
    for (int x = 0; x < 320; ++x) {
      if (std::atan(std::hypot(x - 159.5, y - 89.5) / pixelsPerRadian) < 0.31) continue;
      const glm::dvec3 c = pixel(image, uint32_t(x), uint32_t(y));
      warm += (c.x > 40.0 && c.x > 1.15 * c.z) ? 1 : 0;
    }
  EXPECT_GT(warm, 50) << "the giant's rings should show beside the moon";
}

// The camera on an airless moon looking at the sun with an Earth-like world far behind: the
// far world's atmosphere is composed (its disc shows blue) and the sun's disc is drawn once,
// by the camera's own body: the sun is as bright as it is with an airless world there instead (the moon preset).
TEST_F(SceneRender, AFarAtmosphereIsComposedAndTheSunIsDrawnOnce) {
  auto system = [](const char* world) {
    return sceneFrom(std::string(R"([scene]
name = "sunward"
[[body]]
name = "W"
preset = ")") + world + R"("
gm_m3_s2 = 3.986e14
[body.orbit]
semi_major_axis_m = 1e11
period_s = 1e10
[[body]]
name = "M"
preset = "moon"
parent = "W"
[body.orbit]
semi_major_axis_m = 6e7
period_s = 1e8
mean_anomaly_deg = 180
)");
  };
  double sunPeak[2] = {0.0, 0.0};
  int k = 0;
  for (const char* world : {"earth", "moon"}) {
    const SceneDescription scene = system(world);
    Renderer renderer(context(), scene, smallSettings());
    const std::vector<BodyState> states = sceneStateAt(scene, 0.0);
    SceneView view;
    // 3e6 m from the moon's centre on its sunward side, looking at the sun.
    view.camera.position = states[1].positionM * (1.0 - 3.0e6 / glm::length(states[1].positionM));
    view.camera.forward = glm::normalize(-states[1].positionM);
    view.camera.up = glm::dvec3(0.0, 0.0, 1.0);
    view.bodies = sceneBodyViews(states);
    const RenderResult toSun = renderer.renderScene(view, true);
    for (const glm::vec4& texel : toSun.hdr) sunPeak[k] = std::max(sunPeak[k], double(texel.r));
    if (k == 0) {
      // The world itself, from 2e7 m beyond the moon toward it (the moon behind the camera).
      SceneView back = view;
      back.camera.position = states[1].positionM + 2.0e7 * glm::normalize(states[0].positionM - states[1].positionM);
      back.camera.forward = glm::normalize(states[0].positionM - back.camera.position);
      const Rgba8Image image = renderer.renderScene(back).image;
      int blue = 0;
      for (uint32_t y = 0; y < 180; ++y)
        for (uint32_t x = 0; x < 320; ++x) {
          const glm::dvec3 c = pixel(image, x, y);
          blue += (c.z > 30.0 && c.z > 1.2 * c.x) ? 1 : 0;
        }
      EXPECT_GT(blue, 200) << "the world's sea and sky should show blue";
    }
    ++k;
  }
  ASSERT_GT(sunPeak[1], 100.0) << "the sun's disc should be in the picture";
  EXPECT_NEAR(sunPeak[0] / sunPeak[1], 1.0, 0.02) << "a second compose pass drew the sun again";
}

// How much a body's rings darken its sunlit face: the body alone (`body`, a scene of one body with
// no rings) and with `rings` ([body.rings]), seen from the sun's side 21 degrees south of the
// rings, `eyeRadii` radii from the centre, both without air (the light the air scatters is not
// shadowed by the rings: the sky pass does not know them). `prepare` changes the bodies before they
// are drawn; the shadow falls on the sphere `surfaceM` above the radius. Pixels whose sunward ray
// crosses a dense part of the rings (the CPU reference of terrain.frag's ringShadow says so) give
// `shadowed`, the reference's transmittance there `expected`, pixels in full sun `lit`: each the
// median of the per-pixel ratio with / without. Over all pixels whose sunward ray crosses the rings
// (`crossing`) the mean ratio, and the reference's mean transmittance (`crossingExpected`): a mean
// does not pick the reference's darkest pixels, so it holds where the drawn shadow's fine structure
// lies a pixel off the reference's. Pixels with the rings in front of them are left out, and the
// limb.
struct RingShadowRatios {
  double shadowed = 0.0, expected = 0.0, lit = 0.0, crossing = 0.0, crossingExpected = 0.0;
};
template <class Prepare>
RingShadowRatios ringShadowRatios(vk::Context& context, const std::string& body, const std::string& rings,
                                  double eyeRadii, double surfaceM, Prepare prepare) {
  const SceneDescription scene = sceneFrom(body + rings);
  RenderSettings settings = smallSettings();
  settings.fovYDeg = 30.0;
  const std::vector<BodyState> states = sceneStateAt(scene, 0.0);
  const glm::dmat3 toBody = glm::transpose(states[0].bodyToScene);
  const glm::dvec3 sunBody = toBody * glm::normalize(-states[0].positionM);
  const double radius = scene.bodies[0].planet.radiusM;
  // The rings' shadow on the southern half shows, their near half crosses the northern one.
  const glm::dvec3 eyeBody = eyeRadii * radius * glm::normalize(sunBody - 0.8 * glm::dvec3(0.0, 0.0, 1.0));
  SceneView view;
  view.camera.position = states[0].positionM + states[0].bodyToScene * eyeBody;
  view.camera.forward = glm::normalize(states[0].positionM - view.camera.position);
  const glm::dvec3 pole = states[0].bodyToScene * glm::dvec3(0.0, 0.0, 1.0);
  view.camera.up = glm::normalize(pole - glm::dot(pole, view.camera.forward) * view.camera.forward);
  view.bodies = sceneBodyViews(states);
  // The same view with and without the rings: the body's colours cancel pixel by pixel.
  auto render = [&](const std::string& text) {
    SceneDescription airless = sceneFrom(text);
    airless.bodies[0].planet.atmosphere.enabled = false;
    prepare(airless.bodies[0].planet);
    Renderer renderer(context, airless, settings);
    return renderer.renderScene(view, true).hdr;
  };
  const std::vector<glm::vec4> withRings = render(body + rings), without = render(body);

  // The sun's disc as the body sees it (the renderer's, Renderer::prepareFrame): its size sets the
  // penumbra that blurs the shadow's fine structure. (With Earth's, kSunAngularRadiusRad, 0.0075
  // against 0.0112 here, the reference's shadow was sharper than the drawn one: at Earth's scale
  // the darkest pixels read 0.61 where it said 0.54.)
  const double sunRadiusRad = sunlightAtDistance(glm::length(states[0].positionM)).angularRadiusRad;
  const gpu::RingParams ring = ringGpuParams(*scene.bodies[0].rings, radius, sunRadiusRad);
  const double inner = scene.bodies[0].rings->innerRadiusM, outer = scene.bodies[0].rings->outerRadiusM;
  const glm::dvec3 forward = toBody * view.camera.forward, up = toBody * view.camera.up;
  const glm::dvec3 right = glm::cross(forward, up);
  const double tanHalf = std::tan(0.5 * settings.fovYDeg * 3.14159265358979 / 180.0);
  std::vector<double> shadowedRatio, litRatio, expected;
  double crossingSum = 0.0, crossingExpectedSum = 0.0;
  size_t crossingCount = 0;
  for (uint32_t y = 0; y < settings.height; ++y)
    for (uint32_t x = 0; x < settings.width; ++x) {
      const double ndcX = (x + 0.5) / settings.width * 2.0 - 1.0, ndcY = 1.0 - (y + 0.5) / settings.height * 2.0;
      const glm::dvec3 dir = glm::normalize(forward + ndcX * tanHalf * settings.width / settings.height * right +
                                            ndcY * tanHalf * up);
      // The ray against the surface's sphere (the ground's heights are a few km: flat at this distance).
      const double b = glm::dot(eyeBody, dir),
                   c = glm::dot(eyeBody, eyeBody) - (radius + surfaceM) * (radius + surfaceM);
      if (b * b - c <= 0.0) continue;
      const double t = -b - std::sqrt(b * b - c);
      const glm::dvec3 point = eyeBody + t * dir;
      // Leave out pixels with the rings in front (or near their edge) and the limb.
      const double tPlane = -eyeBody.z / dir.z;
      if (tPlane > 0.0 && tPlane < t) {
        const double r = glm::length(glm::dvec2(eyeBody.x + tPlane * dir.x, eyeBody.y + tPlane * dir.y));
        if (r > 0.95 * inner && r < 1.05 * outer) continue;
      }
      if (glm::dot(glm::normalize(point), sunBody) < 0.3 || glm::dot(glm::normalize(point), -dir) < 0.3) continue;
      const size_t i = size_t(y) * settings.width + x;
      const double lit = without[i].r + without[i].g + without[i].b;
      if (!(lit > 0.0)) continue;
      const double ratio = (withRings[i].r + withRings[i].g + withRings[i].b) / lit;
      const float shadow = ringShadowCpu(glm::vec3(point), glm::vec3(sunBody), ring);
      if (shadow < 0.6f) {
        shadowedRatio.push_back(ratio);
        expected.push_back(shadow);
      }
      if (shadow > 0.999f) litRatio.push_back(ratio);
      // Where the sunward ray meets the rings' plane (clear of their edges' penumbrae).
      if (point.z * sunBody.z < 0.0) {
        const glm::dvec3 onPlane = point - point.z / sunBody.z * sunBody;
        const double r = glm::length(glm::dvec2(onPlane));
        if (r > 1.01 * inner && r < 0.99 * outer) {
          crossingSum += ratio;
          crossingExpectedSum += shadow;
          ++crossingCount;
        }
      }
    }
  EXPECT_GT(shadowedRatio.size(), 100u) << "the view should show the shadow band";
  EXPECT_GT(litRatio.size(), 100u);
  auto median = [](std::vector<double> v) {
    if (v.empty()) return std::nan("");
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  EXPECT_GT(crossingCount, 100u);
  return {median(shadowedRatio), median(expected), median(litRatio), crossingSum / double(crossingCount),
          crossingExpectedSum / double(crossingCount)};
}

std::string ringedBody(const std::string& preset) {
  return R"([scene]
name = "ringed"
[[body]]
name = "G"
preset = ")" +
         preset + R"("
[body.orbit]
semi_major_axis_m = 1e11
period_s = 1e12
mean_anomaly_deg = 90
[body.spin]
tilt_deg = 26.7
)";
}

// The rings shadow the giant (terrain.frag's ringShadow): in their shadow its face is darker, for
// the same sun angle, by the CPU reference's transmittance; in full sun the rings change nothing.
TEST_F(SceneRender, TheRingsShadowTheGiant) {
  const std::string rings = "[body.rings]\ninner_radius_m = 7.45e7\nouter_radius_m = 1.368e8\nseed = 7\n";
  const RingShadowRatios r = ringShadowRatios(context(), ringedBody("giant"), rings, 3.0e8 / 5.8e7, 0.0, [](auto&) {});
  // (The fill light, 1 % of the sun, is not shadowed.)
  EXPECT_NEAR(r.lit, 1.0, 0.02);
  EXPECT_NEAR(r.shadowed, r.expected, 0.06) << "expected transmittance " << r.expected;
  EXPECT_NEAR(r.crossing, r.crossingExpected, 0.03) << "expected transmittance " << r.crossingExpected;
}

// The rings shadow the sea too (water.frag's ringShadow): an Earth under water everywhere (sea
// level above its highest ground), with rings from 1.5 to 2.3 radii. The sea's light without air
// is its upwelling and the sun's glint, both in the sun's light. Before, water.frag left the
// shadow out: the ratios were 1 (shadowed 1.00, crossing 1.00). Now 0.494 and 0.796, as the
// reference's 0.494 and 0.796.
TEST_F(SceneRender, TheRingsShadowTheSea) {
  const std::string rings = "[body.rings]\ninner_radius_m = 9.6e6\nouter_radius_m = 1.47e7\nseed = 7\n";
  const RingShadowRatios r = ringShadowRatios(context(), ringedBody("earth"), rings, 5.0, 20000.0,
                                              [](PlanetDescription& planet) { planet.seaLevelM = 20000.0; });
  EXPECT_NEAR(r.lit, 1.0, 0.02);
  EXPECT_NEAR(r.shadowed, r.expected, 0.06) << "expected transmittance " << r.expected;
  EXPECT_NEAR(r.crossing, r.crossingExpected, 0.03) << "expected transmittance " << r.crossingExpected;
}

}  // namespace
}  // namespace planet::test

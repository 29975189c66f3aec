// Eclipses (issue 23, point 1): the shared function of shaders/common/eclipse.glsl against the
// area of overlap of two discs integrated independently (Eclipse.*), the built-in system's
// documented eclipse times, and pictures of both eclipses on lavapipe (EclipseGpu.*).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "camera/scene_view.h"
#include "core/image_file.h"
#include "gpu_fixture.h"
#include "planet/planet_description.h"
#include "planet/scene_description.h"
#include "planet/terrain_height.h"
#include "reference/eclipse.h"
#include "reference/sunlight.h"
#include "render/renderer.h"
#include "spv/eclipse_eval.comp.h"
#include "test_support.h"
#include "vk/buffer.h"
#include "vk/commands.h"
#include "vk/owned.h"
#include "vk/pipeline.h"

namespace planet::test {
namespace {

constexpr double kPi = std::numbers::pi;

// The documented times of the built-in system (engine/planet/scenes/system.toml, README):
// the Moon's umbra on Terra's sub-solar point, and the Moon in the middle of Terra's umbra.
constexpr double kSolarEclipseS = 7867740.0;
constexpr double kLunarEclipseS = 7941160.0;
// Where the Moon's shadow axis meets Terra at kSolarEclipseS (Terra's frame, degrees).
constexpr double kUmbraLatitudeDeg = 0.04;
constexpr double kUmbraLongitudeDeg = 127.86;

// The share of a unit disc (the sun) that a disc of radius k, centred s away along x, covers:
// the midpoint rule over vertical strips, each strip covered where both discs' chords at its x
// overlap (both chords are centred on y = 0, so that is twice the shorter half chord). No
// closed form: it checks the shared function's lens formula independently.
double coveredByStrips(double k, double s, int strips) {
  const double lo = std::max(-1.0, s - k), hi = std::min(1.0, s + k);
  if (!(hi > lo)) return 0.0;
  const double dx = (hi - lo) / strips;
  double sum = 0.0;
  for (int i = 0; i < strips; ++i) {
    const double x = lo + (i + 0.5) * dx;
    const double sunHalf = std::sqrt(std::max(1.0 - x * x, 0.0));
    const double occluderHalf = std::sqrt(std::max(k * k - (x - s) * (x - s), 0.0));
    sum += 2.0 * std::min(sunHalf, occluderHalf) * dx;
  }
  return sum / kPi;
}

// The penumbra's profile: for occluders smaller than, as large as and much larger than the sun
// (the Moon seen from Terra is ~0.4 to 2 suns here, Terra from the Moon ~13), the covered share
// at 121 separations from concentric to past first contact. The strips' own error is below
// 1e-6 at 40,000 strips (their ends follow a square root: O(n^-1.5)); float must agree to 1e-4
// of the sun's disc (it does to 7e-7: the half chord in Heron's form, the angles from atan),
// double to 1e-6.
TEST(Eclipse, PenumbraProfileMatchesTheAreaOfOverlapOfTwoDiscs) {
  double worstFloat = 0.0, worstDouble = 0.0;
  for (double k : {0.25, 0.6, 0.95, 1.0, 1.05, 2.0, 13.0}) {
    for (int i = 0; i <= 120; ++i) {
      const double s = (1.0 + k + 0.05) * i / 120.0;
      const double expected = coveredByStrips(k, s, 40000);
      worstFloat = std::max(worstFloat, std::abs(double(sunDiscCoveredCpu(float(k), float(s))) - expected));
      worstDouble = std::max(worstDouble, std::abs(sunDiscCovered(k, s) - expected));
      ASSERT_NEAR(sunDiscCoveredCpu(float(k), float(s)), expected, 1e-4) << "k " << k << " s " << s;
    }
  }
  EXPECT_LT(worstDouble, 1e-6);
  std::printf("disc overlap: worst difference from the strips %.2e (float), %.2e (double)\n", worstFloat, worstDouble);
}

// The three regions: the occluder covers the sun (umbra: no light), misses it (full sun), or
// lies inside it (antumbra: an annular eclipse leaves the ring 1 − k²); the lens joins them
// without a jump.
TEST(Eclipse, UmbraIsDarkOutsideIsFullAndAnAnnularEclipseLeavesARing) {
  EXPECT_EQ(sunDiscCoveredCpu(1.2f, 0.1f), 1.0f);
  EXPECT_EQ(sunDiscCoveredCpu(13.0f, 11.9f), 1.0f);
  EXPECT_EQ(sunDiscCoveredCpu(0.5f, 1.6f), 0.0f);
  EXPECT_EQ(sunDiscCoveredCpu(0.9f, 0.05f), 0.9f * 0.9f);
  EXPECT_NEAR(1.0f - sunDiscCoveredCpu(0.9f, 0.0f), 0.19f, 1e-6f);
  for (float k : {0.5f, 0.95f, 1.5f, 13.0f}) {
    const float inner = std::abs(1.0f - k), outer = 1.0f + k;
    EXPECT_NEAR(sunDiscCoveredCpu(k, inner * 1.0001f + 1e-5f), sunDiscCoveredCpu(k, inner), 2e-3f) << k;
    EXPECT_NEAR(sunDiscCoveredCpu(k, outer * 0.9999f), 0.0f, 2e-4f) << k;
  }
  // Monotone: the further apart, the less is covered.
  for (float k : {0.6f, 1.0f, 2.0f}) {
    float previous = 1.0f;
    for (int i = 0; i <= 200; ++i) {
      const float covered = sunDiscCoveredCpu(k, (1.0f + k) * float(i) / 200.0f);
      EXPECT_LE(covered, previous + 1e-6f) << "k " << k << " step " << i;
      previous = covered;
    }
  }
}

// The Moon of the system (radius 1,737.4 km) 60,000 km sunward of a plane facing the sun: its
// shadow on the plane has the cone's radii, the umbra R − L tan ρ and the penumbra's outer edge
// R + L tan ρ (ρ the presets' sun, 0.0075 rad), to 0.1 % (the flat-disc model's rounding).
TEST(Eclipse, TheMoonsShadowHasTheConesRadii) {
  const double radius = 1737400.0, distance = 6.0e7, rho = kSunAngularRadiusRad;
  const glm::vec3 sun(0.0f, 0.0f, 1.0f);
  auto visibleAt = [&](double x) {
    return occluderSunVisibleCpu(glm::vec3(float(-x), 0.0f, float(distance)), float(radius), sun, float(rho));
  };
  const double umbra = radius - distance * std::tan(rho), penumbra = radius + distance * std::tan(rho);
  EXPECT_EQ(visibleAt(0.0), 0.0f);
  EXPECT_EQ(visibleAt(0.999 * umbra), 0.0f);
  EXPECT_GT(visibleAt(1.001 * umbra), 0.0f);
  EXPECT_LT(visibleAt(0.999 * penumbra), 1.0f);
  EXPECT_EQ(visibleAt(1.001 * penumbra), 1.0f);
  // At the shadow's geometric edge the occluder's limb crosses the sun's centre; it curves away
  // from the sun (3.9 suns in radius), so a little more than half the sun shows.
  EXPECT_GT(visibleAt(radius), 0.5f);
  EXPECT_LT(visibleAt(radius), 0.6f);
  // The profile across the penumbra is the disc overlap's: at each point the occluder's
  // angular radius and separation give k and s (in suns).
  for (int i = 0; i <= 20; ++i) {
    const double x = umbra + (penumbra - umbra) * i / 20.0;
    const double d = std::hypot(x, distance);
    const double k = std::asin(radius / d) / rho, s = std::atan2(x, distance) / rho;
    EXPECT_NEAR(visibleAt(x), 1.0 - coveredByStrips(k, s, 40000), 2e-4) << "x " << x;
  }
  std::printf("the Moon's shadow 60,000 km behind it: umbra radius %.0f km, penumbra %.0f km wide\n", umbra / 1e3,
              (penumbra - umbra) / 1e3);
}

// Several occluders multiply their visible shares, the block's rotation turns their centres
// with the sun, and a point inside an occluder gets no sun.
TEST(Eclipse, OccludersMultiplyAndTurnWithTheFrame) {
  const double rho = kSunAngularRadiusRad;
  // Two spheres each half across the sun seen from the origin, on opposite sides of it.
  const double distance = 1.0e8, radius = 1.0e6;
  const std::vector<Occluder> occluders = {{{radius, 0.0, distance}, radius}, {{-radius, 0.0, 2.0 * distance}, radius}};
  const gpu::EclipseParams e = eclipseGpuParams(occluders, glm::dmat3(1.0), rho);
  const glm::vec3 sun(0.0f, 0.0f, 1.0f);
  const float a = occluderSunVisibleCpu(glm::vec3(occluders[0].centreM), float(radius), sun, float(rho));
  const float b = occluderSunVisibleCpu(glm::vec3(occluders[1].centreM), float(radius), sun, float(rho));
  EXPECT_GT(a, 0.05f);
  EXPECT_LT(a, 0.95f);
  EXPECT_NEAR(eclipseSunVisibleCpu(glm::vec3(0.0f), sun, e), a * b, 1e-6f);
  // The same, turned by 90 degrees about x (sun and centres alike).
  const glm::dmat3 turn(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0);
  const gpu::EclipseParams turned = eclipseGpuParams(occluders, turn, rho);
  EXPECT_NEAR(eclipseSunVisibleCpu(glm::vec3(0.0f), glm::vec3(turn * glm::dvec3(sun)), turned), a * b, 1e-5f);
  // A point inside the first sphere, and one beside both shadows.
  EXPECT_EQ(eclipseSunVisibleCpu(glm::vec3(occluders[0].centreM), sun, e), 0.0f);
  EXPECT_EQ(eclipseSunVisibleCpu(glm::vec3(1.0e7f, 0.0f, 0.0f), sun, e), 1.0f);
  EXPECT_EQ(eclipseSunVisibleCpu(glm::vec3(0.0f), sun, eclipseGpuParams({}, glm::dmat3(1.0), rho)), 1.0f);
}

// An occluder with air bends a little red light into its shadow (refractedIntoShadow's crude
// model): Earth's is of the order the eclipsed Moon shows (10⁻⁴ of the sun), red above green
// above blue by the tangent path's reddening; an airless body bends none. A point sees it in
// proportion to the share of the sun the occluder covers.
TEST(Eclipse, AnAtmosphereBendsRedLightIntoItsShadow) {
  const glm::dvec3 earth = refractedIntoShadow(resolvePreset("earth"));
  EXPECT_GT(earth.r, 1e-4);
  EXPECT_LT(earth.r, 3e-3);
  EXPECT_LT(earth.g, 0.3 * earth.r);
  EXPECT_LT(earth.b, 0.3 * earth.g);
  EXPECT_EQ(refractedIntoShadow(resolvePreset("moon")), glm::dvec3(0.0));
  std::printf("Earth's air bends (%.2e, %.2e, %.2e) of the sun into its umbra\n", earth.r, earth.g, earth.b);

  const double rho = kSunAngularRadiusRad, distance = 1.0e8;
  const glm::vec3 sun(0.0f, 0.0f, 1.0f);
  for (double offset : {0.0, 1.0e6}) {  // covered, then half across the sun
    const std::vector<Occluder> occluder = {{{offset, 0.0, distance}, 1.0e6, earth}};
    const gpu::EclipseParams e = eclipseGpuParams(occluder, glm::dmat3(1.0), rho);
    glm::vec3 refracted;
    const float visible = eclipseSunVisibleRefractedCpu(glm::vec3(0.0f), sun, e, refracted);
    EXPECT_NEAR(refracted.r, float((1.0 - visible) * earth.r), 1e-9f) << offset;
    EXPECT_NEAR(refracted.b, float((1.0 - visible) * earth.b), 1e-9f) << offset;
    if (offset == 0.0) {
      EXPECT_EQ(visible, 0.0f);
    } else {
      EXPECT_GT(visible, 0.2f);
      EXPECT_LT(visible, 0.8f);
    }
  }
}

TEST(Eclipse, TooManyOccludersOrABadRadiusAreNamed) {
  const std::vector<Occluder> nine(9, Occluder{{0.0, 0.0, 1.0e8}, 1.0e6});
  EXPECT_EQ(errorOf([&] { eclipseGpuParams(nine, glm::dmat3(1.0), 0.0075); }),
            "9 bodies can hide the sun, at most 8 are drawn");
  const std::vector<Occluder> bad = {{{0.0, 0.0, 1.0e8}, -1.0}};
  EXPECT_EQ(errorOf([&] { eclipseGpuParams(bad, glm::dmat3(1.0), 0.0075); }),
            "occluder radius -1 m must be a finite number >= 0");
  const std::vector<Occluder> bright = {{{0.0, 0.0, 1.0e8}, 1.0e6, {0.5, 2.0, 0.0}}};
  EXPECT_EQ(errorOf([&] { eclipseGpuParams(bright, glm::dmat3(1.0), 0.0075); }),
            "occluder's refracted share 2 is outside [0, 1]");
}

// The scene-frame point of a body's surface at latitude/longitude (its frame) at a time.
glm::dvec3 surfacePoint(const SceneDescription& scene, const std::vector<BodyState>& states, size_t body,
                        double latitudeDeg, double longitudeDeg) {
  return states[body].positionM + states[body].bodyToScene * (directionFromLatLon(latitudeDeg, longitudeDeg) *
                                                              scene.bodies[body].planet.radiusM);
}

// The built-in system's documented times (system.toml, README): at the solar eclipse the
// Moon's umbra (~1,360 km in radius on Terra) covers the documented point of Terra and the
// ground 1,000 km from it, and ground 3,000 km away (past the penumbra's ~2,150 km) is in full
// sun; at the lunar eclipse the whole Moon is in Terra's umbra (its centre and four points of
// its limb), and the Moon half an orbit earlier is in full sun.
TEST(Eclipse, TheSystemShowsBothEclipsesAtItsDocumentedTimes) {
  const SceneDescription scene = resolveScene("system");
  const size_t terra = sceneBodyIndex(scene, "Terra"), moon = sceneBodyIndex(scene, "Moon");
  {
    const std::vector<BodyState> states = sceneStateAt(scene, kSolarEclipseS);
    const glm::dvec3 centre = surfacePoint(scene, states, terra, kUmbraLatitudeDeg, kUmbraLongitudeDeg);
    EXPECT_EQ(sceneSunVisible(scene, states, terra, centre), 0.0);
    // 1,000 km from the centre (9 degrees of Terra) still in the umbra; 3,000 km out in sun.
    EXPECT_EQ(sceneSunVisible(scene, states, terra,
                              surfacePoint(scene, states, terra, kUmbraLatitudeDeg + 9.0, kUmbraLongitudeDeg)),
              0.0);
    EXPECT_EQ(sceneSunVisible(scene, states, terra,
                              surfacePoint(scene, states, terra, kUmbraLatitudeDeg, kUmbraLongitudeDeg + 27.0)),
              1.0);
    // The point faces the sun (the eclipse is on the day side): the sun is within a degree of its zenith.
    const glm::dvec3 up = glm::normalize(centre - states[terra].positionM);
    EXPECT_GT(glm::dot(up, -glm::normalize(centre)), std::cos(kPi / 180.0));
  }
  {
    const std::vector<BodyState> states = sceneStateAt(scene, kLunarEclipseS);
    const glm::dvec3 centre = states[moon].positionM;
    const glm::dvec3 axis = glm::normalize(centre);  // away from the sun
    const glm::dvec3 side = glm::normalize(glm::cross(axis, glm::dvec3(0.0, 0.0, 1.0)));
    const glm::dvec3 other = glm::cross(axis, side);
    const double radius = scene.bodies[moon].planet.radiusM;
    EXPECT_EQ(sceneSunVisible(scene, states, moon, centre), 0.0);
    for (const glm::dvec3& limb : {side, -side, other, -other})
      EXPECT_EQ(sceneSunVisible(scene, states, moon, centre + radius * limb), 0.0);
    const std::vector<BodyState> earlier = sceneStateAt(scene, kLunarEclipseS - 0.5 * scene.bodies[moon].orbit.periodS);
    EXPECT_EQ(sceneSunVisible(scene, earlier, moon, earlier[moon].positionM), 1.0);
  }
}

// --- Pictures (lavapipe) ----------------------------------------------------------------------

using EclipseGpu = GpuTest;

// eclipse_eval.comp: the shared functions evaluated by the GPU at `queries`.
std::vector<glm::vec4> evaluateOnGpu(vk::Context& context, const gpu::EclipseParams& eclipse, uint32_t mode,
                                     const std::vector<glm::vec4>& queries, const glm::vec3& sun) {
  vk::ComputePipeline pipeline =
      vk::createComputePipeline(context, kSpv_eclipse_eval_comp, 3, sizeof(gpu::EclipseEvalPush), {}, 1);
  const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  const size_t bytes = queries.size() * sizeof(glm::vec4);
  vk::Owned<vk::Buffer> params(context,
                               vk::createBuffer(context, sizeof(eclipse), usage, vk::MemoryUsage::DeviceLocal));
  vk::Owned<vk::Buffer> input(context, vk::createBuffer(context, bytes, usage, vk::MemoryUsage::DeviceLocal));
  vk::Owned<vk::Buffer> output(context, vk::createBuffer(context, bytes, usage, vk::MemoryUsage::DeviceLocal));
  std::vector<glm::vec4> results(queries.size());
  try {
    vk::uploadBuffer(context, *params, &eclipse, sizeof(eclipse));
    vk::uploadBuffer(context, *input, queries.data(), bytes);
    const vk::Buffer* buffers[] = {&*params, &*input, &*output};
    VkDescriptorSet set = vk::allocateStorageSet(context, pipeline, buffers);
    gpu::EclipseEvalPush push{};
    push.sun = glm::vec4(sun, 0.0f);
    push.count = uint32_t(queries.size());
    push.mode = mode;
    vk::submitAndWait(context, [&](VkCommandBuffer cmd) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout, 0, 1, &set, 0, nullptr);
      vkCmdPushConstants(cmd, pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
      vkCmdDispatch(cmd, (push.count + gpu::kEclipseEvalWorkgroupSize - 1) / gpu::kEclipseEvalWorkgroupSize, 1, 1);
      // The results are read by a copy or directly by the host.
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                        VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
    });
    vk::readbackBuffer(context, *output, results.data(), bytes);
  } catch (...) {
    vk::destroyComputePipeline(context, pipeline);
    throw;
  }
  vk::destroyComputePipeline(context, pipeline);
  return results;
}

// The GLSL of eclipse.glsl against its C++ compilation: the disc overlap over the profile test's
// grid, and the visible share and refracted light across the Moon's shadow 60,000 km behind it
// (with Earth's air, as if the Moon had it). The GPU's asin and atan are not the C library's:
// within 1e-4 of the sun's disc (7e-5 at worst on lavapipe, for an occluder 13 suns across,
// whose segment multiplies the angle's error by k²), the profile test's tolerance.
TEST_F(EclipseGpu, SharedFunctionsMatchTheCpuReference) {
  std::vector<glm::vec4> covered;
  for (float k : {0.25f, 0.6f, 0.95f, 1.0f, 1.05f, 2.0f, 13.0f})
    for (int i = 0; i <= 120; ++i) covered.emplace_back(k, (1.0f + k + 0.05f) * float(i) / 120.0f, 0.0f, 0.0f);
  const gpu::EclipseParams none = eclipseGpuParams({}, glm::dmat3(1.0), kSunAngularRadiusRad);
  const std::vector<glm::vec4> gpuCovered = evaluateOnGpu(context(), none, gpu::kEclipseEvalCovered, covered, {});
  double worst = 0.0;
  for (size_t i = 0; i < covered.size(); ++i) {
    const float cpu = sunDiscCoveredCpu(covered[i].x, covered[i].y);
    worst = std::max(worst, double(std::abs(gpuCovered[i].x - cpu)));
    ASSERT_NEAR(gpuCovered[i].x, cpu, 1e-4f) << "k " << covered[i].x << " s " << covered[i].y;
  }
  double worstVisible = 0.0;
  const glm::dvec3 earth = refractedIntoShadow(resolvePreset("earth"));
  const std::vector<Occluder> moon = {{{0.0, 0.0, 6.0e7}, 1737400.0, earth}};
  const gpu::EclipseParams e = eclipseGpuParams(moon, glm::dmat3(1.0), kSunAngularRadiusRad);
  const glm::vec3 sun(0.0f, 0.0f, 1.0f);
  std::vector<glm::vec4> points;
  for (int i = 0; i <= 200; ++i) points.emplace_back(3.0e6f * float(i) / 200.0f, 1.0e5f, 0.0f, 0.0f);
  const std::vector<glm::vec4> gpuVisible = evaluateOnGpu(context(), e, gpu::kEclipseEvalVisible, points, sun);
  for (size_t i = 0; i < points.size(); ++i) {
    glm::vec3 refracted;
    const float visible = eclipseSunVisibleRefractedCpu(glm::vec3(points[i]), sun, e, refracted);
    worstVisible = std::max(worstVisible, double(std::abs(gpuVisible[i].x - visible)));
    ASSERT_NEAR(gpuVisible[i].x, visible, 1e-4f) << "x " << points[i].x;
    ASSERT_NEAR(gpuVisible[i].y, refracted.r, 1e-4f * float(earth.r)) << "x " << points[i].x;
  }
  std::printf("eclipse.glsl on the GPU: worst difference from the C++ %.2e (disc overlap), %.2e (visible share)\n",
              worst, worstVisible);
}

// The scene view of the camera `local` on body `body` at time t, optionally turned to `target`.
SceneView sceneView(const std::vector<BodyState>& states, double timeS, size_t body, const CameraBasis& local) {
  SceneView view;
  view.camera = cameraToScene(states[body].positionM, states[body].bodyToScene, local);
  view.bodies = sceneBodyViews(states);
  view.timeS = timeS;
  return view;
}

double luminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// The mean HDR colour of the (2r+1)² pixels around (x, y).
glm::dvec3 colourAround(const RenderResult& result, uint32_t width, int x, int y, int r) {
  glm::dvec3 sum(0.0);
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) sum += glm::dvec3(result.hdr[size_t(y + dy) * width + size_t(x + dx)]);
  return sum / double((2 * r + 1) * (2 * r + 1));
}

// The mean HDR luminance of the (2r+1)² pixels around (x, y).
double meanAround(const RenderResult& result, uint32_t width, int x, int y, int r) {
  double sum = 0.0;
  int n = 0;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      sum += luminance(result.hdr[size_t(y + dy) * width + size_t(x + dx)]);
      ++n;
    }
  return sum / n;
}

// The solar eclipse from 8,000 km above the umbra's centre, looking straight down: the middle
// of the picture (the umbra, ~1,360 km in radius: 9.6 degrees of the view) is dark, in linear
// HDR and on the display, and ground ~3,000 km away (20 degrees off the middle, past the
// penumbra's ~2,150 km) is as sunlit as the same place with the Moon elsewhere. From the ground
// there the sky is dark.
TEST_F(EclipseGpu, GroundInTheMoonsUmbraIsDarkAndOutsideItLit) {
  const SceneDescription scene = resolveScene("system");
  const size_t terra = sceneBodyIndex(scene, "Terra");
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  Renderer renderer(context(), scene, settings);
  CameraPose pose;
  pose.latitudeDeg = kUmbraLatitudeDeg;
  pose.longitudeDeg = kUmbraLongitudeDeg;
  pose.altitudeM = 8.0e6;
  pose.pitchDeg = -90.0;
  const CameraBasis local = cameraBasis(pose, scene.bodies[terra].planet.radiusM);
  const std::vector<BodyState> states = sceneStateAt(scene, kSolarEclipseS);
  const RenderResult eclipse = renderer.renderScene(sceneView(states, kSolarEclipseS, terra, local), true);
  // The same frame with the Moon half an orbit away (Terra's place and turn kept: only the
  // Moon moves), for the light outside the shadow.
  std::vector<BodyState> moved = states;
  const size_t moon = sceneBodyIndex(scene, "Moon");
  moved[moon].positionM = 2.0 * states[terra].positionM - states[moon].positionM;
  const RenderResult clear = renderer.renderScene(sceneView(moved, kSolarEclipseS, terra, local), true);
  const int offset = int(std::lround(45.0 * std::tan(20.0 * kPi / 180.0) / std::tan(30.0 * kPi / 180.0)));
  const double umbra = meanAround(eclipse, 160, 80, 45, 2);
  const double litEclipse = meanAround(eclipse, 160, 80 + offset, 45, 2);
  const double litClear = meanAround(clear, 160, 80 + offset, 45, 2);
  const double middleClear = meanAround(clear, 160, 80, 45, 2);
  writePng((testOutputDir() / "eclipse_solar.png").string(), eclipse.image);
  ASSERT_GT(middleClear, 0.02) << "without the Moon the middle should be sunlit";
  EXPECT_LT(umbra, 1e-3 * middleClear) << "the umbra should be dark: " << umbra << " vs " << middleClear;
  EXPECT_NEAR(litEclipse / litClear, 1.0, 0.02) << "outside the penumbra the ground should be lit as without the Moon";
  const uint8_t* middle = &eclipse.image.pixels[(45 * 160 + 80) * 4];
  EXPECT_LE(std::max({middle[0], middle[1], middle[2]}), 3) << "the umbra should be black on the display";

  // From the ground in the umbra's middle, looking 30 degrees up: the sky (the sky-view table,
  // dimmed along each ray) is dark, under 3 % of the same sky with the Moon elsewhere (what is
  // left, 1.3 % here, is mostly the stars that show through the darkened sky).
  CameraPose ground = pose;
  ground.altitudeM = 0.0;
  ground.pitchDeg = 30.0;
  const CameraBasis groundLocal = cameraBasis(ground, scene.bodies[terra].planet.radiusM);
  const RenderResult skyInUmbra = renderer.renderScene(sceneView(states, kSolarEclipseS, terra, groundLocal), true);
  writePng((testOutputDir() / "eclipse_solar_sky.png").string(), skyInUmbra.image);
  const double skyEclipse = meanAround(skyInUmbra, 160, 80, 20, 10);
  const double skyClear =
      meanAround(renderer.renderScene(sceneView(moved, kSolarEclipseS, terra, groundLocal), true), 160, 80, 20, 10);
  ASSERT_GT(skyClear, 0.01) << "without the Moon the noon sky should be bright";
  EXPECT_LT(skyEclipse, 0.03 * skyClear) << skyEclipse << " vs " << skyClear;
}

// In a scene the frame's depth holds other bodies, which may lie past the air's far side and take
// the sky-view table (SkyView::ownSurfacesOnly is false). A tile where every pixel shows geometry
// is then composed by the ground's pipelines, which have no sky-view code, only where, from inside
// the air, the classify passes show that none of its rays leaves the air (composeTileInsideAir);
// from above the air, never. The picture is that of every tile composed with both sides, bit for
// bit: from 2 km on Terra looking along the horizon (its ground's tiles are the ground's), from
// there looking at the Moon in a 2-degree view (the Moon's disc, 384,000 km past the air, fills
// whole tiles: they are mixed), and from 20,000 km with the Moon beside Terra.
TEST_F(EclipseGpu, ASceneComposesTheGroundWithoutTheSkyViewTableOnlyWhereItsRaysEndInsideTheAir) {
  const SceneDescription scene = resolveScene("system");
  const size_t terra = sceneBodyIndex(scene, "Terra"), moon = sceneBodyIndex(scene, "Moon");
  const std::vector<BodyState> states = sceneStateAt(scene, kSolarEclipseS);
  const double radius = scene.bodies[terra].planet.radiusM;
  CameraPose low;
  low.latitudeDeg = kUmbraLatitudeDeg + 20.0;
  low.longitudeDeg = kUmbraLongitudeDeg;
  low.altitudeM = 2000.0;
  low.pitchDeg = 2.0;
  CameraPose high = low;
  high.altitudeM = 2.0e7;
  high.pitchDeg = -90.0;
  // 2 km above the point of Terra 30 degrees from the one under the Moon, looking at the Moon.
  const glm::dvec3 toMoon =
      glm::transpose(states[terra].bodyToScene) * (states[moon].positionM - states[terra].positionM);
  const glm::dvec3 side = glm::normalize(glm::cross(toMoon, glm::dvec3(0.0, 0.0, 1.0)));
  const glm::dvec3 up =
      glm::normalize(std::cos(glm::radians(30.0)) * glm::normalize(toMoon) + std::sin(glm::radians(30.0)) * side);
  const CameraBasis atMoon = lookingAt(up * (radius + 2000.0), toMoon);
  struct View {
    const char* name;
    CameraBasis camera;
    double fovYDeg;
    bool terraGround;  // whether Terra's compose has tiles of the ground's classes
    bool terraSky;     // ... and tiles of sky (above the horizon, around the Moon)
    bool terraMixed;   // ... and mixed tiles (the Moon's disc)
  };
  const View views[] = {{"2 km, along the horizon", cameraBasis(low, radius), 60.0, true, true, false},
                        {"2 km, the Moon in a 6-degree view", atMoon, 6.0, false, true, true},
                        {"20,000 km", cameraBasis(high, radius), 60.0, false, false, false}};
  for (const View& view : views) {
    SCOPED_TRACE(view.name);
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.fovYDeg = view.fovYDeg;
    RenderSettings mixedSettings = settings;
    mixedSettings.sky.tileClasses = false;
    Renderer classes(context(), scene, settings);
    Renderer mixed(context(), scene, mixedSettings);
    const RenderResult a = classes.renderScene(sceneView(states, kSolarEclipseS, terra, view.camera));
    const RenderResult b = mixed.renderScene(sceneView(states, kSolarEclipseS, terra, view.camera));
    EXPECT_EQ(a.image.pixels, b.image.pixels);
    for (size_t body = 0; body < scene.bodies.size(); ++body) {
      const auto counts = classes.sky(body).readTileCounts();
      std::printf("scene tiles, %s, %s: %u sky, %u ground, %u mixed\n", view.name, scene.bodies[body].name.c_str(),
                  counts[gpu::kSkyTileSky], SkyPass::groundTiles(counts), counts[gpu::kSkyTileMixed]);
      if (body == terra && view.terraGround)
        EXPECT_GT(SkyPass::groundTiles(counts), 0u);
      else
        EXPECT_EQ(SkyPass::groundTiles(counts), 0u) << scene.bodies[body].name;
    }
    const auto terraCounts = classes.sky(terra).readTileCounts();
    if (view.terraSky) {
      EXPECT_GT(terraCounts[gpu::kSkyTileSky], 0u);
    }
    if (view.terraMixed) {
      EXPECT_GT(terraCounts[gpu::kSkyTileMixed], 0u);
    }
    if (a.image.pixels != b.image.pixels) {
      const std::string name = testOutputDir().string() + "/scene_tiles_" + std::to_string(&view - views);
      writePng(name + ".classes.png", a.image);
      writePng(name + ".mixed.png", b.image);
    }
  }
}

// The lunar eclipse from 20,000 km above Terra's night side, looking at the Moon (40,000 km
// away, 5 degrees across in a 10-degree view): the Moon inside Terra's umbra is dark, at most
// 1 % of the same Moon an hour and a half later, outside the shadow (by then it has moved
// 14,000 km along its orbit, past the penumbra, still nearly full), and what light it has is red.
TEST_F(EclipseGpu, TheMoonInTerrasUmbraIsDark) {
  const SceneDescription scene = resolveScene("system");
  const size_t terra = sceneBodyIndex(scene, "Terra"), moon = sceneBodyIndex(scene, "Moon");
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.fovYDeg = 10.0;
  Renderer renderer(context(), scene, settings);
  double moonLight[2] = {0.0, 0.0};
  glm::dvec3 eclipsedColour(0.0);
  int k = 0;
  for (double t : {kLunarEclipseS, kLunarEclipseS + 5400.0}) {
    const std::vector<BodyState> states = sceneStateAt(scene, t);
    const glm::dvec3 toMoon =
        glm::transpose(states[terra].bodyToScene) * (states[moon].positionM - states[terra].positionM);
    const glm::dvec3 position = glm::normalize(toMoon) * (scene.bodies[terra].planet.radiusM + 2.0e7);
    const CameraBasis local = lookingAt(position, toMoon);
    const RenderResult result = renderer.renderScene(sceneView(states, t, terra, local), true);
    moonLight[k] = meanAround(result, 160, 80, 45, 6);
    if (k == 0) {
      writePng((testOutputDir() / "eclipse_lunar.png").string(), result.image);
      eclipsedColour = colourAround(result, 160, 80, 45, 6);
    }
    ++k;
  }
  ASSERT_GT(moonLight[1], 0.02) << "outside the shadow the full Moon should be lit";
  EXPECT_LT(moonLight[0], 0.01 * moonLight[1]) << moonLight[0] << " vs " << moonLight[1];
  // What light it gets is Terra's air's, bent into the umbra: red.
  EXPECT_GT(eclipsedColour.r, 0.0);
  EXPECT_GT(eclipsedColour.r, 3.0 * eclipsedColour.g) << eclipsedColour.r << " " << eclipsedColour.g;
  EXPECT_GE(eclipsedColour.g, eclipsedColour.b);
}

// A moon's shadow on a giant's rings (ring.frag): the moon 150,000 km sunward of a point of the
// rings (its umbra there 610 km in radius, its penumbra 2,860 km), seen from 60,000 km in a
// 15-degree view centred on that point (170 km a pixel). The ring there is under 10 % as bright
// as with the moon elsewhere (what is left is the rings' fill light, which no shadow dims), and
// 30 pixels (5,100 km) away it is as bright.
TEST_F(EclipseGpu, AMoonsShadowFallsOnTheRings) {
  const SceneDescription scene = parseSceneDescription(R"([scene]
name = "ring shadow"
[[body]]
name = "Giant"
preset = "giant"
gm_m3_s2 = 3.7931e16
[body.orbit]
semi_major_axis_m = 1.496e11
mean_anomaly_deg = 90
[body.spin]
tilt_deg = 26.7
[body.rings]
inner_radius_m = 7.45e7
outer_radius_m = 1.368e8
seed = 7
[[body]]
name = "Moon"
preset = "moon"
parent = "Giant"
[body.orbit]
semi_major_axis_m = 1.86e8
mean_anomaly_deg = -53.74
)",
                                                       "ring-shadow.toml");
  // The giant at (0, 1 au, 0): the sun along −y. The moon, at (1.1e8, −1.5e8, 0) from the giant,
  // is 1.5e8 m sunward of the point 1.1e8 m along x of the ring plane (tilted about x); the
  // view is centred on where the line from the moon away from the sun meets that plane.
  const std::vector<BodyState> states = sceneStateAt(scene, 0.0);
  const glm::dvec3 sun = -glm::normalize(states[1].positionM);
  const glm::dvec3 normal = states[0].bodyToScene * glm::dvec3(0.0, 0.0, 1.0);
  const double along = glm::dot(states[1].positionM - states[0].positionM, normal) / glm::dot(sun, normal);
  const glm::dvec3 point = states[1].positionM - along * sun;
  ASSERT_NEAR(glm::length(point - states[0].positionM), 1.1e8, 1e6) << "the shadow should fall mid-ring";
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.fovYDeg = 15.0;
  Renderer renderer(context(), scene, settings);
  SceneView view;
  view.camera.position = point + glm::dvec3(0.0, -5.0e7, 3.0e7);
  view.camera.forward = glm::normalize(point - view.camera.position);
  view.camera.up =
      glm::normalize(glm::cross(glm::cross(view.camera.forward, glm::dvec3(0.0, 0.0, 1.0)), view.camera.forward));
  view.bodies = sceneBodyViews(states);
  const RenderResult eclipse = renderer.renderScene(view, true);
  std::vector<BodyState> moved = states;
  moved[1].positionM = states[0].positionM + glm::dvec3(-1.1e8, 1.5e8, 0.0);  // on the giant's far side
  view.bodies = sceneBodyViews(moved);
  const RenderResult clear = renderer.renderScene(view, true);
  writePng((testOutputDir() / "eclipse_ring.png").string(), eclipse.image);
  const double shadowed = meanAround(eclipse, 160, 80, 45, 1), lit = meanAround(clear, 160, 80, 45, 1);
  ASSERT_GT(lit, 0.01) << "the rings should be sunlit there without the moon";
  EXPECT_LT(shadowed, 0.1 * lit) << shadowed << " vs " << lit;
  EXPECT_NEAR(meanAround(eclipse, 160, 110, 45, 1) / meanAround(clear, 160, 110, 45, 1), 1.0, 0.02);
}

}  // namespace
}  // namespace planet::test

// The terrain renderer on lavapipe (issue 3, points 4, 7, 9, 11): vertex heights against the CPU
// reference, no swimming, no recomputation when nothing moved, the limb where geometry puts
// it, identical images for identical inputs, golden images.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/image_file.h"
#include "gpu_fixture.h"
#include "image_compare.h"
#include "planet/scene_description.h"
#include "planet/terrain_height.h"
#include "render/relief_cube.h"
#include "render/renderer.h"
#include "test_support.h"
#include "vk/buffer.h"
#include "vk/timer.h"

namespace planet::test {
namespace {

using TerrainRender = GpuTest;

// A land point far from the noise origin (the precision rule must hold there).
constexpr double kLat = 37.2;
constexpr double kLon = -118.6;

RenderSettings smallSettings(bool patches) {
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.terrain.patches = patches;
  settings.terrain.patchSettings.resolution = 128;
  settings.terrain.patchSettings.levelCount = 4;
  return settings;
}

std::vector<glm::vec4> readSurface(vk::Context& context, TerrainPass& terrain) {
  std::vector<glm::vec4> surface(terrain.mesh().vertexCount());
  vk::readbackBuffer(context, terrain.surfaceBuffer(), surface.data(), surface.size() * sizeof(glm::vec4));
  return surface;
}

// Height of the drawn surface (the triangles of the mesh, in their (θ, φ) parameterisation) at
// a planet direction: what a viewer sees at that point of the planet.
double drawnHeight(const TerrainPass& terrain, const std::vector<glm::vec4>& surface, const glm::dvec3& direction) {
  const ClipmapMesh& mesh = terrain.mesh();
  const glm::dvec2 thetaPhi = planetToLocalThetaPhi(terrain.frame().orientation, direction);
  const uint32_t outer = mesh.innermostRingAtOrAbove(thetaPhi.x);
  const uint32_t inner = outer + 1;
  EXPECT_LT(inner, mesh.ringCount()) << "test point inside the pole fan";
  const uint32_t n = mesh.params.numPhi;
  const double step = 2.0 * std::numbers::pi / n;
  const uint32_t i = std::min(uint32_t(thetaPhi.y / step), n - 1);
  const double u = thetaPhi.y / step - i;
  const double t = (mesh.ringTheta(outer) - thetaPhi.x) / (mesh.ringTheta(outer) - mesh.ringTheta(inner));
  auto h = [&](uint32_t ring, uint32_t k) { return double(surface[mesh.vertexIndex(ring, k % n)].w); };
  const double o0 = h(outer, i), o1 = h(outer, i + 1), n0 = h(inner, i), n1 = h(inner, i + 1);
  // Triangles (o_i, o_i+1, n_i+1) and (o_i, n_i+1, n_i) of clipmap_mesh.h.
  return u >= t ? o0 + u * (o1 - o0) + t * (n1 - o1) : o0 + t * (n0 - o0) + u * (n1 - n0);
}

TEST_F(TerrainRender, VertexHeightsMatchTheDoubleReferenceAtTheirOctaveBudget) {
  const PlanetDescription planet = resolvePreset("earth");
  RenderSettings settings = smallSettings(false);
  settings.terrain.frustumCulling = false;  // vertices all round the camera are read back
  Renderer renderer(context(), planet, settings);
  RenderResult result = renderer.render({kLat, kLon, 50.0, 30.0, -20.0}, {});
  TerrainPass& terrain = renderer.terrain();
  const std::vector<glm::vec4> surface = readSurface(context(), terrain);
  const ClipmapMesh& mesh = terrain.mesh();
  const TerrainFrameInfo& frame = terrain.frame();
  double worstNear = 0.0, worstFar = 0.0;
  for (uint32_t ring = frame.rings.firstRing; ring <= frame.rings.lastRing; ring += 7)
    for (uint32_t i = 0; i < mesh.params.numPhi; i += 37) {
      const ClipmapVertex& v = mesh.vertices[mesh.vertexIndex(ring, i)];
      const glm::dvec3 direction = localToPlanetDirection(frame.orientation, v.theta, v.phi);
      const double spacing = ringSpacingM(mesh.params, planet.radiusM, ring);
      const double error = std::abs(surface[mesh.vertexIndex(ring, i)].w - terrainHeightM(planet, direction, spacing));
      // Within 10 km of the camera the 1 cm requirement holds; beyond, float offsets of up to
      // thousands of km move the sample by up to ~0.3 m along slopes of the coarse layers.
      (v.theta * planet.radiusM < 1e4 ? worstNear : worstFar) =
          std::max(v.theta * planet.radiusM < 1e4 ? worstNear : worstFar, error);
    }
  EXPECT_LT(worstNear, 0.01);
  EXPECT_LT(worstFar, 0.5);
  std::printf("vertex height vs double reference: max %.4f m within 10 km, %.4f m beyond\n", worstNear, worstFar);
}

TEST_F(TerrainRender, DrawnSurfaceDoesNotSwimWhenTheCameraMoves) {
  // The moon preset's ridged layer is rough down to centimetres everywhere: the hard case.
  const PlanetDescription planet = resolvePreset("moon");
  // Fixed planet points 5..60 m from the camera's ground point, in several directions.
  const glm::dvec3 ground = directionFromLatLon(kLat, kLon);
  std::vector<glm::dvec3> points;
  for (double distance : {5.0, 12.0, 25.0, 60.0})
    for (double bearing : {10.0, 100.0, 200.0, 300.0})
      points.push_back(travelGreatCircle(ground, bearing, distance, planet.radiusM));

  auto measure = [&](bool limitOctaves, double& worstChange, double& spacingAtPoints) {
    RenderSettings settings = smallSettings(false);
    settings.terrain.limitOctaves = limitOctaves;
    settings.terrain.frustumCulling = false;  // the points lie all round the camera
    Renderer renderer(context(), planet, settings);
    TerrainPass& terrain = renderer.terrain();
    // 9.7 m above the ground, which may lie below the radius sphere (a request of 0 m would not be clamped).
    const double altitude = renderer.clampToGround({kLat, kLon, -1.0e5}).altitudeM + 8.0;
    renderer.render({kLat, kLon, altitude}, {});
    std::vector<double> before;
    const std::vector<glm::vec4> surface0 = readSurface(context(), terrain);
    spacingAtPoints = 1e300;
    for (const glm::dvec3& p : points) {
      before.push_back(drawnHeight(terrain, surface0, p));
      const double theta = planetToLocalThetaPhi(terrain.frame().orientation, p).x;
      spacingAtPoints = std::min(spacingAtPoints, ringSpacingM(terrain.mesh().params, planet.radiusM,
                                                               terrain.mesh().innermostRingAtOrAbove(theta)));
    }
    // Move the camera by 0.3 of the finest vertex spacing among the points, four ways.
    worstChange = 0.0;
    for (double bearing : {0.0, 90.0, 180.0, 270.0}) {
      const glm::dvec3 moved = travelGreatCircle(ground, bearing, 0.3 * spacingAtPoints, planet.radiusM);
      const double lat = std::asin(moved.z) * 180.0 / std::numbers::pi;
      const double lon = std::atan2(moved.y, moved.x) * 180.0 / std::numbers::pi;
      renderer.render({lat, lon, altitude}, {});
      const std::vector<glm::vec4> surface = readSurface(context(), terrain);
      for (size_t k = 0; k < points.size(); ++k)
        worstChange = std::max(worstChange, std::abs(drawnHeight(terrain, surface, points[k]) - before[k]));
    }
  };
  double limited = 0.0, unlimited = 0.0, spacing = 0.0;
  measure(true, limited, spacing);
  measure(false, unlimited, spacing);
  std::printf(
      "surface change at fixed points after camera moves of %.3f m: %.4f m with octave limits, %.4f m "
      "without\n",
      0.3 * spacing, limited, unlimited);
  // The stated tolerance: 15 mm for moves of 0.3 of the vertex spacing, 9.7 m above the moon's
  // rough ridged ground (measured on lavapipe: 10.4 mm for moves of 7.7 cm; every octave
  // everywhere, as without limits, swims 24.5 mm; the README's "No swimming" quotes these). It
  // was 5 mm (2.1 mm measured) with Gustavson's 0.6 kernel, whose octaves had less fine
  // structure; the continuous kernel's steeper octaves move more between vertices.
  EXPECT_LT(limited, 0.015);
  EXPECT_LT(limited, 0.5 * unlimited);
}

TEST_F(TerrainRender, HeightsAreNotRecomputedWhenNothingMoved) {
  const PlanetDescription planet = resolvePreset("moon");
  Renderer renderer(context(), planet, smallSettings(true));
  RenderResult first = renderer.render({-20.0, 40.0, 3000.0, 0.0, -30.0}, {90.0, 20.0});
  EXPECT_TRUE(first.terrain.heightsComputed);
  EXPECT_GT(first.terrain.verticesEvaluated, 1000u);
  EXPECT_EQ(first.terrain.patchLevelsRebuilt, 4u);
  RenderResult again = renderer.render({-20.0, 40.0, 3000.0, 0.0, -30.0}, {90.0, 20.0});
  EXPECT_FALSE(again.terrain.heightsComputed);
  EXPECT_EQ(again.terrain.verticesEvaluated, 0u);
  EXPECT_EQ(again.terrain.patchLevelsRebuilt, 0u);
  EXPECT_EQ(again.image.pixels, first.image.pixels);
  // Turning the head brings other cells of the mesh into view (frustum culling): their heights
  // are computed, and the picture is what a renderer that never looked elsewhere draws.
  RenderResult turned = renderer.render({-20.0, 40.0, 3000.0, 135.0, -30.0}, {90.0, 20.0});
  EXPECT_TRUE(turned.terrain.heightsComputed);
  EXPECT_NE(turned.image.pixels, first.image.pixels);
  {
    Renderer fresh(context(), planet, smallSettings(true));
    EXPECT_EQ(fresh.render({-20.0, 40.0, 3000.0, 135.0, -30.0}, {90.0, 20.0}).image.pixels, turned.image.pixels);
  }
  RenderResult back = renderer.render({-20.0, 40.0, 3000.0, 0.0, -30.0}, {90.0, 20.0});
  EXPECT_EQ(back.image.pixels, first.image.pixels);
  RenderResult moved = renderer.render({-20.0, 40.001, 3000.0, 0.0, -30.0}, {90.0, 20.0});
  EXPECT_TRUE(moved.terrain.heightsComputed);
}

// Frustum culling (issue 12, point 5; clipmap_culling.h) drops the cells of the mesh no pixel
// shows: the same picture as the whole rings, with a fraction of the triangles and of the
// vertices evaluated when the camera looks toward the horizon or down from a height.
TEST_F(TerrainRender, FrustumCullingDrawsTheSamePictureWithFewerTriangles) {
  const PlanetDescription planet = resolvePreset("earth");
  struct Case {
    CameraPose camera;
    double maxTriangleShare;
  };
  const Case cases[] = {{{kLat, kLon, 2500.0, 60.0, -8.0}, 0.5},  // toward the horizon
                        {{kLat, kLon, 4.0e5, 0.0, -90.0}, 0.8},   // down from 400 km
                        {{kLat, kLon, 2.0e7, 0.0, -90.0}, 1.0}};  // the whole disc
  for (const Case& c : cases) {
    SCOPED_TRACE("altitude " + std::to_string(c.camera.altitudeM));
    RenderSettings whole = smallSettings(true);
    whole.terrain.frustumCulling = false;
    Renderer culledRenderer(context(), planet, smallSettings(true));
    Renderer wholeRenderer(context(), planet, whole);
    const RenderResult culled = culledRenderer.render(c.camera, {});
    const RenderResult all = wholeRenderer.render(c.camera, {});
    const double share = double(culled.terrain.triangles) / double(all.terrain.triangles);
    std::printf("altitude %.0f m: %llu of %llu triangles (%.0f %%), %u of %u vertices evaluated\n",
                c.camera.altitudeM, (unsigned long long)culled.terrain.triangles,
                (unsigned long long)all.terrain.triangles, 100.0 * share, culled.terrain.verticesEvaluated,
                all.terrain.verticesEvaluated);
    EXPECT_LE(share, c.maxTriangleShare);
    EXPECT_LE(culled.terrain.verticesEvaluated, all.terrain.verticesEvaluated);
    EXPECT_EQ(all.terrain.cellsKept, all.terrain.cellsTotal);
    EXPECT_EQ(culled.image.pixels, all.image.pixels);
    if (culled.image.pixels != all.image.pixels) {
      writePng((std::filesystem::path(testOutputDir()) / "cull_culled.png").string(), culled.image);
      writePng((std::filesystem::path(testOutputDir()) / "cull_whole.png").string(), all.image);
    }
  }
}

// The parts of the ground's shading a frame leaves out (TerrainShading): night from the
// horizon cut's cap around the nadir, the detail from the nearest ground and the smallest pixel.
TEST(TerrainShading, NightAndFootprintBoundsFollowTheView) {
  const double radius = 6.371e6;
  const glm::dvec3 up{0.0, 0.0, 1.0};
  auto sunAt = [&](double elevationDeg) {
    const double e = elevationDeg * std::numbers::pi / 180.0;
    return glm::dvec3(std::cos(e), 0.0, std::sin(e));
  };
  // From 400 km the cap reaches 20.2° (and 3.0° more to see a 9 km peak): the sun 35° up at the
  // nadir is above every horizon in it; 20° up it is not.
  EXPECT_FALSE(nightInView(up * (radius + 4.0e5), sunAt(35.0), radius, 9000.0, 0.0));
  EXPECT_TRUE(nightInView(up * (radius + 4.0e5), sunAt(20.0), radius, 9000.0, 0.0));
  // From 20,000 km nearly a hemisphere is in view: night is, unless the sun stands at the nadir.
  EXPECT_TRUE(nightInView(up * (radius + 2.0e7), sunAt(35.0), radius, 9000.0, 0.0));
  EXPECT_FALSE(nightInView(up * (radius + 2.0e7), sunAt(90.0), radius, 9000.0, 0.0));
  // 160x90 at 60°: f = 77.94 pixels, the corner 91.79 pixels from the centre: 5.375e-3 rad.
  const double fov = std::numbers::pi / 3.0;
  EXPECT_NEAR(smallestFootprintM(up * (radius + 10000.0), radius, 9000.0, fov, 160, 90), 1000.0 * 5.375e-3, 1e-3);
  EXPECT_EQ(smallestFootprintM(up * (radius + 8000.0), radius, 9000.0, fov, 160, 90), 0.0);
  // The relief cube (512 texels a side: 3.9e-3 rad) takes pixels wider than an eighth of that
  // across the line of sight. At 640x360 (f = 311.8 pixels) a pixel 600 km away is 3.0e-4 rad
  // wide on Earth, so pixels need to lie beyond 970 km (924 km with the 5 % margin): an outer
  // ring 0.09 rad out (574 km) or 0.12 rad (765 km) is too near, 0.16 rad (1,020 km) is not.
  EXPECT_FALSE(reliefInView(radius, 600.0, 0.09, 0.0, 7200.0, fov, 360, 512));
  EXPECT_FALSE(reliefInView(radius, 600.0, 0.12, 0.0, 7200.0, fov, 360, 512));
  EXPECT_TRUE(reliefInView(radius, 600.0, 0.16, 0.0, 7200.0, fov, 360, 512));
  EXPECT_TRUE(reliefInView(radius, 600.0, 0.09, 0.0, 7200.0, fov, 90, 512)) << "at 160x90 pixels are 4x wider";
  // Per band (TerrainPass::drawsFor). The footprint beyond the pole is smallestFootprintM's; 2 m up
  // among 9 km peaks, ground 1 km away (θ = 1 km / radius) may stand at the camera's height, so
  // its footprint is 1 km times the corner pixel's angle.
  EXPECT_NEAR(footprintBeyondM(radius, 10000.0, 0.0, 0.0, 9000.0, fov, 160, 90), 1000.0 * 5.375e-3, 1e-3);
  EXPECT_NEAR(footprintBeyondM(radius, 2.0, 1000.0 / radius, 0.0, 9000.0, fov, 160, 90), 1000.0 * 5.375e-3, 2e-3);
  EXPECT_LT(footprintBeyondM(radius, 2.0, 500.0 / radius, 0.0, 9000.0, fov, 160, 90), 2.7);
  // The sun 35° up at the centre: the terminator is 55° away, and the 1° margin reaches it from 34°.
  EXPECT_FALSE(nightWithin(up, sunAt(35.0), 33.5 * std::numbers::pi / 180.0));
  EXPECT_TRUE(nightWithin(up, sunAt(35.0), 34.5 * std::numbers::pi / 180.0));
  EXPECT_FALSE(reliefInView(radius, 4.0e5, 1.0, 0.0, 7200.0, fov, 360, kReliefStandInSize)) << "a stand-in";
}

// Leaving out what a view cannot show leaves the picture bit for bit as it was: each view drawn
// with the frame's shading and with every part the planet has, from the sky (night in view or
// not) to 2 m. And the views do leave parts out (else the test would prove nothing): whole frames,
// and runs of bands within a frame (TerrainPass::drawsFor): the detail octaves only in the bands
// near the camera, the city lights only in the bands that reach the night.
TEST_F(TerrainRender, ShadingWithoutWhatTheViewCannotShowDrawsTheSamePicture) {
  const PlanetDescription planet = resolvePreset("earth");
  RenderSettings all = smallSettings(true);
  all.terrain.shadingPerFrame = false;
  Renderer perFrame(context(), planet, smallSettings(true));
  Renderer everything(context(), planet, all);
  const double peaks = perFrame.terrain().maxTerrainHeightM();
  enum class Split { None, NearDetail, FarLights, FarRelief };
  struct Case {
    CameraPose camera;
    SunPose sun;
    bool lights, detail;
    Split split;
  };
  const Case cases[] = {
      {{kLat, kLon, 4.0e5, 0.0, -90.0}, {135.0, 35.0}, false, false, Split::None},  // day from 400 km
      {{kLat, kLon, 1.2e7, 0.0, -90.0}, {135.0, -30.0}, true, false, Split::None},  // night below, from orbit
      // Day below, the terminator toward the limb: the outer bands only take the lights.
      {{kLat, kLon, 1.2e7, 0.0, -90.0}, {135.0, 35.0}, true, false, Split::FarLights},
      // Just too high for the detail; the relief cube only in the far bands.
      {{kLat, kLon, peaks + 600.0, 60.0, -20.0}, {135.0, 35.0}, false, false, Split::FarRelief},
      // 2 m above the ground: the bands within ~400 m only take the detail.
      {{kLat, kLon, 2.0, 60.0, -20.0}, {135.0, 35.0}, false, true, Split::NearDetail}};
  for (const Case& c : cases) {
    SCOPED_TRACE("altitude " + std::to_string(c.camera.altitudeM));
    const RenderResult shaded = perFrame.render(c.camera, c.sun);
    const RenderResult reference = everything.render(c.camera, c.sun);
    const TerrainFrameInfo& frame = perFrame.terrain().frame();
    EXPECT_EQ(frame.shading.lights, c.lights);
    EXPECT_EQ(frame.shading.groundDetail, c.detail);
    EXPECT_TRUE(everything.terrain().frame().shading.lights && everything.terrain().frame().shading.groundDetail);
    ASSERT_EQ(everything.terrain().frame().draws.size(), 1u) << "one draw with everything";
    ASSERT_FALSE(frame.draws.empty());
    const TerrainShading& nearest = frame.draws.front().shading;
    const TerrainShading& farthest = frame.draws.back().shading;
    for (const TerrainDraw& draw : frame.draws)
      EXPECT_EQ(draw.shading.key() & ~frame.shading.key(), 0u) << "a draw has a part the frame cannot show";
    switch (c.split) {
      case Split::None: EXPECT_EQ(frame.draws.size(), 1u); break;
      case Split::NearDetail: EXPECT_TRUE(nearest.groundDetail && !farthest.groundDetail); break;
      case Split::FarLights: EXPECT_TRUE(!nearest.lights && farthest.lights); break;
      case Split::FarRelief: EXPECT_TRUE(!nearest.relief && farthest.relief); break;
    }
    EXPECT_EQ(shaded.image.pixels, reference.image.pixels);
  }
}

// The ground whose triangles lie too far above sea level for any pixel to be under the sea is
// drawn first with the early depth test (terrain_split.comp), the rest with its depth pushed back
// as before, and the water only over the latter: the pictures are the same bit for bit, inland,
// on a coast and from orbit, and the early list holds most of the ground inland, part of it on
// the coast.
TEST_F(TerrainRender, GroundThatCannotBeSeaFloorIsDrawnFirstAndThePictureIsTheSame) {
  const PlanetDescription planet = resolvePreset("earth");
  RenderSettings unsplitSettings = smallSettings(true);
  unsplitSettings.terrain.splitSeaFloor = false;
  Renderer split(context(), planet, smallSettings(true));
  Renderer unsplit(context(), planet, unsplitSettings);
  struct Case {
    const char* name;
    CameraPose camera;
    double minDryShare, maxDryShare;  // of the drawn triangles, in the early-depth list
  };
  const Case cases[] = {
      // Measured 86 % and 32 % (far triangles are wide, and their margin with them).
      {"mountains, 2 m above the ground", {kLat, kLon, 2.0, 60.0, -20.0}, 0.75, 1.0},
      {"mountains from 5 km", {kLat, kLon, 5000.0, 60.0, -10.0}, 0.2, 1.0},
      {"a coast from 1 km", {33.8, -90.0, 1000.0, 20.0, -15.0}, 0.05, 0.95},
      {"from orbit", {kLat, kLon, 4.0e5, 0.0, -90.0}, 0.0, 1.0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const RenderResult a = split.render(c.camera, {135.0, 35.0});
    const RenderResult b = unsplit.render(c.camera, {135.0, 35.0});
    EXPECT_EQ(a.image.pixels, b.image.pixels) << "the split changed the picture";
    const TerrainFrameInfo& frame = split.terrain().frame();
    ASSERT_TRUE(frame.seaFloorSplit);
    EXPECT_FALSE(unsplit.terrain().frame().seaFloorSplit);
    ASSERT_NE(split.terrain().dryTriangles(), nullptr);
    std::vector<uint32_t> dry(3 * size_t(frame.triangles));
    vk::readbackBuffer(context(), *split.terrain().dryTriangles(), dry.data(), dry.size() * sizeof(uint32_t));
    size_t kept = 0;
    for (size_t t = 0; t < frame.triangles; ++t)
      if (dry[3 * t] != dry[3 * t + 1] || dry[3 * t] != dry[3 * t + 2]) ++kept;
    const double share = double(kept) / double(frame.triangles);
    std::printf("sea floor split, %s: %zu of %zu triangles drawn with the early depth test (%.0f %%)\n", c.name, kept,
                size_t(frame.triangles), 100.0 * share);
    EXPECT_GE(share, c.minDryShare) << kept << " of " << frame.triangles;
    EXPECT_LE(share, c.maxDryShare) << kept << " of " << frame.triangles;
  }
  // Without a sea nothing is pushed back: all of the ground takes the early depth test already.
  Renderer moon(context(), resolvePreset("moon"), smallSettings(true));
  moon.render({kLat, kLon, 2.0, 60.0, -20.0}, {135.0, 35.0});
  EXPECT_FALSE(moon.terrain().frame().seaFloorSplit);
}

// Deferred shading (TerrainSettings::deferredShading): the draw writes the ground's surface into
// the G-buffer and a compute pass shades it with the same code (terrain_shade.glsl), so the
// picture is the forward one bit for bit: over land and sea (the sea floor pushed back), at
// night with city lights, from orbit, on bodies without a sea (the early depth test) and with
// the seed schemes. Its scopes follow one another: the ground's draw, its shading, the sea. A
// wireframe frame is drawn forward, and a scene (several bodies) is refused.
TEST_F(TerrainRender, DeferredShadingDrawsTheForwardPicture) {
  struct Case {
    const char* name;
    const char* preset;
    CameraPose camera;
    SunPose sun;
  };
  const Case cases[] = {
      {"mountains, 2 m above the ground", "earth", {kLat, kLon, 2.0, 60.0, -20.0}, {135.0, 35.0}},
      {"a coast from 1 km", "earth", {33.8, -90.0, 1000.0, 20.0, -15.0}, {135.0, 35.0}},
      {"city lights at night from 800 km", "earth", {45.0, 5.0, 8.0e5, 0.0, -80.0}, {135.0, -40.0}},
      {"from orbit", "earth", {kLat, kLon, 2.0e7, 0.0, -90.0}, {135.0, 35.0}},
      {"the moon from 3 km", "moon", {10.0, 10.0, 3000.0, 0.0, -20.0}, {135.0, 20.0}},
      {"a seed scheme (faults) from 100 km", "faults", {0.0, 0.0, 1.0e5, 0.0, -30.0}, {135.0, 35.0}},
  };
  RenderSettings deferredSettings = smallSettings(true);
  deferredSettings.terrain.deferredShading = true;
  deferredSettings.autoExposure = true;  // the night's lights show
  RenderSettings forwardSettings = smallSettings(true);
  forwardSettings.autoExposure = true;
  std::string preset;
  std::unique_ptr<Renderer> forward, deferred;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    if (preset != c.preset) {
      preset = c.preset;
      forward = std::make_unique<Renderer>(context(), resolvePreset(preset), forwardSettings);
      deferred = std::make_unique<Renderer>(context(), resolvePreset(preset), deferredSettings);
    }
    const RenderResult a = forward->render(c.camera, c.sun);
    const RenderResult b = deferred->render(c.camera, c.sun);
    ASSERT_TRUE(deferred->terrain().shadesDeferred());
    EXPECT_FALSE(forward->terrain().shadesDeferred());
    EXPECT_EQ(a.image.pixels, b.image.pixels) << "the deferred shading changed the picture";
    // Not a blank picture that would match anything: the ground is drawn.
    double sum = 0.0;
    for (size_t i = 0; i < b.image.pixels.size(); i += 4)
      sum += (b.image.pixels[i] + b.image.pixels[i + 1] + b.image.pixels[i + 2]) / 3.0;
    const double mean = sum / double(b.image.pixels.size() / 4);
    std::printf("deferred shading, %s: mean %.1f of 255\n", c.name, mean);
    EXPECT_GT(mean, 1.0);
    if (!context().timestampValidBits) continue;
    std::vector<std::string> names;
    for (const vk::GpuTiming& t : b.timings) names.push_back(t.name);
    const auto terrain = std::find(names.begin(), names.end(), "terrain");
    ASSERT_NE(terrain, names.end());
    ASSERT_LT(terrain + 1, names.end());
    EXPECT_EQ(*(terrain + 1), "ground shading");
    const vk::GpuTiming& draw = b.timings[size_t(terrain - names.begin())];
    const vk::GpuTiming& shading = b.timings[size_t(terrain - names.begin()) + 1];
    EXPECT_NEAR(shading.startMs, draw.startMs + draw.milliseconds, 1e-6) << "the scopes are back to back";
    for (const vk::GpuTiming& t : a.timings) EXPECT_NE(t.name, "ground shading");
  }
  // The wireframe colours the edges in the draw itself: forward, in a deferred renderer too.
  RenderSettings wireframe = deferredSettings;
  wireframe.terrain.wireframe = true;
  RenderSettings wireframeForward = forwardSettings;
  wireframeForward.terrain.wireframe = true;
  Renderer deferredWires(context(), resolvePreset("earth"), wireframe);
  Renderer forwardWires(context(), resolvePreset("earth"), wireframeForward);
  const CameraPose camera{kLat, kLon, 5000.0, 60.0, -10.0};
  EXPECT_EQ(deferredWires.render(camera, {135.0, 35.0}).image.pixels,
            forwardWires.render(camera, {135.0, 35.0}).image.pixels);
  EXPECT_FALSE(deferredWires.terrain().shadesDeferred());
  // A scene's bodies would share the G-buffer, which one body's uniforms shade.
  EXPECT_EQ(errorOf([&] { Renderer scene(context(), resolveScene("system"), deferredSettings); }),
            "terrain shading 'deferred' draws one body, the scene has 3; use 'forward'");
}

// The relief cube's lookup is left out of frames where no pixel can take it (reliefInView): low
// over the ground at 320x180 the farthest drawn ground is too near for a pixel to span an eighth
// of a relief texel, and the picture is the same bit for bit as with the lookup; from 400 km it
// is kept.
TEST_F(TerrainRender, TheReliefCubeIsLeftOutWhereNoPixelCanTakeIt) {
  const PlanetDescription planet = resolvePreset("earth");
  RenderSettings settings = smallSettings(true);
  settings.width = 320;
  settings.height = 180;
  RenderSettings all = settings;
  all.terrain.shadingPerFrame = false;
  Renderer perFrame(context(), planet, settings);
  Renderer everything(context(), planet, all);
  const CameraPose low{kLat, kLon, 600.0, 60.0, -3.0};
  const RenderResult shaded = perFrame.render(low, {});
  const RenderResult reference = everything.render(low, {});
  EXPECT_FALSE(perFrame.terrain().frame().shading.relief);
  EXPECT_TRUE(everything.terrain().frame().shading.relief);
  EXPECT_EQ(shaded.image.pixels, reference.image.pixels);
  perFrame.render({kLat, kLon, 4.0e5, 0.0, -60.0}, {});
  EXPECT_TRUE(perFrame.terrain().frame().shading.relief);
}

// The sea covers every pixel whose patch height is below sea level, also where the mesh's coarser
// triangle lies above it (terrain.frag pushes the pixel back to twice its distance, and the water
// draws over it). Without that, coasts seen from 200 km had a fringe of bare sand polygons.
// The reference is the water-off render, which shows the sea in its own blue colours where the
// patch heights are below sea level. Only pixels whose four neighbours are sea there too count,
// so that a pixel across the coastline does not; of those, the water render may show almost none
// as bare sand (red at least blue; fewer than 70). Shallow water over sand is tinted blue.
// Measured on lavapipe: 7 of 88,002 such pixels are bare sand, 685 without the push-back.
TEST_F(TerrainRender, TheSeaCoversEveryPixelOfGroundBelowSeaLevel) {
  PlanetDescription planet = resolvePreset("earth");
  planet.clouds.enabled = false;
  auto render = [&](bool water) {
    RenderSettings settings;
    settings.width = 480;
    settings.height = 270;
    settings.terrain.water = water;
    Renderer renderer(context(), planet, settings);
    return renderer.render({40.0, 10.0, 2.0e5, 0.0, -40.0}, {135.0, 35.0}).image;
  };
  const Rgba8Image withWater = render(true);
  const Rgba8Image withoutWater = render(false);
  writePng((std::filesystem::path(testOutputDir()) / "sea_over_the_sea_floor.png").string(), withWater);
  const int w = int(withWater.width), h = int(withWater.height);
  auto at = [](const Rgba8Image& image, int x, int y) { return &image.pixels[(size_t(y) * image.width + x) * 4]; };
  auto sea = [&](int x, int y) { return looksLikeSea(at(withoutWater, x, y)); };
  int inner = 0, bare = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      if (!(sea(x, y) && sea(x - 1, y) && sea(x + 1, y) && sea(x, y - 1) && sea(x, y + 1))) continue;
      ++inner;
      const uint8_t* p = at(withWater, x, y);
      bare += p[0] >= p[2];
    }
  std::printf("pixels below sea level (not at the coast): %d, of which bare sand with the water on: %d\n", inner, bare);
  ASSERT_GT(inner, 20000) << "the view should hold sea";
  EXPECT_LT(bare, 70);
}

// Fraction of pixels brighter than black on a circle of radius r pixels about the centre.
double litFraction(const Rgba8Image& image, double r) {
  int lit = 0;
  const int samples = 64;
  for (int k = 0; k < samples; ++k) {
    const double a = 2.0 * std::numbers::pi * (k + 0.5) / samples;
    const int x = int(std::floor(image.width / 2.0 + r * std::cos(a)));
    const int y = int(std::floor(image.height / 2.0 + r * std::sin(a)));
    const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
    lit += (p[0] + p[1] + p[2]) > 6 ? 1 : 0;
  }
  return double(lit) / samples;
}

TEST_F(TerrainRender, LimbIsWhereTheGeometrySays) {
  PlanetDescription planet = resolvePreset("moon");  // no ocean: bright everywhere in daylight
  planet.stars.enabled = false;                      // only the planet lights pixels
  RenderSettings settings = smallSettings(false);
  settings.width = 200;
  settings.height = 200;
  Renderer renderer(context(), planet, settings);
  for (double altitude : {2.0e6, 8.0e6}) {
    RenderResult result = renderer.render({10.0, 20.0, altitude}, {0.0, 90.0});  // sun overhead
    // Angular radius of the sphere seen from r + h, in pixels of a 60° field of view.
    const double alpha = std::asin(planet.radiusM / (planet.radiusM + altitude));
    const double limbPx = 100.0 * std::tan(alpha) / std::tan(std::numbers::pi / 6.0);
    EXPECT_EQ(litFraction(result.image, limbPx - 3.0), 1.0) << altitude;
    EXPECT_EQ(litFraction(result.image, limbPx + 3.0), 0.0) << altitude;
  }
}

// From 2 m above mars's northern lowlands (4.5 km below its radius sphere), the ground is drawn up
// to the horizon. The horizon cut once took the radius sphere as the lowest surface, so the mesh
// ended short of the ground that sight lines below that sphere's horizon reach: a black wedge
// under the hazy sky. In daylight with air no pixel below the horizon is that dark.
TEST_F(TerrainRender, GroundBelowTheRadiusSphereIsDrawnToTheHorizon) {
  const PlanetDescription mars = resolvePreset("mars");
  const CameraPose camera{30.0, -60.0, 2.0, 60.0, 5.0};
  ASSERT_LT(terrainHeightM(mars, directionFromLatLon(camera.latitudeDeg, camera.longitudeDeg)), -100.0);
  RenderSettings settings = smallSettings(true);
  settings.width = 320;
  settings.height = 180;
  const Rgba8Image image = Renderer(context(), mars, settings).render(camera, {100.0, 30.0}).image;
  size_t dark = 0;
  for (size_t i = 0; i < image.pixels.size(); i += 4)
    dark += std::max({image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]}) < 20 ? 1 : 0;
  EXPECT_EQ(dark, 0u);
}

TEST_F(TerrainRender, SameInputsGiveIdenticalImagesAndSeedsChangeThePlanet) {
  PlanetDescription planet = resolvePreset("earth");
  const CameraPose camera{36.0, -87.0, 4.0e5, 30.0, -45.0};  // land at seed 0, ocean at seed 1
  Rgba8Image first, second;
  {
    Renderer renderer(context(), planet, smallSettings(true));
    first = renderer.render(camera, {}).image;
  }
  {
    // The second renderer's first frame is a benchmark's, not read back; the frame after it
    // reads and must be the same picture.
    Renderer renderer(context(), planet, smallSettings(true));
    renderer.setReadImage(false);
    const RenderResult unread = renderer.render(camera, {});
    EXPECT_TRUE(unread.image.pixels.empty());
    EXPECT_EQ(unread.image.width, 0u);
    renderer.setReadImage(true);
    second = renderer.render(camera, {}).image;
  }
  EXPECT_EQ(encodePng(first), encodePng(second));
  for (NoiseLayer& layer : planet.layers) layer.noise.seed += 1;
  Renderer renderer(context(), planet, smallSettings(true));
  EXPECT_LT(psnrRgb(first, renderer.render(camera, {}).image), 30.0);
}

// The patch levels are stored toroidally: a level that moved by a recentre step computes only
// the strips it newly covers and the terrain samples it through its wrap offset. A low flight
// that moves the levels strip by strip must then draw what levels built whole at the end draw.
TEST_F(TerrainRender, PatchLevelsMovedStripByStripDrawWhatAWholeBuildDraws) {
  const PlanetDescription planet = resolvePreset("earth");
  const RenderSettings settings = smallSettings(true);
  Renderer renderer(context(), planet, settings);
  const double altitude = renderer.clampToGround({kLat, kLon, -1.0e5}).altitudeM + 30.0;
  const glm::dvec3 start = directionFromLatLon(kLat, kLon);
  const uint64_t wholeTexels =
      uint64_t(settings.terrain.patchSettings.levelCount) * settings.terrain.patchSettings.resolution *
      settings.terrain.patchSettings.resolution;
  CameraPose pose;
  uint32_t stripFrames = 0;
  // 7 m a frame (the finest level's recentre step here is ~11 m), 12 frames.
  for (int frame = 0; frame <= 12; ++frame) {
    const glm::dvec3 p = travelGreatCircle(start, 60.0, 7.0 * frame, planet.radiusM);
    pose = {latitudeDegOf(p), longitudeDegOf(p), altitude, 60.0, -30.0};
    renderer.render(pose, {});
    const TerrainFrameInfo& info = renderer.terrain().frame();
    if (frame > 0 && info.patchLevelsRebuilt > 0) {
      EXPECT_LT(info.patchTexelsWritten, wholeTexels / 4) << "frame " << frame << ": only new strips";
      ++stripFrames;
    }
  }
  EXPECT_GE(stripFrames, 3u) << "the flight should move the finest level several times";
  const Rgba8Image strips = renderer.render(pose, {}).image;
  EXPECT_EQ(renderer.terrain().frame().patchTexelsWritten, 0u);
  renderer.terrain().invalidatePatches();
  const Rgba8Image whole = renderer.render(pose, {}).image;
  EXPECT_EQ(renderer.terrain().frame().patchTexelsWritten, wholeTexels);
  int worst = 0;
  for (size_t i = 0; i < strips.pixels.size(); ++i) worst = std::max(worst, std::abs(int(strips.pixels[i]) - int(whole.pixels[i])));
  const double psnr = psnrRgb(strips, whole);
  std::printf("[ measured ] strip-by-strip vs whole patch levels: PSNR %.1f dB, largest channel difference %d\n", psnr,
              worst);
  // The kept texels carry the octave budget of where their level was (an ulp of height).
  EXPECT_LE(worst, 2);
  // And a renderer that starts at the end pose: its mesh may be turned differently (it has no
  // flight behind it), the patch texels are the same points, so the pictures agree closely.
  // (Where in its layer a level is sampled, the wrap offset, is what the golden images check:
  // without it they fail.)
  Renderer fresh(context(), planet, settings);
  const double freshPsnr = psnrRgb(strips, fresh.render(pose, {}).image);
  std::printf("[ measured ] after the flight vs a renderer started there: PSNR %.1f dB\n", freshPsnr);
  EXPECT_GE(freshPsnr, 40.0);
}

// With the real-time budget of patch texels per frame (the viewer's and the benchmark's, issue 12
// point 5) the first frame is a load (everything built whole); after a jump the levels it makes
// new are built over several frames, coarsest first, each from a square at its centre grown by
// strips, and no frame writes more than the budget (plus, at most, the one strip every frame may
// take). The frames between draw from what the textures hold: a level is sampled only where its
// layer holds it, the rest goes to coarser levels, so there are no holes; the last frame draws
// what one unbudgeted frame draws, bit for bit.
TEST_F(TerrainRender, APatchBudgetSpreadsNewLevelsOverFramesAndEndsWithTheSamePicture) {
  const PlanetDescription planet = resolvePreset("earth");
  RenderSettings budgeted = smallSettings(true);
  const PatchSettings& patch = budgeted.terrain.patchSettings;
  const uint64_t budget = realTimePatchBudget(patch);
  const uint64_t firstStrip = uint64_t(PatchTextures::kMinStripTexels) * patch.resolution;
  budgeted.terrain.patchTexelsPerFrame = budget;
  Renderer renderer(context(), planet, budgeted);
  const RenderResult start = renderer.render({kLat, kLon, 3000.0, 30.0, -20.0}, {});
  EXPECT_EQ(start.terrain.patchLevelsDeferred, 0u) << "the first frame builds everything";
  EXPECT_EQ(start.terrain.patchTexelsWritten, uint64_t(patch.levelCount) * patch.resolution * patch.resolution);

  const CameraPose pose{kLat, kLon, 40.0, 30.0, -20.0};  // every level's exponent changes
  Rgba8Image whole;
  {
    Renderer single(context(), planet, smallSettings(true));
    whole = single.render(pose, {}).image;
  }
  RenderResult frame = renderer.render(pose, {});
  const Rgba8Image first = frame.image;
  EXPECT_GT(frame.terrain.patchLevelsDeferred, 0u);
  uint32_t frames = 1;
  uint64_t written = frame.terrain.patchTexelsWritten;
  while (frame.terrain.patchLevelsDeferred > 0 && frames < 100) {
    EXPECT_LE(frame.terrain.patchTexelsWritten, std::max(budget, firstStrip)) << "frame " << frames;
    frame = renderer.render(pose, {});
    written += frame.terrain.patchTexelsWritten;
    ++frames;
  }
  EXPECT_EQ(frame.terrain.patchLevelsDeferred, 0u);
  const double early = psnrRgb(first, whole);
  std::printf("[ measured ] %u frames to build the levels (%llu texels), the first frame against the whole build: "
              "%.1f dB\n",
              frames, (unsigned long long)written, early);
  // The new levels' texels (each once), in about as many frames as the budget needs for them.
  const uint64_t levelTexels = uint64_t(patch.resolution) * patch.resolution;
  EXPECT_LE(written, uint64_t(patch.levelCount) * levelTexels);
  EXPECT_GE(frames, uint32_t(written / budget));
  EXPECT_LE(frames, uint32_t(2 * written / budget + patch.levelCount));
  EXPECT_GE(early, 25.0);
  // One more frame: everything is built, and it is the unbudgeted picture.
  frame = renderer.render(pose, {});
  EXPECT_EQ(frame.terrain.patchLevelsRebuilt, 0u);
  EXPECT_EQ(frame.image.pixels, whole.pixels);
}

TEST_F(TerrainRender, TwoMetresAboveTheGroundVerticesAreDenserThanHalfAMetre) {
  const PlanetDescription planet = resolvePreset("earth");
  Renderer renderer(context(), planet, smallSettings(false));
  RenderResult result = renderer.render({kLat, kLon, -100.0, 0.0, -20.0}, {});
  EXPECT_TRUE(result.cameraRaised);
  EXPECT_NEAR(result.terrain.heightAboveGroundM, kMinEyeHeightM, 0.05);
  EXPECT_LT(result.terrain.metresPerVertexAtNadir, 0.5);
  // The fan that closes the mesh under the camera is a few pixels wide (here 160x90 pixels).
  const double pixelM = result.terrain.heightAboveGroundM * std::tan(std::numbers::pi / 6.0) / 45.0;
  EXPECT_LT(result.terrain.poleCapRadiusM, 4.0 * pixelM);
}

// Freeze-LOD (the viewer's debug view): the mesh of the frame before freezing stays, drawn from
// wherever the camera goes; without the freeze the LOD follows the camera.
TEST_F(TerrainRender, FrozenLodKeepsTheMeshAndDrawsItFromTheMovedCamera) {
  PlanetDescription planet = resolvePreset("moon");  // no air, no ocean: lit pixels are ground
  planet.stars.enabled = false;
  // A frozen mesh keeps the cells its own frame's frustum kept: the whole rings here, so that the
  // view from aside (beyond the straight-down start's frustum) has ground to show.
  RenderSettings settings = smallSettings(true);
  settings.terrain.frustumCulling = false;
  Renderer renderer(context(), planet, settings);
  TerrainPass& terrain = renderer.terrain();
  const SunPose sun{0.0, 60.0};
  const CameraPose start{-20.0, 40.0, 3000.0, 0.0, -90.0};
  const RenderResult before = renderer.render(start, sun);
  EXPECT_FALSE(before.terrain.lodFrozen);

  terrain.setFreezeLod(true);
  EXPECT_TRUE(terrain.freezeLod());
  // Frozen where it was: the same frame, nothing recomputed, the same picture.
  const RenderResult same = renderer.render(start, sun);
  EXPECT_TRUE(same.terrain.lodFrozen);
  EXPECT_FALSE(same.terrain.heightsComputed);
  EXPECT_EQ(same.image.pixels, before.image.pixels);

  auto expectFrozen = [&](const TerrainFrameInfo& frame, const char* what) {
    EXPECT_TRUE(frame.lodFrozen) << what;
    EXPECT_EQ(frame.rings.firstRing, before.terrain.rings.firstRing) << what;
    EXPECT_EQ(frame.rings.lastRing, before.terrain.rings.lastRing) << what;
    EXPECT_EQ(frame.orientation.localToPlanet, before.terrain.orientation.localToPlanet) << what;
    EXPECT_EQ(frame.metresPerVertexAtNadir, before.terrain.metresPerVertexAtNadir) << what;
    EXPECT_EQ(frame.patchLayout.levels[0].originA, before.terrain.patchLayout.levels[0].originA) << what;
    EXPECT_FALSE(frame.heightsComputed) << what;
    EXPECT_EQ(frame.patchLevelsRebuilt, 0u) << what;
  };

  // Ten times higher, still looking down: the frozen cap (cut for 3 km) fills the view.
  const CameraPose high{start.latitudeDeg, start.longitudeDeg, 10.0 * start.altitudeM, 0.0, -90.0};
  const RenderResult frozenHigh = renderer.render(high, sun);
  expectFrozen(frozenHigh.terrain, "high");
  EXPECT_NEAR(frozenHigh.terrain.viewOrientation.altitudeM, high.altitudeM, 1e-6);
  EXPECT_EQ(litFraction(frozenHigh.image, 10.0), 1.0);
  EXPECT_EQ(litFraction(frozenHigh.image, 40.0), 1.0);
  EXPECT_NE(frozenHigh.image.pixels, before.image.pixels);

  // Sideways by 600 m, looking ahead and down: the frozen mesh seen from there shows what the
  // LOD chosen there shows (the same ground, slightly different vertices), unlike the view
  // from where the LOD was frozen.
  const CameraPose side{start.latitudeDeg, start.longitudeDeg + 0.02, start.altitudeM, 60.0, -35.0};
  const CameraPose sideFromStart{start.latitudeDeg, start.longitudeDeg, start.altitudeM, 60.0, -35.0};
  const RenderResult frozenSide = renderer.render(side, sun);
  expectFrozen(frozenSide.terrain, "side");
  terrain.setFreezeLod(false);
  const RenderResult liveSide = renderer.render(side, sun);
  EXPECT_FALSE(liveSide.terrain.lodFrozen);
  EXPECT_TRUE(liveSide.terrain.heightsComputed);
  EXPECT_NE(liveSide.terrain.orientation.localToPlanet, before.terrain.orientation.localToPlanet);
  const RenderResult liveSideFromStart = renderer.render(sideFromStart, sun);
  const double psnrSide = psnrRgb(frozenSide.image, liveSide.image);
  const double psnrWrong = psnrRgb(frozenSide.image, liveSideFromStart.image);
  std::printf("frozen view from 600 m aside: PSNR %.1f dB against the live view there, %.1f dB against the start\n",
              psnrSide, psnrWrong);
  EXPECT_GT(psnrSide, 30.0);
  EXPECT_GT(psnrSide, psnrWrong + 6.0);

  // Unfrozen, the LOD follows the camera up.
  const RenderResult liveHigh = renderer.render(high, sun);
  EXPECT_FALSE(liveHigh.terrain.lodFrozen);
  EXPECT_NE(liveHigh.terrain.rings.lastRing, before.terrain.rings.lastRing);
  EXPECT_GT(liveHigh.terrain.metresPerVertexAtNadir, 5.0 * before.terrain.metresPerVertexAtNadir);
}

// The viewer's live toggles give the pictures of passes built with those settings, and toggling
// back gives the first picture again (without rebuilding the patch textures).
TEST_F(TerrainRender, TogglesDrawWhatTheSettingsWouldHave) {
  const PlanetDescription planet = resolvePreset("earth");
  const CameraPose camera{33.8, -90.0, 3500.0, 30.0, -12.0};  // land, coast and sea in view
  auto renderWith = [&](void (*change)(TerrainSettings&)) {
    RenderSettings settings = smallSettings(true);
    change(settings.terrain);
    Renderer renderer(context(), planet, settings);
    return renderer.render(camera, {}).image;
  };
  const Rgba8Image wireframe = renderWith([](TerrainSettings& t) { t.wireframe = true; });
  const Rgba8Image dry = renderWith([](TerrainSettings& t) { t.water = false; });
  const Rgba8Image bright = renderWith([](TerrainSettings& t) {
    t.sunIntensity = 3.0;
    t.ambient = 0.2;
  });

  Renderer renderer(context(), planet, smallSettings(true));
  TerrainPass& terrain = renderer.terrain();
  const RenderResult first = renderer.render(camera, {});
  EXPECT_TRUE(first.terrain.waterDrawn);
  EXPECT_FALSE(first.terrain.wireframe);

  terrain.setWireframe(true);
  const RenderResult edges = renderer.render(camera, {});
  EXPECT_TRUE(edges.terrain.wireframe);
  EXPECT_FALSE(edges.terrain.waterDrawn);
  EXPECT_TRUE(edges.terrain.patchLayout.levels.empty());
  EXPECT_EQ(edges.terrain.patchLevelsRebuilt, 0u);
  EXPECT_EQ(edges.image.pixels, wireframe.pixels);
  terrain.setWireframe(false);
  const RenderResult back = renderer.render(camera, {});
  EXPECT_EQ(back.terrain.patchLevelsRebuilt, 0u);  // the layout is the one the textures hold
  EXPECT_EQ(back.image.pixels, first.image.pixels);

  terrain.setWaterEnabled(false);
  const RenderResult noWater = renderer.render(camera, {});
  EXPECT_FALSE(noWater.terrain.waterDrawn);
  EXPECT_EQ(noWater.image.pixels, dry.pixels);
  terrain.setWaterEnabled(true);
  EXPECT_EQ(renderer.render(camera, {}).image.pixels, first.image.pixels);

  terrain.setSunIntensity(3.0);
  terrain.setAmbient(0.2);
  EXPECT_EQ(renderer.render(camera, {}).image.pixels, bright.pixels);
  terrain.setSunIntensity(TerrainSettings{}.sunIntensity);
  terrain.setAmbient(TerrainSettings{}.ambient);
  EXPECT_EQ(renderer.render(camera, {}).image.pixels, first.image.pixels);

  // A pass that started in wireframe builds its patch textures when the wireframe goes.
  RenderSettings settings = smallSettings(true);
  settings.terrain.wireframe = true;
  Renderer started(context(), planet, settings);
  EXPECT_EQ(started.render(camera, {}).image.pixels, wireframe.pixels);
  started.terrain().setWireframe(false);
  const RenderResult filled = started.render(camera, {});
  EXPECT_EQ(filled.terrain.patchLevelsRebuilt, 4u);
  EXPECT_EQ(filled.image.pixels, first.image.pixels);
}

// Light from the ground around (terrain.frag): a slope turned from the sun sees the sunlit ground
// below its horizon. On Mars without its air and with no fill light there is no other light in
// the shade, so before, such slopes were black; lit by ground of the same colour, their light is
// the albedo's colour twice over (albedo²), redder than the sunlit ground's (albedo alone).
TEST_F(TerrainRender, SlopesTurnedFromTheSunAreLitByTheGroundAround) {
  PlanetDescription planet = resolvePreset("mars");
  planet.atmosphere.enabled = false;
  RenderSettings settings = smallSettings(true);
  settings.terrain.ambient = 0.0;
  Renderer renderer(context(), planet, settings);
  // Looking down at rough ground with the sun 4 degrees up: many slopes face away from it.
  const RenderResult result = renderer.render({-14.0, -70.0, 15000.0, 0.0, -40.0}, {90.0, 4.0}, 0.0, true);
  std::vector<std::pair<double, double>> byLight;  // (r + g + b, r / b) per pixel
  for (const glm::vec4& p : result.hdr) {
    ASSERT_GT(p.r + p.g + p.b, 0.0f) << "a pixel in the shade is black: no light from the ground around";
    byLight.emplace_back(p.r + p.g + p.b, p.r / p.b);
  }
  std::sort(byLight.begin(), byLight.end());
  auto meanRedOverBlue = [&](size_t from, size_t to) {
    double sum = 0.0;
    for (size_t i = from; i < to; ++i) sum += byLight[i].second;
    return sum / double(to - from);
  };
  const size_t n = byLight.size();
  const double shade = meanRedOverBlue(0, n / 20), sunlit = meanRedOverBlue(n / 2, n);
  ASSERT_GT(byLight[n / 2].first, 20.0 * byLight[n / 20].first) << "the view should show shaded slopes";
  EXPECT_GT(shade, 1.5 * sunlit) << "the shade's light should be the ground's colour twice over";
}

// Golden images: lavapipe on Debian 12 renders these bit for bit today; the PSNR threshold
// leaves room for rasteriser rounding in other Mesa versions. Regenerate with
// PLANET_UPDATE_GOLDEN=1 after an intended change (and look at the pictures).
TEST_F(TerrainRender, GoldenImages) {
  const std::string golden = PLANET_GOLDEN_DIR;
  const std::string out = testOutputDir();  // the actual and diff pictures of a failing case
  struct Case {
    const char* name;
    const char* preset;
    CameraPose camera;
    SunPose sun;
  } cases[] = {
      {"earth_orbit", "earth", {20.0, -30.0, 2.0e7, 0.0, -90.0}, {135.0, 35.0}},
      {"earth_10km", "earth", {45.25, 82.6, 1.0e4, 90.0, -12.0}, {150.0, 35.0}},
      {"moon_ground", "moon", {-20.0, 40.0, 2.0, 0.0, -15.0}, {100.0, 12.0}},
      {"earth_ground_noon", "earth", {20.0, -30.0, 2.0, 90.0, 8.0}, {135.0, 55.0}},
      {"earth_ground_sunset", "earth", {20.0, -30.0, 2.0, 135.0, 3.0}, {135.0, 1.0}},
      {"mars_ground", "mars", {-5.0, 140.0, 2.0, 60.0, 5.0}, {100.0, 30.0}},
  };
  for (const Case& c : cases) {
    RenderSettings settings = smallSettings(true);
    settings.width = 192;
    settings.height = 108;
    Renderer renderer(context(), resolvePreset(c.preset), settings);
    Rgba8Image image = renderer.render(c.camera, c.sun).image;
    EXPECT_TRUE(matchesGolden(image, golden + "/" + c.name + ".png", 40.0, out, c.name));
  }
}

}  // namespace
}  // namespace planet::test

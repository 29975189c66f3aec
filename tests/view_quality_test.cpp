// Viewer quality levels (render/view_quality.h): names, the device default, and the render
// settings each level gives for a window.
#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "render/view_quality.h"

namespace planet {
namespace {

TEST(ViewQuality, NamesRoundTripAndBadNamesAreNamed) {
  for (int i = 0; i < kViewQualityCount; ++i)
    EXPECT_EQ(parseViewQuality(viewQualityName(ViewQuality(i))), ViewQuality(i));
  try {
    parseViewQuality("best");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'best'"), std::string::npos) << e.what();
  }
}

TEST(ViewQuality, CpuDevicesStartLowAndGpusHigh) {
  EXPECT_EQ(defaultViewQuality(true), ViewQuality::Low);
  EXPECT_EQ(defaultViewQuality(false), ViewQuality::High);
}

TEST(ViewQuality, HighDrawsWhatPlanetRenderDraws) {
  const RenderSettings render;
  const RenderSettings high = viewRenderSettings(render, ViewQuality::High, render.width, render.height);
  EXPECT_EQ(high.width, render.width);
  EXPECT_EQ(high.height, render.height);
  EXPECT_EQ(high.terrain.mesh.levels, render.terrain.mesh.levels);
  EXPECT_EQ(high.terrain.mesh.ringsPerLevel, render.terrain.mesh.ringsPerLevel);
  EXPECT_EQ(high.terrain.mesh.numPhi, render.terrain.mesh.numPhi);
  EXPECT_EQ(high.terrain.subPixelRings, render.terrain.subPixelRings);
  EXPECT_EQ(high.terrain.patches, render.terrain.patches);
  EXPECT_EQ(high.terrain.patchSettings.resolution, render.terrain.patchSettings.resolution);
  EXPECT_EQ(high.sky.viewSamples, render.sky.viewSamples);
}

// The mesh for an image keeps the clipmap's triangles the same size on screen: rings per level
// and vertices per ring follow the pixels per radian at the image's centre.
TEST(MeshForImage, TrianglesKeepTheirSizeOnScreen) {
  const ClipmapParams reference = TerrainSettings{}.mesh;  // 30 levels x 16 rings x 128 vertices
  auto expectMesh = [&](uint32_t lines, double fovDeg, uint32_t rings, uint32_t numPhi) {
    const ClipmapParams m = meshForImage(reference, lines, fovDeg);
    EXPECT_EQ(m.levels, reference.levels) << lines << " lines at " << fovDeg;
    EXPECT_EQ(m.ringsPerLevel, rings) << lines << " lines at " << fovDeg;
    EXPECT_EQ(m.numPhi, numPhi) << lines << " lines at " << fovDeg;
  };
  expectMesh(540, 60.0, 16, 128);   // planet render's default size draws the mesh it always drew
  expectMesh(360, 60.0, 11, 85);    // the benchmark's 640x360: two thirds of the pixels per radian
  expectMesh(1080, 60.0, 32, 256);  // 1920x1080: twice
  // Half the field of view at 540 lines: tan 30° / tan 15° = 2.155 times the pixels per radian.
  expectMesh(540, 30.0, 34, 276);
  // The viewer's low and medium presets in a 960x540 window are this rule at their render scales.
  for (ViewQuality q : {ViewQuality::Low, ViewQuality::Medium}) {
    const QualityPreset p = qualityPreset(q);
    expectMesh(uint32_t(std::lround(540 * p.renderScale)), 60.0, p.mesh.ringsPerLevel, p.mesh.numPhi);
  }
  // Floors keep a thumbnail's limb round; ceilings are the mesh's own.
  expectMesh(36, 60.0, kMeshMinRingsPerLevel, kMeshMinNumPhi);
  expectMesh(8192, 1.0, kClipmapMaxRingsPerLevel, kClipmapMaxNumPhi);
  EXPECT_NO_THROW(validateClipmapParams(meshForImage(reference, 8192, 1.0)));
}

TEST(ViewQuality, EachLevelUpCostsMoreAndTheRenderSizeFollowsTheWindow) {
  const RenderSettings base;
  double previousWork = 0.0;
  for (int i = 0; i < kViewQualityCount; ++i) {
    const RenderSettings s = viewRenderSettings(base, ViewQuality(i), 960, 540);
    const QualityPreset p = qualityPreset(ViewQuality(i));
    EXPECT_EQ(s.width, uint32_t(960 * p.renderScale + 0.5)) << viewQualityName(ViewQuality(i));
    EXPECT_EQ(s.height, uint32_t(540 * p.renderScale + 0.5)) << viewQualityName(ViewQuality(i));
    EXPECT_NO_THROW(validateRenderSettings(s));
    // Pixels times atmosphere samples plus mesh vertices: a proxy for a frame's work.
    const double work = double(s.width) * s.height * s.sky.viewSamples +
                        double(s.terrain.mesh.levels) * s.terrain.mesh.ringsPerLevel * s.terrain.mesh.numPhi;
    EXPECT_GT(work, previousWork) << viewQualityName(ViewQuality(i));
    previousWork = work;
  }
  // A tiny window still gets a usable render target.
  const RenderSettings tiny = viewRenderSettings(base, ViewQuality::Low, 1, 1);
  EXPECT_EQ(tiny.width, 16u);
  EXPECT_EQ(tiny.height, 16u);
}

TEST(ViewQuality, WireframeAndTheUsersPatchToggleTurnPatchesOff) {
  RenderSettings base;
  base.terrain.patches = false;
  EXPECT_FALSE(viewRenderSettings(base, ViewQuality::Ultra, 100, 100).terrain.patches);
  base.terrain.patches = true;
  base.terrain.wireframe = true;
  EXPECT_FALSE(viewRenderSettings(base, ViewQuality::Ultra, 100, 100).terrain.patches);
  EXPECT_FALSE(viewRenderSettings(RenderSettings{}, ViewQuality::Low, 100, 100).terrain.patches);
  EXPECT_TRUE(viewRenderSettings(RenderSettings{}, ViewQuality::Medium, 100, 100).terrain.patches);
}

TEST(ViewQuality, LowerLevelsDrawFewerStarsAndHighDrawsThePresetsAll) {
  const PlanetDescription earth = resolvePreset("earth");
  EXPECT_EQ(viewPlanet(earth, ViewQuality::High).stars.faintestMagnitude, earth.stars.faintestMagnitude);
  EXPECT_EQ(viewPlanet(earth, ViewQuality::Ultra).stars.faintestMagnitude, earth.stars.faintestMagnitude);
  EXPECT_LT(viewPlanet(earth, ViewQuality::Low).stars.faintestMagnitude, earth.stars.faintestMagnitude);
  EXPECT_LE(viewPlanet(earth, ViewQuality::Low).stars.faintestMagnitude,
            viewPlanet(earth, ViewQuality::Medium).stars.faintestMagnitude);
  // Nothing else of the planet changes.
  PlanetDescription low = viewPlanet(earth, ViewQuality::Low);
  low.stars.faintestMagnitude = earth.stars.faintestMagnitude;
  EXPECT_EQ(descriptionHash(low), descriptionHash(earth));
}

}  // namespace
}  // namespace planet

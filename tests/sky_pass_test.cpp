// The sky pass's choices made on the CPU (no GPU): the cloud pass's resolution by the view and
// the settings' validation.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "camera/camera.h"
#include "core/error.h"
#include "render/sky_pass.h"

namespace planet::test {
namespace {

// Earth's cover (512² faces: a level-0 texel 2 / 512 of the radius at a face's centre) seen with
// a 60° field of view 360 pixels high.
constexpr double kCoverTexelM = 2.0 / 512.0 * 6.371e6;
constexpr double kPixelAngleRad = 60.0 * 3.14159265358979 / 180.0 / 360.0;

TEST(SkyPass, CloudPassRunsAtFullResolutionOnlyFarAboveTheLayer) {
  // Below, inside or just above the layer the cover's texels span hundreds of pixels or more.
  EXPECT_EQ(cloudPassScale(-1500.0, kCoverTexelM, kPixelAngleRad), 2u);
  EXPECT_EQ(cloudPassScale(0.0, kCoverTexelM, kPixelAngleRad), 2u);
  EXPECT_EQ(cloudPassScale(2.0e3, kCoverTexelM, kPixelAngleRad), 2u);
  EXPECT_EQ(cloudPassScale(4.0e5, kCoverTexelM, kPixelAngleRad), 2u);  // a texel spans 21 pixels
  // From 1,000 km a texel spans 8.5 pixels, from 20,000 km less than one.
  EXPECT_EQ(cloudPassScale(1.0e6, kCoverTexelM, kPixelAngleRad), 1u);
  EXPECT_EQ(cloudPassScale(2.0e7, kCoverTexelM, kPixelAngleRad), 1u);
  // The switch: where a texel straight below spans kHalfResolutionTexelPixels pixels (~535 km).
  const double switchM = kCoverTexelM / (kHalfResolutionTexelPixels * kPixelAngleRad);
  EXPECT_NEAR(switchM, 5.35e5, 5e3);
  EXPECT_EQ(cloudPassScale(0.99 * switchM, kCoverTexelM, kPixelAngleRad), 2u);
  EXPECT_EQ(cloudPassScale(1.01 * switchM, kCoverTexelM, kPixelAngleRad), 1u);
  // A frame twice as high (half the pixel angle) keeps half resolution twice as far out.
  EXPECT_EQ(cloudPassScale(1.01 * switchM, kCoverTexelM, 0.5 * kPixelAngleRad), 2u);
}

// Where the compose and the cloud pass run (SkySettings::regions): the pixels a cone of
// directions from the camera can cover (the top of the atmosphere seen from above it, the sun's
// disc), 640x360 at 60° (f = 311.77 pixels) looking straight down.
TEST(SkyPass, RegionsHoldTheConeAndLittleMore) {
  const glm::dmat4 viewProjection = reversedZPerspective(std::numbers::pi / 3.0, 640.0 / 360.0, 1.0) *
                                    viewMatrix(glm::dvec3(0.0, 0.0, -1.0), glm::dvec3(1.0, 0.0, 0.0));
  const glm::dvec3 down(0.0, 0.0, -1.0);
  // A cone of 20° around the view axis is a circle of f tan 20° = 113.5 pixels about the centre;
  // with the 2 pixels of margin, and at most ~2 more (the polygon around it, rounding).
  const PixelRect centred = coneScreenRect(viewProjection, down, 20.0 * std::numbers::pi / 180.0, 640, 360);
  const double r = 311.77 * std::tan(20.0 * std::numbers::pi / 180.0) + 2.0;
  EXPECT_LE(centred.x0, 320.0 - r);
  EXPECT_GE(centred.x0, 320.0 - r - 2.0);
  EXPECT_GE(centred.x1, 320.0 + r);
  EXPECT_LE(centred.x1, 320.0 + r + 2.0);
  EXPECT_LE(centred.y0, 180.0 - r);
  EXPECT_GE(centred.y0, 180.0 - r - 2.0);
  EXPECT_GE(centred.y1, 180.0 + r);
  EXPECT_LE(centred.y1, 180.0 + r + 2.0);
  // Clamped to the image: a cone wider than the view.
  const PixelRect wide = coneScreenRect(viewProjection, down, 60.0 * std::numbers::pi / 180.0, 640, 360);
  EXPECT_EQ(wide.x0, 0u);
  EXPECT_EQ(wide.y0, 0u);
  EXPECT_EQ(wide.x1, 640u);
  EXPECT_EQ(wide.y1, 360u);
  // Behind the camera: nothing. Across the view (the axis along the image's rows, 90° off), a
  // cone of 10° lies past the image's side (45.8° out); one of 50° reaches 40° from the view axis,
  // ~50 columns into one side of the image, about its middle row.
  EXPECT_TRUE(coneScreenRect(viewProjection, -down, 0.1, 640, 360).empty());
  const glm::dvec3 row(0.0, 1.0, 0.0);
  EXPECT_TRUE(coneScreenRect(viewProjection, row, 10.0 * std::numbers::pi / 180.0, 640, 360).empty());
  const PixelRect across = coneScreenRect(viewProjection, row, 50.0 * std::numbers::pi / 180.0, 640, 360);
  EXPECT_FALSE(across.empty());
  EXPECT_LT(across.width(), 80u);
  EXPECT_TRUE(across.x0 == 0 || across.x1 == 640);
  EXPECT_TRUE(across.y0 < 180 && across.y1 > 180);
  const PixelRect half = coneScreenRect(viewProjection, down, 0.5 * std::numbers::pi, 640, 360);
  EXPECT_EQ(half.width() * half.height(), 640u * 360u);
  // In front but 60° off the axis, past the image's side (45.8° out): nothing.
  const glm::dvec3 aside(std::sin(std::numbers::pi / 3.0), 0.0, -std::cos(std::numbers::pi / 3.0));
  const glm::dvec3 aside2(0.0, std::sin(std::numbers::pi / 3.0), -std::cos(std::numbers::pi / 3.0));
  EXPECT_TRUE(coneScreenRect(viewProjection, aside, 0.05, 640, 360).empty());
  EXPECT_TRUE(coneScreenRect(viewProjection, aside2, 0.05, 640, 360).empty());
  // The union of two rectangles, an empty one adding nothing.
  const PixelRect both = unite(PixelRect{10, 20, 30, 40}, PixelRect{25, 5, 50, 35});
  EXPECT_TRUE(both.x0 == 10 && both.y0 == 5 && both.x1 == 50 && both.y1 == 40);
  const PixelRect same = unite(PixelRect{}, PixelRect{1, 2, 3, 4});
  EXPECT_TRUE(same.x0 == 1 && same.y0 == 2 && same.x1 == 3 && same.y1 == 4);
}

TEST(SkyPass, BadSettingsAreOneLineNamingTheValue) {
  EXPECT_NO_THROW(validateSkySettings(SkySettings{}));
  SkySettings settings;
  settings.cloudScale = 3;
  try {
    validateSkySettings(settings);
    FAIL() << "a cloud scale of 3 was accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "cloud pass scale 3 is not 0 (by the view), 1 or 2");
  }
  settings = SkySettings{};
  settings.viewSamples = 1;
  EXPECT_THROW(validateSkySettings(settings), Error);
  settings = SkySettings{};
  settings.exposure = -1.0;
  EXPECT_THROW(validateSkySettings(settings), Error);
}

}  // namespace
}  // namespace planet::test

// The sky pass's choices made on the CPU (no GPU): the cloud pass's resolution by the view and
// the settings' validation.
#include <gtest/gtest.h>

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

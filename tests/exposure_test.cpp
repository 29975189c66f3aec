// Eye adaptation (issue 21, point 4): the adaptation step and the trimmed log-average on the
// CPU (Exposure.*, unit), the luminance pass against that reference and the pictures it gives
// at noon, twilight and night (ExposureGpu.*, gpu on lavapipe), and --exposure as a user types
// it (ExposureCli.*, cli).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/image_file.h"
#include "gpu_fixture.h"
#include "planet/planet_description.h"
#include "reference/atmosphere_model.h"
#include "render/exposure.h"
#include "render/luminance_pass.h"
#include "render/renderer.h"
#include "test_support.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/image.h"

namespace planet::test {
namespace {

using gpu::kExposureBins;
using gpu::kExposureBinsPerStop;
using gpu::kExposureKey;
using gpu::kExposureMax;
using gpu::kExposureMin;

// A frame of `count` pixels, all of luminance `luminance` (grey), no star in them (alpha 0).
std::vector<glm::vec4> greyFrame(size_t count, float luminance) {
  return std::vector<glm::vec4>(count, glm::vec4(luminance, luminance, luminance, 0.0f));
}

// The frame's luminance (the frame's units) of `cdM2` candelas per square metre.
float fromCdM2(double cdM2) { return float(cdM2 / gpu::kExposureSunCdM2); }

// The histogram of a frame in which each of `values` fills one 2 × 2 block (the unit the
// histogram counts): a 2n × 2 frame.
ExposureHistogram blockHistogram(const std::vector<glm::vec4>& values) {
  const uint32_t width = uint32_t(2 * values.size());
  std::vector<glm::vec4> frame(size_t(width) * 2);
  for (size_t i = 0; i < frame.size(); ++i) frame[i] = values[(i % width) / 2];
  return exposureHistogram(frame, width, 2);
}

// ---------------------------------------------------------------------------------------------
// Exposure.* (unit)

// The adaptation is a function of elapsed time only: one step of 1 s, 60 steps of 1/60 s and
// uneven steps that add up to 1 s land on the same exposure. Float rounding of log2/exp2 at
// each of 60 steps bounds the spread (about 1e-7 stops a step); 1e-4 relative is 100 times that.
TEST(Exposure, AdaptationDoesNotDependOnTheFrameRate) {
  for (const auto& [from, to] : {std::pair{10.0, 120.0}, std::pair{120.0, 3.0}}) {
    const double oneStep = adaptExposure(from, to, 1.0);
    double sixtySteps = from;
    for (int i = 0; i < 60; ++i) sixtySteps = adaptExposure(sixtySteps, to, 1.0 / 60.0);
    double uneven = from;
    for (double step : {0.01, 0.3, 0.002, 0.25, 0.038, 0.4}) uneven = adaptExposure(uneven, to, step);
    EXPECT_NEAR(sixtySteps / oneStep, 1.0, 1e-4) << from << " -> " << to;
    EXPECT_NEAR(uneven / oneStep, 1.0, 1e-4) << from << " -> " << to;
    // It moved, but not all the way, and stayed between the two.
    EXPECT_GT(std::abs(std::log2(oneStep / from)), 0.1);
    EXPECT_GT(std::abs(std::log2(to / oneStep)), 0.01);
    EXPECT_GT(oneStep, std::min(from, to));
    EXPECT_LT(oneStep, std::max(from, to));
  }
}

// After five time constants the exposure is within e^−5 (0.7 %) of the way in stops from the
// target, after 30 s it is there (to float rounding); the eye adapts to a brighter scene (the
// exposure falls) faster than to a darker one.
TEST(Exposure, AdaptationConverges) {
  const double from = 16.0, darker = 64.0, brighter = 2.0;  // 2 and 3 stops away
  double rising = from, falling = from;
  for (int i = 0; i < int(5.0 * gpu::kExposureRiseTimeS * 60.0); ++i)
    rising = adaptExposure(rising, darker, 1.0 / 60.0);
  for (int i = 0; i < int(5.0 * gpu::kExposureFallTimeS * 60.0); ++i)
    falling = adaptExposure(falling, brighter, 1.0 / 60.0);
  EXPECT_NEAR(std::log2(darker / rising), 2.0 * std::exp(-5.0), 0.01);
  EXPECT_NEAR(std::log2(falling / brighter), 3.0 * std::exp(-5.0), 0.01);
  EXPECT_NEAR(adaptExposure(from, darker, 30.0) / darker, 1.0, 1e-5);
  // Half a second: the fall covers more of its stops than the rise does.
  const double riseShare = std::log2(adaptExposure(from, darker, 0.5) / from) / 2.0;
  const double fallShare = std::log2(from / adaptExposure(from, brighter, 0.5)) / 3.0;
  EXPECT_GT(fallShare, riseShare + 0.3);
  // At the target it stays (to float rounding of log2 and exp2).
  EXPECT_NEAR(adaptExposure(darker, darker, 0.25) / darker, 1.0, 1e-6);
}

// The first frame (no exposure yet) and a negative step (planet render) take the target.
TEST(Exposure, FirstFrameTakesItsOwnExposure) {
  EXPECT_EQ(adaptExposure(0.0, 42.0, 1.0 / 60.0), 42.0);
  EXPECT_EQ(adaptExposure(5.0, 42.0, -1.0), 42.0);
  EXPECT_NEAR(adaptExposure(5.0, 42.0, 0.0) / 5.0, 1.0, 1e-6);  // no time: no change
}

// A uniform daylit frame (above 1,000 cd/m², sunset's sky: lit ground is 6,000) is exposed
// so that its luminance lands on the key (to within half a bin of the histogram, 1/16 stop);
// black and blinding frames stop at the clamps.
TEST(Exposure, MeasuredLuminanceMapsToTheKey) {
  for (float luminance : {fromCdM2(2000.0), 0.01f, 0.05f}) {
    const ExposureReport r = exposureFromHistogram(blockHistogram(greyFrame(1000, luminance)));
    EXPECT_NEAR(r.log2Luminance, std::log2(luminance), 0.5 / kExposureBinsPerStop) << luminance;
    EXPECT_NEAR(std::log2(r.exposure * luminance / kExposureKey), 0.0, 0.5 / kExposureBinsPerStop) << luminance;
    EXPECT_EQ(r.exposure, r.target);
  }
  EXPECT_FLOAT_EQ(exposureFromHistogram(blockHistogram(greyFrame(1000, 0.0f))).exposure, kExposureMax);
  EXPECT_FLOAT_EQ(exposureFromHistogram(blockHistogram(greyFrame(1000, 1e3f))).exposure, kExposureMin);
}

// A darker scene is brought up, but stays darker on the display, as the eye and a photograph of
// dusk keep it: below 1,000 cd/m² the key falls a quarter of a stop for each stop. The sky at
// the end of civil twilight (about 1 cd/m²) lands 2.5 stops below daylight's key, at nautical
// twilight's end (2e-3 cd/m²) 4.7 below; the natural night sky (2e-4 cd/m²) meets the largest
// exposure, and a darker frame (the model has no airglow) is not lifted further.
TEST(Exposure, DarkerScenesAreBroughtUpButStayDarker) {
  double lastExposure = 0.0, lastKey = 1.0;
  for (double cdM2 : {1000.0, 100.0, 10.0, 1.0, 0.1, 0.01, 2e-3, 3e-4}) {
    const float luminance = fromCdM2(cdM2);
    const ExposureReport r = exposureFromHistogram(blockHistogram(greyFrame(1000, luminance)));
    const double keyStops = std::log2(r.exposure * luminance / kExposureKey);
    // Within half a bin (the measurement is the bin's middle), and float rounding.
    EXPECT_NEAR(keyStops, -0.25 * std::log2(1000.0 / cdM2), 0.5 / kExposureBinsPerStop + 1e-3) << cdM2 << " cd/m²";
    EXPECT_GT(r.exposure, lastExposure) << cdM2 << " cd/m²: brought up more than a brighter scene";
    EXPECT_LT(std::exp2(keyStops), lastKey) << cdM2 << " cd/m²: darker on the display than a brighter scene";
    lastExposure = r.exposure;
    lastKey = std::exp2(keyStops);
  }
  const ExposureReport nightSky = exposureFromHistogram(blockHistogram(greyFrame(1000, fromCdM2(2e-4))));
  EXPECT_NEAR(std::log2(nightSky.exposure / kExposureMax), 0.0, 0.25);
  EXPECT_FLOAT_EQ(exposureFromHistogram(blockHistogram(greyFrame(1000, fromCdM2(2e-5)))).exposure, kExposureMax);
}

// The trimming: black (space, the night sky) is not measured however much of the frame it
// fills, and neither are the darkest half of the rest (shadow) nor the top 2 % (the sun's
// disc): the measurement is the lit ground's, whatever the others' values.
TEST(Exposure, BlackShadowAndTheSunDoNotMoveTheMeasurement) {
  const float ground = 0.01f;
  for (size_t black : {0, 500, 9000}) {
    std::vector<glm::vec4> frame = greyFrame(black, 0.0f);
    for (const auto& [count, luminance] :
         {std::pair{size_t(400), 1e-5f},                                 // 40 % of the lit: deep shadow
          std::pair{size_t(585), ground}, std::pair{size_t(15), 2e4f}})  // 1.5 %: the sun's disc
    {
      const std::vector<glm::vec4> part = greyFrame(count, luminance);
      frame.insert(frame.end(), part.begin(), part.end());
    }
    const ExposureReport r = exposureFromHistogram(blockHistogram(frame));
    EXPECT_NEAR(r.log2Luminance, std::log2(ground), 0.5 / kExposureBinsPerStop) << black << " black pixels";
    // Measured on the lit blocks ranked 50 % .. 98 %.
    EXPECT_NEAR(r.pixels, 480.0, 1e-3) << black << " black pixels";
  }
  // NaN and negative values count as black.
  std::vector<glm::vec4> odd = greyFrame(10, ground);
  odd[0] = glm::vec4(std::nanf(""), 0.0f, 0.0f, 0.0f);
  odd[1] = glm::vec4(-1.0f, -1.0f, -1.0f, 0.0f);
  EXPECT_EQ(blockHistogram(odd)[0], 2u);
  // A block's count is its four pixels' mean: a glint in one pixel of a black block counts.
  std::vector<glm::vec4> glint = greyFrame(4, 0.0f);
  glint[3] = glm::vec4(0.04f, 0.04f, 0.04f, 0.0f);
  EXPECT_EQ(exposureHistogram(glint, 2, 2)[0], 0u);
  EXPECT_NEAR(exposureFromHistogram(exposureHistogram(glint, 2, 2)).log2Luminance, std::log2(0.01), 0.07);
  EXPECT_THROW(exposureHistogram(glint, 3, 2), Error);
  // A star does not: its light is left out, by the share of the pixel that alpha says is the
  // stars' (shared/exposure_params.h): all of it where no compose ran (the stars' negated flux),
  // the share the last compose wrote (over the mark kExposureComposedAlpha) where one did. Over
  // the sky around it, only the sky counts.
  std::vector<glm::vec4> star = greyFrame(4, 0.0f);
  star[3] = glm::vec4(0.04f, 0.04f, 0.04f, -0.3f);
  EXPECT_EQ(exposureHistogram(star, 2, 2)[0], 1u);
  std::vector<glm::vec4> starInSky = greyFrame(4, 1e-6f);
  for (glm::vec4& p : starInSky) p.a = gpu::kExposureComposedAlpha;
  starInSky[3] = glm::vec4(glm::vec3(0.04f + 1e-6f), gpu::kExposureComposedAlpha + 0.04f / (0.04f + 1e-6f));
  EXPECT_NEAR(exposureFromHistogram(exposureHistogram(starInSky, 2, 2)).log2Luminance, std::log2(1e-6), 0.07);
  // City lights count at their physical radiance: the share of the pixel that alpha marks
  // (kExposureLightsAlpha + share) divided by the preset's gain. Ground of 1e-6 under lights
  // drawn at 0.02 with a gain of 2e4 (1e-6 physical) measures 2e-6; with a gain of 1, 0.02.
  std::vector<glm::vec4> lit = greyFrame(4, 0.02f + 1e-6f);
  for (glm::vec4& p : lit) p.a = gpu::kExposureLightsAlpha + 0.02f / (0.02f + 1e-6f);
  EXPECT_NEAR(exposureFromHistogram(exposureHistogram(lit, 2, 2, 2e4)).log2Luminance, std::log2(2e-6), 0.07);
  EXPECT_NEAR(exposureFromHistogram(exposureHistogram(lit, 2, 2, 1.0)).log2Luminance, std::log2(0.02), 0.07);
}

// What auto exposure shows (exposureDisplayScale): a pixel of geometry or sky at the frame's
// exposure; the stars' share at kExposureStarExposure whatever the frame's; the city lights' at
// the smaller of the frame's and kExposureLightsExposure, the fixed default the preset's gain is
// set for, so that a night sky's exposure of 10^5 does not blow them out. An alpha in neither
// mark's range (a ring or the sea blended over a mark) is geometry.
TEST(Exposure, StarsAndCityLightsTakeExposuresOfTheirOwn) {
  using gpu::kExposureComposedAlpha;
  using gpu::kExposureLightsAlpha;
  using gpu::kExposureLightsExposure;
  using gpu::kExposureStarExposure;
  for (double exposure : {2.0, 1e3, 1e5}) {
    EXPECT_DOUBLE_EQ(exposureDisplayScale(exposure, 1.0f), exposure);
    EXPECT_DOUBLE_EQ(exposureDisplayScale(exposure, kExposureComposedAlpha), exposure);
    EXPECT_DOUBLE_EQ(exposureDisplayScale(exposure, -0.5f), kExposureStarExposure);
    EXPECT_NEAR(exposureDisplayScale(exposure, kExposureComposedAlpha + 0.5f),
                0.5 * exposure + 0.5 * kExposureStarExposure, 1e-6 * exposure);
    const double lights = std::min(exposure, double(kExposureLightsExposure));
    EXPECT_DOUBLE_EQ(exposureDisplayScale(exposure, kExposureLightsAlpha + 1.0f), lights);
    EXPECT_NEAR(exposureDisplayScale(exposure, kExposureLightsAlpha + 0.25f), 0.75 * exposure + 0.25 * lights,
                1e-6 * exposure);
    EXPECT_DOUBLE_EQ(exposureDisplayScale(exposure, 3.5f), exposure);
  }
}

// ---------------------------------------------------------------------------------------------
// ExposureGpu.* (gpu)

using ExposureGpu = GpuTest;

// The luminance pass over an HDR image with luminances spread log-uniformly over 40 stops
// (black blocks, the clamps' ends and the open top bin included), a star's light in a tenth of
// the pixels (alpha), counts the same histogram as the CPU reference over the same floats, and
// finds the same log-average and exposure. A block can change bin only where lavapipe's log2 and
// the C library's differ in the last bit at a bin edge: at most 1 in 1,000 may. The average then
// moves by float summation only (1e-4 stops).
TEST_F(ExposureGpu, LuminancePassMatchesTheCpuReference) {
  const VkExtent2D extent{333, 207};  // not a multiple of the 16 × 16 groups
  std::mt19937 random(21);
  std::uniform_real_distribution<float> stops(-36.0f, 4.0f), tint(0.5f, 1.5f), share(0.0f, 1.0f);
  std::vector<glm::vec4> frame;
  uint32_t blackBlocks = 0;
  for (uint32_t i = 0; i < extent.width * extent.height; ++i) {
    const uint32_t x = i % extent.width, y = i / extent.width;
    const bool black = (x / 2 + 1000 * (y / 2)) % 17 == 0;  // whole 2 × 2 blocks
    blackBlocks += black && x % 2 == 0 && y % 2 == 0 ? 1 : 0;
    const float l = black ? 0.0f : std::exp2(stops(random));
    glm::vec4 c(l * tint(random), l, l * tint(random), 0.0f);
    if (i % 10 == 3) c.a = gpu::kExposureComposedAlpha + share(random);  // composed, some of it stars'
    if (i % 10 == 7) c.a = -share(random);                               // stars where none composed
    if (i % 10 == 5) c.a = gpu::kExposureLightsAlpha + share(random);    // city lights, some of the light
    frame.push_back(c);
  }
  vk::Image image =
      vk::createImage2D(context(), extent, VK_FORMAT_R32G32B32A32_SFLOAT,
                        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  vk::uploadImage(context(), image, frame.data(), frame.size() * sizeof(glm::vec4), VK_IMAGE_LAYOUT_GENERAL);
  {
    LuminancePass pass(context());
    pass.setSource(image);
    pass.setLightsGain(3e4);
    vk::submitAndWait(context(), [&](VkCommandBuffer cmd) { pass.record(cmd, 1, -1.0, nullptr); });
    const ExposureHistogram gpuHistogram = pass.readHistogram();
    const ExposureHistogram cpuHistogram = exposureHistogram(frame, extent.width, extent.height, 3e4);
    const uint64_t blocks = uint64_t((extent.width + 1) / 2) * ((extent.height + 1) / 2);
    uint64_t total = 0, moved = 0;
    for (uint32_t b = 0; b < kExposureBins; ++b) {
      total += gpuHistogram[b];
      moved += uint64_t(std::abs(int64_t(gpuHistogram[b]) - int64_t(cpuHistogram[b])));
    }
    EXPECT_EQ(total, blocks);
    EXPECT_LE(moved, 2 * blocks / 1000) << "blocks in another bin than the CPU's";
    EXPECT_GE(gpuHistogram[0], blackBlocks);  // and the blocks darker than 2^-32
    const ExposureReport gpu = pass.report(1);
    const ExposureReport cpu = exposureFromHistogram(cpuHistogram);
    EXPECT_NEAR(gpu.log2Luminance, cpu.log2Luminance, 1e-4);
    EXPECT_NEAR(gpu.exposure / cpu.exposure, 1.0, 1e-4);
    EXPECT_NEAR(gpu.pixels, cpu.pixels, 1.0);
    EXPECT_EQ(gpu.exposure, gpu.target);      // a negative step: no adaptation
    EXPECT_EQ(pass.report(0).exposure, 0.0);  // the other slot recorded nothing
  }
  vk::destroyImage(context(), image);
}

// The frames of the picture tests: 160 × 90 with a small patch set (seconds on lavapipe).
RenderSettings smallSettings(bool autoExposure) {
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.terrain.patchSettings.resolution = 128;
  settings.terrain.patchSettings.levelCount = 3;
  settings.autoExposure = autoExposure;
  return settings;
}

// smallSettings at 320 × 180, for views whose subject (stars, a city) is a pixel or two at 160 × 90.
RenderSettings largerSettings(bool autoExposure) {
  RenderSettings settings = smallSettings(autoExposure);
  settings.width = 320;
  settings.height = 180;
  return settings;
}

// Mean Rec. 709 luma of the display values (0..1) of a frame, and its pixels at 250 or more.
struct DisplayStats {
  double mean = 0.0;
  int saturated = 0;
};
DisplayStats displayStats(const Rgba8Image& image, uint32_t y0 = 0, uint32_t y1 = UINT32_MAX) {
  DisplayStats stats;
  y1 = std::min(y1, image.height);
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
      stats.mean += (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0;
      stats.saturated += std::max({p[0], p[1], p[2]}) >= 250 ? 1 : 0;
    }
  stats.mean /= double(image.width) * double(y1 - y0);
  return stats;
}

// What the frame's luminance pass reported equals the CPU reference over the same HDR frame
// (read back after the compose pass): the bins of a few pixels may differ at a bin edge (last
// bit of log2), which moves the average by far less than 1/100 stop.
void expectReportMatchesCpu(const RenderResult& frame, double lightsGain, const char* name) {
  ASSERT_TRUE(frame.exposure.has_value()) << name;
  const ExposureReport cpu =
      exposureFromHistogram(exposureHistogram(frame.hdr, frame.image.width, frame.image.height, lightsGain));
  EXPECT_NEAR(frame.exposure->log2Luminance, cpu.log2Luminance, 0.01) << name;
  EXPECT_NEAR(std::log2(frame.exposure->exposure / cpu.exposure), 0.0, 0.01) << name;
}

// A valley in Earth's mountains at 45.3° N 83° E, looking north 4° up with the sun ahead of the
// camera (30° azimuth): the sky and the ground share the frame.
constexpr CameraPose kValley{45.3, 83.0, 0.0, 0.0, 4.0};

// Noon, sunset, twilight (sun 4°, 8° and 12° below the horizon) and night (30° below) from the
// ground, fixed exposure against auto. With the fixed default twilight and night are near black
// (display mean below 0.04, where 0.5 is mid-grey); auto exposure keeps noon and sunset in the
// middle band (0.25 .. 0.6), brings twilight up at least four times and into view, darker as
// the sun sinks (the key falls for darker scenes: deep blue at 8°, a glow under a near-black sky
// at 12°), and takes the night to the largest exposure, where only the stars show (0.005 ..
// 0.04): nothing lights this mountain valley's ground at night (the fill light sets with the
// sun, issue 14; no city lights in the mountains). Lit cities keep a night in view:
// CityLightsKeepTheNightInView.
TEST_F(ExposureGpu, AutoExposureBringsTwilightAndNightIntoView) {
  const PlanetDescription earth = resolvePreset("earth");
  Renderer renderer(context(), earth, smallSettings(true));
  struct Case {
    const char* name;
    double sunElevationDeg;
    double autoLow, autoHigh;
  };
  const Case cases[] = {{"noon", 55.0, 0.25, 0.6},
                        {"sunset", 1.0, 0.25, 0.6},
                        {"twilight", -4.0, 0.1, 0.6},
                        {"deep_twilight", -8.0, 0.06, 0.25},
                        {"nautical_twilight", -12.0, 0.03, 0.12},
                        {"night", -30.0, 0.005, 0.04}};
  double lastTwilight = 1.0;
  for (const Case& c : cases) {
    const SunPose sun{30.0, c.sunElevationDeg};
    renderer.setAutoExposure(true);
    const RenderResult automatic = renderer.render(kValley, sun, 0.0, true);
    expectReportMatchesCpu(automatic, earth.lights.gain, c.name);
    renderer.setAutoExposure(false);
    const RenderResult fixed = renderer.render(kValley, sun);
    EXPECT_FALSE(fixed.exposure.has_value());
    writePng((testOutputDir() / fmt::format("exposure_{}_auto.png", c.name)).string(), automatic.image);
    writePng((testOutputDir() / fmt::format("exposure_{}_fixed.png", c.name)).string(), fixed.image);
    const double autoMean = displayStats(automatic.image).mean, fixedMean = displayStats(fixed.image).mean;
    EXPECT_GE(autoMean, c.autoLow) << c.name << " (exposure " << automatic.exposure->exposure << ")";
    EXPECT_LE(autoMean, c.autoHigh) << c.name << " (exposure " << automatic.exposure->exposure << ")";
    if (c.sunElevationDeg <= -8.0 && c.sunElevationDeg > -20.0) {
      // Past civil twilight the sky above the glow is deep blue, not grey: the top rows' blue over
      // their red (at 4° it is purple, as photographs show it toward the sun).
      double red = 0.0, blue = 0.0;
      for (size_t i = 0; i < size_t(automatic.image.width) * 20 * 4; i += 4) {
        red += automatic.image.pixels[i];
        blue += automatic.image.pixels[i + 2];
      }
      EXPECT_GT(blue, 1.3 * red) << c.name << ": the sky above the glow is blue";
    }
    if (c.sunElevationDeg < 0.0) {
      EXPECT_LT(fixedMean, 0.04) << c.name;
      EXPECT_GE(autoMean, 4.0 * fixedMean) << c.name;
      EXPECT_LT(autoMean, lastTwilight) << c.name << ": no darker than with the sun higher";
      lastTwilight = autoMean;
    }
    if (c.sunElevationDeg == -30.0)
      EXPECT_FLOAT_EQ(automatic.exposure->exposure, kExposureMax);
    else
      EXPECT_LT(automatic.exposure->exposure, kExposureMax) << c.name;
  }
}

// The ground in deep twilight takes the sky's light of its own sun elevation, which falls about
// two stops a degree: the mountain valley with the sun 8° and 10° down, its lower third (ground
// only) against the model's irradiance there, E / π (reference/atmosphere_model.h: what a white
// horizontal ground would send back). Its median lies between 0.02 and 0.35 of it (the ground's
// albedo, slopes). Interpolated linearly between the table's entries, 4.6° apart, the ground got
// 3 and 19 times its light: what the entry above gave it, which auto exposure showed as lit hills
// under a dark sky.
TEST_F(ExposureGpu, TwilightGroundTakesTheSkyLightOfItsOwnSunElevation) {
  const PlanetDescription earth = resolvePreset("earth");
  RenderSettings settings = smallSettings(false);
  Renderer renderer(context(), earth, settings);
  for (double elevationDeg : {-8.0, -10.0}) {
    const RenderResult frame = renderer.render(kValley, {30.0, elevationDeg}, 0.0, true);
    std::vector<double> ground;
    for (uint32_t y = settings.height * 2 / 3; y < settings.height; ++y)
      for (uint32_t x = 0; x < settings.width; ++x) {
        const glm::vec4& c = frame.hdr[size_t(y) * settings.width + x];
        ground.push_back(0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b);
      }
    std::nth_element(ground.begin(), ground.begin() + ground.size() / 2, ground.end());
    const glm::dvec3 irradiance =
        skyIrradiance(makeAtmosphereParams(earth), std::sin(elevationDeg * std::numbers::pi / 180.0));
    const double white = (0.2126 * irradiance.r + 0.7152 * irradiance.g + 0.0722 * irradiance.b) / std::numbers::pi;
    const double ratio = ground[ground.size() / 2] / white;
    std::printf("sun %.0f°: the ground's median is %.3f of a white ground's light\n", elevationDeg, ratio);
    EXPECT_GT(ratio, 0.02) << elevationDeg << "°";
    EXPECT_LT(ratio, 0.35) << elevationDeg << "°";
  }
}

// City lights (issue 14) at night under auto exposure, from 30 km over lit lowland near a coast
// looking 30° down: the lights raise the frame's measured luminance (at their physical radiance)
// by at least 3 stops (4.5 today) over the same frame without them and show at the display
// (mean at least 0.06; 0.090 today: they cover a third of the frame), where without them it is
// the black of a night with stars (mean below 0.03; 0.003 today).
TEST_F(ExposureGpu, CityLightsKeepTheNightInView) {
  const PlanetDescription earth = resolvePreset("earth");
  Renderer renderer(context(), earth, smallSettings(true));
  const CameraPose overCities{2.0, -28.0, 3.0e4, 0.0, -30.0};
  const SunPose night{30.0, -30.0};
  const RenderResult lit = renderer.render(overCities, night);
  renderer.terrain().setLightsEnabled(false);
  const RenderResult dark = renderer.render(overCities, night);
  writePng((testOutputDir() / "exposure_night_lights_auto.png").string(), lit.image);
  ASSERT_TRUE(lit.exposure && dark.exposure);
  std::printf("[ measured ] lights raise the measurement %.2f stops; display mean %.3f with them, %.3f without\n",
              lit.exposure->log2Luminance - dark.exposure->log2Luminance, displayStats(lit.image).mean,
              displayStats(dark.image).mean);
  EXPECT_GE(lit.exposure->log2Luminance - dark.exposure->log2Luminance, 3.0);
  EXPECT_GE(displayStats(lit.image).mean, 0.06);
  EXPECT_LT(displayStats(dark.image).mean, 0.03);
}

// City lights from orbit under auto exposure (400 km over the same coast at night, looking 20°
// down toward the limb): the exposure is the night sky's (the airglow over the disc, about 10^6),
// and the lights, drawn 3·10^4 times over their physical radiance for the fixed exposure, blew
// out white under it (246 of the 347 lit pixels below the limb, red over blue 1.2). Shown as at
// kExposureLightsExposure they are orange, as in photographs from the ISS: none of the lit pixels
// is white (each channel 200 or more), red at least three times blue (11.8 measured).
// Without the lights the same pixels are black: what shows is theirs.
TEST_F(ExposureGpu, CityLightsFromOrbitAreOrangeNotBlownOut) {
  const PlanetDescription earth = resolvePreset("earth");
  Renderer renderer(context(), earth, largerSettings(true));
  const CameraPose orbit{2.0, -28.0, 4.0e5, 0.0, -20.0};
  const SunPose night{30.0, -30.0};
  const RenderResult lit = renderer.render(orbit, night);
  renderer.terrain().setLightsEnabled(false);
  const RenderResult dark = renderer.render(orbit, night);
  writePng((testOutputDir() / "exposure_lights_orbit_auto.png").string(), lit.image);
  ASSERT_TRUE(lit.exposure.has_value());
  EXPECT_GT(lit.exposure->exposure, 1e5) << "the night sky's exposure";
  // The rows below the limb (and the lit air over it, on the right).
  auto count = [](const Rgba8Image& image, uint32_t& litPixels, uint32_t& white, double& red, double& blue) {
    litPixels = white = 0;
    red = blue = 0.0;
    for (uint32_t y = 115; y < image.height; ++y)
      for (uint32_t x = 0; x < image.width; ++x) {
        const uint8_t* p = &image.pixels[(size_t(y) * image.width + x) * 4];
        if (std::max({p[0], p[1], p[2]}) <= 40) continue;
        ++litPixels;
        white += std::min({p[0], p[1], p[2]}) >= 200 ? 1 : 0;
        red += p[0];
        blue += p[2];
      }
  };
  uint32_t litPixels = 0, white = 0, darkLit = 0, darkWhite = 0;
  double red = 0.0, blue = 0.0, darkRed = 0.0, darkBlue = 0.0;
  count(lit.image, litPixels, white, red, blue);
  count(dark.image, darkLit, darkWhite, darkRed, darkBlue);
  std::printf("[ measured ] exposure %.3g: %u lit pixels, %u white, red / blue %.2f; %u lit without the lights\n",
              lit.exposure->exposure, litPixels, white, red / std::max(blue, 1.0), darkLit);
  EXPECT_GE(litPixels, 50u) << "cities in view";
  EXPECT_EQ(white, 0u);
  EXPECT_GE(red, 3.0 * blue);
  EXPECT_LE(darkLit, litPixels / 20);
}

// Stars under auto exposure, at night over the sea looking 20° up (nothing but the night sky):
// they neither vanish (more of them show than with the fixed default) nor blow out (the black
// between them is not measured, so it does not push the exposure up; fewer than 1 in 20 star
// pixels saturates).
TEST_F(ExposureGpu, StarsStayVisibleAndUnsaturatedAtNight) {
  const PlanetDescription earth = resolvePreset("earth");
  Renderer renderer(context(), earth, largerSettings(true));
  const CameraPose pose{20.0, -30.0, 2.0, 135.0, 20.0};
  const SunPose night{135.0, -30.0};
  const RenderResult automatic = renderer.render(pose, night);
  renderer.setAutoExposure(false);
  const RenderResult fixed = renderer.render(pose, night);
  writePng((testOutputDir() / "exposure_stars_auto.png").string(), automatic.image);
  auto starPixels = [](const Rgba8Image& image) {
    int count = 0;
    for (size_t i = 0; i < image.pixels.size(); i += 4)
      count += std::max({image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]}) >= 40 ? 1 : 0;
    return count;
  };
  const int autoStars = starPixels(automatic.image), fixedStars = starPixels(fixed.image);
  EXPECT_GE(autoStars, 200);
  EXPECT_GE(autoStars, fixedStars);
  EXPECT_LT(displayStats(automatic.image).saturated, autoStars / 20);
  // The sky between them stays black.
  EXPECT_LT(displayStats(automatic.image).mean, 0.05);
}

// Airglow (issue 21, point 4): the night sky's own light, in the HDR frame, against the double
// CPU reference (reference/atmosphere_model.h, airglowAlong) dimmed by the air's transmittance
// (transmittanceToTop): from the sea at night (sun 30° down), looking 60° and 10° up (5.9 times
// brighter toward the horizon before the air dims it), and from 400 km straight down over the
// ocean (the shell in front of the air, not dimmed). The stars and clouds are off (clouds hide
// it as they hide the stars). Over the 8 × 8 pixels
// around the image's centre, the mean ratio of each pixel's luminance to the reference along its
// own ray is within 1 % of 1 (0.1 % today), with the tables and with the per-pixel march; with
// airglow off (airglow_cd_m2 = 0) they are black (below 1 % of it): the light is the airglow's,
// not sunlight scattered round the planet.
TEST_F(ExposureGpu, NightSkyShowsTheAirglowOfTheReference) {
  PlanetDescription earth = resolvePreset("earth");
  earth.stars.enabled = false;  // the sky's own light alone, through clear air
  earth.clouds.enabled = false;
  const RenderSettings settings = smallSettings(false);
  Renderer renderer(context(), earth, settings);
  PlanetDescription dark = earth;
  dark.atmosphere.airglowCdM2 = 0.0;
  Renderer darkRenderer(context(), dark, settings);
  RenderSettings marched = settings;
  marched.sky.mode = SkyMode::Reference;
  Renderer marchRenderer(context(), earth, marched);
  const gpu::AirglowParams airglow = makeAirglowParams(earth);
  const gpu::AtmosphereParams air = makeAtmosphereParams(earth);
  auto luminance = [](const auto& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  const double tanHalf = std::tan(settings.fovYDeg * std::numbers::pi / 360.0);
  const double aspect = double(settings.width) / double(settings.height);
  const SunPose night{135.0, -30.0};
  struct Case {
    const char* name;
    CameraPose pose;
  };
  const Case cases[] = {{"60 degrees up", {20.0, -30.0, 2.0, 135.0, 60.0}},
                        {"10 degrees up", {20.0, -30.0, 2.0, 135.0, 10.0}},
                        {"from 400 km", {0.0, -140.0, 4.0e5, 0.0, -90.0}}};
  for (const Case& c : cases) {
    const RenderResult frame = renderer.render(c.pose, night, 0.0, true);
    const RenderResult off = darkRenderer.render(c.pose, night, 0.0, true);
    const RenderResult march = marchRenderer.render(c.pose, night, 0.0, true);
    writePng((testOutputDir() / fmt::format("airglow_{}.png", c.name)).string(), frame.image);
    const double pitch = c.pose.pitchDeg * std::numbers::pi / 180.0, h = c.pose.altitudeM;
    double ratioSum = 0.0, marchRatioSum = 0.0, offSum = 0.0, referenceSum = 0.0;
    int count = 0;
    for (uint32_t y = settings.height / 2 - 4; y < settings.height / 2 + 4; ++y)
      for (uint32_t x = settings.width / 2 - 4; x < settings.width / 2 + 4; ++x) {
        const size_t i = size_t(y) * settings.width + x;
        // The pixel's ray: its zenith cosine from the camera's pitch and its place on the screen.
        const double sx = ((x + 0.5) / settings.width * 2.0 - 1.0) * tanHalf * aspect;
        const double sy = (1.0 - (y + 0.5) / settings.height * 2.0) * tanHalf;
        const double mu = (std::sin(pitch) + sy * std::cos(pitch)) / std::sqrt(1.0 + sx * sx + sy * sy);
        const AirglowLight light = airglowAlong(airglow, earth.radiusM, h, mu, mu < 0.0 ? h / -mu : 1e30);
        const double reference = luminance(light.nearLight + light.farLight * transmittanceToTop(air, h, mu));
        ratioSum += luminance(frame.hdr[i]) / reference;
        marchRatioSum += luminance(march.hdr[i]) / reference;
        offSum += luminance(off.hdr[i]);
        referenceSum += reference;
        ++count;
      }
    ASSERT_EQ(count, 64) << c.name;
    const double ratio = ratioSum / count;
    std::printf("%s: the sky's luminance is %.4f of the reference's (%.2f times the zenith's), %d pixels\n", c.name,
                ratio, referenceSum / count / (earth.atmosphere.airglowCdM2 / gpu::kExposureSunCdM2), count);
    EXPECT_NEAR(ratio, 1.0, 0.01) << c.name;
    EXPECT_NEAR(marchRatioSum / count, 1.0, 0.01) << c.name << " (--sky reference)";
    EXPECT_LT(offSum, 0.01 * referenceSum) << c.name;
  }
}

// planet render --exposure auto is deterministic: a frame's exposure is its own, whatever the
// renderer drew before (twilight, then noon, then twilight again give identical pixels).
TEST_F(ExposureGpu, AutoExposureRenderIsTheSameEveryTime) {
  const PlanetDescription earth = resolvePreset("earth");
  Renderer renderer(context(), earth, smallSettings(true));
  const SunPose twilight{30.0, -4.0};
  const RenderResult first = renderer.render(kValley, twilight);
  renderer.render(kValley, {30.0, 55.0});
  const RenderResult again = renderer.render(kValley, twilight);
  EXPECT_EQ(first.image.pixels, again.image.pixels);
  EXPECT_EQ(first.exposure->exposure, again.exposure->exposure);
}

// The viewer's adaptation on the GPU follows the CPU step: after noon (taken outright, the
// first frame), each night frame 0.1 s later moves the exposure exactly as adaptExposure does,
// upward but not yet to the night's target.
TEST_F(ExposureGpu, ViewerAdaptationFollowsTheCpuStep) {
  const PlanetDescription earth = resolvePreset("earth");
  Renderer renderer(context(), earth, smallSettings(true));
  renderer.adaptExposureOver(1.0 / 60.0);
  const RenderResult noon = renderer.render(kValley, {30.0, 55.0});
  EXPECT_EQ(noon.exposure->exposure, noon.exposure->target);  // the first frame
  double previous = noon.exposure->exposure;
  for (int frame = 0; frame < 3; ++frame) {
    renderer.adaptExposureOver(0.1);
    const RenderResult night = renderer.render(kValley, {30.0, -30.0});
    const ExposureReport& e = *night.exposure;
    EXPECT_NEAR(e.exposure / adaptExposure(previous, e.target, 0.1), 1.0, 1e-5) << frame;
    EXPECT_GT(e.exposure, previous * 1.05) << frame;
    EXPECT_LT(e.exposure, e.target * 0.95) << frame;
    previous = e.exposure;
  }
  EXPECT_THROW(renderer.adaptExposureOver(-1.0), Error);
}

// ---------------------------------------------------------------------------------------------
// ExposureCli.* (cli)

std::filesystem::path cliDir() { return processTempDir("exposure_cli"); }
ShellRun planet(const std::string& args) { return runShell(PLANET_EXE, args, "", cliDir()); }

// A bad --exposure on render, bench and view is one line naming the value, exit code 2,
// before any Vulkan work or window.
TEST(ExposureCli, BadExposureIsOneLineNamingIt) {
  for (const char* command : {"render", "bench", "view"})
    for (const char* value : {"0", "-1", "bright", "''", "1e7", "nan", "Auto"}) {
      const ShellRun run = planet(fmt::format("{} --exposure {}", command, value));
      EXPECT_EQ(run.exitCode, 2) << command << " " << value << ": " << run.err;
      const std::string shown = std::string(value) == "''" ? "" : value;
      EXPECT_NE(run.err.find(fmt::format("--exposure must be 'auto' or a number in (0, 1e6], got '{}'", shown)),
                std::string::npos)
          << command << " " << value << ": " << run.err;
      EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    }
}

// planet render --exposure auto says what it measured, and gives the same bytes twice (at night:
// the stars only, at the largest exposure).
TEST(ExposureCli, RenderAutoIsDeterministicAndSaysItsExposure) {
  const std::string common = "render --camera 45.3,83.0,0,0,4 --sun 30,-30 --size 96x54 --exposure auto --out ";
  const ShellRun first = planet(common + (cliDir() / "a.png").string());
  if (first.err.find("no Vulkan") != std::string::npos) GTEST_SKIP() << "no Vulkan device";
  ASSERT_EQ(first.exitCode, 0) << first.err;
  EXPECT_NE(first.out.find("exposure: auto 2.097e+06 (trimmed log-average luminance"), std::string::npos) << first.out;
  EXPECT_NE(first.out.find("at the largest exposure"), std::string::npos) << first.out;
  EXPECT_NE(first.out.find(" luminance "), std::string::npos) << first.out;  // the pass is timed
  const ShellRun second = planet(common + (cliDir() / "b.png").string());
  ASSERT_EQ(second.exitCode, 0) << second.err;
  EXPECT_EQ(readFileBytes(cliDir() / "a.png"), readFileBytes(cliDir() / "b.png"));
  // A fixed exposure prints no measurement and runs no luminance pass.
  const ShellRun fixed = planet("render --size 96x54 --out " + (cliDir() / "c.png").string());
  ASSERT_EQ(fixed.exitCode, 0) << fixed.err;
  EXPECT_EQ(fixed.out.find("exposure:"), std::string::npos) << fixed.out;
  EXPECT_EQ(fixed.out.find(" luminance "), std::string::npos) << fixed.out;
}

}  // namespace
}  // namespace planet::test

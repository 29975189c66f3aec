// The starfield on lavapipe (issue 4, point 4): the GPU catalogue against the CPU reference,
// generation recorded once, and a render of stars alone into a half-float target: finite,
// plausibly many lit pixels, light conserved, identical for a seed and different across seeds.
// Writes a tonemapped picture to <temp>/planet_star_out/ for looking at.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <vector>

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "core/image_file.h"
#include "gpu_fixture.h"
#include "camera/camera.h"
#include "render/star_pass.h"
#include "test_support.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/timer.h"

namespace planet::test {
namespace {

using StarfieldGpu = GpuTest;

constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

// Planet-frame direction → clip space for a camera at the origin looking along `forward`.
glm::mat4 directionToClip(const glm::dvec3& forward, double fovYDeg, double aspect) {
  const glm::dvec3 up = std::abs(forward.z) > 0.99 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, up));
  return glm::mat4(reversedZPerspective(fovYDeg * std::numbers::pi / 180.0, aspect, 1.0) *
                   viewMatrix(glm::normalize(forward), glm::cross(right, glm::normalize(forward))));
}

const glm::dvec3 kForward = glm::normalize(glm::dvec3(1.0, 0.3, 0.2));

struct Frame {
  uint32_t width = 0, height = 0;
  std::vector<glm::vec4> pixels;  // RGBA, row-major, top row first
  std::vector<uint8_t> bytes;     // as read back
  std::vector<vk::GpuTiming> timings;
};

// Generates the catalogue (the first time) and draws it alone into a cleared colour target with
// a depth attachment, as the renderer's frame will.
Frame renderStars(vk::Context& context, StarPass& starfield, uint32_t width, uint32_t height,
                  const glm::mat4& toClip) {
  vk::Image color = vk::createImage2D(context, {width, height}, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
  vk::Image depth =
      vk::createImage2D(context, {width, height}, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
  vk::GpuTimer timer;
  timer.create(context, 4);
  Frame frame;
  frame.width = width;
  frame.height = height;
  try {
    vk::submitAndWait(context, [&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      starfield.recordGenerate(cmd, &timer);
      vk::transitionImage(cmd, color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                          VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
      vk::transitionImage(cmd, depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                          VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
      VkRenderingAttachmentInfo colorAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
      colorAttachment.imageView = color.view;
      colorAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      colorAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
      colorAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      colorAttachment.clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}};
      VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
      depthAttachment.imageView = depth.view;
      depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
      depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
      depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
      depthAttachment.clearValue.depthStencil = {0.0f, 0};
      VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
      rendering.renderArea = {{0, 0}, {width, height}};
      rendering.layerCount = 1;
      rendering.colorAttachmentCount = 1;
      rendering.pColorAttachments = &colorAttachment;
      rendering.pDepthAttachment = &depthAttachment;
      vkCmdBeginRendering(cmd, &rendering);
      VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
      VkRect2D scissor{{0, 0}, {width, height}};
      vkCmdSetViewport(cmd, 0, 1, &viewport);
      vkCmdSetScissor(cmd, 0, 1, &scissor);
      starfield.recordDraw(cmd, toClip, float(height), &timer);
      vkCmdEndRendering(cmd);
    });
    frame.timings = timer.results(context);
    frame.bytes = vk::readbackImage(context, color);
  } catch (...) {
    timer.destroy(context);
    vk::destroyImage(context, depth);
    vk::destroyImage(context, color);
    throw;
  }
  timer.destroy(context);
  vk::destroyImage(context, depth);
  vk::destroyImage(context, color);
  std::vector<uint16_t> halves(frame.bytes.size() / 2);
  std::memcpy(halves.data(), frame.bytes.data(), frame.bytes.size());
  for (size_t i = 0; i + 3 < halves.size(); i += 4)
    frame.pixels.push_back(glm::vec4(glm::unpackHalf1x16(halves[i]), glm::unpackHalf1x16(halves[i + 1]),
                                     glm::unpackHalf1x16(halves[i + 2]), glm::unpackHalf1x16(halves[i + 3])));
  return frame;
}

double luminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// 1 − e^(−exposure · v) per channel, then the sRGB transfer function.
Rgba8Image tonemap(const Frame& frame, double exposure) {
  Rgba8Image image;
  image.width = frame.width;
  image.height = frame.height;
  for (const glm::vec4& p : frame.pixels) {
    for (int c = 0; c < 3; ++c) {
      const double linear = 1.0 - std::exp(-exposure * std::max(0.0f, p[c]));
      const double encoded = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
      image.pixels.push_back(uint8_t(std::lround(255.0 * std::clamp(encoded, 0.0, 1.0))));
    }
    image.pixels.push_back(255);
  }
  return image;
}

double timingOf(const Frame& frame, const std::string& name) {
  for (const vk::GpuTiming& t : frame.timings)
    if (t.name == name) return t.milliseconds;
  return -1.0;
}

bool bitIdenticalDevice(const vk::Context& context) { return context.info.driverId == VK_DRIVER_ID_MESA_LLVMPIPE; }

TEST_F(StarfieldGpu, GpuCatalogueEqualsTheCpuReference) {
  StarSettings big;
  big.seed = 77;
  big.count = 100000;
  big.faintestMagnitude = 9.0f;
  for (const StarSettings& settings : {StarSettings{}, big}) {
    StarPass starfield(context(), settings, kColorFormat, kDepthFormat);
    vk::submitAndWait(context(), [&](VkCommandBuffer cmd) { starfield.recordGenerate(cmd); });
    const std::vector<gpu::StarRecord> gpuStars = starfield.readCatalogue();
    const std::vector<gpu::StarRecord> cpuStars = starCatalogueCpu(settings);
    ASSERT_EQ(gpuStars.size(), cpuStars.size());
    size_t identical = 0;
    float worstDirection = 0.0f, worstMagnitude = 0.0f, worstColour = 0.0f, worstTemperature = 0.0f;
    for (size_t i = 0; i < cpuStars.size(); ++i) {
      const gpu::StarRecord& g = gpuStars[i];
      const gpu::StarRecord& c = cpuStars[i];
      identical += std::memcmp(&g, &c, sizeof(g)) == 0 ? 1 : 0;
      for (int k = 0; k < 3; ++k) {
        worstDirection = std::max(worstDirection, std::abs(g.direction[k] - c.direction[k]));
        worstColour = std::max(worstColour, std::abs(g.color[k] - c.color[k]) / std::max(c.color[k], 1e-30f));
      }
      worstMagnitude = std::max(worstMagnitude, std::abs(g.direction.w - c.direction.w));
      worstTemperature = std::max(worstTemperature, std::abs(g.color.w - c.color.w) / c.color.w);
    }
    std::printf("seed %u, %u stars: %zu identical; worst |Δdirection| %.2e, |Δm| %.2e, colour %.2e, T %.2e\n",
                settings.seed, settings.count, identical, worstDirection, worstMagnitude, worstColour,
                worstTemperature);
    if (bitIdenticalDevice(context())) {
      // Lavapipe rounds +, −, ×, ÷ and sqrt exactly, as the CPU does: every bit agrees.
      EXPECT_EQ(identical, cpuStars.size());
    } else {
      // Other GPUs may round division and sqrt within a few ULP (GLSL's stated precision).
      EXPECT_LT(worstDirection, 1e-6f);
      EXPECT_LT(worstMagnitude, 1e-5f);
      EXPECT_LT(worstColour, 1e-5f);
      EXPECT_LT(worstTemperature, 1e-6f);
    }
  }
}

TEST_F(StarfieldGpu, GenerationIsRecordedOnlyOnce) {
  StarPass starfield(context(), StarSettings{}, kColorFormat, kDepthFormat);
  EXPECT_FALSE(starfield.generated());
  EXPECT_NE(errorOf([&] { starfield.readCatalogue(); }).find("before recordGenerate"), std::string::npos);
  const glm::mat4 toClip = directionToClip(kForward, 60.0, 1.0);
  const Frame first = renderStars(context(), starfield, 64, 64, toClip);
  EXPECT_TRUE(starfield.generated());
  EXPECT_GE(timingOf(first, "star catalogue"), 0.0);
  const Frame second = renderStars(context(), starfield, 64, 64, toClip);
  EXPECT_LT(timingOf(second, "star catalogue"), 0.0) << "the second frame generated the catalogue again";
  EXPECT_GE(timingOf(second, "stars"), 0.0);
  EXPECT_EQ(first.bytes, second.bytes);
}

TEST_F(StarfieldGpu, DrawNeedsTheCatalogueAndAViewportHeight) {
  StarPass starfield(context(), StarSettings{}, kColorFormat, kDepthFormat);
  const glm::mat4 toClip = directionToClip(kForward, 60.0, 1.0);
  std::string early;
  vk::submitAndWait(context(), [&](VkCommandBuffer cmd) {
    early = errorOf([&] { starfield.recordDraw(cmd, toClip, 100.0f, nullptr); });
    starfield.recordGenerate(cmd);
  });
  EXPECT_NE(early.find("before recordGenerate"), std::string::npos) << early;
  vk::submitAndWait(context(), [&](VkCommandBuffer cmd) {
    EXPECT_NE(errorOf([&] { starfield.recordDraw(cmd, toClip, 0.0f, nullptr); }).find("height 0"), std::string::npos);
    EXPECT_NE(errorOf([&] { starfield.recordDraw(cmd, toClip, NAN, nullptr); }).find("height nan"), std::string::npos);
  });
  StarSettings bad;
  bad.count = 0;
  EXPECT_NE(errorOf([&] { StarPass s(context(), bad, kColorFormat, kDepthFormat); }).find("star count 0"),
            std::string::npos);
}

TEST_F(StarfieldGpu, StarsAloneLookLikeAStarrySky) {
  const uint32_t size = 256;
  const StarSettings settings;
  StarPass starfield(context(), settings, kColorFormat, kDepthFormat);
  const glm::mat4 toClip = directionToClip(kForward, 60.0, 1.0);
  const Frame frame = renderStars(context(), starfield, size, size, toClip);
  EXPECT_GT(starfield.maxPointSize(), 1.0f) << "lavapipe has largePoints: sprites up to 3 px";

  // The stars the camera sees (inside the clip volume), and the light they bring.
  const std::vector<gpu::StarRecord> stars = starCatalogueCpu(settings);
  size_t visible = 0;
  double expectedLight = 0.0;
  float brightestVisible = 100.0f;
  for (const gpu::StarRecord& s : stars) {
    const glm::vec4 c = toClip * glm::vec4(s.direction.x, s.direction.y, s.direction.z, 0.0f);
    if (c.w <= 0.0f || std::abs(c.x) > c.w || std::abs(c.y) > c.w) continue;
    ++visible;
    expectedLight += settings.brightness * luminance(s.color);
    brightestVisible = std::min(brightestVisible, s.direction.w);
  }

  size_t lit = 0;
  double light = 0.0, brightest = 0.0, starAlpha = 0.0;
  std::vector<double> litValues;
  for (const glm::vec4& p : frame.pixels) {
    for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(p[c])) << "NaN or Inf in the HDR target";
    // Alpha gets each star's relative flux 10^(−0.4 m), negated, at its pixels (for the sky's
    // fade; the sign tells stars from geometry to auto exposure).
    ASSERT_LE(p.a, 1.0f) << "a star raised alpha";
    starAlpha = std::max(starAlpha, 1.0 - double(p.a));
    const double l = luminance(p);
    ASSERT_GE(l, 0.0);
    light += l;
    brightest = std::max(brightest, l);
    if (l > 1e-4) {
      ++lit;
      litValues.push_back(l);
    }
  }
  std::sort(litValues.begin(), litValues.end());
  const double medianLit = litValues.empty() ? 0.0 : litValues[litValues.size() / 2];
  std::printf(
      "%zu stars in view (brightest m = %.2f), %zu lit pixels; light %.4f of %.4f expected; brightest pixel %.4f, "
      "median lit %.6f\n",
      visible, brightestVisible, lit, light, expectedLight, brightest, medianLit);
  // A 60° square view sees 8 % of the sky: ~1,290 of 16,000 stars.
  EXPECT_GT(visible, 1100u);
  EXPECT_LT(visible, 1500u);
  // A faint star lights the one to four pixels nearest to it (above 1e-4, a magnitude-7 star's
  // share at 30 % of its flux); the few bright ones cover up to 5 × 5, and some overlap.
  EXPECT_GT(lit, visible * 8 / 10);
  EXPECT_LT(lit, visible * 4);
  // Light is conserved: each star's pixels add up to its flux (the Gaussian beyond the sprite's
  // edge, ≤ 1.5 %, is lost; stars near the image's edge lose or bring a little).
  EXPECT_NEAR(light / expectedLight, 1.0, 0.03);
  // A few bright stars among many faint ones.
  EXPECT_GT(brightest, 50.0 * medianLit);
  // The brightest star's relative flux taken from alpha (more where a sprite overlaps another's).
  const double brightestFlux = std::pow(10.0, -0.4 * brightestVisible);
  EXPECT_GE(starAlpha, 0.99 * brightestFlux);
  EXPECT_LT(starAlpha, 1.5 * brightestFlux);

  const std::filesystem::path out = testOutputDir();
  writePng((out / "stars_256.png").string(), tonemap(frame, 8.0));
  std::printf("picture: %s\n", (out / "stars_256.png").c_str());
}

TEST_F(StarfieldGpu, StarsDoNotTwinkleAsTheViewTurnsByFractionsOfAPixel) {
  // Turn the view by quarter pixels: a star's light (the sum over its pixels) and the whole
  // picture's stay the same while the star moves between pixel centres.
  const uint32_t size = 256;
  const StarSettings settings;
  StarPass starfield(context(), settings, kColorFormat, kDepthFormat);
  const double pixelAngle = (60.0 / size) * std::numbers::pi / 180.0;
  // The brightest star well inside the view.
  const std::vector<gpu::StarRecord> stars = starCatalogueCpu(settings);
  const glm::mat4 base = directionToClip(kForward, 60.0, 1.0);
  const gpu::StarRecord* bright = nullptr;
  for (const gpu::StarRecord& s : stars) {
    const glm::vec4 c = base * glm::vec4(s.direction.x, s.direction.y, s.direction.z, 0.0f);
    if (c.w > 0.0f && std::abs(c.x) < 0.9f * c.w && std::abs(c.y) < 0.9f * c.w &&
        (!bright || s.direction.w < bright->direction.w))
      bright = &s;
  }
  ASSERT_NE(bright, nullptr);
  std::vector<double> totals, starLight;
  for (int step = 0; step < 5; ++step) {
    const double a = 0.25 * step * pixelAngle;
    const glm::dvec3 f(std::cos(a) * kForward.x - std::sin(a) * kForward.y,
                       std::sin(a) * kForward.x + std::cos(a) * kForward.y, kForward.z);
    const glm::mat4 toClip = directionToClip(f, 60.0, 1.0);
    const Frame frame = renderStars(context(), starfield, size, size, toClip);
    double total = 0.0;
    for (const glm::vec4& p : frame.pixels) total += luminance(p);
    // The bright star's pixels: the 7 × 7 window around where it projects holds its sprite
    // (at most 5 × 5 pixels) and perhaps a faint neighbour or two.
    const glm::vec4 c = toClip * glm::vec4(bright->direction.x, bright->direction.y, bright->direction.z, 0.0f);
    const int cx = int(std::floor((c.x / c.w * 0.5f + 0.5f) * size));
    const int cy = int(std::floor((c.y / c.w * 0.5f + 0.5f) * size));
    double around = 0.0;
    for (int y = cy - 3; y <= cy + 3; ++y)
      for (int x = cx - 3; x <= cx + 3; ++x) around += luminance(frame.pixels[size_t(y) * size + x]);
    totals.push_back(total);
    starLight.push_back(around);
  }
  const double expected = settings.brightness * luminance(bright->color);
  for (size_t k = 0; k < totals.size(); ++k) {
    std::printf("turned %.2f px: picture %.5f, brightest star (m = %.2f) %.5f of %.5f\n", 0.25 * k, totals[k],
                bright->direction.w, starLight[k], expected);
    EXPECT_NEAR(totals[k] / totals[0], 1.0, 0.01) << k;
    EXPECT_NEAR(starLight[k] / starLight[0], 1.0, 0.01) << k;
    EXPECT_NEAR(starLight[k] / expected, 1.0, 0.05) << k;
  }
}

TEST_F(StarfieldGpu, SameSeedGivesIdenticalBytesAndAnotherSeedDoesNot) {
  const glm::mat4 toClip = directionToClip(kForward, 60.0, 1.0);
  auto render = [&](uint32_t seed) {
    StarSettings settings;
    settings.seed = seed;
    StarPass starfield(context(), settings, kColorFormat, kDepthFormat);
    return renderStars(context(), starfield, 256, 256, toClip).bytes;
  };
  const std::vector<uint8_t> a = render(1);
  const std::vector<uint8_t> b = render(1);
  const std::vector<uint8_t> c = render(2);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST_F(StarfieldGpu, TileCullingChangesNoPixelAndSkipsMostStars) {
  struct View {
    glm::dvec3 forward;
    double fovYDeg;
  } views[] = {
      {kForward, 60.0},                     // the view of the tests above
      {glm::dvec3(0.0, 0.0, 1.0), 60.0},    // the pole: every sector's polar tile meets there
      {glm::dvec3(0.3, -1.0, -0.05), 5.0},  // telephoto, the view inside one or two tiles
      {glm::dvec3(-1.0, 0.2, 0.5), 120.0},  // wide
  };
  StarSettings culled, everything;
  everything.cullTiles = false;
  StarPass a(context(), culled, kColorFormat, kDepthFormat);
  StarPass b(context(), everything, kColorFormat, kDepthFormat);
  for (const View& v : views) {
    const glm::mat4 toClip = directionToClip(glm::normalize(v.forward), v.fovYDeg, 1.0);
    const Frame withCulling = renderStars(context(), a, 192, 192, toClip);
    const Frame without = renderStars(context(), b, 192, 192, toClip);
    EXPECT_EQ(withCulling.bytes, without.bytes) << v.fovYDeg << "°";
    const std::filesystem::path out = testOutputDir();
    writePng((out / ("stars_view" + std::to_string(&v - views) + ".png")).string(), tonemap(withCulling, 8.0));
    EXPECT_EQ(b.drawnStarCount(), everything.count);
    // Stars in view: the share of the sky the square view covers, 4 asin(sin²(fov/2)) / 4π.
    const double half = 0.5 * v.fovYDeg * std::numbers::pi / 180.0;
    const double share = std::asin(std::sin(half) * std::sin(half)) / std::numbers::pi;
    std::printf("fov %5.1f°: %u of %u stars drawn, %.0f in view\n", v.fovYDeg, a.drawnStarCount(), culled.count,
                share * culled.count);
    EXPECT_GE(a.drawnStarCount(), share * culled.count * 0.9);
    if (v.fovYDeg <= 60.0) {
      EXPECT_LT(a.drawnStarCount(), culled.count / 4);
    }
  }
}

}  // namespace
}  // namespace planet::test

// The ring pass on lavapipe (issue 8, points 2 and 3): the ring alone in a half-float target,
// seen from both faces, blended over what was drawn before, hidden by nearer depth, darkened
// behind the planet, its opacity per pixel against the CPU reference (also 10 m above the ring
// plane and 10^9 m away), and the shared GLSL functions (ring_eval.comp) against their C++
// compilation. Writes tonemapped pictures to <temp>/planet_ring_out/ for looking at.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <optional>
#include <vector>

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "core/image_file.h"
#include "gpu_fixture.h"
#include "camera/camera.h"
#include "reference/ring_density.h"
#include "render/ring_pass.h"
#include "spv/ring_eval.comp.h"
#include "test_support.h"
#include "vk/buffer.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/owned.h"
#include "vk/pipeline.h"
#include "vk/timer.h"

namespace planet::test {
namespace {

using RingGpu = GpuTest;

constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr double kSaturnRadiusM = 5.8232e7;
constexpr double kFovY = 60.0 * std::numbers::pi / 180.0;

// A camera at `camera` (body frame) looking along `forward`, with `up` toward the top of the picture.
RingView makeView(const glm::dvec3& camera, const glm::dvec3& forward, const glm::dvec3& up, uint32_t width,
                  uint32_t height, const glm::dvec3& sun, double nearM = 1.0) {
  const glm::dvec3 f = glm::normalize(forward);
  const glm::dvec3 u = glm::normalize(up - glm::dot(up, f) * f);
  RingView view;
  view.viewProjection = reversedZPerspective(kFovY, double(width) / double(height), nearM) * viewMatrix(f, u);
  view.cameraBody = camera;
  view.sunBody = sun;
  view.planetRadiusM = kSaturnRadiusM;
  view.nearPlaneM = nearM;
  view.width = width;
  view.height = height;
  view.ambient = 0.0;  // only the sun: the sides and the shadow compare cleanly
  return view;
}

// Straight down on the whole ring from above (+z) or straight up from below (−z).
RingView wholeRingView(bool above, const glm::dvec3& sun, uint32_t size = 256) {
  const double distance = 1.15 * RingDescription{}.outerRadiusM / std::tan(0.5 * kFovY);
  const double side = above ? 1.0 : -1.0;
  return makeView({0.0, 0.0, side * distance}, {0.0, 0.0, -side}, {0.0, 1.0, 0.0}, size, size, sun);
}

struct Backdrop {
  glm::vec4 clear{0.0f, 0.0f, 0.0f, 0.0f};
  std::vector<std::pair<VkRect2D, glm::vec4>> paint;  // colour rectangles drawn before the ring
  std::optional<VkRect2D> nearDepth;                  // depth 1 (the near plane) here before the ring
};

struct Frame {
  uint32_t width = 0, height = 0;
  std::vector<glm::vec4> pixels;  // RGBA, row-major, top row first
  std::vector<vk::GpuTiming> timings;
  const glm::vec4& at(uint32_t x, uint32_t y) const { return pixels[size_t(y) * width + x]; }
};

// Draws the ring alone into a cleared RGBA16F target with a D32 depth buffer cleared to 0
// (infinitely far, reversed Z), after the backdrop's rectangles.
Frame renderRing(vk::Context& context, RingPass& pass, const RingView& view, const Backdrop& backdrop = {},
                 uint32_t slot = 0) {
  const uint32_t width = view.width, height = view.height;
  vk::Image color = vk::createImage2D(context, {width, height}, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
  vk::Image depth =
      vk::createImage2D(context, {width, height}, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
  vk::GpuTimer timer;
  timer.create(context, 4);
  Frame frame;
  frame.width = width;
  frame.height = height;
  std::vector<uint8_t> bytes;
  try {
    pass.prepare(view, slot);
    vk::submitAndWait(context, [&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      // Fresh images: nothing to wait for; the clears below write them.
      vk::transitionImage(cmd, color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                          VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
      vk::transitionImage(
          cmd, depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
          VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
      VkRenderingAttachmentInfo colorAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
      colorAttachment.imageView = color.view;
      colorAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      colorAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
      colorAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      colorAttachment.clearValue.color = {{backdrop.clear.r, backdrop.clear.g, backdrop.clear.b, backdrop.clear.a}};
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
      // What the opaque passes would have left: colours, and depth nearer than the ring.
      for (const auto& [rect, colour] : backdrop.paint) {
        VkClearAttachment clear{VK_IMAGE_ASPECT_COLOR_BIT, 0, {}};
        clear.clearValue.color = {{colour.r, colour.g, colour.b, colour.a}};
        const VkClearRect clearRect{rect, 0, 1};
        vkCmdClearAttachments(cmd, 1, &clear, 1, &clearRect);
      }
      if (backdrop.nearDepth) {
        VkClearAttachment clear{VK_IMAGE_ASPECT_DEPTH_BIT, 0, {}};
        clear.clearValue.depthStencil = {1.0f, 0};
        const VkClearRect clearRect{*backdrop.nearDepth, 0, 1};
        vkCmdClearAttachments(cmd, 1, &clear, 1, &clearRect);
      }
      VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
      VkRect2D scissor{{0, 0}, {width, height}};
      vkCmdSetViewport(cmd, 0, 1, &viewport);
      vkCmdSetScissor(cmd, 0, 1, &scissor);
      pass.recordDraw(cmd, &timer);
      vkCmdEndRendering(cmd);
    });
    frame.timings = timer.results(context);
    bytes = vk::readbackImage(context, color);
  } catch (...) {
    timer.destroy(context);
    vk::destroyImage(context, depth);
    vk::destroyImage(context, color);
    throw;
  }
  timer.destroy(context);
  vk::destroyImage(context, depth);
  vk::destroyImage(context, color);
  std::vector<uint16_t> halves(bytes.size() / 2);
  std::memcpy(halves.data(), bytes.data(), bytes.size());
  for (size_t i = 0; i + 3 < halves.size(); i += 4)
    frame.pixels.push_back(glm::vec4(glm::unpackHalf1x16(halves[i]), glm::unpackHalf1x16(halves[i + 1]),
                                     glm::unpackHalf1x16(halves[i + 2]), glm::unpackHalf1x16(halves[i + 3])));
  return frame;
}

double luminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// The pixel a body-frame point projects to (nullopt: behind the camera or outside the picture).
std::optional<glm::uvec2> pixelOf(const RingView& view, const glm::dvec3& body) {
  const glm::dvec4 clip = view.viewProjection * glm::dvec4(body - view.cameraBody, 1.0);
  if (clip.w <= 0.0) return std::nullopt;
  const double x = (clip.x / clip.w * 0.5 + 0.5) * view.width, y = (clip.y / clip.w * 0.5 + 0.5) * view.height;
  if (x < 0.0 || y < 0.0 || x >= view.width || y >= view.height) return std::nullopt;
  return glm::uvec2(uint32_t(x), uint32_t(y));
}

// Where pixel centre (x + 0.5, y + 0.5) looks at the ring plane, in double: the ring coordinate
// and the cosine of the view ray to the plane's normal (nullopt: the ray misses the plane).
struct PixelRay {
  double u;
  double cosine;
};
std::optional<PixelRay> rayOf(const RingView& view, const gpu::RingParams& ring, double x, double y) {
  const glm::dmat4 inverse = glm::inverse(view.viewProjection);
  const glm::dvec4 nearPoint = inverse * glm::dvec4(x / view.width * 2.0 - 1.0, y / view.height * 2.0 - 1.0, 1.0, 1.0);
  const glm::dvec3 ray = glm::dvec3(nearPoint) / nearPoint.w;
  const double t = -view.cameraBody.z / ray.z;
  if (!(t > 0.0)) return std::nullopt;
  const glm::dvec3 body = view.cameraBody + t * ray;
  return PixelRay{ringCoordinateCpu(ring, std::hypot(body.x, body.y)), ray.z / glm::length(ray)};
}

// The CPU's opacity for pixel (x, y): the reference at the pixel centre's ring coordinate, with
// the footprint fwidth finds, and the view ray's slant. Derivatives come from the pixel's 2×2
// quad: |Δu| across its row's pair plus |Δu| across its column's pair (fine derivatives; where
// u curves fast, a far view, the neighbour on the other side would give a different footprint).
std::optional<float> expectedAlpha(const RingView& view, const gpu::RingParams& ring, uint32_t x, uint32_t y) {
  const double x0 = double(x & ~1u), y0 = double(y & ~1u);
  const auto centre = rayOf(view, ring, x + 0.5, y + 0.5);
  const auto left = rayOf(view, ring, x0 + 0.5, y + 0.5), right = rayOf(view, ring, x0 + 1.5, y + 0.5);
  const auto top = rayOf(view, ring, x + 0.5, y0 + 0.5), bottom = rayOf(view, ring, x + 0.5, y0 + 1.5);
  if (!centre || !left || !right || !top || !bottom) return std::nullopt;
  const double footprint = std::min(1.0, std::abs(right->u - left->u) + std::abs(bottom->u - top->u));
  return ringSlantOpacityCpu(ringOpacityCpu(ring, float(centre->u), float(footprint)), float(centre->cosine));
}

struct AlphaComparison {
  size_t compared = 0, lit = 0;
  double maxError = 0.0, meanError = 0.0;
};
// Every pixel's alpha (the ring was drawn over alpha 0, so the target's alpha is the ring's)
// against expectedAlpha.
AlphaComparison compareAlpha(const Frame& frame, const RingView& view, const gpu::RingParams& ring) {
  AlphaComparison c;
  for (uint32_t y = 0; y < frame.height; ++y)
    for (uint32_t x = 0; x < frame.width; ++x) {
      const auto expected = expectedAlpha(view, ring, x, y);
      if (!expected) continue;
      const double error = std::abs(double(frame.at(x, y).a) - double(*expected));
      c.maxError = std::max(c.maxError, error);
      c.meanError += error;
      ++c.compared;
      if (*expected > 0.05f) ++c.lit;
    }
  if (c.compared) c.meanError /= double(c.compared);
  return c;
}

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

std::filesystem::path outputDir() { return testOutputDir(); }

void expectFinite(const Frame& frame) {
  for (const glm::vec4& p : frame.pixels)
    for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(p[c])) << "NaN or Inf in the HDR target";
}

// Radii (on the +x axis) where the ring is translucent: opacity between lo and hi.
std::vector<double> radiiWithOpacity(const gpu::RingParams& ring, float lo, float hi, size_t count) {
  const RingDescription d;
  std::vector<double> radii;
  for (int i = 1; i < 400 && radii.size() < count; i += 3) {
    const double r = d.innerRadiusM + (d.outerRadiusM - d.innerRadiusM) * i / 400.0;
    const float a = ringOpacityAtRadiusCpu(ring, r);
    if (a > lo && a < hi) radii.push_back(r);
  }
  return radii;
}

const glm::dvec3 kSunAbove = glm::normalize(glm::dvec3(0.2, 0.1, 1.0));

TEST_F(RingGpu, BothFacesAreLitAndTheSunlitFaceIsBrighter) {
  const RingDescription description;
  RingPass pass(context(), description, kColorFormat, kDepthFormat);
  const RingView above = wholeRingView(true, kSunAbove), below = wholeRingView(false, kSunAbove);
  const Frame top = renderRing(context(), pass, above);
  const Frame bottom = renderRing(context(), pass, below);
  expectFinite(top);
  expectFinite(bottom);
  writePng((outputDir() / "ring_above.png").string(), tonemap(top, 12.0));
  writePng((outputDir() / "ring_below.png").string(), tonemap(bottom, 12.0));
  double topLight = 0.0, bottomLight = 0.0;
  for (const glm::vec4& p : top.pixels) topLight += luminance(p);
  for (const glm::vec4& p : bottom.pixels) bottomLight += luminance(p);
  std::printf("light: sunlit face %.3f, far face %.3f (ratio %.2f)\n", topLight, bottomLight, topLight / bottomLight);
  EXPECT_GT(bottomLight, 0.0) << "the far face is black";
  EXPECT_GT(topLight, 1.5 * bottomLight);
  // The same ring points from both sides: each translucent one is lit on both faces, brighter
  // on the sun's (by 1 / (1 − α) without fill light).
  const gpu::RingParams& ring = pass.uniforms().ring;
  const std::vector<double> radii = radiiWithOpacity(ring, 0.15f, 0.85f, 12);
  ASSERT_GE(radii.size(), 4u);
  for (double r : radii) {
    const glm::dvec3 point(r, 0.0, 0.0);
    const auto a = pixelOf(above, point), b = pixelOf(below, point);
    ASSERT_TRUE(a && b);
    const glm::vec4 lit = top.at(a->x, a->y), unlit = bottom.at(b->x, b->y);
    EXPECT_GT(luminance(unlit), 0.0) << r;
    EXPECT_GT(luminance(lit), 1.1 * luminance(unlit)) << r;
    // The opacity is the same from both sides.
    EXPECT_NEAR(lit.a, unlit.a, 0.01) << r;
  }
}

TEST_F(RingGpu, LitParticlesAreAsBrightAsGroundOfTheSameAlbedo) {
  // Per pixel, colour / alpha is the radiance of the particles the pixel sees: albedo / π · E · μs
  // on the sunlit face, terrain.frag's Lambert for ground; an opaque ring (α = 1) is that bright.
  RingDescription description;
  description.colourVariation = description.colour;  // one albedo
  RingPass pass(context(), description, kColorFormat, kDepthFormat);
  RingView view = wholeRingView(true, kSunAbove);
  view.sunIrradiance = 2.0;
  const Frame frame = renderRing(context(), pass, view);
  const double expected = description.colour.g / std::numbers::pi * 2.0 * kSunAbove.z;
  size_t checked = 0;
  for (const glm::vec4& p : frame.pixels) {
    if (p.a < 0.3f) continue;
    EXPECT_NEAR(p.g / p.a, expected, 0.01 * expected);
    ++checked;
  }
  EXPECT_GT(checked, 1000u);
}

TEST_F(RingGpu, TheBackgroundShowsThroughInProportionToTheOpacity) {
  RingPass pass(context(), RingDescription{}, kColorFormat, kDepthFormat);
  const RingView view = wholeRingView(true, kSunAbove);
  const Frame alone = renderRing(context(), pass, view);
  Backdrop backdrop;
  backdrop.clear = glm::vec4(0.05f, 0.1f, 0.2f, 1.0f);
  backdrop.paint.push_back({VkRect2D{{0, 0}, {view.width, view.height / 2}}, glm::vec4(0.3f, 0.2f, 0.1f, 1.0f)});
  const Frame over = renderRing(context(), pass, view, backdrop);
  // Premultiplied "over": result = ring + background · (1 − α), per channel.
  double worst = 0.0;
  size_t gapPixels = 0, densePixels = 0;
  for (uint32_t y = 0; y < view.height; ++y)
    for (uint32_t x = 0; x < view.width; ++x) {
      const glm::vec4 bg = y < view.height / 2 ? backdrop.paint[0].second : backdrop.clear;
      const glm::vec4 ring = alone.at(x, y), result = over.at(x, y);
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, double(std::abs(result[c] - (ring[c] + bg[c] * (1.0f - ring.a)))));
      EXPECT_NEAR(result.a, 1.0f, 1e-3f);
      if (ring.a > 0.0f && ring.a < 0.1f) {
        ++gapPixels;  // the background shows nearly unchanged
        EXPECT_NEAR(result.b, bg.b, 0.12 * bg.b + 0.01);
      }
      if (ring.a > 0.8f) {
        ++densePixels;  // the background is mostly hidden
        EXPECT_LT(std::abs(result.b - ring.b), 0.25 * bg.b);
      }
    }
  std::printf("worst blend error %.2e; %zu gap and %zu dense pixels\n", worst, gapPixels, densePixels);
  EXPECT_LT(worst, 2e-3);
  EXPECT_GT(gapPixels, 100u);
  EXPECT_GT(densePixels, 100u);
}

TEST_F(RingGpu, ThePlanetShadowsTheRingBehindIt) {
  RingPass pass(context(), RingDescription{}, kColorFormat, kDepthFormat);
  const glm::dvec3 sun = glm::normalize(glm::dvec3(1.0, 0.0, 0.25));  // low over +x: the shadow falls toward −x
  const RingView view = wholeRingView(true, sun);
  const Frame frame = renderRing(context(), pass, view);
  writePng((outputDir() / "ring_planet_shadow.png").string(), tonemap(frame, 12.0));
  const std::vector<double> radii = radiiWithOpacity(pass.uniforms().ring, 0.2f, 1.01f, 8);
  ASSERT_GE(radii.size(), 4u);
  for (double r : radii) {
    const auto lit = pixelOf(view, {r, 0.0, 0.0}), shadowed = pixelOf(view, {-r, 0.0, 0.0});
    ASSERT_TRUE(lit && shadowed);
    const double l = luminance(frame.at(lit->x, lit->y)), s = luminance(frame.at(shadowed->x, shadowed->y));
    std::printf("r = %.3g m: sunward %.4f, behind the planet %.5f\n", r, l, s);
    EXPECT_GT(l, 0.005);
    EXPECT_LT(s, 0.02 * l) << r;
    // Not a hole: the ring is there, only dark (its opacity is symmetric).
    EXPECT_NEAR(frame.at(lit->x, lit->y).a, frame.at(shadowed->x, shadowed->y).a, 0.02) << r;
  }
}

TEST_F(RingGpu, NearerDepthHidesTheRing) {
  RingPass pass(context(), RingDescription{}, kColorFormat, kDepthFormat);
  const RingView view = wholeRingView(true, kSunAbove);
  Backdrop backdrop;
  backdrop.clear = glm::vec4(0.1f, 0.2f, 0.3f, 1.0f);
  // The left half holds something at the near plane (depth 1): in front of the ring.
  backdrop.nearDepth = VkRect2D{{0, 0}, {view.width / 2, view.height}};
  const Frame frame = renderRing(context(), pass, view, backdrop);
  const glm::vec4 background = frame.at(0, 0);  // a corner, outside the ring (as stored in half floats)
  EXPECT_EQ(frame.at(view.width - 1, view.height - 1), background);
  size_t changedLeft = 0, changedRight = 0;
  for (uint32_t y = 0; y < view.height; ++y)
    for (uint32_t x = 0; x < view.width; ++x) {
      const bool differs = frame.at(x, y) != background;
      (x < view.width / 2 ? changedLeft : changedRight) += differs ? 1 : 0;
    }
  std::printf("pixels the ring changed: %zu left (hidden), %zu right\n", changedLeft, changedRight);
  EXPECT_EQ(changedLeft, 0u);
  EXPECT_GT(changedRight, size_t(view.width) * view.height / 8);
}

TEST_F(RingGpu, OpacityPerPixelMatchesTheCpuReference) {
  RingPass pass(context(), RingDescription{}, kColorFormat, kDepthFormat);
  const gpu::RingParams ring = ringGpuParams(RingDescription{}, kSaturnRadiusM, kSunAngularRadiusRad);
  struct Case {
    const char* name;
    RingView view;
    double maxError;  // half floats hold alpha to 4.9e-4
  } cases[] = {
      // The whole ring from above: octaves finer than a pixel left out.
      {"whole ring", wholeRingView(true, kSunAbove), 2e-3},
      // 2,000 km above the ring at r = 10^8 m: a pixel is 18 km, only the finest octave fades.
      {"close-up", makeView({0.0, 1.0e8, 2.0e6}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, 128, 128, kSunAbove), 2e-3},
      // 10 m above the ring plane: the pixels see the ring within metres of the camera's foot.
      {"10 m above", makeView({1.0e8, 0.0, 10.0}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, 64, 64, kSunAbove, 0.1), 2e-3},
      // 10 m below, looking along the ring toward its outer edge and beyond: a grazing view.
      {"10 m below, grazing", makeView({1.0e8, 0.0, -10.0}, {1.0, 0.0, 0.05}, {0.0, 0.0, 1.0}, 128, 64, kSunAbove, 0.1),
       2e-3},
      // 10^9 m away at a slant.
      {"10^9 m away", makeView({4.0e8, -8.0e8, 4.0e8}, {-4.0e8, 8.0e8, -4.0e8}, {0.0, 0.0, 1.0}, 160, 120, kSunAbove),
       2e-3},
  };
  for (const Case& c : cases) {
    const Frame frame = renderRing(context(), pass, c.view);
    expectFinite(frame);
    const AlphaComparison result = compareAlpha(frame, c.view, ring);
    std::printf("%s: %zu pixels on the plane (%zu with alpha > 0.05); |Δα| max %.2e, mean %.2e\n", c.name,
                result.compared, result.lit, result.maxError, result.meanError);
    EXPECT_GT(result.lit, 100u) << c.name;
    EXPECT_LT(result.maxError, c.maxError) << c.name;
    EXPECT_LT(result.meanError, 2e-3) << c.name;
  }
}

// --- The shared functions on the GPU (ring_eval.comp) -----------------------------------------

std::vector<glm::vec4> evaluateOnGpu(vk::Context& context, const gpu::RingParams& ring, uint32_t mode,
                                     const std::vector<glm::vec4>& queries, const glm::vec3& sun = glm::vec3(0.0f)) {
  vk::ComputePipeline pipeline =
      vk::createComputePipeline(context, kSpv_ring_eval_comp, 3, sizeof(gpu::RingEvalPush), {}, 1);
  const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  vk::Owned<vk::Buffer> params(context, vk::createBuffer(context, sizeof(ring), usage, vk::MemoryUsage::DeviceLocal));
  vk::Owned<vk::Buffer> input(
      context, vk::createBuffer(context, queries.size() * sizeof(glm::vec4), usage, vk::MemoryUsage::DeviceLocal));
  vk::Owned<vk::Buffer> output(
      context, vk::createBuffer(context, queries.size() * sizeof(glm::vec4), usage, vk::MemoryUsage::DeviceLocal));
  std::vector<glm::vec4> results(queries.size());
  try {
    vk::uploadBuffer(context, *params, &ring, sizeof(ring));
    vk::uploadBuffer(context, *input, queries.data(), queries.size() * sizeof(glm::vec4));
    const vk::Buffer* buffers[] = {&*params, &*input, &*output};
    VkDescriptorSet set = vk::allocateStorageSet(context, pipeline, buffers);
    gpu::RingEvalPush push{};
    push.sun = glm::vec4(sun, 0.0f);
    push.count = uint32_t(queries.size());
    push.mode = mode;
    vk::submitAndWait(context, [&](VkCommandBuffer cmd) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout, 0, 1, &set, 0, nullptr);
      vkCmdPushConstants(cmd, pipeline.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
      vkCmdDispatch(cmd, (push.count + gpu::kRingEvalWorkgroupSize - 1) / gpu::kRingEvalWorkgroupSize, 1, 1);
      // The results are read by a copy or directly by the host.
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                        VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
    });
    vk::readbackBuffer(context, *output, results.data(), results.size() * sizeof(glm::vec4));
  } catch (...) {
    vk::destroyComputePipeline(context, pipeline);
    throw;
  }
  vk::destroyComputePipeline(context, pipeline);
  return results;
}

bool bitIdenticalDevice(const vk::Context& context) { return context.info.driverId == VK_DRIVER_ID_MESA_LLVMPIPE; }

TEST_F(RingGpu, SharedRingFunctionsMatchTheCpuReference) {
  for (uint32_t seed : {1u, 99u}) {
    RingDescription description;
    description.seed = seed;
    description.gaps = 4;
    const gpu::RingParams ring = ringGpuParams(description, kSaturnRadiusM, kSunAngularRadiusRad);

    // ringSample: u across and beyond the ring, footprints from none to the whole ring.
    std::vector<glm::vec4> queries;
    for (int i = -20; i < 4020; ++i)
      for (float footprint : {0.0f, 3e-4f, 4e-3f, 0.2f}) queries.push_back(glm::vec4(i / 4000.0f, footprint, 0, 0));
    const std::vector<glm::vec4> gpuSamples = evaluateOnGpu(context(), ring, gpu::kRingEvalSample, queries);
    size_t identical = 0;
    float worst = 0.0f;
    for (size_t i = 0; i < queries.size(); ++i) {
      const glm::vec4 cpu = ringSampleCpu(ring, queries[i].x, queries[i].y);
      identical += std::memcmp(&cpu, &gpuSamples[i], sizeof(cpu)) == 0 ? 1 : 0;
      for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(cpu[c] - gpuSamples[i][c]));
    }
    std::printf("seed %u ringSample: %zu of %zu identical, worst |Δ| %.2e\n", seed, identical, queries.size(), worst);
    EXPECT_LT(worst, 1e-5f);
    if (bitIdenticalDevice(context())) {
      EXPECT_EQ(identical, queries.size()) << "lavapipe rounds + − × ÷ exactly";
    }

    // ringShadow on the planet's surface and ringPlanetShadow around the ring, for suns north
    // and south of the ring plane.
    for (const glm::vec3 sun :
         {glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f)), glm::normalize(glm::vec3(-0.9f, 0.1f, -0.3f))}) {
      std::vector<glm::vec4> points;
      for (int i = 0; i < 60; ++i)
        for (int j = 0; j < 60; ++j) {
          const double lat = (i + 0.5) / 60.0 * std::numbers::pi - 0.5 * std::numbers::pi;
          const double lon = (j + 0.5) / 60.0 * 2.0 * std::numbers::pi;
          points.push_back(glm::vec4(
              glm::vec3(kSaturnRadiusM *
                        glm::dvec3(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat))),
              0.0f));
        }
      for (int i = 0; i < 3000; ++i) {
        const double r = 6e7 + 1e8 * i / 3000.0, angle = i * 2.399963;
        points.push_back(glm::vec4(float(r * std::cos(angle)), float(r * std::sin(angle)), 0.0f, 0.0f));
      }
      const std::vector<glm::vec4> gpuShadows = evaluateOnGpu(context(), ring, gpu::kRingEvalShadow, points, sun);
      float worstRing = 0.0f, worstPlanet = 0.0f;
      size_t ringShaded = 0, planetShaded = 0;
      for (size_t i = 0; i < points.size(); ++i) {
        const glm::vec3 p(points[i]);
        const float ringCpu = ringShadowCpu(p, sun, ring), planetCpu = ringPlanetShadowCpu(p, sun, ring);
        worstRing = std::max(worstRing, std::abs(ringCpu - gpuShadows[i].x));
        worstPlanet = std::max(worstPlanet, std::abs(planetCpu - gpuShadows[i].y));
        ringShaded += ringCpu < 0.5f ? 1 : 0;
        planetShaded += planetCpu < 0.5f ? 1 : 0;
      }
      std::printf(
          "seed %u sun (%.2f, %.2f, %.2f): ringShadow worst |Δ| %.2e (%zu points below 0.5), "
          "ringPlanetShadow %.2e (%zu)\n",
          seed, sun.x, sun.y, sun.z, worstRing, ringShaded, worstPlanet, planetShaded);
      EXPECT_GT(ringShaded, 50u) << "no point lies in the ring's shadow: the comparison proves little";
      EXPECT_GT(planetShaded, 50u);
      EXPECT_LT(worstRing, 1e-4f);
      EXPECT_LT(worstPlanet, 1e-4f);
    }
  }
  // ringSlantOpacity (pow: within a few ULP on any device).
  std::vector<glm::vec4> slants;
  for (int i = 0; i <= 50; ++i)
    for (float cosine : {1.0f, 0.7f, 0.2f, 0.01f, 0.0f, -0.5f}) slants.push_back(glm::vec4(i / 50.0f, cosine, 0, 0));
  const std::vector<glm::vec4> gpuSlants =
      evaluateOnGpu(context(), ringGpuParams(RingDescription{}, kSaturnRadiusM, 0.0), gpu::kRingEvalSlant, slants);
  for (size_t i = 0; i < slants.size(); ++i)
    EXPECT_NEAR(gpuSlants[i].x, ringSlantOpacityCpu(slants[i].x, slants[i].y), 1e-5f)
        << slants[i].x << " " << slants[i].y;
}

// --- The pass's contract -------------------------------------------------------------------------

TEST_F(RingGpu, FrameSlotsDrawTheSameAndMisuseIsReported) {
  RingPass pass(context(), RingDescription{}, kColorFormat, kDepthFormat);
  std::string early;
  vk::submitAndWait(context(), [&](VkCommandBuffer cmd) { early = errorOf([&] { pass.recordDraw(cmd, nullptr); }); });
  EXPECT_NE(early.find("before prepare"), std::string::npos) << early;
  const RingView view = wholeRingView(true, kSunAbove, 96);
  EXPECT_NE(errorOf([&] { pass.prepare(view, vk::kFramesInFlight); }).find("frame slot"), std::string::npos);
  RingView bad = view;
  bad.sunBody = glm::dvec3(0.0);
  EXPECT_NE(errorOf([&] { pass.prepare(bad); }).find("sun direction"), std::string::npos);
  bad = view;
  bad.width = 0;
  EXPECT_NE(errorOf([&] { pass.prepare(bad); }).find("viewport"), std::string::npos);
  bad = view;
  bad.planetRadiusM = -1.0;
  EXPECT_NE(errorOf([&] { pass.prepare(bad); }).find("ringed body radius"), std::string::npos);
  bad = view;
  bad.viewProjection = glm::dmat4(0.0);
  EXPECT_NE(errorOf([&] { pass.prepare(bad); }).find("singular"), std::string::npos);

  const Frame slot0 = renderRing(context(), pass, view, {}, 0);
  const Frame slot1 = renderRing(context(), pass, view, {}, 1);
  EXPECT_TRUE(pass.drawn());
  EXPECT_EQ(slot0.pixels, slot1.pixels);
  bool timed = false;
  for (const vk::GpuTiming& t : slot1.timings) timed |= t.name == "rings";
  EXPECT_TRUE(timed) << "no \"rings\" timing scope";

  // In the ring plane the disc is edge-on: nothing is drawn.
  const RingView edgeOn = makeView({2e8, 0.0, 0.0}, {-1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 64, 64, kSunAbove);
  const Frame flat = renderRing(context(), pass, edgeOn);
  EXPECT_FALSE(pass.drawn());
  for (const glm::vec4& p : flat.pixels) EXPECT_EQ(p, glm::vec4(0.0f));

  RingDescription wrong;
  wrong.innerRadiusM = 2e8;
  EXPECT_NE(errorOf([&] { RingPass p(context(), wrong, kColorFormat, kDepthFormat); }).find("inner_radius_m"),
            std::string::npos);
}

// A picture to look at: the ring from 25° above its plane, the sun low behind the camera on the
// right, so that the planet's shadow crosses the far side on the left; a striped backdrop shows
// the translucency.
TEST_F(RingGpu, ObliqueViewPicture) {
  RingPass pass(context(), RingDescription{}, kColorFormat, kDepthFormat);
  const double elevation = 22.0 * std::numbers::pi / 180.0, distance = 2.6e8;
  const glm::dvec3 camera(0.0, -distance * std::cos(elevation), distance * std::sin(elevation));
  const glm::dvec3 sun = glm::normalize(glm::dvec3(0.6, -0.6, 0.3));
  RingView view = makeView(camera, -camera, {0.0, 0.0, 1.0}, 640, 360, sun);
  view.ambient = 0.01;
  Backdrop backdrop;
  backdrop.clear = glm::vec4(0.0005f, 0.0008f, 0.002f, 1.0f);
  for (uint32_t x = 0; x < view.width; x += 80)
    backdrop.paint.push_back({VkRect2D{{int32_t(x), 0}, {20, view.height}}, glm::vec4(0.004f, 0.006f, 0.012f, 1.0f)});
  const Frame frame = renderRing(context(), pass, view, backdrop);
  expectFinite(frame);
  const std::filesystem::path path = outputDir() / "ring_oblique.png";
  writePng(path.string(), tonemap(frame, 14.0));
  for (const vk::GpuTiming& t : frame.timings)
    std::printf("%s: %.2f ms at %ux%u on %s\n", t.name.c_str(), t.milliseconds, view.width, view.height,
                context().info.name.c_str());
  std::printf("picture: %s\n", path.c_str());
  // The shadow: ring points straight behind the planet (opposite the sun) are dark, their
  // mirror images on the sunward side are lit.
  const glm::dvec2 away = -glm::normalize(glm::dvec2(sun));
  for (double r : radiiWithOpacity(pass.uniforms().ring, 0.3f, 1.01f, 3)) {
    const auto dark = pixelOf(view, {away.x * r, away.y * r, 0.0}),
               lit = pixelOf(view, {-away.x * r, -away.y * r, 0.0});
    ASSERT_TRUE(dark && lit);
    EXPECT_LT(luminance(frame.at(dark->x, dark->y)), 0.2 * luminance(frame.at(lit->x, lit->y))) << r;
  }
}

}  // namespace
}  // namespace planet::test

// Two frames in flight (the viewer's pattern): Renderer::prepare(slot) and record(slot) for the
// next frame while the other slot's frame has been submitted and not waited for. Under
// synchronization validation (the fixture), the frames must draw exactly what one frame at a
// time (Renderer::render) draws for the same camera sequence, each slot with its own timings.
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "gpu_fixture.h"
#include "render/renderer.h"
#include "vk/commands.h"
#include "vk/context.h"
#include "vk/frame_ring.h"

namespace planet::test {
namespace {

using FramesInFlight = GpuTest;

RenderSettings smallSettings() {
  RenderSettings settings;
  settings.width = 160;
  settings.height = 90;
  settings.terrain.patchSettings.resolution = 128;
  settings.terrain.patchSettings.levelCount = 4;
  return settings;
}

// A camera sequence that changes the LOD, the octave tables and the patch levels every frame,
// and returns to the first camera in the first slot (its buffers held another LOD meanwhile).
const CameraPose kCameras[] = {
    {37.2, -118.6, 2000.0, 30.0, -20.0},
    {37.25, -118.55, 900.0, 60.0, -15.0},
    {37.2, -118.6, 2000.0, 30.0, -20.0},
    {37.3, -118.5, 5000.0, 90.0, -25.0},
};

void recordFrame(Renderer& renderer, vk::FrameRing& slots, uint32_t slot, const CameraPose& camera, double timeS) {
  const SunPose sun{};
  renderer.prepare(camera, sunDirection(sun, renderer.clampToGround(camera)), timeS, slot);
  renderer.record(slots.begin(slot), slot);
}

TEST_F(FramesInFlight, TwoSlotsDrawWhatOneFrameAtATimeDraws) {
  const PlanetDescription planet = resolvePreset("earth");
  const RenderSettings settings = smallSettings();
  const size_t frames = std::size(kCameras);
  auto timeOf = [](size_t i) { return 0.25 * double(i); };

  std::vector<Rgba8Image> expected;  // one frame at a time
  {
    Renderer renderer(context(), planet, settings);
    for (size_t i = 0; i < frames; ++i) expected.push_back(renderer.render(kCameras[i], {}, timeOf(i)).image);
  }
  auto hasTerrainTiming = [&](const Renderer& renderer, uint32_t slot) {
    if (!context().timestampValidBits) return true;
    for (const vk::GpuTiming& timing : renderer.lastTimings(slot))
      if (timing.name == "terrain") return true;
    return false;
  };

  // Every frame checked: frame i is prepared and recorded while frame i−1 (the other slot)
  // executes; then frame i−1 is waited for and its image read before frame i is submitted.
  {
    Renderer renderer(context(), planet, settings);
    vk::FrameRing slots(context());
    for (size_t i = 0; i < frames; ++i) {
      const uint32_t slot = uint32_t(i % Renderer::kFramesInFlight);
      if (slots.wait(slot)) {
        EXPECT_TRUE(hasTerrainTiming(renderer, slot)) << "frame " << i;
      }
      recordFrame(renderer, slots, slot, kCameras[i], timeOf(i));
      if (i > 0) {
        const uint32_t other = uint32_t((i - 1) % Renderer::kFramesInFlight);
        slots.wait(other);
        EXPECT_TRUE(hasTerrainTiming(renderer, other)) << "frame " << i - 1;
        vk::Image& output = renderer.output();
        EXPECT_EQ(vk::readbackImage(context(), output), expected[i - 1].pixels)
            << "frame " << i - 1 << " differs from one frame at a time";
        // The readback ran between frame i's recording and its submission: the image is left
        // as frame i leaves it.
        output.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      }
      slots.submit(slot);
    }
    slots.waitAll();
    EXPECT_EQ(vk::readbackImage(context(), renderer.output()), expected.back().pixels) << "last frame differs";
  }

  // Fully overlapped, as the viewer runs: a slot's frame is submitted without waiting for the
  // other's. Only the last image can be read; synchronization validation checks every frame.
  {
    Renderer renderer(context(), planet, settings);
    vk::FrameRing slots(context());
    for (size_t i = 0; i < frames; ++i) {
      const uint32_t slot = uint32_t(i % Renderer::kFramesInFlight);
      slots.wait(slot);
      recordFrame(renderer, slots, slot, kCameras[i], timeOf(i));
      slots.submit(slot);
    }
    slots.waitAll();
    EXPECT_EQ(vk::readbackImage(context(), renderer.output()), expected.back().pixels) << "last frame differs";
    for (uint32_t slot = 0; slot < Renderer::kFramesInFlight; ++slot)
      EXPECT_TRUE(hasTerrainTiming(renderer, slot)) << "slot " << slot;
  }
}

TEST_F(FramesInFlight, BadSlotsAndUnpreparedRecordsThrow) {
  const PlanetDescription planet = resolvePreset("moon");
  Renderer renderer(context(), planet, smallSettings());
  const CameraPose camera{10.0, 20.0, 3000.0};
  const glm::dvec3 sun(0.0, 0.0, 1.0);
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const uint32_t bad = Renderer::kFramesInFlight;
  EXPECT_NE(message([&] { renderer.prepare(camera, sun, 0.0, bad); }).find("frame slot 2 is outside"),
            std::string::npos);
  EXPECT_NE(message([&] { (void)renderer.lastTimings(bad); }).find("frame slot 2 is outside"), std::string::npos);
  vk::submitAndWait(context(), [&](VkCommandBuffer cmd) {
    EXPECT_NE(message([&] { renderer.record(cmd, 0); }).find("without a prepare"), std::string::npos);
    renderer.prepare(camera, sun, 0.0, 1);
    EXPECT_NE(message([&] { renderer.record(cmd, 0); }).find("without a prepare"), std::string::npos);
    renderer.record(cmd, 1);  // the refused record left slot 1's prepare in place
    EXPECT_NE(message([&] { renderer.record(cmd, 1); }).find("without a prepare"), std::string::npos);
  });
}

}  // namespace
}  // namespace planet::test

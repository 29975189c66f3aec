// The Vulkan core on a real device (lavapipe in CI): device choice, upload/readback of
// buffers and images, timestamps, and the validation messenger itself.
#include <algorithm>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include "core/error.h"
#include "gpu_fixture.h"
#include "noise/noise_gpu.h"
#include "vk/buffer.h"
#include "vk/commands.h"
#include "shared/sky_params.h"
#include "spv/atmosphere_transmittance.comp.h"
#include "vk/image.h"
#include "vk/owned.h"
#include "vk/pipeline.h"

namespace planet::test {
namespace {

using VkCore = GpuTest;

std::vector<uint8_t> randomBytes(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint8_t> bytes(n);
  for (uint8_t& b : bytes) b = uint8_t(rng());
  return bytes;
}

TEST_F(VkCore, DescribesTheChosenDevice) {
  EXPECT_FALSE(context().info.name.empty());
  EXPECT_FALSE(context().info.driver.empty());
  EXPECT_GE(context().info.apiVersion, uint32_t(VK_API_VERSION_1_3));
  EXPECT_NE(context().graphicsQueue, VkQueue(VK_NULL_HANDLE));
  EXPECT_NE(context().computeQueue, VkQueue(VK_NULL_HANDLE));
}

TEST_F(VkCore, DeviceLocalBufferRoundTripsThroughStaging) {
  std::vector<uint8_t> data = randomBytes(3 << 20, 1);
  vk::Buffer buffer =
      vk::createBuffer(context(), data.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::DeviceLocal);
  vk::uploadBuffer(context(), buffer, data.data(), data.size());
  std::vector<uint8_t> back(data.size());
  vk::readbackBuffer(context(), buffer, back.data(), back.size());
  EXPECT_EQ(back, data);
  // A sub-range at an offset.
  std::vector<uint8_t> part(1000);
  vk::readbackBuffer(context(), buffer, part.data(), part.size(), 12345);
  EXPECT_TRUE(std::equal(part.begin(), part.end(), data.begin() + 12345));
  vk::destroyBuffer(context(), buffer);
}

TEST_F(VkCore, OutOfRangeTransfersAreRefused) {
  vk::Buffer buffer = vk::createBuffer(context(), 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::Upload);
  std::vector<uint8_t> data(300);
  EXPECT_THROW(vk::uploadBuffer(context(), buffer, data.data(), data.size()), Error);
  EXPECT_THROW(vk::readbackBuffer(context(), buffer, data.data(), 16, 250), Error);
  vk::destroyBuffer(context(), buffer);
}

TEST_F(VkCore, ImagesRoundTripInEveryEngineFormat) {
  for (VkFormat format : {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT}) {
    VkExtent2D extent{123, 77};  // not a multiple of any tile size
    std::vector<uint8_t> texels = randomBytes(size_t(extent.width) * extent.height * vk::formatTexelSize(format), 2);
    if (format != VK_FORMAT_R8G8B8A8_UNORM)  // keep float texels finite and non-NaN (NaN payloads may change)
      for (size_t i = 3; i < texels.size(); i += 4) texels[i] &= 0x3f;
    vk::Image image =
        vk::createImage2D(context(), extent, format, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT);
    vk::uploadImage(context(), image, texels.data(), texels.size(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(image.layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(vk::readbackImage(context(), image), texels) << "format " << int(format);
    vk::destroyImage(context(), image);
  }
}

TEST_F(VkCore, TimestampsMeasureGpuWork) {
  noise::GpuNoise gpu(context());
  noise::NoiseSettings settings;
  settings.octaves = 8;
  // The same dispatch over 2^14 and 2^18 points: 16 times the work in every part of it (under
  // ASan, lavapipe's per-point cost outside the noise is as large as 32 octaves of it, so more
  // octaves is no reliable measure of more work; more points is).
  const auto fastestMs = [&](size_t count) {
    std::vector<glm::vec3> points(count, glm::vec3(1.0f, 2.0f, 3.0f));
    for (size_t i = 0; i < points.size(); ++i) points[i].x += float(i) * 1e-3f;
    gpu.setPoints(points);
    gpu.dispatch(settings);  // lavapipe compiles a pipeline's machine code on its first dispatch
    // The fastest of three runs: a busy 2-core machine can stall any single dispatch.
    double ms = 1e300;
    for (int run = 0; run < 3; ++run) ms = std::min(ms, gpu.dispatch(settings));
    return ms;
  };
  const double fewMs = fastestMs(size_t(1) << 14);
  const double manyMs = fastestMs(size_t(1) << 18);
  EXPECT_GT(fewMs, 0.0);
  EXPECT_LT(manyMs, 60000.0);
  // Any correct timer sees 16 times the work as clearly more (a constant one does not).
  EXPECT_GT(manyMs, 3.0 * fewMs) << fewMs << " ms for 2^14 points, " << manyMs << " ms for 2^18";
}

// The context's pipeline store (vk/pipeline_store.h): a second user of the same shader,
// specialization and layout definition gets the first one's pipeline, and keeps drawing the
// same values after the first user and its layout are gone (the fixture fails on any validation
// message, layout compatibility included).
TEST_F(VkCore, PipelineStoreSharesAPipelineAcrossLayoutsOfOneDefinition) {
  noise::NoiseSettings settings;
  settings.octaves = 6;
  std::vector<glm::vec3> points(4096);
  for (size_t i = 0; i < points.size(); ++i) points[i] = glm::vec3(float(i) * 0.01f, 1.5f, -2.0f);
  std::vector<float> first(points.size()), second(points.size()), after(points.size());
  auto a = std::make_unique<noise::GpuNoise>(context());
  a->evaluate(settings, points, first);
  const size_t stored = context().pipelines.storedCount();
  const uint64_t hits = context().pipelines.hits();
  EXPECT_GE(stored, 1u);
  {
    noise::GpuNoise b(context());
    b.evaluate(settings, points, second);
    EXPECT_EQ(context().pipelines.hits(), hits + 1);
    EXPECT_EQ(context().pipelines.storedCount(), stored);
    EXPECT_EQ(second, first);
    a.reset();  // the first user, its layout and its sets go
    b.evaluate(settings, points, after);
    EXPECT_EQ(after, first);
  }
  // Nobody holds it now; it stays for the next user.
  EXPECT_EQ(context().pipelines.storedCount(), stored);
}

// What the store keys on: another specialization is another pipeline; a layout whose set layout
// the store never saw is never shared; pipelines nobody holds are kept up to kKeptUnused.
TEST_F(VkCore, PipelineStoreKeepsDifferentStateApartAndBoundsWhatItKeeps) {
  const VkDescriptorType storageImage[] = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
  const uint32_t push = sizeof(gpu::AtmosphereParams);
  auto make = [&](std::vector<uint32_t> specialization) {
    return vk::Owned<vk::ComputePipeline>(
        context(), vk::createComputePipeline(context(), kSpv_atmosphere_transmittance_comp, storageImage, push,
                                             specialization, 1));
  };
  {
    vk::Owned<vk::ComputePipeline> one = make({7u});
    vk::Owned<vk::ComputePipeline> same = make({7u});
    vk::Owned<vk::ComputePipeline> other = make({8u});
    EXPECT_NE(one->layout, same->layout);
    EXPECT_EQ(one->pipeline, same->pipeline);
    EXPECT_NE(one->pipeline, other->pipeline);
  }

  // A set layout made outside vk::createSetLayout: the store cannot know its definition.
  VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  info.bindingCount = 1;
  info.pBindings = &binding;
  VkDescriptorSetLayout raw = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateDescriptorSetLayout(context().device, &info, nullptr, &raw), VK_SUCCESS);
  vk::Owned<VkDescriptorSetLayout> rawSet(context(), raw);
  vk::Owned<VkPipelineLayout> layout(
      context(), vk::createPipelineLayout(context(), raw, push, VK_SHADER_STAGE_COMPUTE_BIT));
  const size_t before = context().pipelines.storedCount();
  {
    vk::Owned<VkPipeline> p(context(), vk::createComputePipelineWithLayout(context(), kSpv_atmosphere_transmittance_comp,
                                                                          layout.get()));
    vk::Owned<VkPipeline> q(context(), vk::createComputePipelineWithLayout(context(), kSpv_atmosphere_transmittance_comp,
                                                                          layout.get()));
    EXPECT_NE(p.get(), q.get());
    EXPECT_EQ(context().pipelines.storedCount(), before);
  }

  // More distinct pipelines than it keeps, each released at once: the oldest go.
  const uint32_t extra = 6;
  for (uint32_t i = 0; i < vk::PipelineStore::kKeptUnused + extra; ++i) make({100u + i});
  EXPECT_EQ(context().pipelines.storedCount(), vk::PipelineStore::kKeptUnused);
  // The most recent are still there: asking again is a hit, not a new pipeline.
  const uint64_t hits = context().pipelines.hits();
  make({100u + vk::PipelineStore::kKeptUnused + extra - 1});
  EXPECT_EQ(context().pipelines.hits(), hits + 1);
}

TEST(VkValidation, MessengerCatchesDeliberateMisuse) {
  std::unique_ptr<vk::Context> context = createTestContext();
  if (!context) GTEST_SKIP() << "no Vulkan device on this machine";
  // A buffer with no usage flags violates VUID-VkBufferCreateInfo-usage-requiredbitmask.
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 64;
  info.usage = 0;
  VkBuffer buffer = VK_NULL_HANDLE;
  vkCreateBuffer(context->device, &info, nullptr, &buffer);
  if (buffer) vkDestroyBuffer(context->device, buffer, nullptr);
  EXPECT_GE(context->validationMessageCount(), 1u) << "the validation layer did not report the misuse";
}

TEST(VkValidation, SynchronizationValidationCatchesAMissingBarrier) {
  std::unique_ptr<vk::Context> context = createTestContext();
  if (!context) GTEST_SKIP() << "no Vulkan device on this machine";
  // Two transfer writes to the same bytes with no barrier between them: a write-after-write
  // hazard that only synchronization validation reports (the calls are valid one by one).
  vk::Buffer buffer = vk::createBuffer(*context, 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::DeviceLocal);
  vk::submitAndWait(*context, [&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, buffer.buffer, 0, 256, 1u);
    vkCmdFillBuffer(cmd, buffer.buffer, 0, 256, 2u);
  });
  vk::destroyBuffer(*context, buffer);
  EXPECT_GE(context->validationMessageCount(), 1u) << "synchronization validation did not report the hazard";
}

TEST(VkDeviceChoice, UnknownDeviceNameIsAnErrorListingTheDevices) {
  if (!createTestContext()) GTEST_SKIP() << "no Vulkan device on this machine";
  vk::ContextOptions options;
  options.deviceName = "no-such-gpu-xyz";
  try {
    vk::createContext(options);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("no Vulkan device matches 'no-such-gpu-xyz'"), std::string::npos) << message;
    EXPECT_NE(message.find("available:"), std::string::npos) << message;
  }
}

TEST(VkDeviceChoice, NameSubstringSelectsTheDeviceCaseInsensitively) {
  std::unique_ptr<vk::Context> first = createTestContext();
  if (!first) GTEST_SKIP() << "no Vulkan device on this machine";
  std::string name = first->info.name;
  vk::destroyContext(*first);
  vk::ContextOptions options;
  options.deviceName = name.substr(0, 4);
  for (char& c : options.deviceName) c = char(std::toupper(static_cast<unsigned char>(c)));
  std::unique_ptr<vk::Context> chosen = vk::createContext(options);
  EXPECT_EQ(chosen->info.name.substr(0, 4), name.substr(0, 4));
}

}  // namespace
}  // namespace planet::test

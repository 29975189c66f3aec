#include "gpu_fixture.h"

#include <string>

#include "core/error.h"

namespace planet::test {

std::unique_ptr<vk::Context> createTestContext(vk::ContextOptions options) {
  options.validation = true;
  options.synchronizationValidation = true;
  try {
    return vk::createContext(options);
  } catch (const Error& e) {
    if (std::string(e.what()).find("no Vulkan") != std::string::npos) return nullptr;
    throw;
  }
}

std::filesystem::path testOutputDir() {
  const std::filesystem::path dir = PLANET_TEST_OUTPUT_DIR;
  std::filesystem::create_directories(dir);
  return dir;
}

void GpuTest::SetUp() {
  context_ = createTestContext();
  if (!context_) GTEST_SKIP() << "no Vulkan device on this machine";
}

void GpuTest::TearDown() {
  if (!context_) return;
  EXPECT_EQ(context_->validationMessageCount(), 0u) << "Vulkan validation reported messages (printed above)";
  EXPECT_NO_THROW(vk::destroyContext(*context_)) << "allocations leaked";
  context_.reset();
}

}  // namespace planet::test

// Fixture for tests that need a Vulkan device: a context with validation (and synchronization
// validation) on; the test fails if any validation message appears or an allocation leaks,
// and is reported as skipped when the machine has no Vulkan device.
#pragma once

#include <filesystem>
#include <memory>

#include <gtest/gtest.h>

#include "vk/context.h"

namespace planet::test {

// A fresh context with `options` and validation (with synchronization validation) forced on, or
// nullptr when no device exists (the caller skips).
std::unique_ptr<vk::Context> createTestContext(vk::ContextOptions options = {});

// The folder for pictures a person may want to look at after a run (the golden images' actual
// and diff on failure, the ring and star renders): BUILD/tests/output (PLANET_TEST_OUTPUT_DIR,
// tests/CMakeLists.txt), made on first use. It stays after the run, outside the temporary
// directory; each test overwrites its own files there.
std::filesystem::path testOutputDir();

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  vk::Context& context() { return *context_; }

  std::unique_ptr<vk::Context> context_;
};

}  // namespace planet::test

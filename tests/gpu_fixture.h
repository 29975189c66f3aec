// Fixture for tests that need a Vulkan device: a context with validation (and synchronization
// validation) on; the test fails if any validation message appears or an allocation leaks,
// and is reported as skipped when the machine has no Vulkan device.
#pragma once

#include <memory>

#include <gtest/gtest.h>

#include "vk/context.h"

namespace planet::test {

// A fresh context with `options` and validation (with synchronization validation) forced on, or
// nullptr when no device exists (the caller skips).
std::unique_ptr<vk::Context> createTestContext(vk::ContextOptions options = {});

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  vk::Context& context() { return *context_; }

  std::unique_ptr<vk::Context> context_;
};

}  // namespace planet::test

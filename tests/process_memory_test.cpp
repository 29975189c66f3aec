// The process memory helpers (core/process_memory.h): the resident set is readable, and with
// glibc's mmap threshold pinned a large block keeps its own mapping even after a larger one
// was freed (by default that free would raise the threshold and put the next block in the heap).
#include <cstdlib>
#include <cstring>

#include <gtest/gtest.h>

#include "core/process_memory.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace planet {
namespace {

// Keeps the compiler from dropping the allocations below.
void* volatile gSink = nullptr;

TEST(ProcessMemory, ResidentSetIsReadable) { EXPECT_GT(residentKiB(), 0); }

TEST(ProcessMemory, LargeBlocksKeepTheirOwnMappingAfterALargerOneWasFreed) {
#if !defined(__GLIBC__) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "glibc's malloc only (a sanitizer replaces it)";
#else
  keepLargeBlocksOutOfTheHeap();
  // What a shader compile does: a block of several MiB, mapped, then freed.
  void* big = std::malloc(8u << 20);
  ASSERT_NE(big, nullptr);
  std::memset(big, 1, 8u << 20);
  gSink = big;
  std::free(big);
  const size_t mappedBefore = mallinfo2().hblkhd;
  void* block = std::malloc(2 * size_t(kLargeBlockBytes));
  ASSERT_NE(block, nullptr);
  gSink = block;
  const size_t mappedDuring = mallinfo2().hblkhd;
  std::free(block);
  EXPECT_GE(mappedDuring, mappedBefore + 2 * size_t(kLargeBlockBytes)) << "the 2 MiB block came from the heap";
  EXPECT_LT(mallinfo2().hblkhd, mappedDuring) << "the block's mapping was not returned";
#endif
}

}  // namespace
}  // namespace planet

// BlockAllocator: the sub-allocation logic behind planet::vk::Allocator, tested without a GPU.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <vector>

#include "vk/allocator.h"

namespace {

using planet::vk::BlockAllocator;
using planet::vk::ResourceKind;

struct Live {
  VkDeviceSize offset;
  VkDeviceSize size;
  ResourceKind kind;
};

VkDeviceSize pageOf(VkDeviceSize byte, VkDeviceSize granularity) { return byte / granularity; }

// Checks the invariants a caller relies on: inside the block, no overlap, byte counts agree.
void expectDisjointAndInside(const BlockAllocator& block, std::vector<Live> live) {
  std::sort(live.begin(), live.end(), [](const Live& a, const Live& b) { return a.offset < b.offset; });
  VkDeviceSize used = 0;
  for (size_t i = 0; i < live.size(); ++i) {
    used += live[i].size;
    ASSERT_LE(live[i].offset + live[i].size, block.size()) << "allocation " << i;
    if (i + 1 < live.size()) {
      ASSERT_LE(live[i].offset + live[i].size, live[i + 1].offset)
          << "allocations at " << live[i].offset << " and " << live[i + 1].offset << " overlap";
    }
  }
  EXPECT_EQ(block.usedBytes(), used);
  EXPECT_EQ(block.allocationCount(), live.size());
}

// Spec, "Buffer-Image Granularity": a linear and an optimal resource must not share a page.
void expectNoSharedLinearOptimalPage(const std::vector<Live>& live, VkDeviceSize granularity) {
  for (size_t i = 0; i < live.size(); ++i) {
    for (size_t j = 0; j < live.size(); ++j) {
      const Live& a = live[i];
      const Live& b = live[j];
      if (a.kind == b.kind || a.offset >= b.offset) continue;
      // a lies before b: a's last page must come before b's first page.
      ASSERT_LT(pageOf(a.offset + a.size - 1, granularity), pageOf(b.offset, granularity))
          << "linear/optimal at " << a.offset << "+" << a.size << " and " << b.offset << "+" << b.size
          << " share a page of " << granularity;
    }
  }
}

TEST(BlockAllocator, NewBlockIsOneFreeRangeOfItsSize) {
  BlockAllocator block(1000);
  EXPECT_EQ(block.size(), 1000u);
  EXPECT_EQ(block.freeRangeCount(), 1u);
  EXPECT_EQ(block.largestFreeRange(), 1000u);
  EXPECT_EQ(block.usedBytes(), 0u);
  EXPECT_TRUE(block.empty());
}

TEST(BlockAllocator, OffsetsRespectRandomPowerOfTwoAlignments) {
  std::mt19937_64 rng(1);
  BlockAllocator block(256ull << 20);
  std::vector<Live> live;
  for (int i = 0; i < 3000; ++i) {
    const VkDeviceSize alignment = VkDeviceSize(1) << (rng() % 17);  // 1 .. 64 KiB
    const VkDeviceSize size = 1 + rng() % 20000;
    const auto kind = (rng() & 1) ? ResourceKind::Linear : ResourceKind::Optimal;
    const auto offset = block.allocate(size, alignment, kind, 1);
    ASSERT_TRUE(offset.has_value()) << "allocation " << i;
    ASSERT_EQ(*offset % alignment, 0u) << "alignment " << alignment;
    live.push_back({*offset, size, kind});
    // Free some so later allocations land in gaps, not only at the end.
    if (rng() % 3 == 0) {
      const size_t victim = rng() % live.size();
      block.free(live[victim].offset);
      live.erase(live.begin() + std::ptrdiff_t(victim));
    }
  }
  expectDisjointAndInside(block, live);
}

TEST(BlockAllocator, LinearAndOptimalNeighboursNeverShareGranularityPage) {
  for (const VkDeviceSize granularity : {64ull, 1024ull, 4096ull, 131072ull}) {
    SCOPED_TRACE(granularity);
    std::mt19937_64 rng(granularity);
    BlockAllocator block(64ull << 20);
    std::vector<Live> live;
    for (int i = 0; i < 4000; ++i) {
      if (!live.empty() && rng() % 5 < 2) {
        const size_t victim = rng() % live.size();
        block.free(live[victim].offset);
        live.erase(live.begin() + std::ptrdiff_t(victim));
        continue;
      }
      const VkDeviceSize size = 1 + rng() % 50000;
      const VkDeviceSize alignment = VkDeviceSize(1) << (rng() % 9);
      const auto kind = (rng() & 1) ? ResourceKind::Linear : ResourceKind::Optimal;
      if (const auto offset = block.allocate(size, alignment, kind, granularity)) live.push_back({*offset, size, kind});
      if (i % 500 == 0) expectNoSharedLinearOptimalPage(live, granularity);
    }
    ASSERT_GT(live.size(), 100u);  // the check below must see many mixed neighbours
    expectNoSharedLinearOptimalPage(live, granularity);
    expectDisjointAndInside(block, live);
  }
}

TEST(BlockAllocator, OptimalAfterLinearStartsOnNextPage) {
  BlockAllocator block(256);
  EXPECT_EQ(block.allocate(10, 1, ResourceKind::Linear, 128), 0u);
  // Would need [128, 328): does not fit.
  EXPECT_EQ(block.allocate(200, 1, ResourceKind::Optimal, 128), std::nullopt);
  EXPECT_EQ(block.allocate(128, 1, ResourceKind::Optimal, 128), 128u);
  // Same kind packs tightly.
  EXPECT_EQ(block.allocate(10, 1, ResourceKind::Linear, 128), 10u);
}

TEST(BlockAllocator, LinearIsNotPlacedInPageOfFollowingOptimal) {
  BlockAllocator block(256);
  const auto first = block.allocate(64, 1, ResourceKind::Optimal, 128);
  const auto second = block.allocate(64, 1, ResourceKind::Optimal, 128);
  ASSERT_EQ(first, 0u);
  ASSERT_EQ(second, 64u);
  block.free(*first);
  // [0, 64) is free but shares page 0 with the optimal allocation at 64.
  EXPECT_EQ(block.allocate(32, 1, ResourceKind::Linear, 128), 128u);
  // An optimal one may use the gap.
  EXPECT_EQ(block.allocate(32, 1, ResourceKind::Optimal, 128), 0u);
}

TEST(BlockAllocator, PicksSmallestFreeRangeThatFits) {
  BlockAllocator block(1000);
  const auto a = block.allocate(300, 1, ResourceKind::Linear, 1);  // [0, 300)
  const auto b = block.allocate(100, 1, ResourceKind::Linear, 1);  // [300, 400)
  const auto c = block.allocate(100, 1, ResourceKind::Linear, 1);  // [400, 500)
  const auto d = block.allocate(100, 1, ResourceKind::Linear, 1);  // [500, 600)
  ASSERT_TRUE(a && b && c && d);
  block.free(*a);  // free: [0, 300), [600, 1000)
  block.free(*c);  // free: [0, 300), [400, 500), [600, 1000)
  EXPECT_EQ(block.freeRangeCount(), 3u);
  EXPECT_EQ(block.allocate(90, 1, ResourceKind::Linear, 1), 400u);
  EXPECT_EQ(block.allocate(250, 1, ResourceKind::Linear, 1), 0u);
  EXPECT_EQ(block.allocate(350, 1, ResourceKind::Linear, 1), 600u);
}

TEST(BlockAllocator, FreeingEverythingCoalescesToOneRangeOfBlockSize) {
  std::mt19937_64 rng(7);
  const VkDeviceSize blockSize = 16ull << 20;
  BlockAllocator block(blockSize);
  std::vector<Live> live;
  for (int i = 0; i < 5000; ++i) {
    const auto kind = (rng() & 1) ? ResourceKind::Linear : ResourceKind::Optimal;
    const VkDeviceSize alignment = VkDeviceSize(1) << (rng() % 12);
    if (const auto offset = block.allocate(1 + rng() % 8000, alignment, kind, 4096)) live.push_back({*offset, 0, kind});
  }
  ASSERT_GT(live.size(), 1000u);
  std::shuffle(live.begin(), live.end(), rng);
  for (const Live& allocation : live) block.free(allocation.offset);
  EXPECT_TRUE(block.empty());
  EXPECT_EQ(block.usedBytes(), 0u);
  EXPECT_EQ(block.freeRangeCount(), 1u);
  EXPECT_EQ(block.largestFreeRange(), blockSize);
}

TEST(BlockAllocator, RandomStressKeepsFreeRangesBoundedAndRecoversWholeBlock) {
  std::mt19937_64 rng(12345);
  const VkDeviceSize blockSize = 64ull << 20;
  BlockAllocator block(blockSize);
  std::vector<Live> live;
  const VkDeviceSize granularity = 1024;
  uint32_t failures = 0;
  for (int op = 0; op < 100000; ++op) {
    // Bias toward allocating until about 2000 are live, then hover there.
    const bool allocate = live.empty() || rng() % 4000 >= live.size();
    if (allocate) {
      // Mostly small, sometimes large, like buffers next to textures; the large ones push the
      // block close to full, so the failure path is exercised too.
      const VkDeviceSize size = (rng() % 16 == 0) ? 1 + rng() % (1 << 20) : 1 + rng() % 4096;
      const VkDeviceSize alignment = VkDeviceSize(1) << (rng() % 13);
      const auto kind = (rng() & 1) ? ResourceKind::Linear : ResourceKind::Optimal;
      if (const auto offset = block.allocate(size, alignment, kind, granularity)) {
        live.push_back({*offset, size, kind});
      } else {
        // A refusal must be honest: a free range with room for the worst alignment padding
        // and a granularity page at either end would always have fit.
        ++failures;
        ASSERT_LT(block.largestFreeRange(), size + alignment + 2 * granularity) << "op " << op;
      }
    } else {
      const size_t victim = rng() % live.size();
      block.free(live[victim].offset);
      live[victim] = live.back();
      live.pop_back();
    }
    // Coalescing means free ranges never touch, so each sits before an allocation or at
    // the end of the block.
    ASSERT_LE(block.freeRangeCount(), block.allocationCount() + 1) << "op " << op;
  }
  expectDisjointAndInside(block, live);
  EXPECT_GT(failures, 0u);  // the workload really did fill the block at times

  for (const Live& allocation : live) block.free(allocation.offset);
  EXPECT_EQ(block.freeRangeCount(), 1u);
  EXPECT_EQ(block.allocate(blockSize, 1 << 16, ResourceKind::Optimal, granularity), 0u);
}

TEST(BlockAllocator, OutOfSpaceReturnsNullopt) {
  BlockAllocator block(1024);
  EXPECT_EQ(block.allocate(2048, 1, ResourceKind::Linear, 1), std::nullopt);
  EXPECT_EQ(block.allocate(1024, 1, ResourceKind::Linear, 1), 0u);
  EXPECT_EQ(block.allocate(1, 1, ResourceKind::Linear, 1), std::nullopt);
  EXPECT_EQ(block.usedBytes(), 1024u);
  EXPECT_EQ(block.largestFreeRange(), 0u);
  EXPECT_EQ(block.freeRangeCount(), 0u);
}

TEST(BlockAllocator, AlignmentPaddingCanMakeFitImpossible) {
  BlockAllocator block(100);
  EXPECT_EQ(block.allocate(60, 1, ResourceKind::Linear, 1), 0u);
  // 40 bytes are free, but the next 64-aligned offset is 64, leaving only 36.
  EXPECT_EQ(block.allocate(40, 64, ResourceKind::Linear, 1), std::nullopt);
  EXPECT_EQ(block.allocate(40, 4, ResourceKind::Linear, 1), 60u);
}

TEST(BlockAllocator, FreeingUnknownOffsetThrows) {
  BlockAllocator block(1024);
  const auto offset = block.allocate(100, 16, ResourceKind::Linear, 1);
  ASSERT_EQ(offset, 0u);
  EXPECT_THROW(block.free(12345), std::logic_error);
  EXPECT_THROW(block.free(50), std::logic_error);   // inside an allocation, not its start
  EXPECT_THROW(block.free(100), std::logic_error);  // start of the free range
  block.free(*offset);
  EXPECT_THROW(block.free(*offset), std::logic_error);  // double free
  EXPECT_TRUE(block.empty());
  EXPECT_EQ(block.freeRangeCount(), 1u);
}

TEST(BlockAllocator, RejectsZeroSizeAndNonPowerOfTwoAlignment) {
  BlockAllocator block(1024);
  EXPECT_THROW(block.allocate(0, 1, ResourceKind::Linear, 1), std::invalid_argument);
  EXPECT_THROW(block.allocate(16, 3, ResourceKind::Linear, 1), std::invalid_argument);
  EXPECT_THROW(block.allocate(16, 1, ResourceKind::Linear, 100), std::invalid_argument);
  EXPECT_TRUE(block.empty());
}

}  // namespace

#include "view/viewer_stats.h"

#include <fmt/format.h>

#include "core/process_memory.h"
#include "core/statistics.h"

namespace planet::view {
namespace {

constexpr size_t kGraphLength = 240;  // intervals the HUD graphs

}  // namespace

void ViewerStats::addInterval(double dtS) {
  recentMs_.push_back(float(dtS * 1000.0));
  while (recentMs_.size() > kGraphLength) recentMs_.pop_front();
}

double ViewerStats::fps() const {
  std::vector<double> recent(recentMs_.begin(), recentMs_.end());
  const double medianMs = recent.empty() ? 0.0 : percentile(recent, 50.0);
  return medianMs > 0.0 ? 1000.0 / medianMs : 0.0;
}

void ViewerStats::frameDrawn(uint32_t index, double dtS, const vk::Allocator& allocator) {
  if (index == 1) firstMs_ = dtS * 1000.0;
  if (index > 1) frameMs_.push_back(dtS * 1000.0);
  if (index + 1 == kWarmupFrames) {
    warm_ = allocator.stats();
    warmRss_ = residentKiB();
  }
}

void ViewerStats::printFrameTimes(uint32_t frames, const std::string& device) const {
  if (frameMs_.empty()) {
    if (firstMs_ > 0.0) fmt::print("frames: {} on {}, the first frame {:.1f} ms\n", frames, device, firstMs_);
    return;
  }
  fmt::print(
      "frames: {} on {}, median {:.1f} ms ({:.1f} fps), p95 {:.1f} ms, max {:.1f} ms; the first frame {:.1f} ms "
      "(shader variants compiled, patch levels built)\n",
      frames, device, percentile(frameMs_, 50.0), 1000.0 / percentile(frameMs_, 50.0), percentile(frameMs_, 95.0),
      percentile(frameMs_, 100.0), firstMs_);
}

void ViewerStats::printMemory(uint32_t frames, const vk::AllocatorStats& end) const {
  if (frames < kWarmupFrames) return;
  fmt::print(
      "memory after frame {}: {} allocations, {} bytes used, {} blocks, RSS {} KiB; after frame {}: {} allocations, "
      "{} bytes used, {} blocks, RSS {} KiB\n",
      kWarmupFrames, warm_.liveAllocations, warm_.bytesUsed, warm_.blocks, warmRss_, frames, end.liveAllocations,
      end.bytesUsed, end.blocks, residentKiB());
}

}  // namespace planet::view

// What the viewer measures as it runs (issue 5): the recent frame times the HUD graphs, and for
// the lines printed on exit, which a soak or leak check reads, every frame's time and the
// allocator's and resident memory after the warm-up frames against the end.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "vk/allocator.h"

namespace planet::view {

class ViewerStats {
 public:
  static constexpr uint32_t kWarmupFrames = 10;  // allocator and RSS figures are compared after these

  // Each pass of the frame loop that draws the HUD: the wall-clock time since the previous one.
  void addInterval(double dtS);
  // The HUD's graph, most recent last, and the frame rate from its median.
  const std::deque<float>& recentMs() const { return recentMs_; }
  double fps() const;

  // Frame `index` (from 0) was submitted, `dtS` after the previous pass.
  void frameDrawn(uint32_t index, double dtS, const vk::Allocator& allocator);
  // The exit lines after `frames` frames: frame-time percentiles (none without frames), and
  // memory after the warm-up against `end` (none before the warm-up ended).
  void printFrameTimes(uint32_t frames, const std::string& device) const;
  void printMemory(uint32_t frames, const vk::AllocatorStats& end) const;

 private:
  std::deque<float> recentMs_;
  // From the third frame on. The first interval began with the loop, not a frame; the second is
  // the first frame's own work, which on a CPU device is mostly compiling the shaders' variants
  // and building the patch levels (~0.6 s at 720x405 on lavapipe): kept apart as firstMs_, so
  // that the maximum says what flying costs.
  std::vector<double> frameMs_;
  double firstMs_ = 0.0;
  vk::AllocatorStats warm_{};
  int64_t warmRss_ = 0;
};

}  // namespace planet::view

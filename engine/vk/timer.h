// Named GPU timing scopes from timestamp queries: timer.begin(cmd, "noise") ... timer.end(cmd),
// read after the submission's fence with timer.results().
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/owned.h"

namespace planet::vk {

class Context;

struct GpuTiming {
  std::string name;
  double milliseconds = 0.0;
  double startMs = 0.0;  // when the scope began, after the first scope of the recording began
};

class GpuTimer {
 public:
  // Room for `maxScopes` scopes per recording. Throws if the device has no timestamps.
  void create(Context& context, uint32_t maxScopes = 32);
  // Destroys the query pool now; the destructor does it otherwise.
  void destroy(Context& context);

  // Resets the queries; record once at the start of each command buffer that uses the timer.
  void reset(VkCommandBuffer cmd);
  void begin(VkCommandBuffer cmd, const std::string& name);
  void end(VkCommandBuffer cmd);
  // Ends the open scope and begins `name` at the same timestamp (after the open scope's work), for
  // passes that follow one another. On lavapipe, which writes a timestamp when its rasterizer
  // reaches it in the render pass it was recorded in, the switch belongs at the end of the
  // earlier render pass: written after the next pass began, it would wait for that pass's vertex
  // work, which lavapipe does when the draws are recorded.
  void next(VkCommandBuffer cmd, const std::string& name);

  // Durations of the scopes recorded since reset(), in recording order. Call only after the
  // command buffer's fence has signalled.
  std::vector<GpuTiming> results(Context& context) const;
  // The last timestamp written since reset(), in milliseconds of the device's clock (its valid
  // bits): comparable between recordings submitted to one queue, so that two frames' ends give the
  // interval between them on the GPU. 0 without scopes. Call only after the fence has signalled.
  double lastStampMs(Context& context) const;

 private:
  // Writes the next timestamp query (they are written in order from 0) and returns its index.
  uint32_t writeQuery(VkCommandBuffer cmd, VkPipelineStageFlags2 stage);

  Owned<VkQueryPool> pool_;
  uint32_t maxScopes_ = 0;
  double periodNs_ = 1.0;
  uint64_t validMask_ = ~0ull;
  std::vector<std::string> names_;
  // Per scope, its start and end queries; a scope begun by next() starts at the one before's end.
  std::vector<std::pair<uint32_t, uint32_t>> scopeQueries_;
  uint32_t queriesWritten_ = 0;
  uint32_t open_ = UINT32_MAX;  // index of the scope begun but not ended
};

}  // namespace planet::vk

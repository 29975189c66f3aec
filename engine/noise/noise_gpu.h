// GPU evaluation of the noise at a buffer of points by the noise_eval compute shader. The
// parameters travel as push constants, so changing them never recompiles anything.
#pragma once

#include <map>
#include <span>
#include <utility>

#include <glm/glm.hpp>

#include "noise/noise_settings.h"
#include "vk/buffer.h"
#include "vk/owned.h"
#include "vk/pipeline.h"
#include "vk/timer.h"

namespace planet::vk {
class Context;
}

namespace planet::noise {

class GpuNoise {
 public:
  explicit GpuNoise(vk::Context& context);
  GpuNoise(const GpuNoise&) = delete;
  GpuNoise& operator=(const GpuNoise&) = delete;

  // Uploads the points (the buffers grow as needed) for the next dispatch() calls.
  void setPoints(std::span<const glm::vec3> points);
  // Evaluates the noise at the current points; returns the GPU time of the dispatches in ms
  // (timestamps, excluding uploads and readback).
  double dispatch(const NoiseSettings& settings);
  // Copies the values of the last dispatch() out.
  void readValues(std::span<float> out);

  // Caps the points of one vkCmdDispatch (default: what maxComputeWorkGroupCount allows);
  // larger sets are split into several dispatches. Rounded down to whole workgroups.
  void setMaxPointsPerDispatch(size_t points);

  // setPoints + dispatch + readValues.
  void evaluate(const NoiseSettings& settings, std::span<const glm::vec3> points, std::span<float> out);

 private:
  void uploadPermutation(uint32_t seed);
  // The pipeline specialised for this type and hash, created on first use.
  const vk::ComputePipeline& pipelineFor(NoiseType type, NoiseHash hash);

  vk::Context& context_;
  // In the order of creation (destroyed in reverse).
  // Keyed by (type, hash). All share one descriptor set layout definition, so the set
  // allocated from the default pipeline's pool binds to every one of them.
  std::map<std::pair<uint32_t, uint32_t>, vk::Owned<vk::ComputePipeline>> pipelines_;
  const vk::ComputePipeline& setOwner() const;
  vk::GpuTimer timer_;
  vk::Owned<vk::Buffer> permutation_;
  vk::Owned<vk::Buffer> points_;  // points_ and values_: replaced when the points outgrow them
  vk::Owned<vk::Buffer> values_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  size_t capacity_ = 0;  // points the buffers can hold
  size_t count_ = 0;     // points set
  int64_t permutationSeed_ = -1;
  size_t maxPointsPerDispatch_ = 0;
};

}  // namespace planet::noise

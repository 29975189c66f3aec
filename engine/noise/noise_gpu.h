// GPU evaluation of the noise (or the noise with its gradient) at a buffer of points by the
// noise_eval compute shader. The parameters travel as push constants, so changing them never
// recompiles anything.
#pragma once

#include <map>
#include <span>
#include <tuple>

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
  // Evaluates the noise with its gradient, vec4(value, d/dx, d/dy, d/dz) per point, at the
  // current points (common/noise_gradient.glsl); returns the GPU time in ms as dispatch() does.
  double dispatchGradient(const NoiseSettings& settings);
  // Copies the values with gradients of the last dispatchGradient() out.
  void readGradients(std::span<glm::vec4> out);

  // Caps the points of one vkCmdDispatch (default: what maxComputeWorkGroupCount allows);
  // larger sets are split into several dispatches. Rounded down to whole workgroups.
  void setMaxPointsPerDispatch(size_t points);

  // setPoints + dispatch + readValues.
  void evaluate(const NoiseSettings& settings, std::span<const glm::vec3> points, std::span<float> out);
  // setPoints + dispatchGradient + readGradients.
  void evaluateGradient(const NoiseSettings& settings, std::span<const glm::vec3> points, std::span<glm::vec4> out);

 private:
  void uploadPermutation(uint32_t seed);
  // The pipeline specialised for this type, hash and output (value or value with gradient),
  // created on first use.
  const vk::ComputePipeline& pipelineFor(NoiseType type, NoiseHash hash, bool gradient);
  double dispatchVariant(const NoiseSettings& settings, bool gradient);
  // Grows the output buffer to `bytes` (a value or a vec4 per point) and points set_ at the buffers.
  void reserveOutput(size_t bytes);
  void writeSet();

  vk::Context& context_;
  // In the order of creation (destroyed in reverse).
  // Keyed by (type, hash, gradient). All share one descriptor set layout definition, so the set
  // allocated from the default pipeline's pool binds to every one of them.
  std::map<std::tuple<uint32_t, uint32_t, uint32_t>, vk::Owned<vk::ComputePipeline>> pipelines_;
  const vk::ComputePipeline& setOwner() const;
  vk::GpuTimer timer_;
  vk::Owned<vk::Buffer> permutation_;
  vk::Owned<vk::Buffer> points_;  // points_ and values_: replaced when the points outgrow them
  vk::Owned<vk::Buffer> values_;  // a float per point, or a vec4 once a gradient was asked for
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  size_t capacity_ = 0;     // points the points buffer can hold
  size_t outputBytes_ = 0;  // bytes values_ holds
  size_t count_ = 0;        // points set
  int lastDispatch_ = -1;   // -1: none yet; 0: values; 1: values with gradients
  int64_t permutationSeed_ = -1;
  size_t maxPointsPerDispatch_ = 0;
};

}  // namespace planet::noise

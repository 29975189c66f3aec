#include "vk/timer.h"

#include "core/error.h"
#include "vk/context.h"

namespace planet::vk {

void GpuTimer::create(Context& context, uint32_t maxScopes) {
  if (context.timestampValidBits == 0 || context.properties.limits.timestampPeriod <= 0.0f)
    throw Error("device '" + context.info.name + "' does not support timestamp queries");
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = maxScopes * 2;
  VkQueryPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateQueryPool(context.device, &info, nullptr, &pool));
  pool_ = {context, pool};
  maxScopes_ = maxScopes;
  periodNs_ = context.properties.limits.timestampPeriod;
  validMask_ = context.timestampValidBits >= 64 ? ~0ull : ((1ull << context.timestampValidBits) - 1);
}

void GpuTimer::destroy(Context&) { pool_.reset(); }

void GpuTimer::reset(VkCommandBuffer cmd) {
  vkCmdResetQueryPool(cmd, pool_.get(), 0, maxScopes_ * 2);
  names_.clear();
  scopeQueries_.clear();
  queriesWritten_ = 0;
  open_ = UINT32_MAX;
}

uint32_t GpuTimer::writeQuery(VkCommandBuffer cmd, VkPipelineStageFlags2 stage) {
  vkCmdWriteTimestamp2(cmd, stage, pool_.get(), queriesWritten_);
  return queriesWritten_++;
}

void GpuTimer::begin(VkCommandBuffer cmd, const std::string& name) {
  if (open_ != UINT32_MAX) throw Error("GPU timer scope '" + name + "' begun inside '" + names_[open_] + "'");
  if (names_.size() >= maxScopes_) throw Error("GPU timer has no room for scope '" + name + "'");
  open_ = uint32_t(names_.size());
  names_.push_back(name);
  // Top of pipe: the scope starts when its commands could first start.
  scopeQueries_.push_back({writeQuery(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT), 0});
}

void GpuTimer::end(VkCommandBuffer cmd) {
  if (open_ == UINT32_MAX) throw Error("GPU timer end() without begin()");
  // Bottom of pipe: after every command recorded in the scope has finished.
  scopeQueries_[open_].second = writeQuery(cmd, VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT);
  open_ = UINT32_MAX;
}

void GpuTimer::next(VkCommandBuffer cmd, const std::string& name) {
  if (open_ == UINT32_MAX) throw Error("GPU timer next('" + name + "') without begin()");
  if (names_.size() >= maxScopes_) throw Error("GPU timer has no room for scope '" + name + "'");
  const uint32_t previous = open_;
  end(cmd);
  // The end just written is the new scope's start: one timestamp, so no time falls between the
  // two (two stamps written back to back were apart by however long the queue thread was
  // descheduled between them, 5 ms on a loaded 2-core machine).
  open_ = uint32_t(names_.size());
  names_.push_back(name);
  scopeQueries_.push_back({scopeQueries_[previous].second, 0});
}

std::vector<GpuTiming> GpuTimer::results(Context& context) const {
  std::vector<GpuTiming> timings;
  if (names_.empty()) return timings;
  // The queries were written in order from 0, so one read takes them all.
  std::vector<uint64_t> stamps(queriesWritten_);
  VK_CHECK(vkGetQueryPoolResults(context.device, pool_.get(), 0, queriesWritten_, stamps.size() * sizeof(uint64_t),
                                 stamps.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  const uint64_t first = stamps[scopeQueries_[0].first];
  for (size_t i = 0; i < names_.size(); ++i) {
    const auto [begin, end] = scopeQueries_[i];
    const uint64_t ticks = (stamps[end] - stamps[begin]) & validMask_;
    const uint64_t start = (stamps[begin] - first) & validMask_;
    timings.push_back({names_[i], double(ticks) * periodNs_ * 1e-6, double(start) * periodNs_ * 1e-6});
  }
  return timings;
}

double GpuTimer::lastStampMs(Context& context) const {
  if (queriesWritten_ == 0) return 0.0;
  uint64_t stamp = 0;
  VK_CHECK(vkGetQueryPoolResults(context.device, pool_.get(), queriesWritten_ - 1, 1, sizeof(stamp), &stamp,
                                 sizeof(stamp), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  return double(stamp & validMask_) * periodNs_ * 1e-6;
}

}  // namespace planet::vk

#include "vk/pipeline_store.h"

#include <string_view>

#include "core/error.h"
#include "vk/pipeline.h"

namespace planet::vk {

void appendKey(std::string& key, const void* data, size_t size) {
  if (size) key.append(static_cast<const char*>(data), size);
}

void appendSpirvKey(std::string& key, std::span<const uint32_t> spirv) {
  // Two unrelated 64-bit hashes (FNV-1a and the standard library's) and the length: the store's
  // keys stay short, and two different shaders would have to collide in both.
  const std::string_view bytes(reinterpret_cast<const char*>(spirv.data()), spirv.size_bytes());
  uint64_t fnv = 0xcbf29ce484222325ull;
  for (unsigned char c : bytes) fnv = (fnv ^ c) * 0x100000001b3ull;
  appendKey(key, uint64_t(bytes.size()));
  appendKey(key, fnv);
  appendKey(key, uint64_t(std::hash<std::string_view>{}(bytes)));
}

std::string PipelineStore::LayoutDefinition::key() const {
  std::string bytes;
  appendKey(bytes, uint8_t(setLayout ? 1 : 0));
  if (setLayout) {
    appendKeySpan(bytes, std::span<const VkDescriptorType>(setLayout->bindings));
    appendKey(bytes, setLayout->stages);
  }
  appendKey(bytes, pushConstantSize);
  appendKey(bytes, pushStages);
  return bytes;
}

void PipelineStore::noteSetLayout(VkDescriptorSetLayout layout, std::span<const VkDescriptorType> bindings,
                                  VkShaderStageFlags stages) {
  std::lock_guard lock(mutex_);
  setLayouts_[layout] = {{bindings.begin(), bindings.end()}, stages};
}

void PipelineStore::notePipelineLayout(VkPipelineLayout layout, VkDescriptorSetLayout setLayout,
                                       uint32_t pushConstantSize, VkShaderStageFlags pushStages) {
  std::lock_guard lock(mutex_);
  if (setLayout) {
    auto known = setLayouts_.find(setLayout);
    if (known == setLayouts_.end()) {
      layouts_.erase(layout);  // a set layout made elsewhere: this layout's pipelines are not shared
      return;
    }
    layouts_[layout] = {known->second, pushConstantSize, pushConstantSize ? pushStages : 0};
  } else {
    layouts_[layout] = {std::nullopt, pushConstantSize, pushConstantSize ? pushStages : 0};
  }
}

void PipelineStore::forgetSetLayout(VkDescriptorSetLayout layout) {
  std::lock_guard lock(mutex_);
  setLayouts_.erase(layout);
}

void PipelineStore::forgetPipelineLayout(VkPipelineLayout layout) {
  std::lock_guard lock(mutex_);
  layouts_.erase(layout);
}

VkPipeline PipelineStore::get(VkDevice device, VkPipelineLayout layout, const std::string& state,
                              const std::function<VkPipeline(VkPipelineLayout)>& create) {
  std::lock_guard lock(mutex_);
  auto known = layouts_.find(layout);
  if (known == layouts_.end()) return create(layout);  // not shared (released as unknown)
  const LayoutDefinition definition = known->second;
  std::string key = definition.key();
  appendKey(key, uint64_t(state.size()));
  key += state;
  if (auto found = entries_.find(key); found != entries_.end()) {
    ++found->second.users;
    ++hits_;
    return found->second.pipeline;
  }
  // The store's own copy of the layout, for the pipeline to be made with and to outlive it.
  Entry entry;
  try {
    if (definition.setLayout)
      entry.setLayout = createSetLayoutOn(device, definition.setLayout->bindings, definition.setLayout->stages);
    entry.layout =
        createPipelineLayoutOn(device, entry.setLayout, definition.pushConstantSize, definition.pushStages);
    entry.pipeline = create(entry.layout);
  } catch (...) {
    destroyEntry(device, entry);
    throw;
  }
  entry.users = 1;
  keyOf_[entry.pipeline] = key;
  const VkPipeline pipeline = entry.pipeline;
  entries_.emplace(std::move(key), entry);
  return pipeline;
}

bool PipelineStore::release(VkDevice device, VkPipeline pipeline) {
  std::lock_guard lock(mutex_);
  auto key = keyOf_.find(pipeline);
  if (key == keyOf_.end()) return false;
  Entry& entry = entries_.at(key->second);
  if (entry.users == 0) throw Error("a stored pipeline was released more often than it was handed out");
  if (--entry.users == 0) {
    entry.releasedAt = ++releases_;
    trimUnused(device);
  }
  return true;
}

void PipelineStore::trimUnused(VkDevice device) {
  // Called under the lock: drop the least recently released unused pipelines beyond kKeptUnused.
  for (;;) {
    size_t unused = 0;
    auto oldest = entries_.end();
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      if (it->second.users) continue;
      ++unused;
      if (oldest == entries_.end() || it->second.releasedAt < oldest->second.releasedAt) oldest = it;
    }
    if (unused <= kKeptUnused) return;
    keyOf_.erase(oldest->second.pipeline);
    destroyEntry(device, oldest->second);
    entries_.erase(oldest);
  }
}

void PipelineStore::destroyEntry(VkDevice device, Entry& entry) {
  if (entry.pipeline) vkDestroyPipeline(device, entry.pipeline, nullptr);
  if (entry.layout) vkDestroyPipelineLayout(device, entry.layout, nullptr);
  if (entry.setLayout) vkDestroyDescriptorSetLayout(device, entry.setLayout, nullptr);
  entry = Entry{};
}

void PipelineStore::destroyAll(VkDevice device) {
  std::lock_guard lock(mutex_);
  for (auto& [key, entry] : entries_) destroyEntry(device, entry);
  entries_.clear();
  keyOf_.clear();
  setLayouts_.clear();
  layouts_.clear();
}

size_t PipelineStore::storedCount() const {
  std::lock_guard lock(mutex_);
  return entries_.size();
}

uint64_t PipelineStore::hits() const {
  std::lock_guard lock(mutex_);
  return hits_;
}

}  // namespace planet::vk

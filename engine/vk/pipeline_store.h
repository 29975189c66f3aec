// Pipelines shared by everything one Context creates. Creating a pipeline on lavapipe takes
// seconds for the noise shaders (most of it NIR work inside the driver, which has no pipeline
// cache of its own in Mesa 22.3), and every Renderer of a planet created the same ones again: the
// viewer on each rebuild (quality, mesh, field of view), `planet bench --compare` per mode, the
// tests several times a test. The store hands out the pipeline made for the same shaders,
// specialization, layout definition and fixed state instead.
//
// Sharing is safe because a stored pipeline is made with a layout of the store's own, created
// from the caller's layout definition: pipeline layouts with identically defined set layouts and
// push-constant ranges are compatible (Vulkan spec, "Pipeline Layout Compatibility"), so each
// caller binds its sets and pushes its constants with its own layout, and no stored pipeline
// outlives the layout it was made with. Layouts whose definition the store did not see (created
// outside vk::createSetLayout and vk::createPipelineLayout) are never shared.
//
// Callers own what they get as before (vk::Owned or destroyComputePipeline): destroying a
// stored pipeline releases it to the store, which keeps the kKeptUnused most recently released
// ones that no caller holds and destroys older ones; destroyContext destroys the rest.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include <vulkan/vulkan.h>

namespace planet::vk {

class PipelineStore {
 public:
  // Unreferenced pipelines kept for a later caller (the viewer's rebuild, the next Renderer).
  static constexpr size_t kKeptUnused = 48;

  // What the store knows of the layouts created through vk::createSetLayout and
  // vk::createPipelineLayout; forgotten when they are destroyed (handles are reused).
  void noteSetLayout(VkDescriptorSetLayout layout, std::span<const VkDescriptorType> bindings,
                     VkShaderStageFlags stages);
  void notePipelineLayout(VkPipelineLayout layout, VkDescriptorSetLayout setLayout, uint32_t pushConstantSize,
                          VkShaderStageFlags pushStages);
  void forgetSetLayout(VkDescriptorSetLayout layout);
  void forgetPipelineLayout(VkPipelineLayout layout);

  // The pipeline for `state` (every input of the creation but the layout: the caller's own
  // bytes) over a layout defined as `layout`: a stored one, or one `create` makes with a layout
  // of the store's own (then stored). Without a known definition of `layout`, `create` makes it
  // with `layout` and it is not shared. Either way the caller owns one reference.
  VkPipeline get(VkDevice device, VkPipelineLayout layout, const std::string& state,
                 const std::function<VkPipeline(VkPipelineLayout)>& create);

  // Called for every pipeline the vk functions destroy: true when it is a stored one (one
  // reference fewer; the store decides when it goes), false when the caller must destroy it.
  bool release(VkDevice device, VkPipeline pipeline);

  // Destroys every stored pipeline and the store's layouts (the device is still alive).
  void destroyAll(VkDevice device);

  // Counts for tests and logs.
  size_t storedCount() const;
  uint64_t hits() const;

 private:
  struct SetLayoutDefinition {
    std::vector<VkDescriptorType> bindings;  // binding i has type bindings[i]
    VkShaderStageFlags stages = 0;
  };
  struct LayoutDefinition {
    std::optional<SetLayoutDefinition> setLayout;  // none without a set
    uint32_t pushConstantSize = 0;
    VkShaderStageFlags pushStages = 0;
    std::string key() const;
  };
  struct Entry {
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;          // the store's own
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;  // the store's own (or none)
    uint32_t users = 0;
    uint64_t releasedAt = 0;  // order of the last release, for keeping the most recent
  };

  void destroyEntry(VkDevice device, Entry& entry);
  void trimUnused(VkDevice device);

  mutable std::mutex mutex_;
  std::unordered_map<VkDescriptorSetLayout, SetLayoutDefinition> setLayouts_;
  std::unordered_map<VkPipelineLayout, LayoutDefinition> layouts_;
  std::unordered_map<std::string, Entry> entries_;
  std::unordered_map<VkPipeline, std::string> keyOf_;
  uint64_t releases_ = 0;
  uint64_t hits_ = 0;
};

// Appends the bytes of a value or of a span to a pipeline's state key.
void appendKey(std::string& key, const void* data, size_t size);
template <typename T>
void appendKey(std::string& key, const T& value) {
  appendKey(key, &value, sizeof(value));
}
// A shader's SPIR-V, by its length and two hashes of its words.
void appendSpirvKey(std::string& key, std::span<const uint32_t> spirv);
// A span: its length, then its bytes (so that neighbouring spans cannot run into each other).
template <typename T>
void appendKeySpan(std::string& key, std::span<const T> values) {
  appendKey(key, uint64_t(values.size_bytes()));
  appendKey(key, values.data(), values.size_bytes());
}

}  // namespace planet::vk

// Ownership of Vulkan objects: vk::Owned<T> holds one object (a raw handle or one of the thin
// structs Buffer, Image, ComputePipeline, Swapchain) and destroys it when it goes out of scope
// or is assigned another. A pass declares its objects as Owned members in the order it creates
// them; C++ then destroys them in reverse order, in the destructor and also when the
// constructor throws half-way, so no pass writes a release() of its own. The handles stay
// plain: get() gives the object to pass to Vulkan.
#pragma once

#include <utility>

#include <vulkan/vulkan.h>

namespace planet::vk {

class Context;
struct Buffer;
struct Image;
struct ComputePipeline;
struct Swapchain;

// What Owned calls: the object's destroy function, which accepts (and skips) a null object.
void destroyOwned(Context& context, Buffer& buffer);
void destroyOwned(Context& context, Image& image);
void destroyOwned(Context& context, ComputePipeline& pipeline);
void destroyOwned(Context& context, Swapchain& swapchain);
void destroyOwned(Context& context, VkPipeline& pipeline);
void destroyOwned(Context& context, VkPipelineLayout& layout);
void destroyOwned(Context& context, VkDescriptorSetLayout& layout);
// Descriptor sets allocated from the pool go with it.
void destroyOwned(Context& context, VkDescriptorPool& pool);
void destroyOwned(Context& context, VkSampler& sampler);
void destroyOwned(Context& context, VkBufferView& view);
void destroyOwned(Context& context, VkShaderModule& module);
void destroyOwned(Context& context, VkQueryPool& pool);
// Command buffers allocated from the pool go with it.
void destroyOwned(Context& context, VkCommandPool& pool);
void destroyOwned(Context& context, VkFence& fence);
void destroyOwned(Context& context, VkSemaphore& semaphore);
void destroyOwned(Context& context, VkRenderPass& pass);
void destroyOwned(Context& context, VkFramebuffer& framebuffer);
// A surface belongs to the instance (destroy it after every swapchain made on it).
void destroyOwned(Context& context, VkSurfaceKHR& surface);

template <typename T>
class Owned {
 public:
  Owned() = default;
  Owned(Context& context, T object) : context_(&context), object_(object) {}
  Owned(Owned&& other) noexcept : context_(other.context_), object_(std::exchange(other.object_, T{})) {}
  Owned& operator=(Owned&& other) noexcept {
    if (this != &other) {
      reset();
      context_ = other.context_;
      object_ = std::exchange(other.object_, T{});
    }
    return *this;
  }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned() { reset(); }

  // Destroys the object now (nothing when empty).
  void reset() {
    if (context_) destroyOwned(*context_, object_);
    object_ = T{};
  }
  // Gives the object up without destroying it: the caller owns it from now on.
  T release() { return std::exchange(object_, T{}); }

  const T& get() const { return object_; }
  T& operator*() { return object_; }
  const T& operator*() const { return object_; }
  T* operator->() { return &object_; }
  const T* operator->() const { return &object_; }

 private:
  Context* context_ = nullptr;
  T object_{};
};

}  // namespace planet::vk

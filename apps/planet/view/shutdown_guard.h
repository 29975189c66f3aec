// The viewer's libraries that are started and stopped by plain functions, with no handle for
// vk::Owned to hold (GLFW, Dear ImGui's context and backends): a ShutdownGuard member, set once
// the start succeeded, calls the stop function when it goes out of scope. Declared in the order
// of starting, they stop in reverse, in the destructor and when a constructor throws half-way.
#pragma once

#include <utility>

namespace planet::view {

class ShutdownGuard {
 public:
  ShutdownGuard() = default;
  explicit ShutdownGuard(void (*stop)()) : stop_(stop) {}
  ShutdownGuard(ShutdownGuard&& other) noexcept : stop_(std::exchange(other.stop_, nullptr)) {}
  ShutdownGuard& operator=(ShutdownGuard&& other) noexcept {
    if (this != &other) {
      reset();
      stop_ = std::exchange(other.stop_, nullptr);
    }
    return *this;
  }
  ShutdownGuard(const ShutdownGuard&) = delete;
  ShutdownGuard& operator=(const ShutdownGuard&) = delete;
  ~ShutdownGuard() { reset(); }

  // Stops now (nothing when not set or already stopped).
  void reset() {
    if (auto stop = std::exchange(stop_, nullptr)) stop();
  }
  explicit operator bool() const { return stop_ != nullptr; }

 private:
  void (*stop_)() = nullptr;
};

}  // namespace planet::view

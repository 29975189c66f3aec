// The viewer's Renderer as the panel edits it (issue 5): built for the window from the
// ViewerSettings at their quality, rebuilt when the planet, mesh, quality or view change (from
// the settings that last built when the Renderer refuses new ones), resized with the window,
// and its cheap settings (sky, terrain toggles) applied in place.
#pragma once

#include <memory>
#include <string>

#include <vulkan/vulkan.h>

#include "planet/scene_description.h"
#include "render/renderer.h"
#include "view/viewer_ui.h"

namespace planet::vk {
class Context;
class FrameRing;
}  // namespace planet::vk

namespace planet::view {

class ViewerRenderer {
 public:
  // `slots`: where the frames that may still use the Renderer were submitted. `scene`: draw its
  // bodies instead of the settings' planet (planet view --scene); it must outlive this.
  ViewerRenderer(vk::Context& context, vk::FrameRing& slots, const SceneDescription* scene);

  Renderer& get() { return *renderer_; }

  // A new Renderer from `settings` for a window of `window` pixels, once no frame uses the old
  // one, whose memory goes first. Throws planet::Error when the Renderer refuses the settings.
  void build(const ViewerSettings& settings, VkExtent2D window);
  // What the panel changed: a rebuild (when refused: said in `status`, and built again from the
  // settings that last built, which go back into `settings`), else the sky and terrain setters.
  void apply(const UiRequests& requests, ViewerSettings& settings, VkExtent2D window, std::string& status);
  // The window changed size: the render size follows it.
  void resize(const ViewerSettings& settings, VkExtent2D window);

 private:
  RenderSettings renderSettings(const ViewerSettings& settings, VkExtent2D window) const;
  void waitIdle();
  void applyTerrainToggles(const ViewerSettings& settings);

  vk::Context& context_;
  vk::FrameRing& slots_;
  const SceneDescription* scene_;
  std::unique_ptr<Renderer> renderer_;
  ViewerSettings built_;  // what the current Renderer was built from (planet, quality, mesh, view)
};

}  // namespace planet::view

// planet view: the real-time viewer (issue 5). A GLFW window with a Vulkan swapchain; every
// frame the Renderer's passes (the same ones planet render uses) draw into its offscreen
// target, which is blitted to the swapchain image, and Dear ImGui draws the panel and HUD on top.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "planet/planet_description.h"
#include "planet/scene_description.h"
#include "camera/camera.h"
#include "camera/camera_path.h"
#include "render/sky_pass.h"
#include "render/view_quality.h"

namespace planet::view {

struct ViewOptions {
  PlanetDescription planet;          // resolved by the caller (planet view --preset), before any window opens
  std::optional<CameraPose> camera;  // default: over the Atlantic from 20,000 km
  SunPose sun;                       // seen from the starting camera's ground point
  uint32_t width = 1280, height = 720;
  bool vsync = true;
  double fovDeg = 60.0;
  std::optional<ViewQuality> quality;  // default: by device (defaultViewQuality)
  uint32_t frames = 0;                 // exit after this many frames (0: when the window closes)
  std::string screenshot;              // save the last frame here (PNG, without the panel)
  std::optional<CameraPath> path;      // play this camera path (with `frames`: spread over them)
  bool hideUi = false;                 // start with the panel hidden (F2 shows it)
  bool lights = true;                  // the presets' city lights (planet view --no-lights)
  // Eye adaptation (the default), or a fixed exposure.
  bool autoExposure = true;
  double exposure = 10.0;  // SkySettings{}.exposure
  SkyMode skyMode = SkyMode::Tables;   // planet view --sky
  bool deferredShading = false;        // planet view --terrain-shading (TerrainSettings::deferredShading)
  // A scene of several bodies instead of `planet` (planet view --scene): the camera starts on
  // body `sceneBody` at `camera`, the scene's clock at sceneTimeS, running timeScale times real
  // time; T travels to the next body. travelTo starts the autopilot at once (tests, demos).
  std::optional<SceneDescription> scene;
  size_t sceneBody = 0;
  double sceneTimeS = 0.0;
  double timeScale = 1.0;
  std::optional<size_t> travelTo;
  // Vulkan context.
  std::string device;
  bool validation = false;
};

// Opens the window and runs until it closes (or `frames` have been drawn). Throws planet::Error
// with one line when no window can be opened (no display) or no device can present to it.
// Returns the process exit code (1 when validation messages were reported).
int runViewer(const ViewOptions& options);

}  // namespace planet::view

// The viewer's Dear ImGui panel and HUD (issue 5, points 3 and 4): what a person can change
// live, and what the frame costs. Pure UI: it edits a ViewerSettings and says what changed;
// the viewer applies the change (rebuild, or a cheap setter).
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "planet/clipmap_mesh.h"
#include "planet/planet_description.h"
#include "camera/flight_camera.h"
#include "render/renderer.h"
#include "render/view_quality.h"
#include "vk/timer.h"

namespace planet::view {

// Everything the panel edits.
struct ViewerSettings {
  PlanetDescription planet;  // the noise stack, sea level, colours, atmosphere (rebuild on change)
  ViewQuality quality = ViewQuality::High;
  ClipmapParams mesh;  // levels, rings per level, vertices per ring (the quality's until edited)
  double fovDeg = 60.0;
  bool water = true;
  bool lights = true;  // the planet's city lights, where its preset has them
  bool clouds = true;
  bool wireframe = false;
  bool patches = true;
  bool freezeLod = false;
  // Eye adaptation (issue 21, point 4): the exposure follows the view's luminance; else the
  // fixed exposure below.
  bool autoExposure = true;
  double exposure = SkySettings{}.exposure;
  SkyMode skyMode = SkyMode::Tables;
  bool deferredShading = false;  // TerrainSettings::deferredShading (planet view --terrain-shading)
  // The sun is fixed in the planet frame: the point it stands over (subsolar point).
  double sunLatitudeDeg = 0.0;
  double sunLongitudeDeg = 0.0;
  bool sunMoves = false;  // one day per dayLengthS
  double dayLengthS = 600.0;
  double timeS = 0.0;               // animation phase (clouds, waves)
  double cameraLongitudeDeg = 0.0;  // read by the panel: local solar time is relative to it
  bool animate = true;
};

// What an edit requires.
struct UiRequests {
  bool rebuild = false;         // planet, mesh or quality: new Renderer
  bool skyChanged = false;      // exposure, eye adaptation, clouds: Renderer::setSkySettings, setAutoExposure
  bool terrainToggles = false;  // water, wireframe, freeze-LOD: TerrainPass setters
  bool screenshot = false;
  bool goTo = false;
  double goToLatDeg = 0.0, goToLonDeg = 0.0, goToAltitudeM = 0.0;
  std::string loadPreset;  // path or built-in name to load
  std::string savePreset;  // path to save to
  bool toggleMode = false;
};

// What the HUD shows.
struct HudData {
  std::string device;
  double fps = 0.0;
  const std::deque<float>* frameTimesMs = nullptr;  // most recent last
  std::vector<vk::GpuTiming> passes;
  std::optional<ExposureReport> exposure;  // with eye adaptation: the last frame's
  double altitudeM = 0.0;
  double heightAboveGroundM = 0.0;
  double latitudeDeg = 0.0, longitudeDeg = 0.0;
  double metresPerVertex = 0.0;
  uint64_t triangles = 0;
  uint32_t renderWidth = 0, renderHeight = 0;
  FlightMode mode = FlightMode::Orbit;
  double speedMps = 0.0;
  bool pathPlaying = false;
  std::string status;  // last message (saved screenshot, preset error, ...)
};

class ViewerUi {
 public:
  // Builds this frame's windows (between ImGui::NewFrame and ImGui::Render).
  void draw(ViewerSettings& settings, const HudData& hud, UiRequests& requests);
  void toggleHelp() { showHelp_ = !showHelp_; }
  void togglePanel() { showPanel_ = !showPanel_; }
  // The panel's go-to point, for the G key.
  void requestGoTo(UiRequests& requests) const {
    requests.goTo = true;
    requests.goToLatDeg = goTo_[0];
    requests.goToLonDeg = goTo_[1];
    requests.goToAltitudeM = goTo_[2];
  }

 private:
  void drawHud(const HudData& hud);
  void drawPanel(ViewerSettings& settings, UiRequests& requests);
  void drawHelp();
  bool showHelp_ = false;
  bool showPanel_ = true;
  char presetPath_[256] = "my_planet.toml";
  int faultsPlaying_ = -1;  // the faults layer whose count runs up (seed 000's "Run"), or -1
  float goTo_[3] = {27.99f, 86.93f, 10000.0f};
};

// The key help (F1), also printed by `planet view --help`.
const char* viewerKeyHelp();

}  // namespace planet::view

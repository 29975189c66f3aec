// planet render: the command's options, shared by the still (cmd_render.cpp) and the video of a
// camera path (cmd_render_video.cpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli_common.h"
#include "render/renderer.h"

namespace planet::cli {

struct RenderCommand {
  std::string preset{kDefaultPresetName};
  std::string scene;
  std::string lookAt;
  std::string camera;
  std::string sun;
  std::string size = "960x540";
  std::string out = "planet.png";
  std::optional<uint64_t> seed;
  double fovDeg = 60.0;
  bool wireframe = false;
  bool noPatches = false;
  double timeS = 0.0;
  std::string exposure = fmt::format("{:g}", SkySettings{}.exposure);  // a number or "auto"
  bool noClouds = false;
  bool noLights = false;
  std::string mesh = "auto";  // --mesh: auto or RINGSxVERTICES
  bool noWater = false;
  std::string sky{skyModeName(SkySettings{}.mode)};
  std::string terrainShading = "forward";
  // A video of a camera path (--path, --frames, --fps; with --scene also --path-body).
  std::string path;
  std::string pathBody;
  int64_t frames = 0;  // 0: real time, the path's duration × fps + 1
  double fps = 30.0;
};

// The most frames one video may have: an hour at 30 fps.
inline constexpr int64_t kVideoMaxFrames = 108'000;

// `planet render --path FILE`: every frame of the path rendered in turn and piped to ffmpeg.
// `settings` holds what the still and the video share (size, field of view, switches), checked.
int runVideoRender(const GlobalOptions& global, const RenderCommand& cmd, const CLI::App& sub,
                   const RenderSettings& settings);

}  // namespace planet::cli

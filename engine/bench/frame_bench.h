// `planet bench` (issue 6): frame times of the headless renderer along a camera path. Every
// timed frame records its wall-clock time, the GPU time of every pass the Renderer timed (so
// passes added to the Renderer are measured without changes here), the span from the first
// timestamp to the last, and what the terrain decided (triangles, vertices evaluated, metres
// per vertex at the nadir). With `compare`, the same frames are also rendered with each other
// way of producing the vertex heights and with octave limiting off (every mode takes its turn
// at each frame, so that a machine slowing down affects all alike), and each is reported as a
// ratio of its median terrain time to the default's.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/statistics.h"
#include "planet/planet_description.h"
#include "camera/camera.h"
#include "camera/camera_path.h"
#include "render/sky_pass.h"
#include "render/terrain_pass.h"
#include "vk/timer.h"

namespace planet::vk {
class Context;
}

namespace planet {

inline constexpr uint32_t kBenchMaxFrames = 100'000;
inline constexpr uint32_t kBenchMaxWarmup = 10'000;

struct FrameBenchOptions {
  uint32_t width = 640;
  uint32_t height = 360;
  uint32_t frames = 120;  // timed frames, spread evenly over the path (>= 1)
  uint32_t warmup = 5;    // untimed frames first, at the middles of as many equal parts of the path
  double fovYDeg = 60.0;
  SunPose sun;
  bool compare = false;  // also run every other BenchMode
  bool patches = true;   // patch textures (off: vertex normals only, like planet render --no-patches)
  bool lights = true;    // the preset's city lights (off: like planet render --no-lights)
  // Eye adaptation (planet render --exposure auto): each frame measured and exposed on its own
  // (the luminance pass runs and is timed); else the fixed exposure.
  bool autoExposure = false;
  double exposure = SkySettings{}.exposure;
  SkyMode skyMode = SkyMode::Tables;  // planet bench --sky
  bool deferredShading = false;       // planet bench --terrain-shading (TerrainSettings::deferredShading)
  // The clipmap drawn (planet bench --mesh; the CLI's default is meshForImage's for the size);
  // meshAuto only says so in the outputs.
  ClipmapParams mesh = TerrainSettings{}.mesh;
  bool meshAuto = false;
  // The rate of the flight the timed frames sample. Each timed frame follows an untimed lead-in
  // frame 1 / flightFps s of flight earlier, so that it does the work a frame of a real-time
  // flight at that rate does: what depends on the previous frame (the patch levels that moved,
  // the heights) is redone for one frame's movement, not for the path time between two timed
  // frames (1.6 s on the default path with 40 frames: every patch level moved). 0: no lead-in,
  // each timed frame follows the one before it.
  double flightFps = 60.0;
  // 1: each timed frame is submitted and waited for alone, so its wall-clock time is the CPU's
  // preparation and recording, then the GPU's work (the serial frame). vk::kFramesInFlight (2): as
  // the viewer draws, the timed frame is prepared and recorded while the real-time frame before it
  // executes (after a lead-in that settles a frame earlier still), and its time is the interval
  // between the two frames' ends on the GPU's clock: its GPU work and the time the GPU waited for
  // its commands. Needs lead-in frames (flightFps > 0).
  uint32_t framesInFlight = 1;
};
inline constexpr double kBenchMaxFlightFps = 1000.0;

// One way to produce the terrain: the default (compute heights, octave limits on) and those
// it is compared with.
struct BenchMode {
  std::string name;  // compute, vertex_shader, cpu, octaves_off
  HeightSource heightSource = HeightSource::Compute;
  bool limitOctaves = true;
};
// The default mode first; with `compare` the other three after it.
std::vector<BenchMode> benchModes(bool compare);

// The "terrain time" of a frame, the quantity --compare compares: the GPU passes that produce
// and draw the terrain mesh, "heights" (compute heights and normals, or the CPU upload and
// normals), "split" (the ground that cannot be sea floor, TerrainSettings::splitSeaFloor; not in
// vertex_shader mode, whose heights come only with the draw) and the whole render pass that
// draws the geometry ("stars", "terrain", in which vertex_shader mode evaluates the heights, and
// "water"), plus the CPU evaluation of cpu mode. The whole render pass, not the "terrain" scope
// alone: lavapipe writes a timestamp inside a render pass when its rasterizer reaches it, but
// shades vertices when the draw is recorded, so a draw's vertex work lands in the pass's first
// scope (measured: in vertex_shader mode "stars" read 1,746 ms and "terrain" 0.45 ms). The stars
// are the same work in every mode, and so are the patch textures, which are left out.
inline constexpr const char* kTerrainTimePasses[] = {"heights", "split", "stars", "terrain", "ground shading", "water"};

struct FrameRecord {
  uint32_t index = 0;
  double pathTimeS = 0.0;
  CameraPose camera;  // as rendered
  double heightAboveGroundM = 0.0;
  // Wall clock of Renderer::render: CPU work, GPU work, waiting; with two frames in flight the
  // interval between the frame's end and the one's before on the GPU's clock (framesInFlight).
  double frameMs = 0.0;
  double gpuMs = 0.0;                 // first timestamp of the frame to the last
  double prepareMs = 0.0;             // the CPU's preparation (RenderResult::prepareMs), part of cpuMs
  std::vector<vk::GpuTiming> passes;  // GPU scopes in recording order
  double cpuHeightsMs = 0.0;          // cpu mode: the threaded CPU evaluation (inside frameMs, outside gpuMs)
  uint64_t triangles = 0;
  uint32_t verticesEvaluated = 0;
  uint32_t patchLevelsRebuilt = 0;
  uint32_t patchLevelsDeferred = 0;  // levels whose work waited for a later frame (the texel budget)
  double metresPerVertexAtNadir = 0.0;

  double passMs(const std::string& name) const;  // 0 when the pass did not run this frame
  double terrainMs() const;                      // kTerrainTimePasses + cpuHeightsMs
  // The frame's time outside its GPU span: the CPU's (serial), or the GPU's wait for the frame's
  // commands (two in flight).
  double cpuMs() const { return frameMs - gpuMs; }
};

struct ModeRun {
  BenchMode mode;
  std::vector<FrameRecord> frames;
  std::vector<std::string> passNames;  // every GPU pass seen, in order of first appearance
  // Statistics over the timed frames; a pass that did not run in a frame counts 0 ms there.
  Summary frameMs, gpuMs, cpuMs, prepareMs, terrainMs, cpuHeightsMs;
  std::vector<Summary> passMs;  // per passNames
  double minMetresPerVertexAtNadir = 0.0;
  double trianglesMedian = 0.0;
  double verticesEvaluatedMedian = 0.0;
  double patchLevelsRebuiltMean = 0.0;
  uint32_t patchLevelsRebuiltMax = 0;
  uint32_t patchLevelsDeferredMax = 0;
};

struct FrameBenchReport {
  std::string device;
  std::string driver;
  FrameBenchOptions options;
  std::string preset;       // as given (name or file)
  uint64_t presetHash = 0;  // descriptionHash of the planet
  std::string pathSource;   // "default" or the file
  size_t pathKeys = 0;
  double pathDurationS = 0.0;
  std::vector<ModeRun> runs;  // runs[0]: the default mode

  // Median terrain time of `mode` over the default's; 0 when the mode was not run.
  double ratio(const std::string& mode) const;
  nlohmann::json toJson() const;
  // One row per timed frame of every mode: mode, frame, path time, camera, frame/GPU/CPU/terrain
  // times, one pass_<name>_ms column per pass of any mode, triangles, vertices, m/vertex.
  std::string csv() const;
  std::string table() const;
};

// Called before each frame: mode name, warm-up or not, frame index and count, and the previous
// frame's wall time (0 for the first).
using FrameBenchProgress =
    std::function<void(const std::string& mode, bool warmup, uint32_t frame, uint32_t count, double lastFrameMs)>;

// Throws planet::Error for frames or warm-up out of range, or what the Renderer throws.
FrameBenchReport runFrameBench(vk::Context& context, const PlanetDescription& planet, const std::string& preset,
                               const CameraPath& path, const std::string& pathSource, const FrameBenchOptions& options,
                               const FrameBenchProgress& progress = {});

}  // namespace planet

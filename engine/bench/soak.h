// `planet bench soak` (issue 7, point 6): a long run of the real-time path (two frames in
// flight, as the viewer draws) with the camera flying a loop from orbit to the ground and back,
// the sun moving, and the viewer's live parameters changed on a schedule: water, clouds,
// exposure, atmosphere samples, wireframe, frozen LOD, sun intensity, ambient light, and a
// rebuilt Renderer with another noise seed. Every input of frame k is a function of k alone.
// The allocator's statistics and the process's resident memory are sampled as it runs; after
// the warm-up the allocator must hold exactly what it held at the end of the warm-up, and the
// resident memory may grow by at most kSoakRssToleranceKiB. At the end the last image is read
// back and compared byte for byte with the same frame drawn by a fresh Renderer (given the same
// camera positions on the CPU, so that its clipmap orientation is the same; see runSoak).
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
#include "render/view_quality.h"
#include "vk/allocator.h"

namespace planet::vk {
class Context;
}

namespace planet {

inline constexpr uint32_t kSoakMaxFrames = 1'000'000;
// The schedule's periods, in frames (fixed, so that frame k is the same frame in every run).
inline constexpr uint32_t kSoakLoopFrames = 1000;  // one flight orbit → ground → orbit
// A new Renderer, with every layer's seed + 1 or back to + 0, at frame 250 and every 1000 frames
// after it (as the viewer rebuilds when a noise parameter changes).
inline constexpr uint32_t kSoakRebuildFrames = 1000;
inline constexpr uint32_t kSoakRebuildPhase = 250;
inline constexpr uint32_t kSoakSampleFrames = 50;  // memory sampled every this many frames
// Resident memory may grow this much after the warm-up: the median of the last quarter of the
// samples after it minus the median of the first quarter (a leak grows steadily and shows in
// full; the heap's and the driver's swings, measured on lavapipe at up to +8 MiB and back within
// 50 frames, do not). Measured growth on lavapipe over 9,000 frames: −1.3 to +3.5 MiB. Over
// 9,000 frames the tolerance still catches a leak of 1.2 KiB a frame; one 160×90 image (56 KiB)
// a frame would be 370 MiB.
inline constexpr int64_t kSoakRssToleranceKiB = 8 * 1024;
// AddressSanitizer's quarantine holds freed memory (up to 256 MiB) before reusing it, so RSS
// grows in a sanitizer build whatever the program does; there LeakSanitizer checks for leaks.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSoakChecksRss = false;
#else
inline constexpr bool kSoakChecksRss = true;
#endif

struct SoakOptions {
  uint32_t width = 160;
  uint32_t height = 90;
  uint32_t frames = 10'000;  // >= 1
  // < frames: memory is compared from the end of frame `warmup` on. One loop by default, so that
  // every kind of frame of the schedule (and a rebuild) has been drawn once before.
  uint32_t warmup = kSoakLoopFrames;
  ViewQuality quality = ViewQuality::Low;
  double fovYDeg = 60.0;
};

// What frame k draws besides the camera (every field a function of k alone).
struct SoakFrameState {
  double pathTimeS = 0.0;   // on soakCameraPath, looping every kSoakLoopFrames frames
  double timeS = 0.0;       // animation (clouds, waves): 1/30 s per frame
  SunPose sun;              // azimuth turning 0.36° per frame, elevation between −10° and 60°
  uint32_t seedOffset = 0;  // added to every layer's seed; changes with each rebuild
  bool rebuild = false;     // a new Renderer is built before this frame (k mod kSoakRebuildFrames = kSoakRebuildPhase)
  bool water = true;
  bool clouds = true;
  bool wireframe = false;
  bool freezeLod = false;
  double exposure = 10.0;
  uint32_t extraViewSamples = 0;  // atmosphere samples added to the quality's
  double sunIntensity = 1.0;
  double ambient = 0.01;
};
SoakFrameState soakFrameState(uint32_t frame);

// The loop the soak flies (radius of the planet): the default benchmark path (descent from
// 40,000 km to 2 m, traverse at 50 m), then a climb back to the start, 90 s in all.
CameraPath soakCameraPath(double radiusM);

struct SoakSample {
  uint32_t frame = 0;  // frames completed (submitted) when it was taken
  vk::AllocatorStats allocator;
  int64_t rssKiB = 0;
};

struct SoakReport {
  std::string device;
  std::string driver;
  SoakOptions options;
  std::string preset;
  uint64_t presetHash = 0;
  double durationS = 0.0;         // the frames, from the first to the last fence (rebuilds included)
  std::vector<double> frameMs;    // after the warm-up: wall time of each frame's turn (rebuilds left out)
  std::vector<double> gpuMs;      // after the warm-up: first timestamp to last
  std::vector<double> rebuildMs;  // each Renderer rebuild, waiting for the device included
  Summary frame, gpu;             // of the above
  struct SlowFrame {
    uint32_t frame = 0;
    double ms = 0.0;
  };
  std::vector<SlowFrame> slowest;   // the 5 longest frames after the warm-up, longest first
  std::vector<SoakSample> samples;  // at frame 0, the end of the warm-up, every kSoakSampleFrames, the end
  size_t warmSample = 0;            // index of the sample at the end of the warm-up
  SoakSample maxAfterWarmup;        // the largest of each figure after the warm-up (frame: of the largest RSS)
  bool allocatorFlat = false;       // every sample after the warm-up equals the warm one
  int64_t rssGrowthKiB = 0;         // after the warm-up: median of the last quarter − median of the first
  int64_t rssPeakKiB = 0;           // largest RSS after the warm-up minus RSS at its end
  bool rssFlat = false;             // rssGrowthKiB <= kSoakRssToleranceKiB
  uint32_t liveAllocationsWithoutRenderer = 0;  // after the soak's Renderer was destroyed
  bool finalIdentical = false;                  // the last image equals a fresh Renderer's, byte for byte
  uint64_t finalDifferingPixels = 0;
  int finalMaxChannelDifference = 0;
  bool validation = false;  // validation layer on
  uint64_t validationMessages = 0;

  // Allocator and RSS flat, identical final image, no validation message.
  bool passed() const;
  // One line saying what failed (empty when passed()).
  std::string failure() const;
  nlohmann::json toJson() const;
  std::string table() const;
};

// Called before each frame with its index, and the previous frame's wall time (0 for the first).
using SoakProgress = std::function<void(uint32_t frame, uint32_t count, double lastFrameMs, int64_t rssKiB)>;

// Throws planet::Error for options out of range, or what the Renderer throws.
SoakReport runSoak(vk::Context& context, const PlanetDescription& planet, const std::string& preset,
                   const SoakOptions& options, const SoakProgress& progress = {});

}  // namespace planet

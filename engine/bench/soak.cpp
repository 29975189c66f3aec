#include "bench/soak.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <span>

#include <fmt/format.h>

#include "core/error.h"
#include "core/process_memory.h"
#include "render/renderer.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/frame_ring.h"

namespace planet {
namespace {

constexpr double kLoopDurationS = 90.0;  // soakCameraPath's length

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The planet frame k draws: the preset with the frame's seed offset, stars as the quality draws them.
PlanetDescription framePlanet(const PlanetDescription& planet, const SoakFrameState& state, ViewQuality quality) {
  PlanetDescription drawn = viewPlanet(planet, quality);
  for (NoiseLayer& layer : drawn.layers)
    layer.noise.seed = uint32_t((uint64_t(layer.noise.seed) + state.seedOffset) & 0xffffffffu);
  return drawn;
}

// As the viewer builds its Renderer at `quality`, but at exactly the given size.
RenderSettings soakRenderSettings(const SoakOptions& options) {
  RenderSettings base;
  base.fovYDeg = options.fovYDeg;
  RenderSettings settings = viewRenderSettings(base, options.quality, options.width, options.height);
  settings.width = options.width;
  settings.height = options.height;
  return settings;
}

// The viewer's live changes (panel toggles and sky settings), without a rebuild.
void applyLiveState(Renderer& renderer, const SoakFrameState& state, ViewQuality quality) {
  TerrainPass& terrain = renderer.terrain();
  terrain.setWaterEnabled(state.water);
  terrain.setWireframe(state.wireframe);
  terrain.setFreezeLod(state.freezeLod);
  terrain.setSunIntensity(state.sunIntensity);
  terrain.setAmbient(state.ambient);
  SkySettings sky = renderer.settings().sky;
  sky.exposure = state.exposure;
  sky.clouds = state.clouds;
  sky.viewSamples = qualityPreset(quality).atmosphereSamples + state.extraViewSamples;
  renderer.setSkySettings(sky);
}

double gpuSpanMs(const std::vector<vk::GpuTiming>& timings) {
  if (timings.empty()) return 0.0;
  double first = timings.front().startMs, last = first;
  for (const vk::GpuTiming& t : timings) {
    first = std::min(first, t.startMs);
    last = std::max(last, t.startMs + t.milliseconds);
  }
  return last - first;
}

Summary summaryOrZero(const std::vector<double>& values) { return values.empty() ? Summary{} : summarize(values); }

bool sameAllocator(const vk::AllocatorStats& a, const vk::AllocatorStats& b) {
  return a.blocks == b.blocks && a.dedicatedAllocations == b.dedicatedAllocations &&
         a.liveAllocations == b.liveAllocations && a.bytesReserved == b.bytesReserved && a.bytesUsed == b.bytesUsed;
}

nlohmann::json toJson(const Summary& s) {
  return {{"median", s.median}, {"p95", s.p95}, {"p99", s.p99}, {"max", s.max}};
}

nlohmann::json toJson(const SoakSample& s) {
  return {{"frame", s.frame},
          {"live_allocations", s.allocator.liveAllocations},
          {"bytes_used", s.allocator.bytesUsed},
          {"blocks", s.allocator.blocks},
          {"dedicated_allocations", s.allocator.dedicatedAllocations},
          {"bytes_reserved", s.allocator.bytesReserved},
          {"rss_kib", s.rssKiB}};
}

}  // namespace

SoakFrameState soakFrameState(uint32_t frame) {
  SoakFrameState s;
  const double k = double(frame);
  s.pathTimeS = kLoopDurationS * double(frame % kSoakLoopFrames) / double(kSoakLoopFrames);
  s.timeS = k / 30.0;
  s.sun.azimuthDeg = std::fmod(135.0 + 0.36 * k, 360.0);
  s.sun.elevationDeg = 25.0 + 35.0 * std::sin(2.0 * std::numbers::pi * k / 700.0);
  s.seedOffset = ((frame + kSoakRebuildFrames - kSoakRebuildPhase) / kSoakRebuildFrames) % 2;
  s.rebuild = frame % kSoakRebuildFrames == kSoakRebuildPhase;
  // Periods of different lengths, so that the combinations keep changing (wireframe and a
  // frozen LOD fall in different parts of the loop from one loop to the next); each setting
  // holds for a stretch of frames, as a user's click would.
  s.water = (frame / 97) % 3 != 2;
  s.clouds = (frame / 70) % 4 != 3;
  s.wireframe = frame % 310 >= 260 && frame % 310 < 280;
  s.freezeLod = frame % 400 >= 100 && frame % 400 < 140;
  constexpr double kExposures[] = {10.0, 6.0, 16.0};
  s.exposure = kExposures[(frame / 50) % 3];
  s.extraViewSamples = (frame / 160) % 2 ? 4 : 0;
  s.sunIntensity = (frame / 130) % 2 ? 0.6 : 1.0;
  s.ambient = (frame / 190) % 2 ? 0.05 : 0.01;
  return s;
}

CameraPath soakCameraPath(double radiusM) {
  CameraPath path = defaultCameraPath(radiusM);
  const CameraKey start = path.keys.front();
  const CameraKey end = path.keys.back();
  // Climb back: turn round over the traverse's end, then rise over the start to where the
  // descent began, so that the loop closes without a jump.
  path.keys.push_back({70.0, end.latitudeDeg, end.longitudeDeg, 1.0e4, 200.0, -30.0});
  path.keys.push_back({78.0, start.latitudeDeg, start.longitudeDeg, 4.0e5, 120.0, -70.0});
  path.keys.push_back(
      {kLoopDurationS, start.latitudeDeg, start.longitudeDeg, start.heightM, start.headingDeg, start.pitchDeg});
  validateCameraPath(path, "soak camera path");
  return path;
}

bool SoakReport::passed() const { return failure().empty(); }

std::string SoakReport::failure() const {
  std::vector<std::string> problems;
  if (!allocatorFlat) {
    const vk::AllocatorStats& warm = samples[warmSample].allocator;
    problems.push_back(fmt::format(
        "allocator not flat after the warm-up (frame {}: {} allocations, {} bytes; at most {} allocations, {} bytes)",
        samples[warmSample].frame, warm.liveAllocations, warm.bytesUsed, maxAfterWarmup.allocator.liveAllocations,
        maxAfterWarmup.allocator.bytesUsed));
  }
  if (!rssFlat)
    problems.push_back(fmt::format("resident memory grew by {} KiB after the warm-up (tolerance {} KiB)", rssGrowthKiB,
                                   kSoakRssToleranceKiB));
  if (liveAllocationsWithoutRenderer != 0)
    problems.push_back(
        fmt::format("{} allocations left after the Renderer was destroyed", liveAllocationsWithoutRenderer));
  if (!finalIdentical)
    problems.push_back(fmt::format("final image differs from a fresh render ({} pixels, up to {} levels)",
                                   finalDifferingPixels, finalMaxChannelDifference));
  if (validationMessages > 0) problems.push_back(fmt::format("{} validation messages", validationMessages));
  std::string line;
  for (const std::string& p : problems) line += (line.empty() ? "" : "; ") + p;
  return line;
}

nlohmann::json SoakReport::toJson() const {
  nlohmann::json j;
  j["device"] = device;
  j["driver"] = driver;
  j["preset"] = preset;
  j["preset_hash"] = fmt::format("{:016x}", presetHash);
  j["width"] = options.width;
  j["height"] = options.height;
  j["quality"] = viewQualityName(options.quality);
  j["fov_deg"] = options.fovYDeg;
  j["frames"] = options.frames;
  j["warmup"] = options.warmup;
  j["frames_in_flight"] = Renderer::kFramesInFlight;
  j["schedule"] = {{"loop_frames", kSoakLoopFrames},
                   {"loop_duration_s", kLoopDurationS},
                   {"rebuild_frames", kSoakRebuildFrames},
                   {"rebuild_phase", kSoakRebuildPhase},
                   {"sample_frames", kSoakSampleFrames}};
  j["duration_s"] = durationS;
  j["frame_ms"] = planet::toJson(frame);
  j["gpu_ms"] = planet::toJson(gpu);
  j["fps"] = frame.median > 0.0 ? 1000.0 / frame.median : 0.0;
  j["slowest_frames"] = nlohmann::json::array();
  for (const SlowFrame& f : slowest) j["slowest_frames"].push_back({{"frame", f.frame}, {"ms", f.ms}});
  j["rebuilds"] = {{"count", rebuildMs.size()}, {"ms", planet::toJson(summaryOrZero(rebuildMs))}};
  nlohmann::json samplesJson = nlohmann::json::array();
  for (const SoakSample& s : samples) samplesJson.push_back(planet::toJson(s));
  j["samples"] = samplesJson;
  j["memory"] = {{"start", planet::toJson(samples.front())},
                 {"after_warmup", planet::toJson(samples[warmSample])},
                 {"end", planet::toJson(samples.back())},
                 {"max_after_warmup", planet::toJson(maxAfterWarmup)},
                 {"allocator_flat", allocatorFlat},
                 {"rss_growth_kib", rssGrowthKiB},
                 {"rss_growth_is",
                  "median RSS of the last quarter of the samples after the warm-up minus that of the "
                  "first quarter"},
                 {"rss_peak_kib", rssPeakKiB},
                 {"rss_tolerance_kib", kSoakRssToleranceKiB},
                 {"rss_flat", rssFlat},
                 {"rss_checked", kSoakChecksRss},
                 {"live_allocations_without_renderer", liveAllocationsWithoutRenderer}};
  j["final_image"] = {{"frame", options.frames - 1},
                      {"identical_to_fresh_render", finalIdentical},
                      {"differing_pixels", finalDifferingPixels},
                      {"max_channel_difference", finalMaxChannelDifference}};
  j["validation"] = {{"enabled", validation}, {"messages", validationMessages}};
  j["passed"] = passed();
  return j;
}

std::string SoakReport::table() const {
  std::string out = fmt::format("device: {} ({})\n", device, driver);
  out += fmt::format(
      "soak: {} (hash {:016x}), {}x{}, quality {}, {} frames ({} warm-up), {} frames in flight; a {} s loop every {} "
      "frames, a new renderer at frame {} and every {} after\n",
      preset, presetHash, options.width, options.height, viewQualityName(options.quality), options.frames,
      options.warmup, Renderer::kFramesInFlight, kLoopDurationS, kSoakLoopFrames, kSoakRebuildPhase,
      kSoakRebuildFrames);
  out += fmt::format("duration: {:.1f} s\n\n", durationS);
  out += fmt::format("{:<36} {:>9} {:>9} {:>9} {:>9}\n", "ms, after the warm-up", "median", "p95", "p99", "max");
  auto row = [&](const std::string& name, const Summary& s) {
    out += fmt::format("{:<36} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f}\n", name, s.median, s.p95, s.p99, s.max);
  };
  row("frame (wall clock per frame)", frame);
  row("GPU (first to last timestamp)", gpu);
  row(fmt::format("renderer rebuild ({} of them)", rebuildMs.size()), summaryOrZero(rebuildMs));
  std::string slow;
  for (const SlowFrame& f : slowest) slow += fmt::format("{}{} ({:.0f} ms)", slow.empty() ? "" : ", ", f.frame, f.ms);
  out += fmt::format("slowest frames: {}\n", slow);
  out += fmt::format("\n{:<28} {:>11} {:>12} {:>7} {:>14} {:>11}\n", "memory", "allocations", "bytes used", "blocks",
                     "bytes reserved", "RSS KiB");
  auto memoryRow = [&](const std::string& name, const SoakSample& s) {
    out += fmt::format("{:<28} {:>11} {:>12} {:>7} {:>14} {:>11}\n", name, s.allocator.liveAllocations,
                       s.allocator.bytesUsed, s.allocator.blocks, s.allocator.bytesReserved, s.rssKiB);
  };
  memoryRow("start (frame 0)", samples.front());
  memoryRow(fmt::format("after warm-up (frame {})", samples[warmSample].frame), samples[warmSample]);
  memoryRow(fmt::format("end (frame {})", samples.back().frame), samples.back());
  memoryRow(fmt::format("max after warm-up (RSS: {})", maxAfterWarmup.frame), maxAfterWarmup);
  out += fmt::format("\nallocator after the warm-up: {} ({} samples)\n",
                     allocatorFlat ? "flat, every sample equal" : "NOT flat", samples.size() - warmSample);
  out += fmt::format(
      "resident memory after the warm-up: grew by {} KiB (median of the last quarter of the samples minus the first's; "
      "tolerance {} KiB): {}; peak {:+} KiB over the warm-up's end\n",
      rssGrowthKiB, kSoakRssToleranceKiB,
      !kSoakChecksRss ? "not checked in an AddressSanitizer build (its quarantine keeps freed memory resident; "
                        "LeakSanitizer checks for leaks instead)"
      : rssFlat       ? "flat"
                      : "NOT flat",
      rssPeakKiB);
  out += fmt::format("live allocations once the renderer was destroyed: {}\n", liveAllocationsWithoutRenderer);
  out += fmt::format("final image identical to a fresh render: {}\n",
                     finalIdentical ? "yes"
                                    : fmt::format("no ({} pixels differ, by up to {} levels)", finalDifferingPixels,
                                                  finalMaxChannelDifference));
  out += validation ? fmt::format("validation: on, {} messages\n", validationMessages) : "validation: off\n";
  return out;
}

SoakReport runSoak(vk::Context& context, const PlanetDescription& planet, const std::string& preset,
                   const SoakOptions& options, const SoakProgress& progress) {
  if (options.frames < 1 || options.frames > kSoakMaxFrames)
    throw Error(fmt::format("frames must be in 1..{}, got {}", kSoakMaxFrames, options.frames));
  if (options.warmup >= options.frames)
    throw Error(
        fmt::format("warm-up frames must be fewer than the frames ({}), got {}", options.frames, options.warmup));
  const RenderSettings settings = soakRenderSettings(options);
  validateRenderSettings(settings);
  SoakReport report;
  report.device = context.info.name;
  report.driver = context.info.driver;
  report.options = options;
  report.preset = preset;
  report.presetHash = descriptionHash(planet);
  report.validation = context.validation;

  const CameraPath path = soakCameraPath(planet.radiusM);
  auto build = [&](const SoakFrameState& state) {
    auto renderer = std::make_unique<Renderer>(context, framePlanet(planet, state, options.quality), settings);
    renderer->prepareAllPipelines();  // as the viewer does
    return renderer;
  };
  auto sample = [&](uint32_t framesDone) {
    report.samples.push_back({framesDone, context.allocator.stats(), residentKiB()});
    if (framesDone == options.warmup) report.warmSample = report.samples.size() - 1;
  };

  const uint32_t last = options.frames - 1;
  SoakFrameState state = soakFrameState(0);
  PlanetDescription drawn = framePlanet(planet, state, options.quality);
  std::unique_ptr<Renderer> renderer = build(state);
  CameraPose lastPose{};  // of the last frame drawn
  // The report's own storage, taken before the first sample, so that it does not count as growth.
  report.frameMs.reserve(options.frames - options.warmup);
  report.gpuMs.reserve(options.frames - options.warmup);
  report.samples.reserve(options.frames / kSoakSampleFrames + 3);
  {
    vk::FrameRing ring(context);
    uint32_t slotFrame[Renderer::kFramesInFlight] = {};
    // Waits for `slot`'s last frame and keeps its GPU time (the Renderer's timings of that slot).
    auto finish = [&](uint32_t slot) {
      if (ring.wait(slot) && slotFrame[slot] >= options.warmup)
        report.gpuMs.push_back(gpuSpanMs(renderer->lastTimings(slot)));
    };
    sample(0);
    double lastMs = 0.0;
    const Clock::time_point soakStart = Clock::now();
    for (uint32_t k = 0; k < options.frames; ++k) {
      if (progress) progress(k, options.frames, lastMs, report.samples.back().rssKiB);
      state = soakFrameState(k);
      // A frozen LOD is an earlier frame's, which a fresh Renderer cannot have: the last frame is never frozen.
      if (k == last) state.freezeLod = false;
      if (state.rebuild) {
        const Clock::time_point rebuildStart = Clock::now();
        for (uint32_t slot = 0; slot < Renderer::kFramesInFlight; ++slot) finish(slot);
        renderer.reset();  // its memory goes back before the new one takes its own
        renderer = build(state);
        drawn = framePlanet(planet, state, options.quality);
        report.rebuildMs.push_back(millisecondsSince(rebuildStart));
      }
      const Clock::time_point frameStart = Clock::now();
      applyLiveState(*renderer, state, options.quality);
      const uint32_t slot = k % Renderer::kFramesInFlight;
      finish(slot);
      const CameraPose pose = cameraPoseAt(sampleCameraPath(path, state.pathTimeS), drawn);
      lastPose = pose;
      const glm::dvec3 sun = sunDirection(state.sun, renderer->clampToGround(pose));
      renderer->prepare(pose, sun, state.timeS, slot);
      renderer->record(ring.begin(slot), slot);
      ring.submit(slot);
      slotFrame[slot] = k;
      lastMs = millisecondsSince(frameStart);
      if (k >= options.warmup) report.frameMs.push_back(lastMs);
      const uint32_t done = k + 1;
      if (done == options.warmup || done % kSoakSampleFrames == 0 || done == options.frames) sample(done);
    }
    for (uint32_t slot = 0; slot < Renderer::kFramesInFlight; ++slot) finish(slot);
    report.durationS = std::chrono::duration<double>(Clock::now() - soakStart).count();
  }
  report.frame = summaryOrZero(report.frameMs);
  for (size_t i = 0; i < report.frameMs.size(); ++i)
    report.slowest.push_back({options.warmup + uint32_t(i), report.frameMs[i]});
  std::sort(report.slowest.begin(), report.slowest.end(),
            [](const SoakReport::SlowFrame& a, const SoakReport::SlowFrame& b) { return a.ms > b.ms; });
  report.slowest.resize(std::min<size_t>(report.slowest.size(), 5));
  report.gpu = summaryOrZero(report.gpuMs);

  const SoakSample& warm = report.samples[report.warmSample];
  report.maxAfterWarmup = warm;
  report.allocatorFlat = true;
  for (size_t i = report.warmSample; i < report.samples.size(); ++i) {
    const SoakSample& s = report.samples[i];
    report.allocatorFlat = report.allocatorFlat && sameAllocator(s.allocator, warm.allocator);
    SoakSample& m = report.maxAfterWarmup;
    if (s.rssKiB > m.rssKiB) m.frame = s.frame;  // of the largest RSS
    m.allocator.blocks = std::max(m.allocator.blocks, s.allocator.blocks);
    m.allocator.dedicatedAllocations = std::max(m.allocator.dedicatedAllocations, s.allocator.dedicatedAllocations);
    m.allocator.liveAllocations = std::max(m.allocator.liveAllocations, s.allocator.liveAllocations);
    m.allocator.bytesReserved = std::max(m.allocator.bytesReserved, s.allocator.bytesReserved);
    m.allocator.bytesUsed = std::max(m.allocator.bytesUsed, s.allocator.bytesUsed);
    m.rssKiB = std::max(m.rssKiB, s.rssKiB);
  }
  report.rssPeakKiB = report.maxAfterWarmup.rssKiB - warm.rssKiB;
  std::vector<double> rss;
  for (size_t i = report.warmSample; i < report.samples.size(); ++i) rss.push_back(double(report.samples[i].rssKiB));
  const size_t quarter = std::max<size_t>(1, rss.size() / 4);
  const double firstQuarter = percentile(std::span(rss).first(quarter), 50.0);
  const double lastQuarter = percentile(std::span(rss).last(quarter), 50.0);
  report.rssGrowthKiB = int64_t(std::llround(lastQuarter - firstQuarter));
  report.rssFlat = !kSoakChecksRss || report.rssGrowthKiB <= kSoakRssToleranceKiB;

  // The last frame against a fresh Renderer built and set up the same way, which draws it with
  // nothing computed before it, on the CPU or the GPU: nothing may be left over from the soak.
  // (The clipmap's spin comes from the pose alone, clipmap_orientation.h, so no earlier
  // positions need replaying.)
  const std::vector<uint8_t> soaked = vk::readbackImage(context, renderer->output());
  renderer.reset();
  report.liveAllocationsWithoutRenderer = context.allocator.stats().liveAllocations;
  renderer = build(state);
  applyLiveState(*renderer, state, options.quality);
  const std::vector<uint8_t> fresh = renderer->render(lastPose, state.sun, state.timeS).image.pixels;
  renderer.reset();
  report.finalIdentical = soaked == fresh;
  if (soaked.size() == fresh.size())
    for (size_t p = 0; p + 3 < soaked.size(); p += 4) {
      int difference = 0;
      for (size_t c = 0; c < 4; ++c)
        difference = std::max(difference, std::abs(int(soaked[p + c]) - int(fresh[p + c])));
      if (difference > 0) ++report.finalDifferingPixels;
      report.finalMaxChannelDifference = std::max(report.finalMaxChannelDifference, difference);
    }
  report.validationMessages = context.validationMessageCount();
  return report;
}

}  // namespace planet

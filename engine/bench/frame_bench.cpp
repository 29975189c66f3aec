#include "bench/frame_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "core/error.h"
#include "render/renderer.h"
#include "render/view_quality.h"
#include "vk/context.h"
#include "vk/frame_ring.h"

namespace planet {
namespace {

nlohmann::json toJson(const Summary& s) {
  return {{"median", s.median}, {"p95", s.p95}, {"p99", s.p99}, {"max", s.max}};
}

template <typename Fn>
Summary summaryOf(const std::vector<FrameRecord>& frames, Fn value) {
  std::vector<double> values;
  values.reserve(frames.size());
  for (const FrameRecord& f : frames) values.push_back(double(value(f)));
  return summarize(values);
}

// One frame of one mode, as the benchmark records it.
FrameRecord recordFrame(uint32_t index, double timeS, double frameMs, RenderResult& result) {
  FrameRecord f;
  f.index = index;
  f.pathTimeS = timeS;
  f.camera = result.camera;
  f.heightAboveGroundM = result.terrain.heightAboveGroundM;
  f.frameMs = frameMs;
  f.prepareMs = result.prepareMs;
  f.passes = std::move(result.timings);
  if (!f.passes.empty()) {
    double first = f.passes.front().startMs, last = first;
    for (const vk::GpuTiming& t : f.passes) {
      first = std::min(first, t.startMs);
      last = std::max(last, t.startMs + t.milliseconds);
    }
    f.gpuMs = last - first;
  }
  f.cpuHeightsMs = result.terrain.cpuHeightsMs;
  f.triangles = result.terrain.triangles;
  f.verticesEvaluated = result.terrain.verticesEvaluated;
  f.patchLevelsRebuilt = result.terrain.patchLevelsRebuilt;
  f.patchLevelsDeferred = result.terrain.patchLevelsDeferred;
  f.metresPerVertexAtNadir = result.terrain.metresPerVertexAtNadir;
  return f;
}

// A timed frame drawn with two frames in flight (FrameBenchOptions::framesInFlight), as the viewer
// draws: the frame before it (`previous`, a real-time frame earlier) is submitted, and the timed
// one is prepared and recorded while that executes. Its time is the interval between the two
// frames' ends on the GPU's clock: its own GPU work and whatever time the GPU waited for its
// commands (the CPU's preparation and recording, where they take longer than the frame before
// takes the GPU).
FrameRecord pipelinedFrame(Renderer& renderer, vk::FrameRing& ring, const CameraPose& previous, const CameraPose& pose,
                           const SunPose& sun, uint32_t index, double timeS) {
  RenderResult result;
  auto submit = [&](const CameraPose& camera, uint32_t slot) {
    const glm::dvec3 sunPlanet = sunDirection(sun, renderer.clampToGround(camera));
    const auto start = std::chrono::steady_clock::now();
    result.camera = renderer.prepare(camera, sunPlanet, 0.0, slot).camera;  // as rendered
    result.prepareMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    renderer.record(ring.begin(slot), slot);
    ring.submit(slot);
  };
  submit(previous, 0);
  submit(pose, 1);
  ring.waitAll();
  result.timings = renderer.lastTimings(1);
  result.terrain = renderer.terrain().frame();
  return recordFrame(index, timeS, renderer.lastFrameEndMs(1) - renderer.lastFrameEndMs(0), result);
}

void addFrame(ModeRun& run, FrameRecord f) {
  // A pass seen for the first time goes after the pass recorded before it in this frame, so
  // that the list keeps recording order when the first frames skip a pass.
  auto after = run.passNames.begin();
  for (const vk::GpuTiming& t : f.passes) {
    auto found = std::find(run.passNames.begin(), run.passNames.end(), t.name);
    if (found == run.passNames.end()) found = run.passNames.insert(after, t.name);
    after = found + 1;
  }
  run.frames.push_back(std::move(f));
}

void summarizeRun(ModeRun& run) {
  run.frameMs = summaryOf(run.frames, [](const FrameRecord& f) { return f.frameMs; });
  run.gpuMs = summaryOf(run.frames, [](const FrameRecord& f) { return f.gpuMs; });
  run.cpuMs = summaryOf(run.frames, [](const FrameRecord& f) { return f.cpuMs(); });
  run.prepareMs = summaryOf(run.frames, [](const FrameRecord& f) { return f.prepareMs; });
  run.terrainMs = summaryOf(run.frames, [](const FrameRecord& f) { return f.terrainMs(); });
  run.cpuHeightsMs = summaryOf(run.frames, [](const FrameRecord& f) { return f.cpuHeightsMs; });
  for (const std::string& name : run.passNames)
    run.passMs.push_back(summaryOf(run.frames, [&](const FrameRecord& f) { return f.passMs(name); }));
  run.minMetresPerVertexAtNadir = run.frames.front().metresPerVertexAtNadir;
  for (const FrameRecord& f : run.frames)
    run.minMetresPerVertexAtNadir = std::min(run.minMetresPerVertexAtNadir, f.metresPerVertexAtNadir);
  run.trianglesMedian = summaryOf(run.frames, [](const FrameRecord& f) { return f.triangles; }).median;
  run.verticesEvaluatedMedian = summaryOf(run.frames, [](const FrameRecord& f) { return f.verticesEvaluated; }).median;
  for (const FrameRecord& f : run.frames) {
    run.patchLevelsRebuiltMean += double(f.patchLevelsRebuilt) / double(run.frames.size());
    run.patchLevelsRebuiltMax = std::max(run.patchLevelsRebuiltMax, f.patchLevelsRebuilt);
    run.patchLevelsDeferredMax = std::max(run.patchLevelsDeferredMax, f.patchLevelsDeferred);
  }
}

// Every mode flies the path at once, frame by frame in turn, so that a machine that slows down
// for a while (a busy neighbour, a core taken away) slows every mode alike and the ratios
// between modes stay fair. Each mode has its own Renderer, so none changes another's work.

std::vector<ModeRun> runModes(vk::Context& context, const PlanetDescription& planet, const CameraPath& path,
                              const FrameBenchOptions& options, const FrameBenchProgress& progress) {
  const std::vector<BenchMode> modes = benchModes(options.compare);
  std::vector<std::unique_ptr<Renderer>> renderers;
  std::vector<ModeRun> runs(modes.size());
  for (size_t m = 0; m < modes.size(); ++m) {
    RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.fovYDeg = options.fovYDeg;
    settings.terrain.heightSource = modes[m].heightSource;
    settings.terrain.limitOctaves = modes[m].limitOctaves;
    settings.terrain.patches = options.patches;
    settings.terrain.mesh = options.mesh;
    settings.terrain.patchTexelsPerFrame = realTimePatchBudget(settings.terrain.patchSettings);  // as the viewer
    settings.terrain.lights = options.lights;
    settings.autoExposure = options.autoExposure;
    settings.sky.exposure = options.exposure;
    settings.sky.mode = options.skyMode;
    settings.terrain.deferredShading = options.deferredShading;
    renderers.push_back(std::make_unique<Renderer>(context, planet, settings));
    // Frame times without the copy of the image to the host, which the viewer does not make.
    renderers.back()->setReadImage(false);
    runs[m].mode = modes[m];
  }
  std::vector<double> lastMs(modes.size(), 0.0);
  const bool pipelined = options.framesInFlight > 1;
  std::vector<std::unique_ptr<vk::FrameRing>> rings;
  if (pipelined)
    for (size_t m = 0; m < modes.size(); ++m) rings.push_back(std::make_unique<vk::FrameRing>(context));
  for (int phase = 0; phase < 2; ++phase) {
    const bool warmup = phase == 0;
    const uint32_t count = warmup ? options.warmup : options.frames;
    for (uint32_t i = 0; i < count; ++i) {
      // Warm-up frames at the middles of `count` equal parts of the path: none repeats the first
      // timed frame's pose, which would let that frame skip its height pass.
      double timeS =
          warmup ? path.startS() + path.durationS() * (double(i) + 0.5) / double(count) : frameTimeS(path, i, count);
      // The lead-in frame, a real-time frame before: at the path's start the pair moves on by
      // one frame instead (a lead-in at the same pose would let the timed frame skip its work).
      const bool leadIn = !warmup && options.flightFps > 0.0;
      const double frameS = leadIn ? 1.0 / options.flightFps : 0.0;
      // Two in flight: the lead-in settles a frame earlier still, and the frame in flight before
      // the timed one (previousPose) is an ordinary real-time frame.
      const double leadS = pipelined ? 2.0 * frameS : frameS;
      if (leadIn && timeS - leadS < path.startS()) timeS = std::min(path.startS() + leadS, path.endS());
      const CameraPose leadPose = cameraPoseAt(sampleCameraPath(path, std::max(timeS - leadS, path.startS())), planet);
      const CameraPose previousPose =
          cameraPoseAt(sampleCameraPath(path, std::max(timeS - frameS, path.startS())), planet);
      const CameraPose pose = cameraPoseAt(sampleCameraPath(path, timeS), planet);
      for (size_t m = 0; m < modes.size(); ++m) {
        if (progress) progress(modes[m].name, warmup, i, count, lastMs[m]);
        // The lead-in settles what a real-time flight would have settled by then: it is drawn
        // without the patch texel budget, so every level is up to date at the lead-in pose (a
        // jump between timed frames can make every level stale, which a flight at
        // options.flightFps would have built strip by strip on the way); the timed frame then
        // has the budget and one frame's movement.
        Renderer& renderer = *renderers[m];
        if (leadIn) {
          for (size_t b = 0; b < renderer.bodyCount(); ++b) renderer.terrain(b).setPatchTexelsPerFrame(0);
          renderer.render(leadPose, options.sun);
          for (size_t b = 0; b < renderer.bodyCount(); ++b) {
            TerrainPass& terrain = renderer.terrain(b);
            terrain.setPatchTexelsPerFrame(realTimePatchBudget(terrain.settings().patchSettings));
          }
        }
        if (pipelined && !warmup) {
          FrameRecord f = pipelinedFrame(renderer, *rings[m], previousPose, pose, options.sun, i, timeS);
          lastMs[m] = f.frameMs;
          addFrame(runs[m], std::move(f));
          continue;
        }
        const auto start = std::chrono::steady_clock::now();
        RenderResult result = renderer.render(pose, options.sun);
        lastMs[m] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (!warmup) addFrame(runs[m], recordFrame(i, timeS, lastMs[m], result));
      }
    }
  }
  for (ModeRun& run : runs) summarizeRun(run);
  return runs;
}

std::string terrainTimeDefinition() {
  std::string names;
  for (const char* pass : kTerrainTimePasses) names += fmt::format("{}{}", names.empty() ? "" : " + ", pass);
  return names + " (+ CPU heights in cpu mode)";
}

}  // namespace

std::vector<BenchMode> benchModes(bool compare) {
  std::vector<BenchMode> modes = {{"compute", HeightSource::Compute, true}};
  if (compare) {
    modes.push_back({"vertex_shader", HeightSource::VertexShader, true});
    modes.push_back({"cpu", HeightSource::Cpu, true});
    modes.push_back({"octaves_off", HeightSource::Compute, false});
  }
  return modes;
}

double FrameRecord::passMs(const std::string& name) const {
  double sum = 0.0;
  for (const vk::GpuTiming& t : passes)
    if (t.name == name) sum += t.milliseconds;
  return sum;
}

double FrameRecord::terrainMs() const {
  double sum = cpuHeightsMs;
  for (const char* pass : kTerrainTimePasses) sum += passMs(pass);
  return sum;
}

double FrameBenchReport::ratio(const std::string& mode) const {
  for (const ModeRun& run : runs)
    if (run.mode.name == mode && runs.front().terrainMs.median > 0.0)
      return run.terrainMs.median / runs.front().terrainMs.median;
  return 0.0;
}

nlohmann::json FrameBenchReport::toJson() const {
  const ModeRun& main = runs.front();
  nlohmann::json j;
  j["device"] = device;
  j["driver"] = driver;
  j["width"] = options.width;
  j["height"] = options.height;
  j["fov_deg"] = options.fovYDeg;
  j["patches"] = options.patches;
  j["mesh"] = {{"levels", options.mesh.levels},
               {"rings_per_level", options.mesh.ringsPerLevel},
               {"vertices_per_ring", options.mesh.numPhi},
               {"auto", options.meshAuto}};
  j["lights"] = options.lights;
  if (options.autoExposure)
    j["exposure"] = "auto";
  else
    j["exposure"] = options.exposure;
  j["sky"] = skyModeName(options.skyMode);
  j["terrain_shading"] = options.deferredShading ? "deferred" : "forward";
  j["frames"] = options.frames;
  j["warmup"] = options.warmup;
  j["flight_fps"] = options.flightFps;
  j["frames_in_flight"] = options.framesInFlight;
  j["preset"] = preset;
  j["preset_hash"] = fmt::format("{:016x}", presetHash);
  j["path"] = {{"source", pathSource}, {"keys", pathKeys}, {"duration_s", pathDurationS}};
  j["mode"] = main.mode.name;
  j["frame_ms"] = planet::toJson(main.frameMs);
  j["gpu_ms"] = planet::toJson(main.gpuMs);
  j["cpu_ms"] = planet::toJson(main.cpuMs);
  j["prepare_ms"] = planet::toJson(main.prepareMs);
  j["fps"] = main.frameMs.median > 0.0 ? 1000.0 / main.frameMs.median : 0.0;
  j["passes"] = nlohmann::json::object();
  for (size_t p = 0; p < main.passNames.size(); ++p) j["passes"][main.passNames[p]] = planet::toJson(main.passMs[p]);
  j["terrain_ms"] = planet::toJson(main.terrainMs);
  j["terrain_ms_is"] = terrainTimeDefinition();
  j["nadir_m_per_vertex_min"] = main.minMetresPerVertexAtNadir;
  j["triangles_median"] = uint64_t(std::llround(main.trianglesMedian));
  j["vertices_evaluated_median"] = uint64_t(std::llround(main.verticesEvaluatedMedian));
  j["patch_levels_rebuilt"] = {{"mean", main.patchLevelsRebuiltMean}, {"max", main.patchLevelsRebuiltMax}};
  j["patch_levels_deferred_max"] = main.patchLevelsDeferredMax;
  j["compare"] = nlohmann::json::object();
  j["modes"] = nlohmann::json::object();
  for (const ModeRun& run : runs) {
    if (&run != &main) j["compare"][run.mode.name] = ratio(run.mode.name);
    nlohmann::json m;
    m["height_source"] = heightSourceName(run.mode.heightSource);
    m["limit_octaves"] = run.mode.limitOctaves;
    m["frame_ms"] = planet::toJson(run.frameMs);
    m["gpu_ms"] = planet::toJson(run.gpuMs);
    m["terrain_ms"] = planet::toJson(run.terrainMs);
    m["cpu_heights_ms"] = planet::toJson(run.cpuHeightsMs);
    m["passes"] = nlohmann::json::object();
    for (size_t p = 0; p < run.passNames.size(); ++p) m["passes"][run.passNames[p]] = planet::toJson(run.passMs[p]);
    j["modes"][run.mode.name] = m;
  }
  j["per_frame"] = nlohmann::json::array();
  for (const FrameRecord& f : main.frames) {
    nlohmann::json passes = nlohmann::json::object();
    for (const vk::GpuTiming& t : f.passes) passes[t.name] = f.passMs(t.name);
    j["per_frame"].push_back({{"frame", f.index},
                              {"time_s", f.pathTimeS},
                              {"lat_deg", f.camera.latitudeDeg},
                              {"lon_deg", f.camera.longitudeDeg},
                              {"altitude_m", f.camera.altitudeM},
                              {"height_m", f.heightAboveGroundM},
                              {"frame_ms", f.frameMs},
                              {"gpu_ms", f.gpuMs},
                              {"cpu_ms", f.cpuMs()},
                              {"prepare_ms", f.prepareMs},
                              {"terrain_ms", f.terrainMs()},
                              {"passes", passes},
                              {"triangles", f.triangles},
                              {"vertices_evaluated", f.verticesEvaluated},
                              {"patch_levels_rebuilt", f.patchLevelsRebuilt},
                              {"patch_levels_deferred", f.patchLevelsDeferred},
                              {"m_per_vertex_nadir", f.metresPerVertexAtNadir}});
  }
  return j;
}

std::string FrameBenchReport::csv() const {
  std::vector<std::string> passes;
  for (const ModeRun& run : runs)
    for (const std::string& name : run.passNames)
      if (std::find(passes.begin(), passes.end(), name) == passes.end()) passes.push_back(name);
  std::string out =
      "mode,frame,time_s,lat_deg,lon_deg,altitude_m,height_m,frame_ms,gpu_ms,cpu_ms,prepare_ms,terrain_ms,cpu_heights_"
      "ms";
  for (const std::string& name : passes) out += ",pass_" + name + "_ms";
  out += ",triangles,vertices_evaluated,patch_levels_rebuilt,m_per_vertex_nadir\n";
  for (const ModeRun& run : runs)
    for (const FrameRecord& f : run.frames) {
      out +=
          fmt::format("{},{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}", run.mode.name, f.index,
                      f.pathTimeS, f.camera.latitudeDeg, f.camera.longitudeDeg, f.camera.altitudeM,
                      f.heightAboveGroundM, f.frameMs, f.gpuMs, f.cpuMs(), f.prepareMs, f.terrainMs(), f.cpuHeightsMs);
      for (const std::string& name : passes) out += fmt::format(",{:.4f}", f.passMs(name));
      out += fmt::format(",{},{},{},{}\n", f.triangles, f.verticesEvaluated, f.patchLevelsRebuilt,
                         f.metresPerVertexAtNadir);
    }
  return out;
}

std::string FrameBenchReport::table() const {
  const ModeRun& main = runs.front();
  std::string out = fmt::format("device: {} ({})\n", device, driver);
  out += fmt::format(
      "preset: {} (hash {:016x}), {}x{}{}{}{}{}, exposure {}, path: {} ({} keys, {} s), {} frames after {} "
      "warm-up\n",
      preset, presetHash, options.width, options.height, options.patches ? "" : " without patches",
      options.lights ? "" : " without lights", options.skyMode == SkyMode::Reference ? ", reference sky" : "",
      options.deferredShading ? ", deferred terrain shading" : "",
      options.autoExposure ? "auto" : fmt::format("{:g}", options.exposure), pathSource, pathKeys, pathDurationS,
      options.frames, options.warmup);
  out += options.flightFps > 0.0
             ? fmt::format("each timed frame follows an untimed one 1/{} s of flight before it (a {} fps flight)\n",
                           options.flightFps, options.flightFps)
             : std::string("no lead-in frames: each timed frame follows the timed one before it\n");
  out += options.framesInFlight > 1
             ? fmt::format(
                   "{} frames in flight, as the viewer draws: each timed frame is prepared and recorded while "
                   "the frame before it executes; its time is from that frame's end to its own on the GPU's "
                   "clock\n",
                   options.framesInFlight)
             : std::string("one frame at a time: each frame's CPU preparation and recording, then its GPU work\n");
  out += fmt::format("mesh: {}\n\n", describeMesh(options.mesh, options.meshAuto, options.height, options.fovYDeg));
  out += fmt::format("{:<34} {:>9} {:>9} {:>9} {:>9}\n", "ms (mode " + main.mode.name + ")", "median", "p95", "p99",
                     "max");
  auto row = [&](const std::string& name, const Summary& s) {
    out += fmt::format("{:<34} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f}\n", name, s.median, s.p95, s.p99, s.max);
  };
  const bool pipelined = options.framesInFlight > 1;
  row(pipelined ? "frame (GPU clock, end to end)" : "frame (wall clock)", main.frameMs);
  row("GPU (first to last timestamp)", main.gpuMs);
  row(pipelined ? "GPU waiting (frame - GPU)" : "CPU (frame - GPU)", main.cpuMs);
  row("  of which prepare (cull, uniforms)", main.prepareMs);
  for (size_t p = 0; p < main.passNames.size(); ++p) row("  pass " + main.passNames[p], main.passMs[p]);
  row("terrain time", main.terrainMs);
  out += fmt::format("\nframes per second (median frame): {:.2f}\n", 1000.0 / main.frameMs.median);
  out += fmt::format("metres per vertex at the nadir: {:.4g} at the lowest point\n", main.minMetresPerVertexAtNadir);
  out += fmt::format("triangles drawn (median): {:.0f}, vertices evaluated (median): {:.0f}\n", main.trianglesMedian,
                     main.verticesEvaluatedMedian);
  if (options.patches)
    out += fmt::format(
        "patch levels rebuilt per frame: mean {:.2f}, max {} (at most {} texels a frame, a recentre step; up to {} "
        "levels not whole)\n",
        main.patchLevelsRebuiltMean, main.patchLevelsRebuiltMax, realTimePatchBudget(PatchSettings{}),
        main.patchLevelsDeferredMax);
  out += fmt::format("terrain time = {}\n", terrainTimeDefinition());
  if (runs.size() > 1) {
    out += fmt::format("\ncompare: median terrain time over {}'s ({:.2f} ms)\n", main.mode.name, main.terrainMs.median);
    for (const ModeRun& run : runs)
      if (&run != &main)
        out += fmt::format("  {:<14} {:>7.2f}x  (terrain {:.2f} ms, frame {:.2f} ms median)\n", run.mode.name,
                           ratio(run.mode.name), run.terrainMs.median, run.frameMs.median);
  }
  return out;
}

FrameBenchReport runFrameBench(vk::Context& context, const PlanetDescription& planet, const std::string& preset,
                               const CameraPath& path, const std::string& pathSource, const FrameBenchOptions& options,
                               const FrameBenchProgress& progress) {
  if (options.frames < 1 || options.frames > kBenchMaxFrames)
    throw Error(fmt::format("frames must be in 1..{}, got {}", kBenchMaxFrames, options.frames));
  if (!(options.flightFps == 0.0 || (options.flightFps >= 1.0 && options.flightFps <= kBenchMaxFlightFps)))
    throw Error(fmt::format("the flight rate must be 0 or in 1..{} frames per second, got {}", kBenchMaxFlightFps,
                            options.flightFps));
  if (options.framesInFlight != 1 && options.framesInFlight != vk::kFramesInFlight)
    throw Error(fmt::format("frames in flight must be 1 or {}, got {}", vk::kFramesInFlight, options.framesInFlight));
  if (options.framesInFlight > 1 && options.flightFps == 0.0)
    throw Error("two frames in flight need the lead-in frames of a real-time flight (a flight rate above 0)");
  if (options.warmup > kBenchMaxWarmup)
    throw Error(fmt::format("warm-up frames must be in 0..{}, got {}", kBenchMaxWarmup, options.warmup));
  validateCameraPath(path, pathSource);
  FrameBenchReport report;
  report.device = context.info.name;
  report.driver = context.info.driver;
  report.options = options;
  report.preset = preset;
  report.presetHash = descriptionHash(planet);
  report.pathSource = pathSource;
  report.pathKeys = path.keys.size();
  report.pathDurationS = path.durationS();
  report.runs = runModes(context, planet, path, options, progress);
  return report;
}

}  // namespace planet

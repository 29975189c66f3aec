// planet export heightmap | mesh: files for other tools from the CPU reference (no Vulkan):
// whole-planet heightmaps with a JSON sidecar, and glTF / OBJ meshes of a region
// (engine/export). The heights are terrainHeightM's, as `planet height` prints them.
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include "cli_common.h"
#include "core/error.h"
#include "export/heightmap_export.h"
#include "export/mesh_files.h"
#include "export/region_mesh.h"

namespace planet::cli {
namespace {

constexpr uint32_t kMaxThreads = 256;

struct CommonExportOptions {
  std::string preset{kDefaultPresetName};
  std::optional<uint64_t> seed;
  std::string format;  // empty: from the extension of --out
  std::string out;
  bool filtered = false;
  uint32_t threads = 0;
};

struct HeightmapCommand : CommonExportOptions {
  std::string projection = "equirect";
  std::string size;  // empty: 2048x1024 (equirect) or 512 (cube-map face)
};

struct MeshCommand : CommonExportOptions {
  std::string region;
  std::string resolution = "256";
};

// --threads checked, and the preset resolved with --seed applied: the planet, and the source
// the written files record.
PlanetDescription resolveExportPlanet(const CommonExportOptions& o, ExportSource& source) {
  if (o.threads > kMaxThreads)
    throw UsageError(fmt::format("--threads must be in 0..{} (0: one per core), got {}", kMaxThreads, o.threads));
  PlanetDescription planet;
  try {
    planet = resolvePreset(o.preset);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (o.seed) applySeedOffset(planet, *o.seed);
  source.preset = o.preset;
  source.seedOffset = o.seed.value_or(0);
  return planet;
}

bool endsWith(const std::string& text, std::string_view suffix) {
  if (text.size() < suffix.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(uint8_t(text[text.size() - suffix.size() + i])) != suffix[i]) return false;
  return true;
}

// --format, or the one that --out's extension names; each format's extensions are listed
// with it. A given --format whose name contradicts a known extension of --out is an error (a
// .png file that holds raw floats opens in no viewer).
std::string chooseFormat(const std::string& given, const std::string& out,
                         std::initializer_list<std::pair<const char*, const char*>> formatsByExtension,
                         const std::string& expected) {
  std::string byExtension;
  for (const auto& [format, extension] : formatsByExtension)
    if (endsWith(out, extension)) byExtension = format;
  if (given.empty()) {
    if (byExtension.empty())
      throw UsageError(fmt::format("--format not given and --out '{}' does not end in {}", out, expected));
    return byExtension;
  }
  if (!byExtension.empty() && byExtension != given) {
    // Only a contradiction when the given format is a known one; an unknown one is reported by its parser.
    for (const auto& [format, extension] : formatsByExtension)
      if (given == format)
        throw UsageError(
            fmt::format("--format {} does not match --out '{}' (a file of that name is {})", given, out, byExtension));
  }
  return given;
}

// A whole number of text: digits only.
std::optional<uint64_t> wholeNumber(std::string_view text) {
  uint64_t value = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
  return value;
}

HeightmapSpec parseHeightmapSize(HeightmapProjection projection, const std::string& text, bool filtered) {
  const size_t x = text.find('x');
  const std::optional<uint64_t> first = wholeNumber(std::string_view(text).substr(0, x));
  const std::optional<uint64_t> second =
      x == std::string::npos ? std::nullopt : wholeNumber(std::string_view(text).substr(x + 1));
  if (!first || (x != std::string::npos && !second)) {
    throw UsageError(projection == HeightmapProjection::Equirect
                         ? fmt::format("--size expects W or WxH in pixels, got '{}'", text)
                         : fmt::format("--size expects the face size N (or NxN) in pixels, got '{}'", text));
  }
  if (projection == HeightmapProjection::Equirect) {
    const uint64_t width = *first, height = second ? *second : std::max<uint64_t>(1, *first / 2);
    if (width < 1 || height < 1 || width > kEquirectMaxWidth || height > kEquirectMaxHeight)
      throw UsageError(fmt::format("--size {} is outside 1x1 .. {}x{} for an equirect map", text, kEquirectMaxWidth,
                                   kEquirectMaxHeight));
    return equirectSpec(uint32_t(width), uint32_t(height), filtered);
  }
  if (second && *second != *first)
    throw UsageError(fmt::format("--size {} is not square: a cube-map face is N x N (the strip is 6N x N)", text));
  if (*first < 1 || *first > kCubeMapMaxFaceSize)
    throw UsageError(fmt::format("--size {} is outside 1 .. {} for a cube-map face", text, kCubeMapMaxFaceSize));
  return cubeMapSpec(uint32_t(*first), filtered);
}

// The image and its sidecar go into one directory: the sidecar's name must not be a directory either.
void checkHeightmapOutputs(const std::string& out) {
  checkOutputFile("--out", out);
  std::error_code ignored;
  if (std::filesystem::is_directory(sidecarPath(out), ignored))
    throw UsageError(
        fmt::format("the sidecar of --out '{}' would be '{}', which is a directory", out, sidecarPath(out)));
}

std::string threadText(uint32_t threads) {
  const unsigned count = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  return fmt::format("{} thread{}", count, count == 1 ? "" : "s");
}

int runHeightmap(const HeightmapCommand& cmd, const CLI::App& sub) {
  HeightmapProjection projection;
  HeightmapEncoding encoding;
  try {
    projection = parseHeightmapProjection(cmd.projection);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  const std::string size =
      sub.count("--size") ? cmd.size : (projection == HeightmapProjection::Equirect ? "2048x1024" : "512");
  const HeightmapSpec spec = parseHeightmapSize(projection, size, cmd.filtered);
  checkHeightmapOutputs(cmd.out);
  const std::string format = chooseFormat(cmd.format, cmd.out, {{"png16", ".png"}, {"raw", ".raw"}}, ".png or .raw");
  try {
    encoding = parseHeightmapEncoding(format);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  ExportSource source;
  const PlanetDescription planet = resolveExportPlanet(cmd, source);

  const auto start = std::chrono::steady_clock::now();
  Heightmap map;
  {
    ProgressLine progress(fmt::format("export heightmap {}x{}", spec.width, spec.height));
    map = computeHeightmap(planet, spec, cmd.threads, std::ref(progress));
  }
  const double computeS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeHeightmap(cmd.out, planet, source, map, encoding);
  const double totalS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("wrote {} ({}x{} {} {}, {}, heights {:.4f} .. {:.4f} m) and {}\n", cmd.out, spec.width, spec.height,
             projectionName(projection), encodingName(encoding), detailText(map.spacingM), map.minM, map.maxM,
             sidecarPath(cmd.out));
  fmt::print("{} (preset {}): {} heights in {:.2f} s on {} ({:.0f} thousand a second), {:.2f} s with the files\n",
             planet.name, cmd.preset, map.heightsM.size(), computeS, threadText(cmd.threads),
             double(map.heightsM.size()) / computeS / 1000.0, totalS);
  return 0;
}

// "SOUTH,WEST,NORTH,EAST" in degrees.
MeshRegion parseRegion(const std::string& text) {
  double values[4];
  size_t begin = 0;
  for (int k = 0; k < 4; ++k) {
    const size_t end = k < 3 ? text.find(',', begin) : text.size();
    std::string_view part =
        end == std::string::npos ? std::string_view() : std::string_view(text).substr(begin, end - begin);
    if (part.size() > 1 && part[0] == '+') part.remove_prefix(1);
    auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), values[k]);
    if (end == std::string::npos || part.empty() || ec != std::errc() || ptr != part.data() + part.size() ||
        !std::isfinite(values[k]))
      throw UsageError(fmt::format("--region expects SOUTH,WEST,NORTH,EAST in degrees, got '{}'", text));
    begin = end + 1;
  }
  const MeshRegion region{values[0], values[1], values[2], values[3]};
  try {
    validateMeshRegion(region);
  } catch (const Error& e) {
    throw UsageError(fmt::format("--region {}: {}", text, e.what()));
  }
  return region;
}

// "N" vertices per side, or "Dm": the fewest vertices whose cells are at most D metres on a side.
uint32_t parseResolution(const std::string& text, double radiusM, const MeshRegion& region) {
  uint64_t n = 0;
  if (const std::optional<uint64_t> count = wholeNumber(text)) {
    n = *count;
  } else if (text.size() > 1 && text.back() == 'm') {
    const std::string_view number = std::string_view(text).substr(0, text.size() - 1);
    double metres = 0.0;
    auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), metres);
    if (ec != std::errc() || ptr != number.data() + number.size() || !std::isfinite(metres) || !(metres > 0.0))
      throw UsageError(
          fmt::format("--resolution expects vertices per side N or a spacing in metres like 30m, got '{}'", text));
    const RegionExtentM extent = regionExtentM(radiusM, region);
    const double cells = std::ceil(std::max(extent.northSouth, extent.eastWest) / metres);
    if (cells + 1.0 > double(kMeshMaxResolution))
      throw UsageError(fmt::format("--resolution {} needs {:.0f} vertices per side for this region, at most {}", text,
                                   cells + 1.0, kMeshMaxResolution));
    n = std::max<uint64_t>(kMeshMinResolution, uint64_t(cells) + 1);
  } else {
    throw UsageError(
        fmt::format("--resolution expects vertices per side N or a spacing in metres like 30m, got '{}'", text));
  }
  if (n < kMeshMinResolution || n > kMeshMaxResolution)
    throw UsageError(fmt::format("--resolution {} is outside {}..{} vertices per side", text, kMeshMinResolution,
                                 kMeshMaxResolution));
  return uint32_t(n);
}

int runMesh(const MeshCommand& cmd) {
  const MeshRegion region = parseRegion(cmd.region);
  checkOutputFile("--out", cmd.out);
  const std::string format =
      chooseFormat(cmd.format, cmd.out, {{"gltf", ".gltf"}, {"glb", ".glb"}, {"obj", ".obj"}}, ".gltf, .glb or .obj");
  MeshFormat meshFormat;
  try {
    meshFormat = parseMeshFormat(format);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  ExportSource source;
  // The preset first: a spacing in metres needs its radius.
  const PlanetDescription planet = resolveExportPlanet(cmd, source);
  MeshSpec spec;
  spec.region = region;
  spec.resolution = parseResolution(cmd.resolution, planet.radiusM, region);
  spec.filtered = cmd.filtered;

  const auto start = std::chrono::steady_clock::now();
  RegionMesh mesh;
  {
    ProgressLine progress(fmt::format("export mesh {}x{}", spec.resolution, spec.resolution));
    mesh = computeRegionMesh(planet, spec, cmd.threads, std::ref(progress));
  }
  writeMesh(cmd.out, planet, source, mesh, meshFormat);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const RegionExtentM extent = regionExtentM(planet.radiusM, region);
  fmt::print("wrote {} ({}, {}x{} vertices, {} triangles, {}, heights {:.4f} .. {:.4f} m)\n", cmd.out,
             meshFormat == MeshFormat::Obj ? "OBJ" : (meshFormat == MeshFormat::Glb ? "glTF 2.0 binary" : "glTF 2.0"),
             spec.resolution, spec.resolution, mesh.indices.size() / 3, detailText(mesh.spacingM), mesh.minHeightM,
             mesh.maxHeightM);
  const glm::dvec3& o = mesh.frame.originM;
  fmt::print(
      "region {:.3f} x {:.3f} km (north-south x east-west at its widest), cell {:.2f} m; origin (planet frame) "
      "{:.3f}, {:.3f}, {:.3f} m; x east, y up, z south; {:.2f} s on {}\n",
      extent.northSouth / 1000.0, extent.eastWest / 1000.0,
      std::max(extent.northSouth, extent.eastWest) / double(spec.resolution - 1), o.x, o.y, o.z, seconds,
      threadText(cmd.threads));
  return 0;
}

void addCommonOptions(CLI::App& sub, CommonExportOptions& o, const char* formats) {
  sub.add_option("--preset", o.preset, "Built-in preset (earth, moon, mars, giant, faults, mpd) or a .toml file")->capture_default_str();
  sub.add_option("--seed", o.seed, "Added to every layer's seed, as in planet render");
  sub.add_option("--out", o.out, "File to write (replaced atomically)")->required();
  sub.add_option("--format", o.format, formats);
  sub.add_flag("--filtered", o.filtered,
               "Limit each layer's octaves to what the sample spacing can show (no aliasing); default: full detail, "
               "the heights planet height prints");
  sub.add_option("--threads", o.threads, "Threads evaluating heights (0: one per core)")->capture_default_str();
}

}  // namespace

void addExportCommand(CLI::App& app, int& exitCode) {
  CLI::App* group =
      app.add_subcommand("export", "Write heightmaps or meshes for other tools from the CPU reference (no GPU needed)");

  auto map = std::make_shared<HeightmapCommand>();
  CLI::App* heightmap = group->add_subcommand(
      "heightmap",
      "The whole planet as an equirectangular or cube-map heightmap (16-bit PNG or float32 raw) with a JSON sidecar "
      "FILE.json that says how to turn pixels back into heights and points");
  addCommonOptions(*heightmap, *map,
                   "png16 (16-bit grey PNG, linear between the sidecar's min and max) | raw (little-endian float32 "
                   "metres, row-major, no header) [default: from --out's extension, .png or .raw]");
  heightmap
      ->add_option("--projection", map->projection,
                   "equirect (pixel centres at latitude 90 - (y + 0.5) * 180 / H, longitude -180 + (x + 0.5) * "
                   "360 / W) | cubemap (one 6N x N strip, faces +x, -x, +y, -y, +z, -z left to right, each seen "
                   "from outside; the sidecar lists their axes)")
      ->capture_default_str();
  heightmap->add_option("--size", map->size,
                        "equirect: W or WxH pixels (W alone: H = W / 2; at most 16384x8192) [default: 2048x1024]; "
                        "cubemap: face size N (at most 4096) [default: 512]");
  checkNumbersAsText(*heightmap);
  heightmap->callback([&exitCode, map, heightmap] { exitCode = runHeightmap(*map, *heightmap); });

  auto mesh = std::make_shared<MeshCommand>();
  CLI::App* meshCommand = group->add_subcommand(
      "mesh",
      "A region as a triangulated grid (glTF 2.0 or OBJ): float positions in metres around the region's centre "
      "(x east, y up, z south), normals, and the centre's planet-frame position in double in the metadata");
  addCommonOptions(*meshCommand, *mesh,
                   "gltf (one file, buffer embedded as base64) | glb (binary glTF) | obj [default: from --out's "
                   "extension]");
  meshCommand
      ->add_option("--region", mesh->region,
                   "SOUTH,WEST,NORTH,EAST in degrees (south-west corner, then north-east; to cross 180 give EAST "
                   "above 180)")
      ->required();
  meshCommand
      ->add_option("--resolution", mesh->resolution,
                   "Vertices per side N (2..2048), or a spacing like 30m: the fewest vertices with cells at most that "
                   "long")
      ->capture_default_str();
  checkNumbersAsText(*meshCommand);
  meshCommand->callback([&exitCode, mesh] { exitCode = runMesh(*mesh); });
}

}  // namespace planet::cli

// Compiled with -ffp-contract=off (the project-wide rule, top CMakeLists.txt): a pixel's latitude and longitude are
// the sidecar's formulas to the last bit, so that `planet height --at` of them gives the same
// height.
#include "export/heightmap_export.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"
#include "core/file.h"
#include "core/image_file.h"
#include "planet/terrain_height.h"
#include "planet/cube_face.h"

namespace planet {
namespace {

constexpr const char* kFaceNames[kCubeFaceCount] = {"+x", "-x", "+y", "-y", "+z", "-z"};

nlohmann::ordered_json vectorJson(const glm::dvec3& v) { return nlohmann::ordered_json::array({v.x, v.y, v.z}); }

}  // namespace

const char* projectionName(HeightmapProjection projection) {
  return projection == HeightmapProjection::Equirect ? "equirect" : "cubemap";
}

const char* encodingName(HeightmapEncoding encoding) { return encoding == HeightmapEncoding::Png16 ? "png16" : "raw"; }

HeightmapProjection parseHeightmapProjection(std::string_view name) {
  if (name == "equirect") return HeightmapProjection::Equirect;
  if (name == "cubemap") return HeightmapProjection::CubeMap;
  throw Error(fmt::format("unknown projection '{}' (expected equirect or cubemap)", name));
}

HeightmapEncoding parseHeightmapEncoding(std::string_view name) {
  if (name == "png16") return HeightmapEncoding::Png16;
  if (name == "raw") return HeightmapEncoding::RawFloat32;
  throw Error(fmt::format("unknown heightmap format '{}' (expected png16 or raw)", name));
}

HeightmapSpec equirectSpec(uint32_t width, uint32_t height, bool filtered) {
  return {HeightmapProjection::Equirect, width, height, filtered};
}

HeightmapSpec cubeMapSpec(uint32_t faceSize, bool filtered) {
  return {HeightmapProjection::CubeMap, faceSize * uint32_t(kCubeFaceCount), faceSize, filtered};
}

void validateHeightmapSpec(const HeightmapSpec& spec) {
  if (spec.projection == HeightmapProjection::Equirect) {
    if (spec.width < 1 || spec.height < 1 || spec.width > kEquirectMaxWidth || spec.height > kEquirectMaxHeight)
      throw Error(fmt::format("equirect size {}x{} is outside 1x1 .. {}x{}", spec.width, spec.height, kEquirectMaxWidth,
                              kEquirectMaxHeight));
    return;
  }
  if (spec.height < 1 || spec.height > kCubeMapMaxFaceSize)
    throw Error(fmt::format("cube-map face size {} is outside 1 .. {}", spec.height, kCubeMapMaxFaceSize));
  if (uint64_t(spec.width) != uint64_t(spec.height) * kCubeFaceCount)
    throw Error(fmt::format("a cube-map strip is 6N x N pixels, got {}x{}", spec.width, spec.height));
}

glm::dvec2 equirectPixelCentreDeg(uint32_t x, uint32_t y, uint32_t width, uint32_t height) {
  const double latitude = 90.0 * double(int64_t(height) - 2 * int64_t(y) - 1) / double(height);
  const double longitude = 180.0 * double(2 * int64_t(x) + 1 - int64_t(width)) / double(width);
  return {latitude, longitude};
}

glm::dvec3 heightmapPixelDirection(const HeightmapSpec& spec, uint32_t x, uint32_t y) {
  if (spec.projection == HeightmapProjection::Equirect) {
    const glm::dvec2 latLon = equirectPixelCentreDeg(x, y, spec.width, spec.height);
    return directionFromLatLon(latLon.x, latLon.y);
  }
  const int64_t n = spec.height;
  const int face = int(x / spec.height);
  const int64_t i = int64_t(x) - face * n;
  const double a = double(2 * i + 1 - n) / double(n);
  const double b = double(n - 2 * int64_t(y) - 1) / double(n);
  return cubeFaceDirection(face, a, b);
}

double heightmapSpacingM(const PlanetDescription& planet, const HeightmapSpec& spec) {
  if (!spec.filtered) return 0.0;
  if (spec.projection == HeightmapProjection::Equirect)
    return std::max(std::numbers::pi * planet.radiusM / spec.height,
                    2.0 * std::numbers::pi * planet.radiusM / spec.width);
  return 2.0 * planet.radiusM / spec.height;
}

Heightmap computeHeightmap(const PlanetDescription& planet, const HeightmapSpec& spec, unsigned threads,
                           const ProgressCallback& progress) {
  validateHeightmapSpec(spec);
  Heightmap map;
  map.spec = spec;
  map.spacingM = heightmapSpacingM(planet, spec);
  map.heightsM.resize(size_t(spec.width) * spec.height);
  // One row per chunk: a row of the largest image is ~70 ms of work, fine-grained enough to
  // balance and to report progress smoothly.
  parallelFor(
      spec.height, 1, threads,
      [&](size_t begin, size_t end) {
        for (size_t y = begin; y < end; ++y)
          for (uint32_t x = 0; x < spec.width; ++x)
            map.heightsM[y * spec.width + x] =
                float(terrainHeightM(planet, heightmapPixelDirection(spec, x, uint32_t(y)), map.spacingM));
      },
      progress ? ProgressCallback([&](size_t done, size_t total) { progress(done * spec.width, total * spec.width); })
               : ProgressCallback());
  const auto [lowest, highest] = std::minmax_element(map.heightsM.begin(), map.heightsM.end());
  map.minM = *lowest;
  map.maxM = *highest;
  return map;
}

std::vector<uint16_t> quantizeHeights(const Heightmap& heightmap) {
  std::vector<uint16_t> values(heightmap.heightsM.size(), 0);
  const double range = heightmap.maxM - heightmap.minM;
  if (!(range > 0.0)) return values;
  for (size_t i = 0; i < values.size(); ++i) {
    const double t = (double(heightmap.heightsM[i]) - heightmap.minM) / range;
    values[i] = uint16_t(std::clamp<long>(std::lround(t * 65535.0), 0, 65535));
  }
  return values;
}

std::string encodeHeightmap(const Heightmap& heightmap, HeightmapEncoding encoding) {
  if (encoding == HeightmapEncoding::Png16) {
    const Grey16Image image{heightmap.spec.width, heightmap.spec.height, quantizeHeights(heightmap)};
    const std::vector<uint8_t> png = encodePng16(image);
    return std::string(png.begin(), png.end());
  }
  std::string bytes(heightmap.heightsM.size() * 4, '\0');
  for (size_t i = 0; i < heightmap.heightsM.size(); ++i) {
    const uint32_t bits = std::bit_cast<uint32_t>(heightmap.heightsM[i]);
    for (int k = 0; k < 4; ++k) bytes[4 * i + size_t(k)] = char(uint8_t(bits >> (8 * k)));
  }
  return bytes;
}

nlohmann::ordered_json heightmapSidecar(const PlanetDescription& planet, const ExportSource& source,
                                        const Heightmap& heightmap, HeightmapEncoding encoding,
                                        const std::string& imageFileName, std::string_view imageBytes) {
  const HeightmapSpec& spec = heightmap.spec;
  nlohmann::ordered_json j;
  j["format"] = "planet-heightmap";
  j["version"] = 1;
  j["generator"] = "planet export heightmap";
  j["source"] = exportProvenance(planet, source, heightmap.spacingM);
  j["projection"] = projectionName(spec.projection);
  j["width"] = spec.width;
  j["height"] = spec.height;
  nlohmann::ordered_json centre;
  centre["x"] = "column from the left, 0 .. width - 1";
  centre["y"] = "row from the top, 0 .. height - 1";
  if (spec.projection == HeightmapProjection::Equirect) {
    centre["latitude_deg"] = "90 * (height - 2 * y - 1) / height";
    centre["longitude_deg"] = "180 * (2 * x + 1 - width) / width";
    centre["direction"] = "(cos(lat) * cos(lon), cos(lat) * sin(lon), sin(lat)), as planet height --at LAT,LON";
  } else {
    j["face_size"] = spec.height;
    centre["face"] = "floor(x / face_size): faces[face]";
    centre["i"] = "x - face * face_size";
    centre["j"] = "y";
    centre["a"] = "(2 * i + 1 - face_size) / face_size";
    centre["b"] = "(face_size - 2 * j - 1) / face_size";
    centre["direction"] =
        "normalize(normal + a * axis_a + b * axis_b): seen from outside, columns run along axis_a "
        "and rows down against axis_b";
    nlohmann::ordered_json faces = nlohmann::ordered_json::array();
    for (int f = 0; f < kCubeFaceCount; ++f) {
      const CubeFace face = cubeFace(f);
      faces.push_back({{"index", f},
                       {"name", kFaceNames[f]},
                       {"x_offset", uint64_t(f) * spec.height},
                       {"normal", vectorJson(face.normal)},
                       {"axis_a", vectorJson(face.axisA)},
                       {"axis_b", vectorJson(face.axisB)}});
    }
    j["faces"] = faces;
  }
  j["pixel_centre"] = centre;
  j["encoding"] = encodingName(encoding);
  if (encoding == HeightmapEncoding::Png16) {
    j["png16"] = {{"channels", 1},
                  {"bit_depth", 16},
                  {"height_m", "min_height_m + value / 65535 * (max_height_m - min_height_m)"},
                  {"value", "round((height_m - min_height_m) / (max_height_m - min_height_m) * 65535)"},
                  {"step_m", (heightmap.maxM - heightmap.minM) / 65535.0}};
  } else {
    j["raw"] = {{"dtype", "float32"},
                {"byte_order", "little-endian"},
                {"layout", "row-major, top row first, width * height values, no header"},
                {"bytes", uint64_t(spec.width) * spec.height * 4}};
  }
  j["min_height_m"] = heightmap.minM;
  j["max_height_m"] = heightmap.maxM;
  j["image_file"] = imageFileName;
  j["image_fnv1a64"] = fmt::format("{:016x}", fnv1a64(imageBytes));
  return j;
}

std::string sidecarPath(const std::string& path) { return path + ".json"; }

void writeHeightmap(const std::string& path, const PlanetDescription& planet, const ExportSource& source,
                    const Heightmap& heightmap, HeightmapEncoding encoding) {
  const std::string image = encodeHeightmap(heightmap, encoding);
  const std::string name = std::filesystem::path(path).filename().string();
  const std::string sidecar = heightmapSidecar(planet, source, heightmap, encoding, name, image).dump(2) + "\n";
  const FileContents files[] = {{path, image}, {sidecarPath(path), sidecar}};
  writeFilesAtomic(files);
}

}  // namespace planet

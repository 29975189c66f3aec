// planet export's engine (engine/export): heightmap pixels are the documented points at the
// reference heights, the sidecar describes them, cube faces meet along their edges; an image
// and its sidecar are written together or not.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/file.h"
#include "export/heightmap_export.h"
#include "planet/terrain_height.h"
#include "render/patch_layout.h"
#include "test_support.h"

namespace planet {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

const PlanetDescription& earth() {
  static const PlanetDescription planet = resolvePreset("earth");
  return planet;
}

glm::dvec3 jsonVector(const nlohmann::json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// ---- Heightmaps ------------------------------------------------------------------------------

TEST(ExportHeightmap, EquirectPixelCentresAreHalfAPixelInsideTheEdges) {
  // 64 x 32: pixels are 5.625 degrees square; the first centre is half of that from 90 N, 180 W.
  EXPECT_EQ(equirectPixelCentreDeg(0, 0, 64, 32), glm::dvec2(87.1875, -177.1875));
  EXPECT_EQ(equirectPixelCentreDeg(63, 31, 64, 32), glm::dvec2(-87.1875, 177.1875));
  EXPECT_EQ(equirectPixelCentreDeg(32, 16, 64, 32), glm::dvec2(-2.8125, 2.8125));
  const HeightmapSpec spec = equirectSpec(64, 32);
  EXPECT_EQ(heightmapPixelDirection(spec, 10, 20),
            directionFromLatLon(equirectPixelCentreDeg(10, 20, 64, 32).x, equirectPixelCentreDeg(10, 20, 64, 32).y));
  // The same as the sidecar's alternative form 90 - (y + 0.5) * 180 / H, -180 + (x + 0.5) * 360 / W.
  for (uint32_t y = 0; y < 32; ++y)
    EXPECT_NEAR(equirectPixelCentreDeg(0, y, 64, 32).x, 90.0 - (y + 0.5) * 5.625, 1e-12);
}

TEST(ExportHeightmap, HeightsAreTheReferenceAtEveryPixelCentreOnAnyThreadCount) {
  const HeightmapSpec spec = equirectSpec(24, 12);
  const Heightmap one = computeHeightmap(earth(), spec, 1);
  const Heightmap three = computeHeightmap(earth(), spec, 3);
  EXPECT_EQ(one.heightsM, three.heightsM);
  ASSERT_EQ(one.heightsM.size(), 24u * 12u);
  EXPECT_EQ(one.spacingM, 0.0);
  for (uint32_t y = 0; y < 12; ++y)
    for (uint32_t x = 0; x < 24; ++x) {
      const double latitude = 90.0 - (y + 0.5) * 180.0 / 12.0, longitude = -180.0 + (x + 0.5) * 360.0 / 24.0;
      ASSERT_FLOAT_EQ(one.heightsM[y * 24 + x],
                      float(terrainHeightM(earth(), directionFromLatLon(latitude, longitude))))
          << x << "," << y;
    }
  EXPECT_EQ(one.minM, double(*std::min_element(one.heightsM.begin(), one.heightsM.end())));
  EXPECT_EQ(one.maxM, double(*std::max_element(one.heightsM.begin(), one.heightsM.end())));
  EXPECT_LT(one.minM, 0.0);  // the earth preset has oceans and land
  EXPECT_GT(one.maxM, 0.0);
}

TEST(ExportHeightmap, FilteredHeightsLimitOctavesToTheLargestPixelExtent) {
  const HeightmapSpec spec = equirectSpec(16, 8, true);
  const double spacing = heightmapSpacingM(earth(), spec);
  EXPECT_DOUBLE_EQ(spacing, std::numbers::pi * earth().radiusM / 8.0);
  EXPECT_DOUBLE_EQ(heightmapSpacingM(earth(), equirectSpec(8, 8, true)),
                   2.0 * std::numbers::pi * earth().radiusM / 8.0);
  EXPECT_DOUBLE_EQ(heightmapSpacingM(earth(), cubeMapSpec(10, true)), 2.0 * earth().radiusM / 10.0);
  EXPECT_EQ(heightmapSpacingM(earth(), equirectSpec(16, 8)), 0.0);
  const Heightmap filtered = computeHeightmap(earth(), spec);
  const Heightmap full = computeHeightmap(earth(), equirectSpec(16, 8));
  EXPECT_EQ(filtered.spacingM, spacing);
  size_t differ = 0;
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      const glm::dvec3 d = heightmapPixelDirection(spec, x, y);
      ASSERT_EQ(filtered.heightsM[y * 16 + x], float(terrainHeightM(earth(), d, spacing)));
      differ += filtered.heightsM[y * 16 + x] != full.heightsM[y * 16 + x];
    }
  EXPECT_GT(differ, 100u) << "at a 2,500 km spacing most octaves are left out";
}

// The direction of cube-map pixel (x, y) as the sidecar describes it, from its JSON alone.
glm::dvec3 sidecarCubeDirection(const nlohmann::json& sidecar, uint32_t x, uint32_t y) {
  const int64_t n = sidecar["face_size"].get<int64_t>();
  const nlohmann::json& face = sidecar["faces"][size_t(x / n)];
  EXPECT_EQ(face["x_offset"].get<int64_t>(), int64_t(x / n) * n);
  const int64_t i = int64_t(x) - face["x_offset"].get<int64_t>(), j = y;
  const double a = double(2 * i + 1 - n) / double(n), b = double(n - 2 * j - 1) / double(n);
  return glm::normalize(jsonVector(face["normal"]) + a * jsonVector(face["axis_a"]) + b * jsonVector(face["axis_b"]));
}

TEST(ExportHeightmap, CubeMapFacesAreTheProjectsCubeFacesSeenFromOutside) {
  const uint32_t n = 6;
  const Heightmap map = computeHeightmap(earth(), cubeMapSpec(n));
  ASSERT_EQ(map.spec.width, 6 * n);
  ASSERT_EQ(map.spec.height, n);
  const std::string image = encodeHeightmap(map, HeightmapEncoding::RawFloat32);
  const nlohmann::json sidecar = nlohmann::json::parse(
      heightmapSidecar(earth(), {"earth", 0}, map, HeightmapEncoding::RawFloat32, "c.raw", image).dump());
  EXPECT_EQ(sidecar["projection"], "cubemap");
  EXPECT_EQ(sidecar["face_size"], n);
  ASSERT_EQ(sidecar["faces"].size(), 6u);
  // Left to right: +x, -x, +y, -y, +z, -z.
  const glm::dvec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const char* names[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  for (int f = 0; f < 6; ++f) {
    const nlohmann::json& face = sidecar["faces"][size_t(f)];
    EXPECT_EQ(face["name"], names[f]);
    EXPECT_EQ(jsonVector(face["normal"]), normals[f]);
    EXPECT_EQ(jsonVector(face["axis_a"]), cubeFace(f).axisA);
    EXPECT_EQ(jsonVector(face["axis_b"]), cubeFace(f).axisB);
    // Not mirrored: columns along axis_a and rows up along axis_b form a right-handed frame with the normal.
    EXPECT_EQ(glm::cross(jsonVector(face["axis_a"]), jsonVector(face["axis_b"])), normals[f]);
    const glm::dvec3 right = sidecarCubeDirection(sidecar, f * n + n - 1, n / 2);
    const glm::dvec3 left = sidecarCubeDirection(sidecar, f * n, n / 2);
    const glm::dvec3 top = sidecarCubeDirection(sidecar, f * n + n / 2, 0);
    const glm::dvec3 bottom = sidecarCubeDirection(sidecar, f * n + n / 2, n - 1);
    EXPECT_GT(glm::dot(right - left, jsonVector(face["axis_a"])), 0.5);
    EXPECT_GT(glm::dot(top - bottom, jsonVector(face["axis_b"])), 0.5);
  }
  // Every pixel: the sidecar's direction is the export's, lies on its own face, and holds the reference height there.
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < 6 * n; ++x) {
      const glm::dvec3 d = sidecarCubeDirection(sidecar, x, y);
      ASSERT_LT(angleBetween(d, heightmapPixelDirection(map.spec, x, y)), 1e-15) << x << "," << y;
      EXPECT_EQ(dominantCubeFace(d), int(x / n));
      float stored;
      std::memcpy(&stored, image.data() + 4 * (size_t(y) * 6 * n + x), 4);
      ASSERT_EQ(stored, float(terrainHeightM(earth(), d))) << x << "," << y;
    }
}

TEST(ExportHeightmap, AdjacentCubeFacesMeetAlongTheirSharedEdges) {
  const uint32_t n = 8;
  const HeightmapSpec spec = cubeMapSpec(n);
  struct Border {
    uint32_t x, y;
    glm::dvec3 direction;
  };
  std::vector<Border> border;
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < 6 * n; ++x)
      if (x % n == 0 || x % n == n - 1 || y == 0 || y == n - 1)
        border.push_back({x, y, heightmapPixelDirection(spec, x, y)});
  // Within a face, the border pixels' neighbours along the edge are this far apart at most.
  double inFace = 0.0;
  for (uint32_t k = 0; k + 1 < n; ++k)
    inFace = std::max(
        inFace, angleBetween(heightmapPixelDirection(spec, n - 1, k), heightmapPixelDirection(spec, n - 1, k + 1)));
  // Each face's four edges: the nearest pixel across the edge lies on the face whose normal is
  // the edge's outward axis (at a corner, three faces meet and two are equally near), as close as
  // a neighbour within the face, and at the same place along the edge: halfway between the two
  // centres is a point of the edge in both faces' coordinates.
  for (int f = 0; f < 6; ++f) {
    const CubeFace face = cubeFace(f);
    struct Edge {
      glm::dvec3 outward;
      uint32_t i0, j0, di, dj;  // first pixel and step along the edge
    } edges[4] = {{face.axisA, n - 1, 0, 0, 1},
                  {-face.axisA, 0, 0, 0, 1},
                  {face.axisB, 0, 0, 1, 0},
                  {-face.axisB, 0, n - 1, 1, 0}};
    for (const Edge& edge : edges) {
      const int neighbour = dominantCubeFace(edge.outward);
      for (uint32_t k = 0; k < n; ++k) {
        const uint32_t x = f * n + edge.i0 + k * edge.di, y = edge.j0 + k * edge.dj;
        const std::string where = fmt::format("face {} pixel {},{}", f, x, y);
        const glm::dvec3 d = heightmapPixelDirection(spec, x, y);
        auto nearestOn = [&](auto accept) {
          const Border* best = nullptr;
          for (const Border& b : border)
            if (accept(int(b.x / n)) && (!best || angleBetween(d, b.direction) < angleBetween(d, best->direction)))
              best = &b;
          return best;
        };
        const Border* anyFace = nearestOn([&](int g) { return g != f; });
        const Border* twin = nearestOn([&](int g) { return g == neighbour; });
        ASSERT_TRUE(anyFace && twin) << where;
        if (k != 0 && k != n - 1) {
          EXPECT_EQ(int(anyFace->x / n), neighbour) << where;
        }
        EXPECT_NEAR(angleBetween(d, twin->direction), angleBetween(d, anyFace->direction), 1e-12) << where;
        EXPECT_LE(angleBetween(d, twin->direction), 1.01 * inFace) << where;
        const glm::dvec3 middle = glm::normalize(d + twin->direction);
        const glm::dvec2 here = cubeFaceCoordinates(f, middle);
        const glm::dvec2 there = cubeFaceCoordinates(neighbour, middle);
        EXPECT_NEAR(std::max(std::abs(here.x), std::abs(here.y)), 1.0, 1e-9) << where;
        EXPECT_NEAR(std::max(std::abs(there.x), std::abs(there.y)), 1.0, 1e-9) << where;
      }
    }
  }
}

TEST(ExportHeightmap, Png16ValuesMapBackWithinHalfAStep) {
  const Heightmap map = computeHeightmap(earth(), equirectSpec(32, 16));
  const std::vector<uint16_t> values = quantizeHeights(map);
  const double step = (map.maxM - map.minM) / 65535.0;
  EXPECT_EQ(*std::min_element(values.begin(), values.end()), 0);
  EXPECT_EQ(*std::max_element(values.begin(), values.end()), 65535);
  for (size_t i = 0; i < values.size(); ++i)
    ASSERT_LE(std::abs(map.minM + values[i] / 65535.0 * (map.maxM - map.minM) - map.heightsM[i]),
              0.5 * step * (1 + 1e-9))
        << i;
  // A flat planet: every value 0, and the mapping gives min back.
  Heightmap flat = map;
  std::fill(flat.heightsM.begin(), flat.heightsM.end(), 12.5f);
  flat.minM = flat.maxM = 12.5;
  for (uint16_t v : quantizeHeights(flat)) ASSERT_EQ(v, 0);
}

TEST(ExportHeightmap, RawIsLittleEndianFloat32RowMajorTopRowFirst) {
  Heightmap map;
  map.spec = equirectSpec(2, 1);
  map.heightsM = {1.0f, -2.5f};
  const std::string raw = encodeHeightmap(map, HeightmapEncoding::RawFloat32);
  // 1.0f is 0x3f800000 and -2.5f 0xc0200000, least significant byte first.
  EXPECT_EQ(raw, std::string("\x00\x00\x80\x3f\x00\x00\x20\xc0", 8));
}

TEST(ExportHeightmap, SizesOutsideTheLimitsAreRefusedNamingTheSize) {
  EXPECT_EQ(errorOf([] { validateHeightmapSpec(equirectSpec(16385, 8)); }),
            "equirect size 16385x8 is outside 1x1 .. 16384x8192");
  EXPECT_EQ(errorOf([] { validateHeightmapSpec(equirectSpec(0, 8)); }),
            "equirect size 0x8 is outside 1x1 .. 16384x8192");
  EXPECT_EQ(errorOf([] { validateHeightmapSpec(cubeMapSpec(4097)); }), "cube-map face size 4097 is outside 1 .. 4096");
  EXPECT_EQ(errorOf([] {
              validateHeightmapSpec({HeightmapProjection::CubeMap, 10, 2, false});
            }),
            "a cube-map strip is 6N x N pixels, got 10x2");
  EXPECT_EQ(errorOf([] { computeHeightmap(earth(), equirectSpec(1, 0)); }),
            "equirect size 1x0 is outside 1x1 .. 16384x8192");
  EXPECT_NO_THROW(validateHeightmapSpec(equirectSpec(16384, 8192)));
  EXPECT_EQ(errorOf([] { parseHeightmapProjection("mercator"); }),
            "unknown projection 'mercator' (expected equirect or cubemap)");
  EXPECT_EQ(errorOf([] { parseHeightmapEncoding("tiff"); }), "unknown heightmap format 'tiff' (expected png16 or raw)");
}

TEST(ExportHeightmap, TheImageAndItsSidecarAreWrittenTogetherOrNotAtAll) {
  const fs::path dir = test::processTempDir("export_test") / "write";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Heightmap map = computeHeightmap(earth(), equirectSpec(8, 4));
  const std::string path = (dir / "map.png").string();
  writeHeightmap(path, earth(), {"earth", 0}, map, HeightmapEncoding::Png16);
  const nlohmann::json sidecar = nlohmann::json::parse(test::readFileBytes(path + ".json"));
  EXPECT_EQ(sidecar["image_file"], "map.png");
  EXPECT_EQ(sidecar["image_fnv1a64"], fmt::format("{:016x}", fnv1a64(test::readFileBytes(path))));
  EXPECT_EQ(sidecar["source"]["preset_hash"], fmt::format("{:016x}", descriptionHash(earth())));

  // A sidecar name taken by a directory: neither file is replaced, no temporary is left.
  const std::string second = (dir / "second.raw").string();
  fs::create_directory(second + ".json");
  EXPECT_NE(errorOf([&] {
              writeHeightmap(second, earth(), {"earth", 0}, map, HeightmapEncoding::RawFloat32);
            }).find("cannot write '" + second + ".json'"),
            std::string::npos);
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"map.png", "map.png.json", "second.raw.json"}));
  // A missing directory for a later file: the earlier file's temporary is removed too.
  const FileContents files[] = {{(dir / "a.txt").string(), "a"}, {(dir / "missing" / "b.txt").string(), "b"}};
  EXPECT_NE(errorOf([&] { writeFilesAtomic(files); }).find("missing/b.txt"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "a.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace planet

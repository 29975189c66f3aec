// planet export's engine (engine/export): heightmap pixels are the documented points at the
// reference heights, the sidecar describes them, cube faces meet along their edges; meshes are
// the documented grids with outward normals and front faces, and tiles agree on their borders;
// glTF, GLB and OBJ carry the same mesh; an image and its sidecar are written together or not.
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
#include "export/mesh_files.h"
#include "export/region_mesh.h"
#include "planet/terrain_height.h"
#include "planet/cube_face.h"
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
  const test::TempDir dir("export_test");
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
  for (const auto& entry : fs::directory_iterator(dir.path())) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"map.png", "map.png.json", "second.raw.json"}));
  // A missing directory for a later file: the earlier file's temporary is removed too.
  const FileContents files[] = {{(dir / "a.txt").string(), "a"}, {(dir / "missing" / "b.txt").string(), "b"}};
  EXPECT_NE(errorOf([&] { writeFilesAtomic(files); }).find("missing/b.txt"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "a.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 3);
}

// ---- Meshes ----------------------------------------------------------------------------------

// A 0.1 x 0.1 degree region in the Alps (about 11 x 8 km), 9 x 9 vertices.
MeshSpec alpsSpec(uint32_t n = 9) { return {{45.0, 7.0, 45.1, 7.1}, n, false}; }

glm::dvec3 planetPoint(const RegionMesh& mesh, const glm::vec3& p) {
  return mesh.frame.originM + double(p.x) * mesh.frame.east + double(p.y) * mesh.frame.up +
         double(p.z) * mesh.frame.south;
}

glm::dvec3 planetVector(const RegionMesh& mesh, const glm::vec3& v) {
  return double(v.x) * mesh.frame.east + double(v.y) * mesh.frame.up + double(v.z) * mesh.frame.south;
}

TEST(ExportMesh, VerticesAreTheDocumentedGridAtTheReferenceHeights) {
  const MeshSpec spec = alpsSpec();
  const RegionMesh mesh = computeRegionMesh(earth(), spec, 2);
  ASSERT_EQ(mesh.positions.size(), 81u);
  ASSERT_EQ(mesh.normals.size(), 81u);
  // The frame: right-handed, east/up/south at the centre, origin on the radius sphere under it.
  const glm::dvec3 up = directionFromLatLon(45.05, 7.05);
  EXPECT_LT(glm::length(mesh.frame.up - up), 1e-15);
  EXPECT_LT(glm::length(mesh.frame.originM - earth().radiusM * up), 1e-6);
  EXPECT_LT(glm::length(glm::cross(mesh.frame.east, mesh.frame.up) - mesh.frame.south), 1e-15);
  EXPECT_GT(glm::dot(mesh.frame.east,
                     glm::dvec3(-std::sin(7.05 * std::numbers::pi / 180), std::cos(7.05 * std::numbers::pi / 180), 0)),
            0.999999);
  EXPECT_LT(mesh.frame.south.z, 0.0);
  double lowest = 1e9, highest = -1e9;
  for (uint32_t j = 0; j < 9; ++j)
    for (uint32_t i = 0; i < 9; ++i) {
      const glm::dvec3 point = planetPoint(mesh, mesh.positions[j * 9 + i]);
      // Row j from north to south, column i from west to east, corners on the region's corners.
      const double latitude = 45.1 + (45.0 - 45.1) * j / 8.0, longitude = 7.0 + (7.1 - 7.0) * i / 8.0;
      EXPECT_LT(angleBetween(glm::normalize(point), directionFromLatLon(latitude, longitude)) * earth().radiusM, 0.002)
          << i << "," << j;
      const double height = glm::length(point) - earth().radiusM;
      ASSERT_NEAR(height, terrainHeightM(earth(), glm::normalize(point)), 0.01) << i << "," << j;
      lowest = std::min(lowest, height);
      highest = std::max(highest, height);
    }
  EXPECT_NEAR(mesh.minHeightM, lowest, 0.01);
  EXPECT_NEAR(mesh.maxHeightM, highest, 0.01);
  // North-west first, south-east last.
  EXPECT_LT(mesh.positions.front().x, 0.0f);
  EXPECT_LT(mesh.positions.front().z, 0.0f);
  EXPECT_GT(mesh.positions.back().x, 0.0f);
  EXPECT_GT(mesh.positions.back().z, 0.0f);
}

TEST(ExportMesh, TrianglesAreTwoPerCellFacingUpAndNormalsAreUnitAndOutward) {
  const uint32_t n = 17;
  const RegionMesh mesh = computeRegionMesh(earth(), alpsSpec(n));
  ASSERT_EQ(mesh.indices.size(), 6u * (n - 1) * (n - 1));
  std::vector<glm::dvec3> faceNormalSum(mesh.positions.size(), glm::dvec3(0.0));
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    for (int k = 0; k < 3; ++k) ASSERT_LT(mesh.indices[t + k], n * n);
    const glm::dvec3 a = planetPoint(mesh, mesh.positions[mesh.indices[t]]);
    const glm::dvec3 b = planetPoint(mesh, mesh.positions[mesh.indices[t + 1]]);
    const glm::dvec3 c = planetPoint(mesh, mesh.positions[mesh.indices[t + 2]]);
    const glm::dvec3 geometric = glm::cross(b - a, c - a);
    // Counter-clockwise seen from above: the right-hand normal points away from the centre.
    ASSERT_GT(glm::dot(glm::normalize(geometric), glm::normalize(a)), 0.5) << "triangle " << t / 3;
    for (int k = 0; k < 3; ++k) faceNormalSum[mesh.indices[t + k]] += glm::normalize(geometric);
  }
  double angleSum = 0.0;
  for (size_t v = 0; v < mesh.normals.size(); ++v) {
    const glm::dvec3 normal = planetVector(mesh, mesh.normals[v]);
    ASSERT_NEAR(glm::length(normal), 1.0, 1e-6) << v;
    ASSERT_GT(glm::dot(normal, glm::normalize(planetPoint(mesh, mesh.positions[v]))), 0.5) << v;
    // It follows the surface: close to the mean of the triangles around the vertex. On rough
    // ground the central difference and the faces' mean part by up to ~13° (measured); a normal
    // in the wrong frame or from the wrong neighbours is off by tens of degrees everywhere.
    const double angle = angleBetween(normal, glm::normalize(faceNormalSum[v]));
    EXPECT_LT(angle, 25.0 * std::numbers::pi / 180.0) << v;
    angleSum += angle;
  }
  EXPECT_LT(angleSum / double(mesh.normals.size()), 5.0 * std::numbers::pi / 180.0);
}

TEST(ExportMesh, TilesSharingABorderHaveTheSameBorderVerticesAndNormals) {
  const RegionMesh west = computeRegionMesh(earth(), {{45.0, 7.0, 45.1, 7.05}, 9, false});
  const RegionMesh east = computeRegionMesh(earth(), {{45.0, 7.05, 45.1, 7.1}, 9, false});
  for (uint32_t j = 0; j < 9; ++j) {
    const size_t w = j * 9 + 8, e = j * 9;
    EXPECT_LT(glm::length(planetPoint(west, west.positions[w]) - planetPoint(east, east.positions[e])), 0.002) << j;
    EXPECT_LT(glm::length(planetVector(west, west.normals[w]) - planetVector(east, east.normals[e])), 1e-5) << j;
  }
}

TEST(ExportMesh, APoleRowHasRadialNormalsAndARegionMayCrossTheAntimeridian) {
  const RegionMesh polar = computeRegionMesh(earth(), {{80.0, 0.0, 90.0, 360.0}, 5, false});
  // (Their heights need not agree: the reference itself differs by metres between longitudes
  // 1 mm from the pole, where the planes x = y and x = z through the noise origin meet.)
  for (uint32_t i = 0; i < 5; ++i) {
    EXPECT_LT(angleBetween(planetVector(polar, polar.normals[i]), glm::dvec3(0, 0, 1)), 1e-6) << i;
    EXPECT_LT(angleBetween(planetPoint(polar, polar.positions[i]), glm::dvec3(0, 0, 1)), 1e-8)
        << i;  // float offsets of a 1,100 km region
  }
  const RegionMesh across = computeRegionMesh(earth(), {{-1.0, 179.5, 1.0, 180.5}, 3, false});
  EXPECT_LT(angleBetween(glm::normalize(planetPoint(across, across.positions[4])), directionFromLatLon(0, -180)), 1e-9);
}

TEST(ExportMesh, FilteredHeightsUseTheCellSize) {
  MeshSpec spec = alpsSpec(5);
  spec.filtered = true;
  const RegionExtentM extent = regionExtentM(earth().radiusM, spec.region);
  EXPECT_NEAR(extent.northSouth, earth().radiusM * 0.1 * std::numbers::pi / 180.0, 1e-6);
  EXPECT_NEAR(extent.eastWest, extent.northSouth * std::cos(45.0 * std::numbers::pi / 180.0), 1e-6);
  EXPECT_DOUBLE_EQ(meshSpacingM(earth(), spec), extent.northSouth / 4.0);
  const RegionMesh mesh = computeRegionMesh(earth(), spec);
  EXPECT_EQ(mesh.spacingM, meshSpacingM(earth(), spec));
  const glm::dvec3 point = planetPoint(mesh, mesh.positions[12]);
  EXPECT_NEAR(glm::length(point) - earth().radiusM, terrainHeightM(earth(), glm::normalize(point), mesh.spacingM),
              0.01);
}

TEST(ExportMesh, BadRegionsAndResolutionsAreRefusedNamingTheValue) {
  auto regionError = [](MeshRegion r) { return errorOf([&] { validateMeshRegion(r); }); };
  EXPECT_EQ(regionError({0, 0, 95, 1}), "region latitude 95 is outside [-90, 90] degrees");
  EXPECT_EQ(regionError({5, 0, 1, 1}), "region south latitude 5 must be less than north latitude 1");
  EXPECT_EQ(regionError({0, 170, 1, -170}),
            "region west longitude 170 must be less than east longitude -170 (to cross 180 degrees give an east "
            "longitude above 180)");
  EXPECT_EQ(regionError({0, -200, 1, 200}), "region spans 400 degrees of longitude, at most 360");
  EXPECT_EQ(regionError({0, 0, 1, 400}), "region longitude 400 is outside [-360, 360] degrees");
  EXPECT_EQ(regionError({0, std::nan(""), 1, 1}), "region coordinates must be finite, got nan");
  EXPECT_EQ(errorOf([] { computeRegionMesh(earth(), alpsSpec(1)); }),
            "mesh resolution must be in 2..2048 vertices per side, got 1");
  EXPECT_EQ(errorOf([] { computeRegionMesh(earth(), alpsSpec(2049)); }),
            "mesh resolution must be in 2..2048 vertices per side, got 2049");
}

// ---- Mesh files ------------------------------------------------------------------------------

uint32_t littleEndian32(const std::string& bytes, size_t at) {
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | uint8_t(bytes[at + size_t(k)]);
  return v;
}

std::string decodeBase64(std::string_view text) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
  };
  std::string out;
  uint32_t group = 0;
  int bits = 0;
  for (char c : text) {
    if (c == '=') break;
    group = (group << 6) | uint32_t(value(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(char((group >> bits) & 0xFFu));
    }
  }
  return out;
}

TEST(ExportMeshFiles, GlbHoldsTheGltfsJsonAndBufferInAlignedChunks) {
  const RegionMesh mesh = computeRegionMesh(earth(), alpsSpec(5));
  const nlohmann::ordered_json metadata = meshMetadata(earth(), {"earth", 0}, mesh);
  const std::string glb = encodeGltf(mesh, metadata, true);
  nlohmann::json gltf = nlohmann::json::parse(encodeGltf(mesh, metadata, false));
  // Header: magic "glTF", version 2, the total length.
  ASSERT_GE(glb.size(), 28u);
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  EXPECT_EQ(littleEndian32(glb, 4), 2u);
  EXPECT_EQ(littleEndian32(glb, 8), glb.size());
  const uint32_t jsonLength = littleEndian32(glb, 12);
  EXPECT_EQ(glb.substr(16, 4), "JSON");
  EXPECT_EQ(jsonLength % 4, 0u);
  const size_t binAt = 20 + jsonLength;
  const uint32_t binLength = littleEndian32(glb, binAt);
  EXPECT_EQ(glb.substr(binAt + 4, 4), std::string("BIN\0", 4));
  EXPECT_EQ(binLength % 4, 0u);
  EXPECT_EQ(binAt + 8 + binLength, glb.size());
  nlohmann::json fromGlb = nlohmann::json::parse(glb.substr(20, jsonLength));
  // The same document but for the buffer's URI, and the same bytes in the buffer.
  const std::string uri = gltf["buffers"][0]["uri"].get<std::string>();
  const std::string prefix = "data:application/octet-stream;base64,";
  ASSERT_EQ(uri.substr(0, prefix.size()), prefix);
  const std::string buffer = decodeBase64(std::string_view(uri).substr(prefix.size()));
  EXPECT_EQ(buffer.size(), gltf["buffers"][0]["byteLength"].get<size_t>());
  EXPECT_EQ(glb.substr(binAt + 8, buffer.size()), buffer);
  gltf["buffers"][0].erase("uri");
  EXPECT_EQ(fromGlb, gltf);
  // The metadata is the node's extras.
  EXPECT_EQ(gltf["nodes"][0]["extras"], nlohmann::json::parse(metadata.dump()));
  EXPECT_EQ(gltf["nodes"][0].count("translation"), 0u);
}

TEST(ExportMeshFiles, ObjHeaderCarriesTheFrameInDoubleAndTheMetadata) {
  const RegionMesh mesh = computeRegionMesh(earth(), alpsSpec(3));
  const nlohmann::ordered_json metadata = meshMetadata(earth(), {"earth", 7}, mesh);
  const std::string obj = encodeObj(mesh, metadata);
  auto lineAfter = [&](const std::string& key) {
    const size_t at = obj.find("\n# " + key + " ");
    EXPECT_NE(at, std::string::npos) << key;
    return obj.substr(at + 4 + key.size(), obj.find('\n', at + 1) - at - 4 - key.size());
  };
  glm::dvec3 origin;
  std::sscanf(lineAfter("origin_m").c_str(), "%lf %lf %lf", &origin.x, &origin.y, &origin.z);
  EXPECT_EQ(origin, mesh.frame.originM);  // 17 significant digits: the double itself
  EXPECT_EQ(nlohmann::json::parse(lineAfter("metadata")), nlohmann::json::parse(metadata.dump()));
  EXPECT_EQ(metadata["source"]["seed_offset"], 7);
  EXPECT_EQ(std::count(obj.begin(), obj.end(), '\n'), 9 + 9 + 9 + 8);  // header + o, v, vn, f
  EXPECT_NE(obj.find("\nf 1//1 4//4 5//5\n"), std::string::npos) << "north-west, south-west, south-east, 1-based";
}

}  // namespace
}  // namespace planet

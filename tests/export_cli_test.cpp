// `planet export` as a user runs it: the files it writes read back, with nothing but their
// sidecar or metadata, to the heights `planet height` prints at the same points.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image_file.h"
#include "planet/terrain_height.h"
#include "test_support.h"

namespace planet {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() { return test::processTempDir("export_cli_test"); }

test::ShellRun planetRun(const std::string& args) { return test::runShell(PLANET_EXE, args, "", tempDir()); }

const PlanetDescription& earth() {
  static const PlanetDescription planet = resolvePreset("earth");
  return planet;
}

// The shortest text that reads back as the same double, so `planet height --at` gets the very point.
std::string exact(double value) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

// What `planet height --at LAT,LON [--seed S]` prints.
std::string planetHeight(double latitude, double longitude, const std::string& extra = "") {
  test::ShellRun run = planetRun("height --at " + exact(latitude) + "," + exact(longitude) + extra);
  EXPECT_EQ(run.exitCode, 0) << run.err;
  return run.out;
}

float littleEndianFloat(const std::string& bytes, size_t index) {
  uint32_t bits = 0;
  for (int k = 3; k >= 0; --k) bits = (bits << 8) | uint8_t(bytes[4 * index + size_t(k)]);
  return std::bit_cast<float>(bits);
}

// Pixel centres by the sidecar's equirect formulas.
double sidecarLatitude(const nlohmann::json& s, uint32_t y) {
  const double h = s["height"].get<double>();
  return 90.0 * (h - 2.0 * y - 1.0) / h;
}
double sidecarLongitude(const nlohmann::json& s, uint32_t x) {
  const double w = s["width"].get<double>();
  return 180.0 * (2.0 * x + 1.0 - w) / w;
}

TEST(ExportCli, HeightmapPng16AndRawReadBackThroughTheSidecarToPlanetHeight) {
  const std::string png = (tempDir() / "earth.png").string(), raw = (tempDir() / "earth.raw").string();
  for (const std::string& out : {png, raw}) {
    test::ShellRun run = planetRun("export heightmap --size 64x32 --out " + out);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "") << "a quick export prints no progress lines when stderr is not a terminal";
    EXPECT_NE(run.out.find("wrote " + out + " (64x32 equirect "), std::string::npos) << run.out;
  }
  const nlohmann::json pngSidecar = nlohmann::json::parse(test::readFileBytes(png + ".json"));
  const nlohmann::json rawSidecar = nlohmann::json::parse(test::readFileBytes(raw + ".json"));
  for (const nlohmann::json* s : {&pngSidecar, &rawSidecar}) {
    EXPECT_EQ((*s)["format"], "planet-heightmap");
    EXPECT_EQ((*s)["projection"], "equirect");
    EXPECT_EQ((*s)["width"], 64);
    EXPECT_EQ((*s)["height"], 32);
    EXPECT_EQ((*s)["source"]["preset"], "earth");
    EXPECT_EQ((*s)["source"]["preset_hash"], fmt::format("{:016x}", descriptionHash(earth())));
    EXPECT_EQ((*s)["source"]["radius_m"], earth().radiusM);
    EXPECT_EQ((*s)["source"]["spacing_m"], 0.0);
  }
  EXPECT_EQ(pngSidecar["encoding"], "png16");
  EXPECT_EQ(rawSidecar["encoding"], "raw");
  EXPECT_EQ(rawSidecar["raw"]["dtype"], "float32");
  EXPECT_EQ(rawSidecar["raw"]["byte_order"], "little-endian");
  EXPECT_EQ(pngSidecar["image_file"], "earth.png");
  EXPECT_EQ(pngSidecar["image_fnv1a64"], fmt::format("{:016x}", fnv1a64(test::readFileBytes(png))));
  EXPECT_EQ(rawSidecar["image_fnv1a64"], fmt::format("{:016x}", fnv1a64(test::readFileBytes(raw))));

  const std::string rawBytes = test::readFileBytes(raw);
  ASSERT_EQ(rawBytes.size(), 64u * 32u * 4u);
  const Grey16Image image = readPng16(png);
  ASSERT_EQ(image.width, 64u);
  ASSERT_EQ(image.height, 32u);
  const double min = pngSidecar["min_height_m"].get<double>(), max = pngSidecar["max_height_m"].get<double>();
  EXPECT_EQ(rawSidecar["min_height_m"].get<double>(), min);
  EXPECT_EQ(rawSidecar["max_height_m"].get<double>(), max);
  const double step = (max - min) / 65535.0;
  float lowest = 1e30f, highest = -1e30f;
  for (uint32_t y = 0; y < 32; ++y)
    for (uint32_t x = 0; x < 64; ++x) {
      const size_t i = size_t(y) * 64 + x;
      const double reference =
          terrainHeightM(earth(), directionFromLatLon(sidecarLatitude(rawSidecar, y), sidecarLongitude(rawSidecar, x)));
      const float stored = littleEndianFloat(rawBytes, i);
      ASSERT_FLOAT_EQ(stored, float(reference)) << x << "," << y;
      // png16: the sidecar's linear mapping, within half a step (plus the float rounding before it).
      const double decoded = min + image.pixels[i] / 65535.0 * (max - min);
      ASSERT_LE(std::abs(decoded - reference), 0.5 * step + 1e-3) << x << "," << y;
      lowest = std::min(lowest, stored);
      highest = std::max(highest, stored);
    }
  EXPECT_EQ(double(lowest), min);
  EXPECT_EQ(double(highest), max);

  // planet height at three pixel centres prints the reference to the last digit, and the raw
  // float is that value to float precision.
  for (auto [x, y] : {std::pair{0u, 0u}, {37u, 11u}, {63u, 31u}}) {
    const double latitude = sidecarLatitude(rawSidecar, y), longitude = sidecarLongitude(rawSidecar, x);
    const std::string printed = planetHeight(latitude, longitude);
    EXPECT_EQ(printed, fmt::format("{:.4f}\n", terrainHeightM(earth(), directionFromLatLon(latitude, longitude))));
    const float stored = littleEndianFloat(rawBytes, size_t(y) * 64 + x);
    EXPECT_NEAR(double(stored), std::stod(printed), 0.5 * std::abs(stored) * 0x1p-23 + 5e-5) << x << "," << y;
  }
}

TEST(ExportCli, CubeMapIsOneStripOfSixFacesTheSidecarDescribes) {
  const std::string out = (tempDir() / "cube.raw").string();
  test::ShellRun run = planetRun("export heightmap --projection cubemap --size 6 --preset moon --out " + out);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json s = nlohmann::json::parse(test::readFileBytes(out + ".json"));
  EXPECT_EQ(s["projection"], "cubemap");
  EXPECT_EQ(s["width"], 36);
  EXPECT_EQ(s["height"], 6);
  EXPECT_EQ(s["face_size"], 6);
  const std::string bytes = test::readFileBytes(out);
  ASSERT_EQ(bytes.size(), 36u * 6u * 4u);
  const PlanetDescription moon = resolvePreset("moon");
  for (uint32_t y = 0; y < 6; ++y)
    for (uint32_t x = 0; x < 36; ++x) {
      const nlohmann::json& face = s["faces"][x / 6];
      auto v = [&](const char* key) {
        return glm::dvec3(face[key][0].get<double>(), face[key][1].get<double>(), face[key][2].get<double>());
      };
      const double a = (2.0 * (x - face["x_offset"].get<double>()) + 1.0 - 6.0) / 6.0, b = (6.0 - 2.0 * y - 1.0) / 6.0;
      const glm::dvec3 direction = glm::normalize(v("normal") + a * v("axis_a") + b * v("axis_b"));
      ASSERT_FLOAT_EQ(littleEndianFloat(bytes, size_t(y) * 36 + x), float(terrainHeightM(moon, direction)))
          << x << "," << y;
    }
}

TEST(ExportCli, SeedAndFilteredChangeTheHeightsAsPlanetHeightAndTheSpacingSay) {
  const std::string seeded = (tempDir() / "seeded.raw").string();
  ASSERT_EQ(planetRun("export heightmap --size 8 --seed 5 --out " + seeded).exitCode, 0);
  const nlohmann::json s = nlohmann::json::parse(test::readFileBytes(seeded + ".json"));
  EXPECT_EQ(s["height"], 4);  // --size W alone: W x W/2
  EXPECT_EQ(s["source"]["seed_offset"], 5);
  EXPECT_NE(s["source"]["preset_hash"], fmt::format("{:016x}", descriptionHash(earth())));
  const double latitude = sidecarLatitude(s, 1), longitude = sidecarLongitude(s, 2);
  const std::string printed = planetHeight(latitude, longitude, " --seed 5");
  EXPECT_NE(printed, planetHeight(latitude, longitude)) << "another seed, another planet";
  EXPECT_NEAR(double(littleEndianFloat(test::readFileBytes(seeded), 1 * 8 + 2)), std::stod(printed), 1e-3);

  const std::string filtered = (tempDir() / "filtered.raw").string();
  ASSERT_EQ(planetRun("export heightmap --size 8x4 --filtered --out " + filtered).exitCode, 0);
  const nlohmann::json f = nlohmann::json::parse(test::readFileBytes(filtered + ".json"));
  const double spacing = f["source"]["spacing_m"].get<double>();
  EXPECT_EQ(f["source"]["detail"], "filtered");
  EXPECT_DOUBLE_EQ(spacing, 2.0 * std::numbers::pi * earth().radiusM / 8.0);
  const glm::dvec3 d = directionFromLatLon(sidecarLatitude(f, 3), sidecarLongitude(f, 7));
  EXPECT_FLOAT_EQ(littleEndianFloat(test::readFileBytes(filtered), 3 * 8 + 7),
                  float(terrainHeightM(earth(), d, spacing)));
}

// ---- Meshes ----------------------------------------------------------------------------------

struct ParsedMesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<uint32_t> indices;
  glm::dvec3 origin{0.0}, axisX{0.0}, axisY{0.0}, axisZ{0.0};
};

glm::dvec3 jsonVector(const nlohmann::json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

// A small OBJ reader: the header's frame lines, v, vn, and f a//a b//b c//c.
ParsedMesh parseObj(const std::string& text) {
  ParsedMesh mesh;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream in(line);
    std::string key;
    in >> key;
    if (key == "#") {
      std::string name;
      in >> name;
      glm::dvec3* target = name == "origin_m" ? &mesh.origin
                           : name == "axis_x" ? &mesh.axisX
                           : name == "axis_y" ? &mesh.axisY
                           : name == "axis_z" ? &mesh.axisZ
                                              : nullptr;
      if (target) in >> target->x >> target->y >> target->z;
    } else if (key == "v" || key == "vn") {
      glm::vec3 v;
      in >> v.x >> v.y >> v.z;
      (key == "v" ? mesh.positions : mesh.normals).push_back(v);
    } else if (key == "f") {
      for (int k = 0; k < 3; ++k) {
        std::string corner;
        in >> corner;
        const uint32_t v = uint32_t(std::stoul(corner.substr(0, corner.find('/'))));
        EXPECT_EQ(corner.substr(corner.find("//") + 2), corner.substr(0, corner.find('/'))) << "normal index = vertex";
        mesh.indices.push_back(v - 1);
      }
      std::string extra;
      EXPECT_FALSE(in >> extra) << "triangles only: " << line;
    }
  }
  return mesh;
}

std::string decodeBase64(std::string_view text) {
  std::string out;
  uint32_t group = 0;
  int bits = 0;
  for (char c : text) {
    if (c == '=') break;
    const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* at = std::strchr(alphabet, c);
    EXPECT_TRUE(at && c != '\0') << "not base64: " << c;
    group = (group << 6) | uint32_t(at - alphabet);
    if ((bits += 6) >= 8) out.push_back(char((group >> (bits -= 8)) & 0xFFu));
  }
  return out;
}

// The glTF document's checks a loader makes (glTF 2.0: accessors, buffer views, bounds), then its data.
ParsedMesh readGltf(const nlohmann::json& gltf, const std::string& buffer) {
  ParsedMesh mesh;
  EXPECT_EQ(gltf["asset"]["version"], "2.0");
  EXPECT_EQ(gltf["scenes"][gltf["scene"].get<size_t>()]["nodes"], nlohmann::json::array({0}));
  const nlohmann::json& node = gltf["nodes"][0];
  EXPECT_FALSE(node.contains("translation") || node.contains("matrix")) << "the mesh sits at the origin";
  const nlohmann::json& primitive = gltf["meshes"][node["mesh"].get<size_t>()]["primitives"][0];
  EXPECT_EQ(primitive["mode"], 4);  // triangles
  EXPECT_EQ(gltf["buffers"].size(), 1u);
  EXPECT_EQ(gltf["buffers"][0]["byteLength"].get<size_t>(), buffer.size());
  size_t viewBytes = 0;
  for (const auto& view : gltf["bufferViews"]) {
    EXPECT_EQ(view["byteOffset"].get<size_t>() % 4, 0u);
    EXPECT_LE(view["byteOffset"].get<size_t>() + view["byteLength"].get<size_t>(), buffer.size());
    viewBytes += view["byteLength"].get<size_t>();
  }
  EXPECT_EQ(viewBytes, buffer.size());
  auto read = [&](size_t accessorIndex, int componentType, const char* type, int targetWanted) {
    const nlohmann::json& accessor = gltf["accessors"][accessorIndex];
    EXPECT_EQ(accessor["componentType"], componentType);
    EXPECT_EQ(accessor["type"], type);
    const nlohmann::json& view = gltf["bufferViews"][accessor["bufferView"].get<size_t>()];
    EXPECT_EQ(view["target"], targetWanted);
    const size_t components = std::string(type) == "VEC3" ? 3 : 1;
    const size_t count = accessor["count"].get<size_t>();
    if (view.contains("byteStride")) {
      EXPECT_EQ(view["byteStride"], 4 * components);
    }
    EXPECT_EQ(view["byteLength"].get<size_t>(), count * components * 4);
    std::vector<uint32_t> words(count * components);
    std::memcpy(words.data(), buffer.data() + view["byteOffset"].get<size_t>() + accessor.value("byteOffset", 0),
                words.size() * 4);
    return words;
  };
  const auto& attributes = primitive["attributes"];
  for (const auto& [name, list] : {std::pair{"POSITION", &mesh.positions}, {"NORMAL", &mesh.normals}}) {
    const std::vector<uint32_t> words = read(attributes[name].get<size_t>(), 5126, "VEC3", 34962);
    for (size_t i = 0; i < words.size(); i += 3)
      list->push_back(
          {std::bit_cast<float>(words[i]), std::bit_cast<float>(words[i + 1]), std::bit_cast<float>(words[i + 2])});
  }
  mesh.indices = read(primitive["indices"].get<size_t>(), 5125, "SCALAR", 34963);
  // POSITION's min and max are the exact bounds of the data, as the specification requires.
  const nlohmann::json& position = gltf["accessors"][attributes["POSITION"].get<size_t>()];
  for (int c = 0; c < 3; ++c) {
    float lo = 1e30f, hi = -1e30f;
    for (const glm::vec3& p : mesh.positions) lo = std::min(lo, p[c]), hi = std::max(hi, p[c]);
    EXPECT_EQ(position["min"][c].get<double>(), double(lo));
    EXPECT_EQ(position["max"][c].get<double>(), double(hi));
  }
  const nlohmann::json& extras = node["extras"];
  mesh.origin = jsonVector(extras["origin_m"]);
  mesh.axisX = jsonVector(extras["axes"]["x"]);
  mesh.axisY = jsonVector(extras["axes"]["y"]);
  mesh.axisZ = jsonVector(extras["axes"]["z"]);
  return mesh;
}

ParsedMesh parseGltf(const std::string& text) {
  const nlohmann::json gltf = nlohmann::json::parse(text);
  const std::string uri = gltf["buffers"][0]["uri"].get<std::string>();
  const std::string prefix = "data:application/octet-stream;base64,";
  EXPECT_EQ(uri.substr(0, prefix.size()), prefix);
  return readGltf(gltf, decodeBase64(std::string_view(uri).substr(prefix.size())));
}

ParsedMesh parseGlb(const std::string& bytes) {
  auto word = [&](size_t at) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
  };
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(word(4), 2u);
  EXPECT_EQ(word(8), bytes.size());
  const uint32_t jsonLength = word(12);
  EXPECT_EQ(bytes.substr(16, 4), "JSON");
  const size_t bin = 20 + jsonLength;
  EXPECT_EQ(bytes.substr(bin + 4, 4), std::string("BIN\0", 4));
  const nlohmann::json gltf = nlohmann::json::parse(bytes.substr(20, jsonLength));
  return readGltf(gltf, bytes.substr(bin + 8, gltf["buffers"][0]["byteLength"].get<size_t>()));
}

TEST(ExportCli, MeshObjGltfAndGlbParseBackToTheReferenceHeights) {
  const uint32_t n = 24;
  const std::string region = "45.8,6.8,45.9,6.9";  // about 11 x 8 km around Mont Blanc's latitude
  std::vector<ParsedMesh> meshes;
  for (const char* format : {"obj", "gltf", "glb"}) {
    const std::string out = (tempDir() / (std::string("region.") + format)).string();
    test::ShellRun run = planetRun(fmt::format("export mesh --region {} --resolution {} --out {}", region, n, out));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find(fmt::format("wrote {} (", out)), std::string::npos) << run.out;
    const std::string bytes = test::readFileBytes(out);
    meshes.push_back(std::string(format) == "obj"    ? parseObj(bytes)
                     : std::string(format) == "gltf" ? parseGltf(bytes)
                                                     : parseGlb(bytes));
  }
  for (const ParsedMesh& mesh : meshes) {
    ASSERT_EQ(mesh.positions.size(), n * n);
    ASSERT_EQ(mesh.normals.size(), n * n);
    ASSERT_EQ(mesh.indices.size(), 3u * 2u * (n - 1) * (n - 1));
    for (uint32_t index : mesh.indices) ASSERT_LT(index, n * n);
    // The same floats in every format (OBJ's nine digits round-trip a float).
    EXPECT_EQ(mesh.positions, meshes[0].positions);
    EXPECT_EQ(mesh.normals, meshes[0].normals);
    EXPECT_EQ(mesh.indices, meshes[0].indices);
    EXPECT_EQ(mesh.origin, meshes[0].origin);
    auto toPlanet = [&](const glm::vec3& v) {
      return double(v.x) * mesh.axisX + double(v.y) * mesh.axisY + double(v.z) * mesh.axisZ;
    };
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      // Reconstructed in double from the recorded origin and the float offset.
      const glm::dvec3 point = mesh.origin + toPlanet(mesh.positions[v]);
      const glm::dvec3 up = glm::normalize(point);
      ASSERT_NEAR(glm::length(point) - earth().radiusM, terrainHeightM(earth(), up), 0.01) << "vertex " << v;
      const glm::dvec3 normal = toPlanet(mesh.normals[v]);
      ASSERT_NEAR(glm::length(normal), 1.0, 1e-5) << "vertex " << v;
      ASSERT_GT(glm::dot(normal, up), 0.0) << "vertex " << v << " normal points inward";
    }
    // Vertex 0 is the north-west corner, the last the south-east one.
    const glm::dvec3 first = glm::normalize(mesh.origin + toPlanet(mesh.positions.front()));
    const glm::dvec3 last = glm::normalize(mesh.origin + toPlanet(mesh.positions.back()));
    EXPECT_LT(glm::length(first - directionFromLatLon(45.9, 6.8)) * earth().radiusM, 0.01);
    EXPECT_LT(glm::length(last - directionFromLatLon(45.8, 6.9)) * earth().radiusM, 0.01);
  }
}

TEST(ExportCli, MeshResolutionInMetresPicksTheFewestVerticesWithCellsThatShort) {
  const std::string out = (tempDir() / "metres.obj").string();
  // 0.01 degrees of latitude is 1,112 m: 100 m cells need 12 cells, 13 vertices per side.
  test::ShellRun run = planetRun("export mesh --region 10,20,10.01,20.01 --resolution 100m --out " + out);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("13x13 vertices, 288 triangles"), std::string::npos) << run.out;
  EXPECT_EQ(parseObj(test::readFileBytes(out)).positions.size(), 13u * 13u);
}

}  // namespace
}  // namespace planet

#include "export/mesh_files.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include <fmt/format.h>

#include "core/error.h"
#include "core/file.h"

namespace planet {
namespace {

// glTF 2.0 constants (the specification's accessor component types and buffer view targets).
constexpr int kComponentFloat = 5126;
constexpr int kComponentUnsignedInt = 5125;
constexpr int kTargetArrayBuffer = 34962;
constexpr int kTargetElementArrayBuffer = 34963;
constexpr int kModeTriangles = 4;
// GLB container (glTF 2.0, "Binary glTF Layout"): magic "glTF", version 2, chunk types.
constexpr uint32_t kGlbMagic = 0x46546C67u;
constexpr uint32_t kGlbVersion = 2;
constexpr uint32_t kChunkJson = 0x4E4F534Au;
constexpr uint32_t kChunkBin = 0x004E4942u;

nlohmann::ordered_json vectorJson(const glm::dvec3& v) { return nlohmann::ordered_json::array({v.x, v.y, v.z}); }
nlohmann::ordered_json vectorJson(const glm::vec3& v) {
  return nlohmann::ordered_json::array({double(v.x), double(v.y), double(v.z)});
}

void appendLittleEndian32(std::string& out, uint32_t value) {
  for (int k = 0; k < 4; ++k) out.push_back(char(uint8_t(value >> (8 * k))));
}

void appendFloats(std::string& out, const std::vector<glm::vec3>& values) {
  for (const glm::vec3& v : values)
    for (int c = 0; c < 3; ++c) appendLittleEndian32(out, std::bit_cast<uint32_t>(v[c]));
}

// RFC 4648 base64 with padding.
std::string base64(std::string_view bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t count = std::min<size_t>(3, bytes.size() - i);
    uint32_t group = 0;
    for (size_t k = 0; k < 3; ++k) group = (group << 8) | (k < count ? uint8_t(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out.push_back(k <= count ? kAlphabet[(group >> (18 - 6 * k)) & 63u] : '=');
  }
  return out;
}

std::string regionText(const MeshRegion& r) {
  return fmt::format("{},{},{},{}", r.southDeg, r.westDeg, r.northDeg, r.eastDeg);
}

}  // namespace

const char* meshFormatName(MeshFormat format) {
  switch (format) {
    case MeshFormat::Gltf: return "gltf";
    case MeshFormat::Glb: return "glb";
    case MeshFormat::Obj: return "obj";
  }
  return "?";
}

MeshFormat parseMeshFormat(std::string_view name) {
  if (name == "gltf") return MeshFormat::Gltf;
  if (name == "glb") return MeshFormat::Glb;
  if (name == "obj") return MeshFormat::Obj;
  throw Error(fmt::format("unknown mesh format '{}' (expected gltf, glb or obj)", name));
}

nlohmann::ordered_json meshMetadata(const PlanetDescription& planet, const ExportSource& source,
                                    const RegionMesh& mesh) {
  const MeshRegion& r = mesh.spec.region;
  const uint64_t n = mesh.spec.resolution;
  nlohmann::ordered_json j;
  j["format"] = "planet-mesh";
  j["version"] = 1;
  j["generator"] = "planet export mesh";
  j["source"] = exportProvenance(planet, source, mesh.spacingM);
  j["region_deg"] = {{"south", r.southDeg}, {"west", r.westDeg}, {"north", r.northDeg}, {"east", r.eastDeg}};
  j["resolution"] = n;
  j["vertices"] = n * n;
  j["triangles"] = 2 * (n - 1) * (n - 1);
  j["vertex_order"] = "index j * resolution + i: row j from north to south, column i from west to east";
  j["vertex_latitude_deg"] = "(1 - t) * north + t * south, t = j / (resolution - 1)";
  j["vertex_longitude_deg"] = "(1 - s) * west + s * east, s = i / (resolution - 1)";
  j["centre_deg"] = {0.5 * (r.southDeg + r.northDeg), 0.5 * (r.westDeg + r.eastDeg)};
  j["origin_m"] = vectorJson(mesh.frame.originM);
  j["axes"] = {
      {"x", vectorJson(mesh.frame.east)}, {"y", vectorJson(mesh.frame.up)}, {"z", vectorJson(mesh.frame.south)}};
  j["position"] =
      "planet-frame point = origin_m + x * axes.x + y * axes.y + z * axes.z (x east, y up, z south at "
      "the centre; origin_m is the radius-sphere point under it); height = |point| - radius_m";
  j["triangle_winding"] = "counter-clockwise seen from above";
  j["min_height_m"] = mesh.minHeightM;
  j["max_height_m"] = mesh.maxHeightM;
  return j;
}

std::string encodeGltf(const RegionMesh& mesh, const nlohmann::ordered_json& metadata, bool binary) {
  const size_t vertexBytes = mesh.positions.size() * 12;
  const size_t indexBytes = mesh.indices.size() * 4;
  std::string buffer;
  buffer.reserve(2 * vertexBytes + indexBytes);
  appendFloats(buffer, mesh.positions);
  appendFloats(buffer, mesh.normals);
  for (uint32_t index : mesh.indices) appendLittleEndian32(buffer, index);

  nlohmann::ordered_json gltf;
  gltf["asset"] = {{"version", "2.0"}, {"generator", "planet export mesh"}};
  gltf["scene"] = 0;
  gltf["scenes"] = nlohmann::ordered_json::array({{{"nodes", {0}}}});
  nlohmann::ordered_json node;
  node["name"] =
      fmt::format("{} {}", metadata["source"]["planet_name"].get<std::string>(), regionText(mesh.spec.region));
  node["mesh"] = 0;
  node["extras"] = metadata;
  gltf["nodes"] = nlohmann::ordered_json::array({node});
  gltf["meshes"] = nlohmann::ordered_json::array(
      {{{"name", "terrain"},
        {"primitives",
         nlohmann::ordered_json::array(
             {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"mode", kModeTriangles}}})}}});
  nlohmann::ordered_json bufferJson = {{"byteLength", buffer.size()}};
  if (!binary) bufferJson["uri"] = "data:application/octet-stream;base64," + base64(buffer);
  gltf["buffers"] = nlohmann::ordered_json::array({bufferJson});
  gltf["bufferViews"] = nlohmann::ordered_json::array({{{"buffer", 0},
                                                        {"byteOffset", 0},
                                                        {"byteLength", vertexBytes},
                                                        {"byteStride", 12},
                                                        {"target", kTargetArrayBuffer}},
                                                       {{"buffer", 0},
                                                        {"byteOffset", vertexBytes},
                                                        {"byteLength", vertexBytes},
                                                        {"byteStride", 12},
                                                        {"target", kTargetArrayBuffer}},
                                                       {{"buffer", 0},
                                                        {"byteOffset", 2 * vertexBytes},
                                                        {"byteLength", indexBytes},
                                                        {"target", kTargetElementArrayBuffer}}});
  gltf["accessors"] = nlohmann::ordered_json::array(
      {{{"bufferView", 0},
        {"componentType", kComponentFloat},
        {"count", mesh.positions.size()},
        {"type", "VEC3"},
        {"min", vectorJson(mesh.positionMin)},
        {"max", vectorJson(mesh.positionMax)}},
       {{"bufferView", 1}, {"componentType", kComponentFloat}, {"count", mesh.normals.size()}, {"type", "VEC3"}},
       {{"bufferView", 2},
        {"componentType", kComponentUnsignedInt},
        {"count", mesh.indices.size()},
        {"type", "SCALAR"}}});
  std::string json = gltf.dump(binary ? -1 : 1);
  if (!binary) return json + "\n";

  while (json.size() % 4 != 0) json.push_back(' ');
  while (buffer.size() % 4 != 0) buffer.push_back('\0');
  const uint64_t total = 12 + 8 + json.size() + 8 + buffer.size();
  if (total > UINT32_MAX) throw Error(fmt::format("a .glb holds at most 4 GiB, this mesh needs {} bytes", total));
  std::string glb;
  glb.reserve(size_t(total));
  appendLittleEndian32(glb, kGlbMagic);
  appendLittleEndian32(glb, kGlbVersion);
  appendLittleEndian32(glb, uint32_t(total));
  appendLittleEndian32(glb, uint32_t(json.size()));
  appendLittleEndian32(glb, kChunkJson);
  glb += json;
  appendLittleEndian32(glb, uint32_t(buffer.size()));
  appendLittleEndian32(glb, kChunkBin);
  glb += buffer;
  return glb;
}

std::string encodeObj(const RegionMesh& mesh, const nlohmann::ordered_json& metadata) {
  const nlohmann::ordered_json& source = metadata["source"];
  const LocalFrame& f = mesh.frame;
  fmt::memory_buffer out;
  auto line = [&](std::string_view format, const auto&... args) {
    fmt::format_to(std::back_inserter(out), fmt::runtime(format), args...);
    out.push_back('\n');
  };
  auto triple = [](const glm::dvec3& v) { return fmt::format("{:.17g} {:.17g} {:.17g}", v.x, v.y, v.z); };
  line(
      "# planet export mesh: {} (preset {}, hash {}, seed offset {}), region {} (south,west,north,east degrees), "
      "{}",
      source["planet_name"].get<std::string>(), source["preset"].get<std::string>(),
      source["preset_hash"].get<std::string>(), source["seed_offset"].get<uint64_t>(), regionText(mesh.spec.region),
      detailText(mesh.spacingM));
  line("# {} x {} vertices, {} triangles; metres, x east, y up, z south at the region's centre", mesh.spec.resolution,
       mesh.spec.resolution, mesh.indices.size() / 3);
  line("# planet-frame point = origin_m + x * axis_x + y * axis_y + z * axis_z; height = |point| - {:.17g}",
       source["radius_m"].get<double>());
  line("# origin_m {}", triple(f.originM));
  line("# axis_x {}", triple(f.east));
  line("# axis_y {}", triple(f.up));
  line("# axis_z {}", triple(f.south));
  line("# metadata {}", metadata.dump());
  line("o terrain");
  for (const glm::vec3& p : mesh.positions) line("v {:.9g} {:.9g} {:.9g}", p.x, p.y, p.z);
  for (const glm::vec3& n : mesh.normals) line("vn {:.9g} {:.9g} {:.9g}", n.x, n.y, n.z);
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const uint32_t a = mesh.indices[t] + 1, b = mesh.indices[t + 1] + 1, c = mesh.indices[t + 2] + 1;
    line("f {}//{} {}//{} {}//{}", a, a, b, b, c, c);
  }
  return std::string(out.data(), out.size());
}

void writeMesh(const std::string& path, const PlanetDescription& planet, const ExportSource& source,
               const RegionMesh& mesh, MeshFormat format) {
  const nlohmann::ordered_json metadata = meshMetadata(planet, source, mesh);
  writeFileAtomic(path, format == MeshFormat::Obj ? encodeObj(mesh, metadata)
                                                  : encodeGltf(mesh, metadata, format == MeshFormat::Glb));
}

}  // namespace planet

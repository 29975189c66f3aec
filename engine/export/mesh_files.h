// A RegionMesh (region_mesh.h) as a file other tools open: glTF 2.0 (one .gltf with the buffer
// embedded as a base64 data URI, or binary .glb) or Wavefront OBJ. Every format carries the same
// metadata (meshMetadata): where the mesh came from and how its local positions map back to the
// planet. glTF keeps it in the node's "extras" (Blender: the object's custom properties), OBJ in
// comment lines before the data. The node has no transform: the mesh sits at the origin, in
// metres, y up, as a user expects when opening it; the planet-frame origin (6,371 km away for
// Earth, where a float would be 0.5 m coarse) is in the metadata, in double.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "export/export_source.h"
#include "export/region_mesh.h"

namespace planet {

enum class MeshFormat { Gltf, Glb, Obj };

const char* meshFormatName(MeshFormat format);  // "gltf", "glb", "obj"
// Throws planet::Error naming the bad text.
MeshFormat parseMeshFormat(std::string_view name);

// Format and version, provenance (export_source.h), the region, resolution, vertex and triangle
// counts, the vertex order and lat/lon formulas, the local frame (origin_m, axes x/y/z, centre)
// and the vertices' height range.
nlohmann::ordered_json meshMetadata(const PlanetDescription& planet, const ExportSource& source,
                                    const RegionMesh& mesh);

// glTF 2.0: one scene, one node (name, extras = metadata), one mesh of one indexed triangle
// primitive; POSITION and NORMAL float VEC3 (componentType 5126) in their own buffer views
// (target 34962, byteStride 12), POSITION with exact min/max; indices unsigned int (5125,
// target 34963). `binary`: a .glb (JSON chunk padded with spaces, BIN chunk with zeros, both to
// 4 bytes); else a .gltf whose buffer is a data:application/octet-stream;base64 URI.
std::string encodeGltf(const RegionMesh& mesh, const nlohmann::ordered_json& metadata, bool binary);
// OBJ: "# " header lines (origin_m, axis_x, axis_y, axis_z, then the metadata as one JSON line),
// then v, vn and f v//vn lines (1-based); numbers with 9 significant digits, which round-trip
// a float exactly.
std::string encodeObj(const RegionMesh& mesh, const nlohmann::ordered_json& metadata);

// Writes the mesh to `path` atomically (core/file.h).
void writeMesh(const std::string& path, const PlanetDescription& planet, const ExportSource& source,
               const RegionMesh& mesh, MeshFormat format);

}  // namespace planet

// Heightmaps of a whole planet from the CPU reference (terrain_height.h) for other tools:
// equirectangular or cube-map images of the heights, as 16-bit PNG or little-endian float32
// raw, each with a JSON sidecar that says how to turn a pixel back into a height and a point.
//
// Pixel centres (x from the left column, y from the top row, both from 0):
//   equirect W x H:  latitude  = 90 * (H - 2y - 1) / H   degrees (90 - (y + 0.5) * 180 / H)
//                    longitude = 180 * (2x + 1 - W) / W  degrees (-180 + (x + 0.5) * 360 / W)
//                    direction = directionFromLatLon(latitude, longitude), as `planet height --at`
//   cube map, face size N, one strip 6N x N: face f = x / N (0..5: +x, -x, +y, -y, +z, -z, the
//                    project's cube faces, planet/cube_face.h), i = x - f*N, j = y;
//                    a = (2i + 1 - N) / N, b = (N - 2j - 1) / N  (both in (-1, 1))
//                    direction = normalize(normal_f + a * axisA_f + b * axisB_f)
//                    so a face's columns run along axisA and its rows down against axisB: each
//                    face looks as seen from outside the planet, not mirrored.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/parallel_for.h"
#include "export/export_source.h"
#include "planet/planet_description.h"

namespace planet {

enum class HeightmapProjection { Equirect, CubeMap };
enum class HeightmapEncoding {
  Png16,       // 16-bit grey PNG: height_m = min + value / 65535 * (max - min), value rounded to nearest
  RawFloat32,  // width * height little-endian IEEE float32, row-major, top row first, no header
};

const char* projectionName(HeightmapProjection projection);  // "equirect", "cubemap"
const char* encodingName(HeightmapEncoding encoding);        // "png16", "raw"
// Throw planet::Error naming the bad text.
HeightmapProjection parseHeightmapProjection(std::string_view name);
HeightmapEncoding parseHeightmapEncoding(std::string_view name);

// Size limits: 16384 x 8192 is 134 M heights (about 6 minutes at the 400 thousand a second of
// 2 cores, and 1.5 GiB of memory for the floats, the 16-bit values and the PNG being built).
inline constexpr uint32_t kEquirectMaxWidth = 16384;
inline constexpr uint32_t kEquirectMaxHeight = 8192;
inline constexpr uint32_t kCubeMapMaxFaceSize = 4096;  // 6 faces: 100 M heights

struct HeightmapSpec {
  HeightmapProjection projection = HeightmapProjection::Equirect;
  uint32_t width = 0;     // image width in pixels (cube map: 6 * faceSize)
  uint32_t height = 0;    // image height in pixels (cube map: faceSize)
  bool filtered = false;  // octaves limited to heightmapSpacingM instead of full detail
};

HeightmapSpec equirectSpec(uint32_t width, uint32_t height, bool filtered = false);
HeightmapSpec cubeMapSpec(uint32_t faceSize, bool filtered = false);
// Throws planet::Error naming the size for a spec outside the limits above (or a cube map
// whose image is not 6N x N).
void validateHeightmapSpec(const HeightmapSpec& spec);

// The centre of equirect pixel (x, y) as (latitude, longitude) in degrees (formula above).
glm::dvec2 equirectPixelCentreDeg(uint32_t x, uint32_t y, uint32_t width, uint32_t height);
// The unit direction (planet frame) of the centre of pixel (x, y).
glm::dvec3 heightmapPixelDirection(const HeightmapSpec& spec, uint32_t x, uint32_t y);
// The octave limit of a filtered spec: the largest pixel extent anywhere in the image (equirect:
// max(pi R / H, 2 pi R / W); cube map: 2 R / N at a face centre); 0 for full detail.
double heightmapSpacingM(const PlanetDescription& planet, const HeightmapSpec& spec);

struct Heightmap {
  HeightmapSpec spec;
  double spacingM = 0.0;        // the octave limit the heights were evaluated with (0: full detail)
  std::vector<float> heightsM;  // width * height, row-major, top row first
  double minM = 0.0, maxM = 0.0;
};

// Every pixel's terrainHeightM(planet, direction, spacing) rounded to float, on `threads`
// threads (0: all), reporting progress in pixels. Throws planet::Error for a bad spec.
Heightmap computeHeightmap(const PlanetDescription& planet, const HeightmapSpec& spec, unsigned threads = 0,
                           const ProgressCallback& progress = {});

// The 16-bit values of a png16 file: round((h - min) / (max - min) * 65535) (all 0 when max == min).
std::vector<uint16_t> quantizeHeights(const Heightmap& heightmap);
// The bytes of the image file in `encoding`.
std::string encodeHeightmap(const Heightmap& heightmap, HeightmapEncoding encoding);

// The sidecar: format and version, the provenance (export_source.h), projection, size, the
// pixel-centre formulas above in words and, for a cube map, each face's offset, normal and axes;
// the encoding with its mapping (png16) or dtype (raw), min and max heights, the image file's
// name and FNV-1a 64 hash of its bytes.
nlohmann::ordered_json heightmapSidecar(const PlanetDescription& planet, const ExportSource& source,
                                        const Heightmap& heightmap, HeightmapEncoding encoding,
                                        const std::string& imageFileName, std::string_view imageBytes);

// The sidecar's name for an image at `path`: path + ".json".
std::string sidecarPath(const std::string& path);

// Writes the image to `path` and its sidecar to sidecarPath(path), together (core/file.h
// writeFilesAtomic): a failure leaves neither.
void writeHeightmap(const std::string& path, const PlanetDescription& planet, const ExportSource& source,
                    const Heightmap& heightmap, HeightmapEncoding encoding);

}  // namespace planet

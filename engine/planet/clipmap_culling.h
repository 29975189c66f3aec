// Frustum culling of the clipmap mesh's ring bands by sector (issue 12, point 5). The hemisphere
// mesh (clipmap_mesh.h) is centred below the camera, so a camera that looks toward the horizon
// sees only a wedge of every far ring, and one that looks down from orbit only the rings near the
// nadir: the rest is shaded and evaluated for nothing (on lavapipe the height pass and the
// single-threaded vertex work of the draw scale with it).
//
// The drawn bands are cut into cells of kCullBandsPerCell bands by kCullSectors runs of quads in
// φ. A cell is culled when every point of a hull around it lies outside one plane of the view
// frustum (the four sides and the near plane): its corners and the middle of its φ edges, at the
// terrain's lowest and highest heights, the highest raised by the sphere's bulge over the cell,
// so the hull holds the ground whatever its heights. The pole fan is always drawn. Culling
// removes triangles that no pixel shows, so the picture is the same, bit for bit.
//
// The result is what the terrain pass needs for the frame: the triangle list of the kept quads
// (taken from the mesh's own index layout, so every triangle keeps its winding), near to far for
// the early depth test (the pole fan, then band by band outward), and the vertices
// those triangles use, as runs of at most `chunkSize` consecutive vertex indices (a compute
// workgroup each), the pole last.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "planet/clipmap_mesh.h"

namespace planet {

inline constexpr uint32_t kCullBandsPerCell = 4;
inline constexpr uint32_t kCullSectors = 32;  // at most numPhi of them

// The camera and the ground for culling, in the mesh's local frame (pole on +z), in metres.
struct ClipmapCullView {
  // Clip coordinates of a camera-relative point q: viewProjection · (q, 1), with
  // q = R·(sinθ cosφ, sinθ sinφ, cosθ − 1) + h·(direction) − (0, 0, cameraZ), as terrain.vert
  // places a vertex (reversed Z: the near plane at z = w, infinitely far at z = 0).
  glm::dmat4 viewProjection{1.0};
  double radiusM = 0.0;
  double cameraZ = 0.0;
  double minHeightM = 0.0;  // the lowest and highest ground (or sea) the mesh can show
  double maxHeightM = 0.0;
};

struct ClipmapCull {
  // Triangle list, near to far: the pole fan, then the kept quads of bands lastRing−1 .. firstRing.
  std::vector<uint32_t> indices;
  struct Chunk {
    uint32_t firstVertex = 0;
    uint32_t count = 0;  // 1 .. chunkSize
  };
  std::vector<Chunk> chunks;  // the vertices the triangles use, ring by ring, the pole last
  // Where band firstRing + k's kept quads start in `indices` (at k), so that a draw can take a
  // run of bands: band b's quads end where band b − 1's (the next outward) start, and band
  // firstRing's at the end; the pole fan ends where band lastRing − 1's start.
  std::vector<uint32_t> bandFirstIndex;
  uint32_t cellsKept = 0;
  uint32_t cellsTotal = 0;
  // Which vertices of the rings the kept triangles use: the cull's scratch, kept for its capacity.
  std::vector<uint8_t> vertexMarks;
  uint32_t vertexCount() const;
};

// The bands firstRing..lastRing−1 of `mesh` and the fan that closes ring lastRing at the pole
// (lastRing < ringCount; the fan's triangles are (ring lastRing, i), (i + 1), pole), culled for
// `view`. With `cull` false every cell is kept (the whole range, in the same form). Throws
// planet::Error for a bad ring range or chunkSize 0.
ClipmapCull cullClipmap(const ClipmapMesh& mesh, uint32_t firstRing, uint32_t lastRing, const ClipmapCullView& view,
                        uint32_t chunkSize, bool cull = true);
// The same into `out`, whose vectors keep their capacity (the renderer's every frame).
void cullClipmap(const ClipmapMesh& mesh, uint32_t firstRing, uint32_t lastRing, const ClipmapCullView& view,
                 uint32_t chunkSize, bool cull, ClipmapCull& out);

}  // namespace planet

// The static hemisphere mesh of a spherical clipmap (Clasen & Hege 2006, "Terrain rendering
// using spherical clipmaps"; as implemented in Hayes-McCoy 2010, §4.3–4.4). It is built once on
// the CPU and uploaded once; every frame the renderer only rotates its pole toward the camera's
// nadir and chooses which rings to draw.
//
// Local frame: the pole (θ = 0) is on +z, θ is the angle from the pole, φ the azimuth from +x
// toward +y. Unit direction = (cos φ sin θ, sin φ sin θ, cos θ).
//
// Rings: ring j (0..m−1) of level ℓ (1..L) sits at θ = π·2^−ℓ·2^(−j/m), so all rings form one
// geometric progression θ_k = (π/2)·2^(−k/m), k = (ℓ−1)·m + j = 0..L·m−1, with constant ratio
// 2^(−1/m). Ring 0 is the rim (θ = π/2); ring L·m−1 is the innermost. Constant triangle size on
// screen comes from this spacing, not from any per-level switch: there are no level seams,
// T-junctions or transition regions (every ring has the same N vertices).
//
// Choice: the innermost ring k = L·m−1 is KEPT and the pole added as an extra vertex, so every
// ring of every level exists (the dissertation drops that ring and puts the pole in its place,
// giving (L·m−1)·N + 1 vertices). The pole is addressed as "ring" R = L·m (θ = 0) wherever a
// ring index is taken, so ring indices 0..R run from the rim to the pole.
//
// Counts, with R = L·m rings and N = numPhi:
//   vertexCount   = R·N + 1
//   triangleCount = 2·N·(R−1) + N = (2R−1)·N     (R−1 bands of N quads, plus the pole fan)
//   indexCount    = 3·triangleCount
//
// Vertex layout: ring k, φ index i (φ_i = 2π·i/N) is vertex k·N + i; the pole is vertex R·N.
//
// Index layout (uint32 triangle list), ordered from the rim inward so that any run of rings is
// one contiguous range:
//   band b (0 ≤ b ≤ R−2), the quads between ring b and ring b+1: indices [6N·b, 6N·(b+1)),
//     quad i = triangles (o_i, o_{i+1}, n_{i+1}) and (o_i, n_{i+1}, n_i), where o = ring b,
//     n = ring b+1 and i+1 wraps to 0 (the φ seam is closed; no spiral);
//   band R−1, the pole fan between ring R−1 and the pole: indices [6N·(R−1), 6N·(R−1) + 3N),
//     triangle i = (c_i, c_{i+1}, pole) with c = ring R−1.
// Every triangle is counter-clockwise seen from outside the sphere (outward normal = +radial).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace planet {

// Bounds of ClipmapParams. With all three at their maximum the mesh has 42M vertices and 252M
// indices, still addressable with uint32 indices.
inline constexpr uint32_t kClipmapMaxLevels = 40;          // π·2^−40 ≈ 18 µm of arc on an earth-sized planet
inline constexpr uint32_t kClipmapMaxRingsPerLevel = 256;  // ring ratio 2^(−1/256) ≈ 0.9973
inline constexpr uint32_t kClipmapMinNumPhi = 3;           // fewer vertices cannot enclose the pole
inline constexpr uint32_t kClipmapMaxNumPhi = 4096;

struct ClipmapParams {
  uint32_t levels = 18;         // L: levels; each halves θ (level ℓ spans θ ∈ (π·2^−(ℓ+1), π·2^−ℓ])
  uint32_t ringsPerLevel = 16;  // m: rings per level; consecutive rings differ by the factor 2^(−1/m)
  uint32_t numPhi = 128;        // N: vertices per ring (and triangles in the pole fan)
};

// One mesh vertex. Plain float/uint members with a 16-byte multiple size so that it can move
// unchanged into a GLSL-shared header (shaders/shared) later.
struct ClipmapVertex {
  glm::vec4 direction;  // unit direction (xyz) in the local frame; w = 1 (a point on the unit sphere)
  float theta;          // angle from the pole, radians, [0, π/2]
  float phi;            // azimuth, radians, [0, 2π)
  uint32_t ring;        // k = 0 (rim) .. R−1 (innermost); R for the pole vertex
  uint32_t level;       // ℓ = 1..L (k / m + 1); L for the pole vertex
};
static_assert(sizeof(ClipmapVertex) == 32, "ClipmapVertex must stay 32 bytes (two vec4 of a GLSL-shared struct)");

// A range of the index buffer, for vkCmdDrawIndexed(cmd, indexCount, 1, firstIndex, 0, 0).
struct IndexRange {
  uint32_t firstIndex = 0;
  uint32_t indexCount = 0;
};

// Throws planet::Error naming the first bad value: levels outside 1..40, ringsPerLevel outside
// 1..256, numPhi outside 3..4096.
void validateClipmapParams(const ClipmapParams& params);

// Counts (see the formulas at the top). The parameters are not validated here.
uint32_t clipmapRingCount(const ClipmapParams& params);  // R = L·m (the pole not included)
uint32_t clipmapVertexCount(const ClipmapParams& params);
uint32_t clipmapTriangleCount(const ClipmapParams& params);
uint32_t clipmapIndexCount(const ClipmapParams& params);

// θ of ring k = 0..R, computed as π·2^−ℓ·2^(−j/m); ring R (the pole) has θ = 0. Throws
// planet::Error for k > R.
double clipmapRingTheta(const ClipmapParams& params, uint32_t ring);
// ℓ = k / m + 1 for ring k = 0..R (the pole, ring R, belongs to level L). Throws for k > R.
uint32_t clipmapLevelOfRing(const ClipmapParams& params, uint32_t ring);

// The innermost ring (largest k, the pole R included) with θ_k ≥ theta: the outer edge of the
// drawn region when everything beyond theta (the horizon) may be skipped. theta > π/2 gives 0
// (no ring is further out than the rim); theta ≤ 0 gives R. Throws for NaN.
uint32_t clipmapInnermostRingAtOrAbove(const ClipmapParams& params, double theta);
// The outermost ring (smallest k, the pole R included) with θ_k ≤ theta: the inner edge of the
// drawn region when everything inside theta (sub-pixel rings) may be skipped. theta ≥ π/2
// gives 0; theta < 0 gives R. Throws for NaN.
uint32_t clipmapOutermostRingAtOrBelow(const ClipmapParams& params, double theta);

// The triangles between ring firstRing and ring lastRing (0 ≤ firstRing ≤ lastRing ≤ R), i.e.
// bands firstRing..lastRing−1; lastRing = R includes the pole fan. firstRing == lastRing gives
// an empty range. Throws planet::Error for firstRing > lastRing or lastRing > R.
IndexRange clipmapRingBandRange(const ClipmapParams& params, uint32_t firstRing, uint32_t lastRing);
// The smallest run of bands that covers θ ∈ [thetaMin, thetaMax] (clamped to [0, π/2]):
// clipmapRingBandRange(innermostRingAtOrAbove(thetaMax), outermostRingAtOrBelow(thetaMin)).
// The pole fan is included only when thetaMin < θ of ring R−1; otherwise the cap inside the
// range is left open and the renderer must cover it. Throws for NaN or thetaMin > thetaMax.
IndexRange clipmapThetaBandRange(const ClipmapParams& params, double thetaMin, double thetaMax);

struct ClipmapMesh {
  ClipmapParams params;
  std::vector<ClipmapVertex> vertices;  // vertexCount() entries, layout above
  std::vector<uint32_t> indices;        // indexCount() entries, layout above

  uint32_t ringCount() const { return clipmapRingCount(params); }
  uint32_t poleRing() const { return clipmapRingCount(params); }  // the ring index that names the pole
  uint32_t vertexCount() const { return clipmapVertexCount(params); }
  uint32_t triangleCount() const { return clipmapTriangleCount(params); }
  uint32_t indexCount() const { return clipmapIndexCount(params); }
  uint32_t vertexIndex(uint32_t ring, uint32_t phiIndex) const { return ring * params.numPhi + phiIndex; }
  uint32_t poleVertex() const { return clipmapRingCount(params) * params.numPhi; }

  double ringTheta(uint32_t ring) const { return clipmapRingTheta(params, ring); }
  uint32_t levelOfRing(uint32_t ring) const { return clipmapLevelOfRing(params, ring); }
  uint32_t innermostRingAtOrAbove(double theta) const { return clipmapInnermostRingAtOrAbove(params, theta); }
  uint32_t outermostRingAtOrBelow(double theta) const { return clipmapOutermostRingAtOrBelow(params, theta); }
  IndexRange ringBandRange(uint32_t firstRing, uint32_t lastRing) const {
    return clipmapRingBandRange(params, firstRing, lastRing);
  }
  IndexRange thetaBandRange(double thetaMin, double thetaMax) const {
    return clipmapThetaBandRange(params, thetaMin, thetaMax);
  }
};

// Validates the parameters, then builds the vertices and indices (layout above).
ClipmapMesh buildClipmapMesh(const ClipmapParams& params);

}  // namespace planet

#include "planet/clipmap_culling.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"

namespace planet {

uint32_t ClipmapCull::vertexCount() const {
  uint32_t count = 0;
  for (const Chunk& c : chunks) count += c.count;
  return count;
}

namespace {

// Whether some frustum plane has every point of `clip` outside it (x, y in [−w, w]; reversed Z:
// z ≤ w in front of the near plane).
template <size_t N>
bool outsideOnePlane(const std::array<glm::dvec4, N>& clip) {
  const auto allOutside = [&](auto&& distance) {
    return std::all_of(clip.begin(), clip.end(), [&](const glm::dvec4& c) { return distance(c) < 0.0; });
  };
  return allOutside([](const glm::dvec4& c) { return c.w + c.x; }) ||
         allOutside([](const glm::dvec4& c) { return c.w - c.x; }) ||
         allOutside([](const glm::dvec4& c) { return c.w + c.y; }) ||
         allOutside([](const glm::dvec4& c) { return c.w - c.y; }) ||
         allOutside([](const glm::dvec4& c) { return c.w - c.z; });
}

}  // namespace

ClipmapCull cullClipmap(const ClipmapMesh& mesh, uint32_t firstRing, uint32_t lastRing, const ClipmapCullView& view,
                        uint32_t chunkSize, bool cull) {
  ClipmapCull result;
  cullClipmap(mesh, firstRing, lastRing, view, chunkSize, cull, result);
  return result;
}

void cullClipmap(const ClipmapMesh& mesh, uint32_t firstRing, uint32_t lastRing, const ClipmapCullView& view,
                 uint32_t chunkSize, bool cull, ClipmapCull& result) {
  const uint32_t rings = mesh.ringCount();
  if (firstRing > lastRing || lastRing >= rings)
    throw Error(fmt::format("cullClipmap: ring range {}..{} is outside 0..{}", firstRing, lastRing, rings - 1));
  if (chunkSize == 0) throw Error("cullClipmap: chunkSize must be at least 1");
  const uint32_t n = mesh.params.numPhi;
  const uint32_t sectors = std::min(kCullSectors, n);
  const auto sectorStart = [&](uint32_t s) { return uint32_t(uint64_t(s) * n / sectors); };

  // The sines and cosines the hulls take, each computed once (a 1920x1080 frame's mesh has ~5,000
  // cells of 12 points): of the sectors' edges and middles in φ (point 2s is sector s's first
  // edge, 2s + 1 its middle, 2s + 2 its last edge), and of a cell row's two rings in θ.
  const double phiStep = 2.0 * 3.14159265358979323846 / double(n);
  std::vector<glm::dvec2> phiCosSin(2 * size_t(sectors) + 1);
  for (uint32_t s = 0; s < sectors; ++s) {
    const double phi0 = sectorStart(s) * phiStep, phi1 = sectorStart(s + 1) * phiStep;
    const double phiMid = 0.5 * (phi0 + phi1);
    phiCosSin[2 * s] = {std::cos(phi0), std::sin(phi0)};
    phiCosSin[2 * s + 1] = {std::cos(phiMid), std::sin(phiMid)};
    phiCosSin[2 * s + 2] = {std::cos(phi1), std::sin(phi1)};
  }
  struct Ring {
    double sinTheta, cosTheta, halfSin;  // sin θ, cos θ, sin(θ / 2)
  };
  const auto ringAt = [](double theta) { return Ring{std::sin(theta), std::cos(theta), std::sin(0.5 * theta)}; };
  // A point of the mesh's surface on `ring` at the φ of point k and height h, in clip coordinates.
  const double r = view.radiusM;
  const auto clipOf = [&](const Ring& ring, size_t k, double h) {
    const glm::dvec3 dir(ring.sinTheta * phiCosSin[k].x, ring.sinTheta * phiCosSin[k].y, ring.cosTheta);
    const glm::dvec3 q =
        r * glm::dvec3(dir.x, dir.y, -2.0 * ring.halfSin * ring.halfSin) + h * dir - glm::dvec3(0.0, 0.0, view.cameraZ);
    return view.viewProjection * glm::dvec4(q, 1.0);
  };

  // The vectors keep their capacity from the last cull: a 1920x1080 frame's list is 2.3 MB, which
  // fresh memory would fault in page by page every frame.
  result.indices.clear();
  result.chunks.clear();
  result.bandFirstIndex.assign(lastRing - firstRing, 0);
  result.cellsKept = result.cellsTotal = 0;
  // needed[(ring − firstRing) · n + i]: vertex i of the ring is used by a kept triangle.
  std::vector<uint8_t>& needed = result.vertexMarks;
  needed.assign(size_t(lastRing - firstRing + 1) * n, 0);
  const auto need = [&](uint32_t ring, uint32_t i) { needed[size_t(ring - firstRing) * n + i] = 1; };
  // Room for every band's quads and the fan: the list is built without moving it.
  result.indices.reserve(size_t(6) * n * (lastRing - firstRing) + size_t(3) * n);
  // Near to far, so that a depth test before shading (terrain.frag, planets without a sea) finds
  // the nearer ground already drawn and skips what it hides: first the fan that closes ring
  // lastRing at the pole (below the camera), then the cells from the innermost band outward.
  for (uint32_t i = 0; i < n; ++i) {
    result.indices.insert(result.indices.end(),
                          {mesh.vertexIndex(lastRing, i), mesh.vertexIndex(lastRing, (i + 1) % n), mesh.poleVertex()});
    need(lastRing, i);
  }
  // Cells of kCullBandsPerCell bands counted from the rim (band firstRing), innermost cell first.
  const uint32_t cellCount = (lastRing - firstRing + kCullBandsPerCell - 1) / kCullBandsPerCell;
  for (uint32_t cell = cellCount; cell-- > 0;) {
    const uint32_t band = firstRing + cell * kCullBandsPerCell;
    const uint32_t bandEnd = std::min(band + kCullBandsPerCell, lastRing);  // bands band..bandEnd−1
    const double outer = mesh.ringTheta(band), inner = mesh.ringTheta(bandEnd);
    const Ring outerRing = ringAt(outer), innerRing = ringAt(inner);
    std::vector<uint32_t> keptSectors;
    for (uint32_t s = 0; s < sectors; ++s) {
      const uint32_t q0 = sectorStart(s), q1 = sectorStart(s + 1);  // quads q0..q1−1
      ++result.cellsTotal;
      bool keep = true;
      if (cull) {
        const double phi0 = q0 * phiStep, phi1 = q1 * phiStep;
        // The sphere bulges over the chords between the hull's points by R(1 − cos(α/2)), α
        // the largest angle between neighbouring points: across the cell in θ, or half its φ
        // span along a ring.
        const double alpha = std::max(outer - inner, 0.5 * (phi1 - phi0) * outerRing.sinTheta);
        const double bulge = (r + view.maxHeightM) * (1.0 - std::cos(0.5 * alpha)) / std::cos(0.5 * alpha);
        const double low = view.minHeightM, high = view.maxHeightM + bulge;
        const size_t k = 2 * size_t(s);  // the sector's first edge, middle and last edge: k, k + 1, k + 2
        const std::array<glm::dvec4, 12> hull = {
            clipOf(outerRing, k, low),  clipOf(outerRing, k + 1, low),  clipOf(outerRing, k + 2, low),
            clipOf(innerRing, k, low),  clipOf(innerRing, k + 1, low),  clipOf(innerRing, k + 2, low),
            clipOf(outerRing, k, high), clipOf(outerRing, k + 1, high), clipOf(outerRing, k + 2, high),
            clipOf(innerRing, k, high), clipOf(innerRing, k + 1, high), clipOf(innerRing, k + 2, high)};
        keep = !outsideOnePlane(hull);
      }
      if (!keep) continue;
      ++result.cellsKept;
      keptSectors.push_back(s);
    }
    // The kept cells' quads band by band, the inner band first.
    for (uint32_t b = bandEnd; b-- > band;) {
      result.bandFirstIndex[b - firstRing] = uint32_t(result.indices.size());
      for (uint32_t s : keptSectors) {
        const uint32_t q0 = sectorStart(s), q1 = sectorStart(s + 1);
        const size_t base = size_t(6) * n * b;
        result.indices.insert(result.indices.end(), mesh.indices.begin() + ptrdiff_t(base + 6 * size_t(q0)),
                              mesh.indices.begin() + ptrdiff_t(base + 6 * size_t(q1)));
        // Quads q0..q1−1 use vertices q0..q1 of both rings (q1 = n is vertex 0).
        for (uint32_t ring : {b, b + 1}) {
          uint8_t* row = &needed[size_t(ring - firstRing) * n];
          std::fill(row + q0, row + q1, uint8_t(1));
          row[q1 % n] = 1;
        }
      }
    }
  }
  // The needed vertices as runs of consecutive indices, cut into chunks.
  for (uint32_t ring = firstRing; ring <= lastRing; ++ring) {
    const uint8_t* used = &needed[size_t(ring - firstRing) * n];
    for (uint32_t i = 0; i < n;) {
      if (!used[i]) {
        ++i;
        continue;
      }
      uint32_t end = i;
      while (end < n && used[end] && end - i < chunkSize) ++end;
      result.chunks.push_back({mesh.vertexIndex(ring, i), end - i});
      i = end;
    }
  }
  result.chunks.push_back({mesh.poleVertex(), 1});
}

}  // namespace planet

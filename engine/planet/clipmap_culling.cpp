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
  const uint32_t rings = mesh.ringCount();
  if (firstRing > lastRing || lastRing >= rings)
    throw Error(fmt::format("cullClipmap: ring range {}..{} is outside 0..{}", firstRing, lastRing, rings - 1));
  if (chunkSize == 0) throw Error("cullClipmap: chunkSize must be at least 1");
  const uint32_t n = mesh.params.numPhi;
  const uint32_t sectors = std::min(kCullSectors, n);
  const auto sectorStart = [&](uint32_t s) { return uint32_t(uint64_t(s) * n / sectors); };

  // A point of the mesh's surface at (θ, φ) and height h, in clip coordinates.
  const double r = view.radiusM;
  const auto clipOf = [&](double theta, double phi, double h) {
    const double s = std::sin(theta);
    const glm::dvec3 dir(s * std::cos(phi), s * std::sin(phi), std::cos(theta));
    const double half = std::sin(0.5 * theta);
    const glm::dvec3 q =
        r * glm::dvec3(dir.x, dir.y, -2.0 * half * half) + h * dir - glm::dvec3(0.0, 0.0, view.cameraZ);
    return view.viewProjection * glm::dvec4(q, 1.0);
  };

  ClipmapCull result;
  result.bandFirstIndex.resize(lastRing - firstRing);
  // needed[ring][i]: vertex i of the ring is used by a kept triangle.
  std::vector<std::vector<bool>> needed(lastRing - firstRing + 1, std::vector<bool>(n, false));
  const double phiStep = 2.0 * 3.14159265358979323846 / double(n);
  // Near to far, so that a depth test before shading (terrain.frag, planets without a sea) finds
  // the nearer ground already drawn and skips what it hides: first the fan that closes ring
  // lastRing at the pole (below the camera), then the cells from the innermost band outward.
  for (uint32_t i = 0; i < n; ++i) {
    result.indices.insert(result.indices.end(),
                          {mesh.vertexIndex(lastRing, i), mesh.vertexIndex(lastRing, (i + 1) % n), mesh.poleVertex()});
    needed[lastRing - firstRing][i] = true;
  }
  // Cells of kCullBandsPerCell bands counted from the rim (band firstRing), innermost cell first.
  const uint32_t cellCount = (lastRing - firstRing + kCullBandsPerCell - 1) / kCullBandsPerCell;
  for (uint32_t cell = cellCount; cell-- > 0;) {
    const uint32_t band = firstRing + cell * kCullBandsPerCell;
    const uint32_t bandEnd = std::min(band + kCullBandsPerCell, lastRing);  // bands band..bandEnd−1
    const double outer = mesh.ringTheta(band), inner = mesh.ringTheta(bandEnd);
    std::vector<uint32_t> keptSectors;
    for (uint32_t s = 0; s < sectors; ++s) {
      const uint32_t q0 = sectorStart(s), q1 = sectorStart(s + 1);  // quads q0..q1−1
      ++result.cellsTotal;
      bool keep = true;
      if (cull) {
        const double phi0 = q0 * phiStep, phi1 = q1 * phiStep, phiMid = 0.5 * (phi0 + phi1);
        // The sphere bulges over the chords between the hull's points by R(1 − cos(α/2)), α
        // the largest angle between neighbouring points: across the cell in θ, or half its φ
        // span along a ring.
        const double alpha = std::max(outer - inner, 0.5 * (phi1 - phi0) * std::sin(outer));
        const double bulge = (r + view.maxHeightM) * (1.0 - std::cos(0.5 * alpha)) / std::cos(0.5 * alpha);
        const double low = view.minHeightM, high = view.maxHeightM + bulge;
        const std::array<glm::dvec4, 12> hull = {
            clipOf(outer, phi0, low),   clipOf(outer, phiMid, low),   clipOf(outer, phi1, low),
            clipOf(inner, phi0, low),   clipOf(inner, phiMid, low),   clipOf(inner, phi1, low),
            clipOf(outer, phi0, high),  clipOf(outer, phiMid, high),  clipOf(outer, phi1, high),
            clipOf(inner, phi0, high),  clipOf(inner, phiMid, high),  clipOf(inner, phi1, high)};
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
        for (uint32_t i = q0; i <= q1; ++i) {
          needed[b - firstRing][i % n] = true;
          needed[b + 1 - firstRing][i % n] = true;
        }
      }
    }
  }
  // The needed vertices as runs of consecutive indices, cut into chunks.
  for (uint32_t ring = firstRing; ring <= lastRing; ++ring) {
    const std::vector<bool>& used = needed[ring - firstRing];
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
  return result;
}

}  // namespace planet

// Frustum culling of the clipmap mesh (clipmap_culling.h, issue 12 point 5): conservative (no
// triangle that shows a pixel is dropped), exact without culling, and its vertex chunks cover
// what its triangles use.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "camera/camera.h"
#include "core/error.h"
#include "planet/clipmap_culling.h"

namespace planet::test {
namespace {

constexpr double kRadius = 6.371e6;

// A camera `altitude` metres above the mesh's pole, looking along heading/pitch in the local
// frame (x toward φ = 0), with the terrain pass's projection.
ClipmapCullView viewFrom(double altitude, double headingDeg, double pitchDeg, double minH, double maxH) {
  const double h = headingDeg * std::numbers::pi / 180.0, p = pitchDeg * std::numbers::pi / 180.0;
  const glm::dvec3 forward(std::cos(p) * std::cos(h), std::cos(p) * std::sin(h), std::sin(p));
  const glm::dvec3 up = std::abs(std::sin(p)) > 0.99 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
  ClipmapCullView view;
  view.viewProjection =
      reversedZPerspective(60.0 * std::numbers::pi / 180.0, 16.0 / 9.0, std::max(0.25 * altitude, 0.01)) *
      viewMatrix(forward, up);
  view.radiusM = kRadius;
  view.cameraZ = altitude;
  view.minHeightM = minH;
  view.maxHeightM = maxH;
  return view;
}

// Clip coordinates of mesh vertex v at height h, as terrain.vert places it.
glm::dvec4 clipOfVertex(const ClipmapMesh& mesh, uint32_t v, const ClipmapCullView& view, double h) {
  const ClipmapVertex& vertex = mesh.vertices[v];
  const double s = std::sin(vertex.theta), half = std::sin(0.5 * vertex.theta);
  const glm::dvec3 dir(s * std::cos(vertex.phi), s * std::sin(vertex.phi), std::cos(vertex.theta));
  const glm::dvec3 q = kRadius * glm::dvec3(dir.x, dir.y, -2.0 * half * half) + h * dir - glm::dvec3(0, 0, view.cameraZ);
  return view.viewProjection * glm::dvec4(q, 1.0);
}

bool inFrustum(const glm::dvec4& c) {
  return c.w > 0.0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && c.z <= c.w;
}

std::set<uint32_t> chunkVertices(const ClipmapCull& cull) {
  std::set<uint32_t> vertices;
  for (const ClipmapCull::Chunk& c : cull.chunks) {
    EXPECT_GE(c.count, 1u);
    EXPECT_LE(c.count, 64u);
    for (uint32_t i = 0; i < c.count; ++i) EXPECT_TRUE(vertices.insert(c.firstVertex + i).second) << "twice";
  }
  return vertices;
}

TEST(ClipmapCulling, WithoutCullingItIsTheRingRangeAndItsFanExactly) {
  const ClipmapMesh mesh = buildClipmapMesh({8, 8, 64});
  const uint32_t first = 5, last = 40;
  const ClipmapCull cull = cullClipmap(mesh, first, last, viewFrom(1000.0, 0.0, 0.0, 0.0, 0.0), 64, false);
  const IndexRange bands = mesh.ringBandRange(first, last);
  std::vector<uint32_t> expected(mesh.indices.begin() + bands.firstIndex,
                                 mesh.indices.begin() + bands.firstIndex + bands.indexCount);
  const uint32_t n = mesh.params.numPhi;
  for (uint32_t i = 0; i < n; ++i)
    expected.insert(expected.end(), {mesh.vertexIndex(last, i), mesh.vertexIndex(last, (i + 1) % n), mesh.poleVertex()});
  std::vector<uint32_t> got = cull.indices;
  // The same triangles (the culled list goes cell by cell, the mesh band by band).
  auto triangles = [](const std::vector<uint32_t>& list) {
    std::multiset<std::tuple<uint32_t, uint32_t, uint32_t>> t;
    for (size_t i = 0; i + 2 < list.size(); i += 3) t.insert({list[i], list[i + 1], list[i + 2]});
    return t;
  };
  EXPECT_EQ(triangles(got), triangles(expected));
  EXPECT_EQ(cull.cellsKept, cull.cellsTotal);
  // Every vertex of rings first..last and the pole, once.
  const std::set<uint32_t> vertices = chunkVertices(cull);
  EXPECT_EQ(vertices.size(), size_t(last - first + 1) * n + 1);
  EXPECT_EQ(*vertices.begin(), mesh.vertexIndex(first, 0));
  EXPECT_EQ(*vertices.rbegin(), mesh.poleVertex());
  EXPECT_EQ(cull.vertexCount(), vertices.size());
}

// Conservative: every quad with a vertex inside the frustum, at any height in the bounds, is
// kept; and the chunks hold every vertex the kept triangles use. Views: toward the horizon from
// 2 m and 2 km, down from 400 km, oblique from 100 km, from 20,000 km.
TEST(ClipmapCulling, KeepsEveryQuadTheFrustumCanSeeAndDropsMostOfTheRest) {
  const ClipmapMesh mesh = buildClipmapMesh({30, 16, 128});
  struct Case {
    double altitude, heading, pitch;
    uint32_t first, last;
    double maxKept;  // share of the quads kept at most (the view's saving)
  };
  // Near the ground the hull of a cell beside the camera spans the terrain's whole height range
  // (a cliff could stand there), so rings of a few metres are kept all round: 59 % at 2 m.
  const Case cases[] = {{2.0, 60.0, -8.0, 40, 440, 0.65},
                        {2000.0, 200.0, -8.0, 40, 300, 0.45},
                        {400000.0, 0.0, -90.0, 20, 170, 0.75},
                        {100000.0, 30.0, -45.0, 20, 200, 0.6},
                        {2.0e7, 0.0, -90.0, 0, 60, 1.0}};
  const uint32_t n = mesh.params.numPhi;
  for (const Case& c : cases) {
    SCOPED_TRACE("altitude " + std::to_string(c.altitude) + " pitch " + std::to_string(c.pitch));
    const ClipmapCullView view = viewFrom(c.altitude, c.heading, c.pitch, -500.0, 3000.0);
    const ClipmapCull cull = cullClipmap(mesh, c.first, c.last, view, 64);
    std::set<std::pair<uint32_t, uint32_t>> kept;  // quads by (band, i): their first triangle's first two vertices
    for (size_t t = 0; t + 2 < cull.indices.size(); t += 3) kept.insert({cull.indices[t], cull.indices[t + 1]});
    size_t visibleQuads = 0, quads = 0;
    for (uint32_t band = c.first; band < c.last; ++band)
      for (uint32_t i = 0; i < n; ++i) {
        ++quads;
        const uint32_t corners[] = {mesh.vertexIndex(band, i), mesh.vertexIndex(band, (i + 1) % n),
                                    mesh.vertexIndex(band + 1, i), mesh.vertexIndex(band + 1, (i + 1) % n)};
        bool visible = false;
        for (uint32_t v : corners)
          for (double h : {-500.0, 0.0, 1500.0, 3000.0}) visible |= inFrustum(clipOfVertex(mesh, v, view, h));
        if (!visible) continue;
        ++visibleQuads;
        EXPECT_TRUE(kept.count({corners[0], corners[1]})) << "band " << band << " quad " << i << " dropped";
      }
    const double share = double(cull.indices.size() / 3 - n) / (2.0 * double(quads));
    std::printf("altitude %.0f m pitch %.0f: %zu of %zu quads have a vertex in view, %.1f %% kept\n", c.altitude,
                c.pitch, visibleQuads, quads, 100.0 * share);
    EXPECT_LE(share, c.maxKept);
    EXPECT_GE(share * double(quads), double(visibleQuads));
    // The chunks hold what the triangles use, and nothing of the culled cells beyond their edges.
    const std::set<uint32_t> vertices = chunkVertices(cull);
    std::set<uint32_t> used(cull.indices.begin(), cull.indices.end());
    EXPECT_EQ(vertices, used);
  }
}

// The triangles come near to far: the pole fan under the camera first, then band by band outward
// (a triangle's innermost vertex never moves inward along the list), so that the early depth test
// of a planet without a sea (terrain.frag) finds nearer ground drawn before what it hides.
TEST(ClipmapCulling, TrianglesComeNearToFar) {
  const ClipmapMesh mesh = buildClipmapMesh({30, 16, 128});
  const uint32_t n = mesh.params.numPhi;
  for (bool cull : {false, true}) {
    SCOPED_TRACE(cull ? "culled" : "whole");
    const ClipmapCull result = cullClipmap(mesh, 40, 300, viewFrom(2000.0, 200.0, -8.0, -500.0, 3000.0), 64, cull);
    ASSERT_GT(result.indices.size(), size_t(3 * n));
    auto innermost = [&](size_t t) {
      uint32_t ring = 0;
      for (size_t k = 0; k < 3; ++k) ring = std::max(ring, mesh.vertices[result.indices[3 * t + k]].ring);
      return ring;
    };
    for (size_t t = 0; t < n; ++t) EXPECT_EQ(innermost(t), mesh.ringCount()) << "triangle " << t << " is not the fan's";
    for (size_t t = 1; t < result.indices.size() / 3; ++t)
      ASSERT_LE(innermost(t), innermost(t - 1)) << "triangle " << t << " is nearer than the one before";
    EXPECT_EQ(innermost(result.indices.size() / 3 - 1), 41u) << "the last band is the outermost, 40..41";
    // Each band's run starts where bandFirstIndex says and holds that band's triangles only (the
    // terrain pass draws runs of bands with pipelines of their own).
    ASSERT_EQ(result.bandFirstIndex.size(), 260u);
    EXPECT_EQ(result.bandFirstIndex.back(), 3 * n) << "band 299 follows the fan";
    for (uint32_t b = 40; b < 300; ++b) {
      const size_t begin = result.bandFirstIndex[b - 40];
      const size_t end = b > 40 ? result.bandFirstIndex[b - 41] : result.indices.size();
      ASSERT_EQ(begin % 3, 0u);
      ASSERT_LE(begin, end);
      for (size_t t = begin / 3; t < end / 3; ++t)
        ASSERT_EQ(innermost(t), b + 1) << "triangle " << t << " of band " << b;
    }
  }
}

TEST(ClipmapCulling, BadRangesThrow) {
  const ClipmapMesh mesh = buildClipmapMesh({8, 8, 64});
  const ClipmapCullView view = viewFrom(1000.0, 0.0, 0.0, 0.0, 0.0);
  EXPECT_THROW(cullClipmap(mesh, 10, 5, view, 64), Error);
  EXPECT_THROW(cullClipmap(mesh, 0, mesh.ringCount(), view, 64), Error);
  EXPECT_THROW(cullClipmap(mesh, 0, 10, view, 0), Error);
}

}  // namespace
}  // namespace planet::test

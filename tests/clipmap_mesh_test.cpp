// The spherical clipmap hemisphere mesh (Clasen & Hege 2006; Hayes-McCoy 2010 §4.3–4.4):
// counts, ring spacing, vertex data, triangle orientation and topology, the φ seam, the pole
// fan, ring-band index ranges and parameter validation.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"

#include "core/error.h"
#include "planet/clipmap_mesh.h"

namespace planet {
namespace {

constexpr double kPi = std::numbers::pi;

// Small and large, one ring per level, odd N, the minimum N, many rings per level, and the
// deepest levels (θ ≈ 1e−12 at the innermost ring, where float cos θ is exactly 1).
const std::vector<ClipmapParams> kParamSets = {
    {1, 1, 3}, {2, 1, 3}, {1, 3, 5}, {3, 4, 7}, {5, 8, 64}, {2, 256, 3}, {40, 2, 3}, {18, 16, 128},
};

std::string describe(const ClipmapParams& p) {
  return "L=" + std::to_string(p.levels) + " m=" + std::to_string(p.ringsPerLevel) + " N=" + std::to_string(p.numPhi);
}

using test::errorOf;

glm::dvec3 directionOf(const ClipmapMesh& mesh, uint32_t vertex) {
  const glm::vec4& d = mesh.vertices.at(vertex).direction;
  return glm::dvec3(d.x, d.y, d.z);
}

// Distance between two angles on the circle, in [0, π].
double circularDistance(double a, double b) {
  double d = std::fmod(std::abs(a - b), 2.0 * kPi);
  return std::min(d, 2.0 * kPi - d);
}

// The band a triangle belongs to: the smallest ring index among its vertices (the pole counts as
// ring R), so quads between rings b and b+1 are band b and the pole fan is band R−1.
uint32_t bandOfTriangle(const ClipmapMesh& mesh, uint32_t triangle) {
  uint32_t band = mesh.poleRing();
  for (uint32_t c = 0; c < 3; ++c) band = std::min(band, mesh.vertices[mesh.indices[3 * triangle + c]].ring);
  return band;
}

TEST(ClipmapMesh, VertexIsTwoVec4sWithTheDocumentedOffsets) {
  EXPECT_EQ(sizeof(ClipmapVertex) % 16, 0u);
  EXPECT_EQ(offsetof(ClipmapVertex, direction), 0u);
  EXPECT_EQ(offsetof(ClipmapVertex, theta), 16u);
  EXPECT_EQ(offsetof(ClipmapVertex, phi), 20u);
  EXPECT_EQ(offsetof(ClipmapVertex, ring), 24u);
  EXPECT_EQ(offsetof(ClipmapVertex, level), 28u);
}

TEST(ClipmapMesh, VertexAndTriangleCountsMatchTheFormulas) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    ClipmapMesh mesh = buildClipmapMesh(p);
    uint32_t rings = p.levels * p.ringsPerLevel;
    EXPECT_EQ(mesh.ringCount(), rings);
    EXPECT_EQ(mesh.vertexCount(), rings * p.numPhi + 1);
    EXPECT_EQ(mesh.triangleCount(), 2 * p.numPhi * (rings - 1) + p.numPhi);
    EXPECT_EQ(mesh.indexCount(), 3 * mesh.triangleCount());
    EXPECT_EQ(mesh.vertices.size(), mesh.vertexCount());
    EXPECT_EQ(mesh.indices.size(), mesh.indexCount());
    for (uint32_t index : mesh.indices) ASSERT_LT(index, mesh.vertexCount());
  }
  // Defaults: 288 rings of 128 vertices plus the pole; 287 bands of 256 triangles plus a fan of 128.
  ClipmapParams defaults;
  EXPECT_EQ(clipmapVertexCount(defaults), 36865u);
  EXPECT_EQ(clipmapTriangleCount(defaults), 73600u);
}

TEST(ClipmapMesh, RingThetaIsPiTimesTwoToMinusLevelTimesTwoToMinusJOverM) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    uint32_t rings = clipmapRingCount(p);
    for (uint32_t k = 0; k < rings; ++k) {
      uint32_t level = k / p.ringsPerLevel + 1, j = k % p.ringsPerLevel;
      double expected = kPi * std::pow(2.0, -double(level)) * std::pow(2.0, -double(j) / double(p.ringsPerLevel));
      ASSERT_NEAR(clipmapRingTheta(p, k), expected, 1e-14 * expected) << "ring " << k;
      // The same ring seen as one geometric progression from the rim.
      ASSERT_NEAR(clipmapRingTheta(p, k), 0.5 * kPi * std::pow(2.0, -double(k) / double(p.ringsPerLevel)),
                  1e-14 * expected);
      ASSERT_EQ(clipmapLevelOfRing(p, k), level);
    }
    EXPECT_EQ(clipmapRingTheta(p, 0), 0.5 * kPi);  // the rim
    EXPECT_EQ(clipmapRingTheta(p, rings), 0.0);    // the pole
    EXPECT_EQ(clipmapLevelOfRing(p, rings), p.levels);
  }
}

TEST(ClipmapMesh, ConsecutiveRingsHaveTheConstantRatioTwoToMinusOneOverM) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    double ratio = std::pow(2.0, -1.0 / double(p.ringsPerLevel));
    for (uint32_t k = 0; k + 1 < clipmapRingCount(p); ++k)
      ASSERT_NEAR(clipmapRingTheta(p, k + 1) / clipmapRingTheta(p, k), ratio, 1e-13) << "ring " << k;
  }
}

TEST(ClipmapMesh, VerticesAreUnitDirectionsAtTheirRingThetaAndPhi) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    ClipmapMesh mesh = buildClipmapMesh(p);
    for (uint32_t k = 0; k < mesh.ringCount(); ++k) {
      double theta = mesh.ringTheta(k);
      for (uint32_t i = 0; i < p.numPhi; ++i) {
        uint32_t index = mesh.vertexIndex(k, i);
        ASSERT_EQ(index, k * p.numPhi + i);
        const ClipmapVertex& v = mesh.vertices[index];
        ASSERT_EQ(v.ring, k);
        ASSERT_EQ(v.level, k / p.ringsPerLevel + 1);
        ASSERT_EQ(v.direction.w, 1.0f);
        ASSERT_EQ(v.theta, float(theta));
        double phi = 2.0 * kPi * double(i) / double(p.numPhi);
        ASSERT_EQ(v.phi, float(phi));
        glm::dvec3 d = directionOf(mesh, index);
        ASSERT_NEAR(glm::length(d), 1.0, 1e-6);
        // θ from atan2 stays accurate for the tiny θ of deep levels, where acos(z) does not.
        ASSERT_NEAR(std::atan2(std::hypot(d.x, d.y), d.z), theta, 1e-6 * theta + 1e-7) << "ring " << k << " i " << i;
        ASSERT_LT(circularDistance(std::atan2(d.y, d.x), phi), 2e-6) << "ring " << k << " i " << i;
      }
    }
    const ClipmapVertex& pole = mesh.vertices[mesh.poleVertex()];
    EXPECT_EQ(mesh.poleVertex(), mesh.vertexCount() - 1);
    EXPECT_EQ(pole.direction, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
    EXPECT_EQ(pole.theta, 0.0f);
    EXPECT_EQ(pole.ring, mesh.poleRing());
    EXPECT_EQ(pole.level, p.levels);
  }
}

TEST(ClipmapMesh, TrianglesAreNonDegenerateAndCounterClockwiseSeenFromOutside) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    ClipmapMesh mesh = buildClipmapMesh(p);
    for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
      uint32_t ia = mesh.indices[3 * t], ib = mesh.indices[3 * t + 1], ic = mesh.indices[3 * t + 2];
      ASSERT_TRUE(ia != ib && ib != ic && ia != ic) << "triangle " << t << " repeats a vertex";
      glm::dvec3 a = directionOf(mesh, ia), b = directionOf(mesh, ib), c = directionOf(mesh, ic);
      glm::dvec3 normal = glm::cross(b - a, c - a);
      double longestEdge = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
      // Positive area, and not a sliver: twice the area against the longest edge squared.
      ASSERT_GT(glm::length(normal), 1e-6 * longestEdge * longestEdge) << "triangle " << t;
      ASSERT_GT(glm::dot(normal, a + b + c), 0.0) << "triangle " << t << " faces inward";
    }
  }
}

TEST(ClipmapMesh, MeshIsAClosedDiscEveryInnerEdgeSharedByTwoTriangles) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    ClipmapMesh mesh = buildClipmapMesh(p);
    std::map<std::pair<uint32_t, uint32_t>, int> edgeUses;
    std::set<std::pair<uint32_t, uint32_t>> directedEdges;
    std::vector<bool> used(mesh.vertexCount(), false);
    for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
      for (uint32_t c = 0; c < 3; ++c) {
        uint32_t from = mesh.indices[3 * t + c], to = mesh.indices[3 * t + (c + 1) % 3];
        used[from] = true;
        // Consistent orientation: two triangles sharing an edge traverse it in opposite directions.
        ASSERT_TRUE(directedEdges.insert({from, to}).second) << "directed edge " << from << "->" << to << " twice";
        ++edgeUses[{std::min(from, to), std::max(from, to)}];
      }
    }
    for (const auto& [edge, uses] : edgeUses) {
      bool rim = mesh.vertices[edge.first].ring == 0 && mesh.vertices[edge.second].ring == 0;
      ASSERT_EQ(uses, rim ? 1 : 2) << "edge " << edge.first << "-" << edge.second;
    }
    EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));
    long long v = mesh.vertexCount(), e = static_cast<long long>(edgeUses.size()), f = mesh.triangleCount();
    EXPECT_EQ(v - e + f, 1);  // Euler characteristic of a disc
  }
}

TEST(ClipmapMesh, PhiSeamIsClosedWithConcentricRingsNotASpiral) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    ClipmapMesh mesh = buildClipmapMesh(p);
    const double maxStep = 2.0 * kPi / double(p.numPhi) * 1.01;
    std::vector<std::set<std::pair<uint32_t, uint32_t>>> ringEdges(mesh.ringCount());
    for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
      for (uint32_t c = 0; c < 3; ++c) {
        const ClipmapVertex& a = mesh.vertices[mesh.indices[3 * t + c]];
        const ClipmapVertex& b = mesh.vertices[mesh.indices[3 * t + (c + 1) % 3]];
        if (a.ring == mesh.poleRing() || b.ring == mesh.poleRing()) continue;
        uint32_t ringGap = a.ring > b.ring ? a.ring - b.ring : b.ring - a.ring;
        ASSERT_LE(ringGap, 1u) << "triangle " << t << " skips a ring";
        ASSERT_LE(circularDistance(a.phi, b.phi), maxStep) << "triangle " << t;
        if (a.ring == b.ring) {
          uint32_t ia = mesh.indices[3 * t + c] - a.ring * p.numPhi,
                   ib = mesh.indices[3 * t + (c + 1) % 3] - a.ring * p.numPhi;
          ringEdges[a.ring].insert({std::min(ia, ib), std::max(ia, ib)});
        }
      }
    }
    // Every ring is a closed cycle of exactly N edges i—(i+1) mod N, the seam edge (N−1)—0 included.
    for (uint32_t k = 0; k < mesh.ringCount(); ++k) {
      ASSERT_EQ(ringEdges[k].size(), p.numPhi) << "ring " << k;
      for (uint32_t i = 0; i < p.numPhi; ++i) {
        uint32_t j = (i + 1) % p.numPhi;
        ASSERT_EQ(ringEdges[k].count({std::min(i, j), std::max(i, j)}), 1u) << "ring " << k << " edge " << i;
      }
    }
  }
}

TEST(ClipmapMesh, PoleFanHasNumPhiTrianglesAllTouchingThePole) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    ClipmapMesh mesh = buildClipmapMesh(p);
    uint32_t touching = 0;
    std::set<uint32_t> rimOfFan;
    for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
      uint32_t ring[3], vertex[3];
      for (uint32_t c = 0; c < 3; ++c) {
        vertex[c] = mesh.indices[3 * t + c];
        ring[c] = mesh.vertices[vertex[c]].ring;
      }
      bool hasPole = std::count(vertex, vertex + 3, mesh.poleVertex()) == 1;
      if (!hasPole) continue;
      ++touching;
      for (uint32_t c = 0; c < 3; ++c) {
        if (vertex[c] == mesh.poleVertex()) continue;
        EXPECT_EQ(ring[c], mesh.ringCount() - 1) << "fan triangle " << t << " reaches past the innermost ring";
        rimOfFan.insert(vertex[c]);
      }
    }
    EXPECT_EQ(touching, p.numPhi);
    EXPECT_EQ(rimOfFan.size(), p.numPhi);
    // The fan is the last band of the index buffer.
    IndexRange fan = mesh.ringBandRange(mesh.ringCount() - 1, mesh.poleRing());
    EXPECT_EQ(fan.indexCount, 3 * p.numPhi);
    EXPECT_EQ(fan.firstIndex + fan.indexCount, mesh.indexCount());
    for (uint32_t i = fan.firstIndex; i < fan.firstIndex + fan.indexCount; i += 3)
      EXPECT_EQ(std::count(&mesh.indices[i], &mesh.indices[i] + 3, mesh.poleVertex()), 1);
  }
}

TEST(ClipmapMesh, TrianglesAreOrderedByBandFromRimToPole) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    ClipmapMesh mesh = buildClipmapMesh(p);
    for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
      uint32_t band = bandOfTriangle(mesh, t);
      uint32_t expected = t < 2 * p.numPhi * (mesh.ringCount() - 1) ? t / (2 * p.numPhi) : mesh.ringCount() - 1;
      ASSERT_EQ(band, expected) << "triangle " << t;
      for (uint32_t c = 0; c < 3; ++c) {
        uint32_t ring = mesh.vertices[mesh.indices[3 * t + c]].ring;
        ASSERT_TRUE(ring == band || ring == band + 1) << "triangle " << t << " leaves its band";
      }
    }
  }
}

TEST(ClipmapMesh, RingBandRangeSelectsExactlyTheTrianglesBetweenTheRings) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    ClipmapMesh mesh = buildClipmapMesh(p);
    const uint32_t pole = mesh.poleRing();
    std::vector<uint32_t> bands(mesh.triangleCount());
    for (uint32_t t = 0; t < mesh.triangleCount(); ++t) bands[t] = bandOfTriangle(mesh, t);
    // All pairs for small meshes; a spread including the rim, the pole and level boundaries otherwise.
    std::vector<uint32_t> rings;
    if (pole <= 16) {
      for (uint32_t k = 0; k <= pole; ++k) rings.push_back(k);
    } else {
      rings = {0, 1, p.ringsPerLevel - 1, p.ringsPerLevel, pole / 2, pole - 2, pole - 1, pole};
    }
    for (uint32_t first : rings) {
      for (uint32_t last : rings) {
        if (first > last) continue;
        IndexRange range = mesh.ringBandRange(first, last);
        ASSERT_EQ(range.firstIndex % 3, 0u);
        ASSERT_EQ(range.indexCount % 3, 0u);
        ASSERT_LE(range.firstIndex + range.indexCount, mesh.indexCount());
        uint32_t begin = range.firstIndex / 3, end = begin + range.indexCount / 3;
        for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
          bool inRange = t >= begin && t < end;
          bool wanted = bands[t] >= first && bands[t] < last;
          ASSERT_EQ(inRange, wanted) << "rings " << first << ".." << last << " triangle " << t;
        }
      }
    }
    IndexRange all = mesh.ringBandRange(0, pole);
    EXPECT_EQ(all.firstIndex, 0u);
    EXPECT_EQ(all.indexCount, mesh.indexCount());
  }
}

// Linear-scan definitions of the two ring lookups, over rings 0..R with the pole at θ = 0.
uint32_t bruteInnermostAtOrAbove(const ClipmapParams& p, double theta) {
  uint32_t best = 0;
  for (uint32_t k = 0; k <= clipmapRingCount(p); ++k)
    if (clipmapRingTheta(p, k) >= theta) best = k;
  return best;
}

uint32_t bruteOutermostAtOrBelow(const ClipmapParams& p, double theta) {
  for (uint32_t k = 0; k <= clipmapRingCount(p); ++k)
    if (clipmapRingTheta(p, k) <= theta) return k;
  return clipmapRingCount(p);
}

TEST(ClipmapMesh, RingLookupsAgreeWithALinearScan) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    const uint32_t pole = clipmapRingCount(p);
    for (uint32_t k = 0; k <= pole; ++k) {
      double theta = clipmapRingTheta(p, k);
      ASSERT_EQ(clipmapInnermostRingAtOrAbove(p, theta), k);
      ASSERT_EQ(clipmapOutermostRingAtOrBelow(p, theta), k);
      if (k > 0 && k < pole) {
        ASSERT_EQ(clipmapInnermostRingAtOrAbove(p, theta * (1.0 + 1e-12)), k - 1);
        ASSERT_EQ(clipmapOutermostRingAtOrBelow(p, theta * (1.0 - 1e-12)), k + 1);
      }
    }
    for (int s = 0; s <= 2000; ++s) {
      double theta = 2.0 * std::pow(1e-14, double(s) / 2000.0);  // 2 .. 2e−14, geometric
      ASSERT_EQ(clipmapInnermostRingAtOrAbove(p, theta), bruteInnermostAtOrAbove(p, theta)) << theta;
      ASSERT_EQ(clipmapOutermostRingAtOrBelow(p, theta), bruteOutermostAtOrBelow(p, theta)) << theta;
    }
    EXPECT_EQ(clipmapInnermostRingAtOrAbove(p, 0.0), pole);
    EXPECT_EQ(clipmapInnermostRingAtOrAbove(p, -1.0), pole);
    EXPECT_EQ(clipmapInnermostRingAtOrAbove(p, 3.0), 0u);
    EXPECT_EQ(clipmapOutermostRingAtOrBelow(p, 0.0), pole);
    EXPECT_EQ(clipmapOutermostRingAtOrBelow(p, -1.0), pole);
    EXPECT_EQ(clipmapOutermostRingAtOrBelow(p, 3.0), 0u);
  }
}

TEST(ClipmapMesh, ThetaBandRangeCoversTheRequestedThetaWithTheFewestBands) {
  for (const ClipmapParams& p : kParamSets) {
    SCOPED_TRACE(describe(p));
    const uint32_t pole = clipmapRingCount(p);
    IndexRange all = clipmapThetaBandRange(p, 0.0, 0.5 * kPi);
    EXPECT_EQ(all.firstIndex, 0u);
    EXPECT_EQ(all.indexCount, clipmapIndexCount(p));
    for (double thetaMin : {0.0, 1e-9, 1e-3, 0.05, 0.3, 1.0, 1.5707}) {
      for (double thetaMax : {1e-9, 1e-3, 0.05, 0.3, 1.0, 1.5707, 0.5 * kPi, 2.0}) {
        if (thetaMin > thetaMax) continue;
        IndexRange range = clipmapThetaBandRange(p, thetaMin, thetaMax);
        uint32_t outer = bruteInnermostAtOrAbove(p, thetaMax), inner = bruteOutermostAtOrBelow(p, thetaMin);
        IndexRange expected = clipmapRingBandRange(p, outer, inner);
        ASSERT_EQ(range.firstIndex, expected.firstIndex) << thetaMin << " " << thetaMax;
        ASSERT_EQ(range.indexCount, expected.indexCount) << thetaMin << " " << thetaMax;
        // Coverage: the outer ring lies at or beyond thetaMax (or is the rim), the inner ring at
        // or inside thetaMin; one band fewer on either side would not cover.
        EXPECT_TRUE(clipmapRingTheta(p, outer) >= thetaMax || outer == 0);
        EXPECT_LE(clipmapRingTheta(p, inner), thetaMin);
        if (outer < pole) {
          EXPECT_LT(clipmapRingTheta(p, outer + 1), thetaMax);
        }
        if (inner > 0) {
          EXPECT_GT(clipmapRingTheta(p, inner - 1), thetaMin);
        }
        EXPECT_EQ(range.firstIndex + range.indexCount == clipmapIndexCount(p) && range.indexCount > 0,
                  thetaMin < clipmapRingTheta(p, pole - 1));  // the fan only when the range reaches inside ring R−1
      }
    }
  }
}

TEST(ClipmapMesh, BadParametersThrowNamingTheParameterAndValue) {
  struct Case {
    ClipmapParams params;
    const char* message;
  };
  const Case cases[] = {
      {{0, 16, 128}, "levels must be in 1..40, got 0"},
      {{41, 16, 128}, "levels must be in 1..40, got 41"},
      {{18, 0, 128}, "ringsPerLevel must be in 1..256, got 0"},
      {{18, 257, 128}, "ringsPerLevel must be in 1..256, got 257"},
      {{18, 16, 2}, "numPhi must be in 3..4096, got 2"},
      {{18, 16, 0}, "numPhi must be in 3..4096, got 0"},
      {{18, 16, 4097}, "numPhi must be in 3..4096, got 4097"},
  };
  for (const Case& c : cases) {
    std::string message = errorOf([&] { buildClipmapMesh(c.params); });
    EXPECT_NE(message.find(c.message), std::string::npos) << "got '" << message << "', wanted '" << c.message << "'";
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  EXPECT_EQ(errorOf([] { validateClipmapParams({1, 1, 3}); }), "");
  EXPECT_EQ(errorOf([] {
              validateClipmapParams({kClipmapMaxLevels, kClipmapMaxRingsPerLevel, kClipmapMaxNumPhi});
            }),
            "");
}

TEST(ClipmapMesh, OutOfRangeRingsAndThetasThrow) {
  ClipmapParams p{2, 3, 8};  // rings 0..5, pole 6
  EXPECT_NE(errorOf([&] { clipmapRingTheta(p, 7); }).find("ring 7 is out of range 0..6"), std::string::npos);
  EXPECT_NE(errorOf([&] { clipmapLevelOfRing(p, 7); }).find("ring 7"), std::string::npos);
  EXPECT_NE(errorOf([&] { clipmapRingBandRange(p, 0, 7); }).find("lastRing 7"), std::string::npos);
  EXPECT_NE(errorOf([&] { clipmapRingBandRange(p, 4, 3); }).find("firstRing 4 is after lastRing 3"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { clipmapThetaBandRange(p, 0.5, 0.25); }).find("thetaMin"), std::string::npos);
  EXPECT_NE(errorOf([&] { clipmapInnermostRingAtOrAbove(p, std::nan("")); }).find("NaN"), std::string::npos);
  EXPECT_NE(errorOf([&] { clipmapOutermostRingAtOrBelow(p, std::nan("")); }).find("NaN"), std::string::npos);
  EXPECT_NE(errorOf([&] { clipmapThetaBandRange(p, std::nan(""), 1.0); }).find("NaN"), std::string::npos);
  EXPECT_EQ(clipmapRingBandRange(p, 3, 3).indexCount, 0u);
}

}  // namespace
}  // namespace planet

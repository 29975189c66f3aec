// Planetary rings on the CPU (issue 8, point 3): every bad field of a ring description as one
// line naming it, the TOML ring table (good, unknown keys, wrong types, values out of range with
// their line), and the CPU reference of the density (seed 001 Algorithm 3): deterministic,
// seeded, within [0, 1], zero outside the annulus, with gaps and dense bands, octaves fading
// with the footprint, and the two shadows' geometry.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "reference/ring_density.h"
#include "planet/ring_description.h"
#include "test_support.h"

namespace planet {
namespace {

using test::errorOf;

constexpr double kSaturnRadiusM = 5.8232e7;
constexpr double kSun = 0.0075;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string validationError(const RingDescription& ring) {
  const std::string message = errorOf([&] { validateRingDescription(ring); });
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  return message;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(RingDescription, DefaultsAreValidAndSaturnLike) {
  const RingDescription ring;
  EXPECT_EQ(validationError(ring), "");
  EXPECT_GT(ring.innerRadiusM, kSaturnRadiusM);
  EXPECT_EQ(ring.octaves, 10u) << "seed 001: ten octaves";
  // Pale tan: red above green above blue.
  EXPECT_GT(ring.colour.r, ring.colour.g);
  EXPECT_GT(ring.colour.g, ring.colour.b);
}

TEST(RingDescription, EveryBadFieldIsNamed) {
  struct Case {
    const char* expected;
    void (*edit)(RingDescription&);
  } cases[] = {
      {"inner_radius_m must be a positive finite number of metres, got 0",
       [](RingDescription& r) { r.innerRadiusM = 0.0; }},
      {"inner_radius_m must be a positive finite number of metres, got -5",
       [](RingDescription& r) { r.innerRadiusM = -5.0; }},
      {"inner_radius_m must be a positive finite number of metres, got nan",
       [](RingDescription& r) { r.innerRadiusM = kNaN; }},
      {"outer_radius_m must be a positive finite number of metres, got inf",
       [](RingDescription& r) { r.outerRadiusM = kInf; }},
      {"inner_radius_m (2e+08) must be below outer_radius_m (1.368e+08)",
       [](RingDescription& r) { r.innerRadiusM = 2e8; }},
      {"inner_radius_m (1.368e+08) must be below outer_radius_m (1.368e+08)",
       [](RingDescription& r) { r.innerRadiusM = r.outerRadiusM; }},
      {"ring width", [](RingDescription& r) { r.innerRadiusM = r.outerRadiusM - 1.0; }},
      {"colour[1] must be in [0, 1], got 1.5", [](RingDescription& r) { r.colour.g = 1.5; }},
      {"colour[0] must be in [0, 1], got nan", [](RingDescription& r) { r.colour.r = kNaN; }},
      {"colour_variation[2] must be in [0, 1], got -0.1", [](RingDescription& r) { r.colourVariation.b = -0.1; }},
      {"opacity must be in [0, 1], got 1.01", [](RingDescription& r) { r.opacity = 1.01; }},
      {"opacity must be in [0, 1], got nan", [](RingDescription& r) { r.opacity = kNaN; }},
      {"octaves must be in 1..16, got 0", [](RingDescription& r) { r.octaves = 0; }},
      {"octaves must be in 1..16, got 17", [](RingDescription& r) { r.octaves = 17; }},
      {"gaps must be in 0..4, got 5", [](RingDescription& r) { r.gaps = 5; }},
  };
  for (const Case& c : cases) {
    RingDescription ring;
    c.edit(ring);
    const std::string message = validationError(ring);
    EXPECT_TRUE(contains(message, c.expected)) << "expected '" << c.expected << "', got '" << message << "'";
    EXPECT_TRUE(message.starts_with("ring ")) << message;
  }
  // The edges of the ranges are allowed.
  RingDescription edges;
  edges.colour = glm::dvec3(0.0);
  edges.colourVariation = glm::dvec3(1.0);
  edges.opacity = 0.0;
  edges.octaves = 16;
  edges.gaps = 4;
  EXPECT_EQ(validationError(edges), "");
  edges.opacity = 1.0;
  edges.octaves = 1;
  edges.gaps = 0;
  EXPECT_EQ(validationError(edges), "");
}

TEST(RingDescription, GpuParamsCheckTheBodyAndTheSun) {
  const RingDescription ring;
  const gpu::RingParams p = ringGpuParams(ring, kSaturnRadiusM, kSun);
  EXPECT_FLOAT_EQ(p.radii.x, float(ring.innerRadiusM));
  EXPECT_FLOAT_EQ(p.radii.y, float(ring.outerRadiusM));
  EXPECT_FLOAT_EQ(p.radii.z, float(1.0 / (ring.outerRadiusM - ring.innerRadiusM)));
  EXPECT_FLOAT_EQ(p.radii.w, float(kSaturnRadiusM));
  EXPECT_EQ(p.octaves, 10u);
  EXPECT_EQ(p.gapCount, 2u);
  for (uint32_t g = 0; g < p.gapCount; ++g) {
    EXPECT_GE(p.gaps[g].x, 0.2f);
    EXPECT_LE(p.gaps[g].x, 0.8f);
    EXPECT_GT(p.gaps[g].y, 0.0f);
    EXPECT_GT(p.gaps[g].z, 0.85f);
  }
  EXPECT_TRUE(contains(errorOf([&] { ringGpuParams(ring, 0.0, kSun); }), "ringed body radius"));
  EXPECT_TRUE(contains(errorOf([&] { ringGpuParams(ring, kNaN, kSun); }), "got nan"));
  EXPECT_TRUE(contains(errorOf([&] { ringGpuParams(ring, kSaturnRadiusM, -1.0); }), "sun angular radius"));
  RingDescription bad;
  bad.octaves = 0;
  EXPECT_TRUE(contains(errorOf([&] { ringGpuParams(bad, kSaturnRadiusM, kSun); }), "octaves"));
}

// --- TOML -----------------------------------------------------------------------------------------

// Line 1 is the header, then one key per line.
constexpr std::string_view kRingToml = R"([rings]
inner_radius_m = 92_000_000
outer_radius_m = 1.2e8
seed = 4000000000
colour = [0.7, 0.6, 0.5]
colour_variation = [0.3, 0.3, 0]
opacity = 0.8
octaves = 8
gaps = 1
)";

std::string edited(std::string_view from, std::string_view to) {
  std::string out(kRingToml);
  const size_t at = out.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) out.replace(at, from.size(), to);
  return out;
}

RingDescription parseRings(std::string_view text) {
  const toml::table root = toml::parse(text, std::string_view("scene.toml"));
  return parseRingTable(*root["rings"].as_table(), "scene.toml");
}

std::string tomlError(std::string_view text) {
  const std::string message = errorOf([&] { parseRings(text); });
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  return message;
}

TEST(RingToml, GoodTableIsReadExactly) {
  const RingDescription ring = parseRings(kRingToml);
  EXPECT_EQ(ring.innerRadiusM, 9.2e7);
  EXPECT_EQ(ring.outerRadiusM, 1.2e8);
  EXPECT_EQ(ring.seed, 4000000000u);
  EXPECT_EQ(ring.colour, glm::dvec3(0.7, 0.6, 0.5));
  EXPECT_EQ(ring.colourVariation, glm::dvec3(0.3, 0.3, 0.0));
  EXPECT_EQ(ring.opacity, 0.8);
  EXPECT_EQ(ring.octaves, 8u);
  EXPECT_EQ(ring.gaps, 1u);
}

TEST(RingToml, AnEmptyTableGivesTheDefaults) {
  const RingDescription ring = parseRings("[rings]\n");
  const RingDescription defaults;
  EXPECT_EQ(ring.innerRadiusM, defaults.innerRadiusM);
  EXPECT_EQ(ring.outerRadiusM, defaults.outerRadiusM);
  EXPECT_EQ(ring.seed, defaults.seed);
  EXPECT_EQ(ring.colour, defaults.colour);
  EXPECT_EQ(ring.octaves, defaults.octaves);
}

TEST(RingToml, UnknownKeysAreErrorsNamingTheKey) {
  EXPECT_EQ(tomlError(edited("opacity = 0.8", "opacty = 0.8")), "scene.toml:7: unknown key 'opacty' in the ring table");
  EXPECT_EQ(tomlError(edited("gaps = 1", "color = [1, 1, 1]")), "scene.toml:9: unknown key 'color' in the ring table");
}

TEST(RingToml, WrongTypesNameTheKeyAndTheType) {
  EXPECT_EQ(tomlError(edited("opacity = 0.8", "opacity = \"high\"")),
            "scene.toml:7: 'opacity' must be a number, got string");
  EXPECT_EQ(tomlError(edited("octaves = 8", "octaves = 8.5")), "scene.toml:8: 'octaves' must be an integer, got float");
  EXPECT_EQ(tomlError(edited("seed = 4000000000", "seed = true")),
            "scene.toml:4: 'seed' must be an integer, got boolean");
  EXPECT_EQ(tomlError(edited("colour = [0.7, 0.6, 0.5]", "colour = 0.7")),
            "scene.toml:5: 'colour' must be an array of 3 numbers [r, g, b], got float");
  EXPECT_EQ(tomlError(edited("colour = [0.7, 0.6, 0.5]", "colour = [0.7, 0.6]")),
            "scene.toml:5: 'colour' must be an array of 3 numbers [r, g, b], got 2 elements");
  EXPECT_EQ(tomlError(edited("colour_variation = [0.3, 0.3, 0]", "colour_variation = [0.3, \"x\", 0]")),
            "scene.toml:6: colour_variation[1] must be a number, got string");
  EXPECT_EQ(tomlError(edited("inner_radius_m = 92_000_000", "inner_radius_m = [1]")),
            "scene.toml:2: 'inner_radius_m' must be a number, got array");
}

TEST(RingToml, BadValuesNameTheFieldAtItsLine) {
  EXPECT_EQ(tomlError(edited("seed = 4000000000", "seed = -1")),
            "scene.toml:4: seed must be in [0, 4294967295], got -1");
  EXPECT_EQ(tomlError(edited("seed = 4000000000", "seed = 4294967296")),
            "scene.toml:4: seed must be in [0, 4294967295], got 4294967296");
  EXPECT_EQ(tomlError(edited("opacity = 0.8", "opacity = 2")), "scene.toml:7: opacity must be in [0, 1], got 2");
  EXPECT_EQ(tomlError(edited("octaves = 8", "octaves = 0")), "scene.toml:8: octaves must be in [1, 16], got 0");
  EXPECT_EQ(tomlError(edited("gaps = 1", "gaps = 9")), "scene.toml:9: gaps must be in [0, 4], got 9");
  EXPECT_EQ(tomlError(edited("outer_radius_m = 1.2e8", "outer_radius_m = 9e7")),
            "scene.toml:2: ring inner_radius_m (9.2e+07) must be below outer_radius_m (9e+07)");
  EXPECT_EQ(tomlError(edited("outer_radius_m = 1.2e8", "outer_radius_m = nan")),
            "scene.toml:3: outer_radius_m must be a finite number, got nan");
  EXPECT_EQ(tomlError(edited("colour_variation = [0.3, 0.3, 0]", "colour_variation = [0.3, 0.3, 3]")),
            "scene.toml:6: colour_variation[2] must be in [0, 1], got 3");
  EXPECT_EQ(tomlError(edited("colour = [0.7, 0.6, 0.5]", "colour = [0.7, -1, 0.5]")),
            "scene.toml:5: colour[1] must be in [0, 1], got -1");
  // A table built in code has no lines: the message starts with `where` alone.
  toml::table table;
  table.insert("opacity", -0.5);
  EXPECT_EQ(errorOf([&] { parseRingTable(table, "preset [bodies.rings]"); }),
            "preset [bodies.rings]: opacity must be in [0, 1], got -0.5");
}

// --- The density --------------------------------------------------------------------------------

gpu::RingParams saturnParams(uint32_t seed = 1) {
  RingDescription ring;
  ring.seed = seed;
  return ringGpuParams(ring, kSaturnRadiusM, kSun);
}

constexpr int kSamples = 4000;
float uAt(int i) { return (float(i) + 0.5f) / float(kSamples); }

TEST(RingDensity, IsDeterministicAndDependsOnTheSeed) {
  const gpu::RingParams a = saturnParams(1), b = saturnParams(2);
  int differ = 0;
  for (int i = 0; i < kSamples; ++i) {
    const float u = uAt(i);
    EXPECT_EQ(ringSampleCpu(a, u), ringSampleCpu(saturnParams(1), u));
    if (std::abs(ringOpacityCpu(a, u) - ringOpacityCpu(b, u)) > 0.05f) ++differ;
  }
  EXPECT_GT(differ, kSamples / 3) << "seeds 1 and 2 give nearly the same ring";
}

TEST(RingDensity, OpacityAndColourStayInRange) {
  for (uint32_t seed = 0; seed < 20; ++seed) {
    const gpu::RingParams p = saturnParams(seed);
    for (int i = -10; i < kSamples + 10; ++i) {
      for (float footprint : {0.0f, 1e-3f, 0.1f, 1.0f}) {
        const glm::vec4 s = ringSampleCpu(p, uAt(i), footprint);
        ASSERT_GE(s.a, 0.0f) << seed << " " << uAt(i);
        ASSERT_LE(s.a, 1.0f) << seed << " " << uAt(i);
        if (!(uAt(i) > 0.0f && uAt(i) < 1.0f)) {
          ASSERT_EQ(s, glm::vec4(0.0f)) << "outside the ring: nothing";
          continue;
        }
        for (int c = 0; c < 3; ++c) {
          // Between the two colours.
          ASSERT_GE(s[c], std::min(p.colour[c], p.variation[c]) - 1e-6f);
          ASSERT_LE(s[c], std::max(p.colour[c], p.variation[c]) + 1e-6f);
        }
      }
    }
  }
}

TEST(RingDensity, IsZeroOutsideTheAnnulusAndFadesAtBothEdges) {
  const gpu::RingParams p = saturnParams();
  const RingDescription ring;
  for (double r :
       {0.0, 1e7, ring.innerRadiusM - 1.0, ring.innerRadiusM, ring.outerRadiusM, ring.outerRadiusM + 1.0, 3e8, 1e12})
    EXPECT_EQ(ringOpacityAtRadiusCpu(p, r), 0.0f) << r;
  for (float u :
       {-1.0f, 0.0f, 1.0f, 2.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()})
    EXPECT_EQ(ringOpacityCpu(p, u), 0.0f) << u;
  // Within the first and last 0.2 % of the width it is nearly transparent, whatever the noise.
  for (uint32_t seed = 0; seed < 20; ++seed) {
    const gpu::RingParams s = saturnParams(seed);
    EXPECT_LT(ringOpacityCpu(s, 0.002f), 0.03f) << seed;
    EXPECT_LT(ringOpacityCpu(s, 0.998f), 0.03f) << seed;
  }
}

TEST(RingDensity, HasGapsAndDenseBands) {
  for (uint32_t seed : {1u, 2u, 3u, 77u}) {
    const gpu::RingParams p = saturnParams(seed);
    int gaps = 0, dense = 0;
    for (int i = 0; i < kSamples; ++i) {
      const float a = ringOpacityCpu(p, uAt(i));
      gaps += a < 0.1f ? 1 : 0;
      dense += a > 0.5f ? 1 : 0;
    }
    std::printf("seed %u: %.0f %% below 0.1, %.0f %% above 0.5\n", seed, 100.0 * gaps / kSamples,
                100.0 * dense / kSamples);
    EXPECT_GT(gaps, kSamples / 20) << seed;
    EXPECT_GT(dense, kSamples / 50) << seed;
    // The seeded gaps are nearly empty at their centres.
    for (uint32_t g = 0; g < p.gapCount; ++g) EXPECT_LT(ringOpacityCpu(p, p.gaps[g].x), 0.1f) << seed << " gap " << g;
  }
}

TEST(RingDensity, OpacityScalesWithTheDescription) {
  RingDescription half;
  half.opacity = 0.5;
  const gpu::RingParams full = saturnParams(), scaled = ringGpuParams(half, kSaturnRadiusM, kSun);
  for (int i = 0; i < kSamples; i += 37)
    EXPECT_FLOAT_EQ(ringOpacityCpu(scaled, uAt(i)), 0.5f * ringOpacityCpu(full, uAt(i)));
  half.opacity = 0.0;
  const gpu::RingParams none = ringGpuParams(half, kSaturnRadiusM, kSun);
  for (int i = 0; i < kSamples; i += 37) EXPECT_EQ(ringOpacityCpu(none, uAt(i)), 0.0f);
}

TEST(RingDensity, FinerOctavesFadeWithTheFootprint) {
  // The opacity's roughness (mean |Δα| between neighbours 1/40,000 apart) falls as the
  // footprint grows: octaves finer than the pixel are left out. A footprint of 0 keeps them all.
  const gpu::RingParams p = saturnParams();
  auto roughness = [&](float footprint) {
    double sum = 0.0;
    for (int i = 0; i < 40000; ++i) {
      const float u = 0.1f + 0.8f * float(i) / 40000.0f;
      sum += std::abs(ringOpacityCpu(p, u + 2e-5f, footprint) - ringOpacityCpu(p, u, footprint));
    }
    return sum;
  };
  const double sharp = roughness(0.0f), medium = roughness(2e-3f), coarse = roughness(0.05f);
  std::printf("roughness: footprint 0: %.4f, 2e-3: %.4f, 0.05: %.4f\n", sharp, medium, coarse);
  EXPECT_GT(sharp, medium * 1.05);
  EXPECT_GT(medium, coarse * 1.05);
  // Tiny footprints change nothing (every octave's cells span more than 4 of them).
  for (int i = 0; i < kSamples; i += 13) EXPECT_EQ(ringOpacityCpu(p, uAt(i), 1e-5f), ringOpacityCpu(p, uAt(i), 0.0f));
}

TEST(RingDensity, SlantPathsAreMoreOpaque) {
  for (float alpha : {0.0f, 0.1f, 0.5f, 0.9f, 1.0f}) {
    EXPECT_NEAR(ringSlantOpacityCpu(alpha, 1.0f), alpha, 1e-6f);
    EXPECT_NEAR(ringSlantOpacityCpu(alpha, -1.0f), alpha, 1e-6f) << "either side";
    EXPECT_GE(ringSlantOpacityCpu(alpha, 0.3f), alpha);
    EXPECT_LE(ringSlantOpacityCpu(alpha, 0.3f), 1.0f);
    EXPECT_TRUE(std::isfinite(ringSlantOpacityCpu(alpha, 0.0f)));
  }
  // 1 − (1 − 0.5)^2 at 60° from the normal.
  EXPECT_NEAR(ringSlantOpacityCpu(0.5f, 0.5f), 0.75f, 1e-6f);
}

TEST(RingShadow, FallsOnlyWhereTheSunRayCrossesTheRing) {
  const gpu::RingParams p = saturnParams();
  const RingDescription ring;
  const glm::vec3 sun =
      glm::normalize(glm::vec3(0.0f, 0.8f, 0.6f));  // north of the ring plane, low enough to reach past it
  // A point on the southern hemisphere looks at the sun through the ring's plane: its shadow is
  // 1 − slant opacity at the crossing's radius.
  int shaded = 0, checked = 0;
  for (int i = 0; i < 400; ++i) {
    const double lat = -0.05 - 1.4 * i / 400.0;
    const glm::dvec3 point = kSaturnRadiusM * glm::dvec3(0.0, std::cos(lat), std::sin(lat));
    const double t = -point.z / double(sun.z);
    const glm::dvec3 hit = point + t * glm::dvec3(sun);
    const double r = std::hypot(hit.x, hit.y);
    const float shadow = ringShadowCpu(glm::vec3(point), sun, p);
    ASSERT_GE(shadow, 0.0f);
    ASSERT_LE(shadow, 1.0f);
    if (r < ring.innerRadiusM || r > ring.outerRadiusM) {
      EXPECT_EQ(shadow, 1.0f) << lat;
    } else {
      ++checked;
      if (shadow < 0.5f) ++shaded;
    }
  }
  EXPECT_GT(checked, 20);
  EXPECT_GT(shaded, 0) << "the dense bands cast no shadow";
  // On the sun's side of the plane nothing is in the way.
  for (double lat : {0.01, 0.5, 1.5}) {
    const glm::dvec3 point = kSaturnRadiusM * glm::dvec3(0.0, std::cos(lat), std::sin(lat));
    EXPECT_EQ(ringShadowCpu(glm::vec3(point), sun, p), 1.0f) << lat;
  }
  // A sun in the ring plane never crosses it.
  EXPECT_EQ(ringShadowCpu(glm::vec3(0.0f, 0.0f, -float(kSaturnRadiusM)), glm::vec3(1.0f, 0.0f, 0.0f), p), 1.0f);
}

TEST(RingShadow, ThePlanetShadowsTheRingBehindIt) {
  const gpu::RingParams p = saturnParams();
  const glm::vec3 sun = glm::normalize(glm::vec3(1.0f, 0.0f, 0.25f));
  const float r = 1.0e8f;
  EXPECT_EQ(ringPlanetShadowCpu(glm::vec3(r, 0.0f, 0.0f), sun, p), 1.0f) << "the sunward side";
  EXPECT_EQ(ringPlanetShadowCpu(glm::vec3(-r, 0.0f, 0.0f), sun, p), 0.0f) << "straight behind the planet";
  EXPECT_EQ(ringPlanetShadowCpu(glm::vec3(-r, 1.5f * float(kSaturnRadiusM), 0.0f), sun, p), 1.0f)
      << "beside the shadow";
  // The penumbra is smooth: the visible fraction rises monotonically across the edge.
  float previous = 0.0f;
  for (int i = 0; i <= 100; ++i) {
    const float y = float(kSaturnRadiusM) * (0.9f + 0.2f * float(i) / 100.0f);
    const float v = ringPlanetShadowCpu(glm::vec3(-r, y, 0.0f), sun, p);
    EXPECT_GE(v, previous - 1e-6f) << y;
    previous = v;
  }
  EXPECT_EQ(previous, 1.0f);
}

}  // namespace
}  // namespace planet

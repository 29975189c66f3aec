// Scenes of several bodies (issue 8, points 1, 2 and 6): Kepler orbits against closed-form
// values, body spin, the built-in scene, and every class of bad scene input as one line.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "planet/orbit.h"
#include "planet/scene_description.h"
#include "test_support.h"

namespace planet {
namespace {

constexpr double kPi = std::numbers::pi;

std::string errorOf(auto&& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Orbit, CircularOrbitIsACircleTravelledAtConstantSpeed) {
  OrbitElements o;
  o.semiMajorAxisM = 4.0e8;
  o.periodS = 1000.0;
  for (double t : {0.0, 125.0, 250.0, 333.0, 500.0, 999.0, 1e6 + 17.0}) {
    const double angle = 2.0 * kPi * t / o.periodS;
    const glm::dvec3 p = orbitPosition(o, t);
    EXPECT_NEAR(p.x, o.semiMajorAxisM * std::cos(angle), 1e-6 * o.semiMajorAxisM) << t;
    EXPECT_NEAR(p.y, o.semiMajorAxisM * std::sin(angle), 1e-6 * o.semiMajorAxisM) << t;
    EXPECT_EQ(p.z, 0.0);
  }
}

TEST(Orbit, EllipseHasItsPeriapsisApoapsisAndFocusWhereKeplerPutsThem) {
  OrbitElements o;
  o.semiMajorAxisM = 1.0e9;
  o.eccentricity = 0.6;
  o.periodS = 3600.0;
  const double a = o.semiMajorAxisM, e = o.eccentricity;
  // Periapsis at t = 0 on +x, apoapsis half a period later on −x (the parent is at a focus).
  EXPECT_NEAR(orbitPosition(o, 0.0).x, a * (1.0 - e), 1e-3);
  EXPECT_NEAR(orbitPosition(o, 1800.0).x, -a * (1.0 + e), 1e-3);
  EXPECT_NEAR(orbitPosition(o, 1800.0).y, 0.0, 1e-3);
  // Every point lies on the ellipse r = a(1 − e²) / (1 + e cos ν).
  for (double t = 0.0; t < 3600.0; t += 97.0) {
    const glm::dvec3 p = orbitPosition(o, t);
    const double r = glm::length(p);
    const double nu = std::atan2(p.y, p.x);
    EXPECT_NEAR(r, a * (1.0 - e * e) / (1.0 + e * std::cos(nu)), 1e-6 * a) << t;
  }
  // Kepler's second law: equal areas in equal times (the sector swept in 10 ms, near and far).
  auto sweep = [&](double t) {
    const glm::dvec3 p0 = orbitPosition(o, t), p1 = orbitPosition(o, t + 0.01);
    return 0.5 * std::abs(p0.x * p1.y - p0.y * p1.x);
  };
  EXPECT_NEAR(sweep(0.0) / sweep(1800.0), 1.0, 1e-6);
  EXPECT_NEAR(sweep(600.0) / sweep(1800.0), 1.0, 1e-6);
}

TEST(Orbit, KeplerSolutionSatisfiesTheEquationForEveryEccentricity) {
  for (double e : {0.0, 0.1, 0.5, 0.9, 0.99}) {
    for (double m = -20.0; m <= 20.0; m += 0.37) {
      const double E = solveKepler(m, e);
      EXPECT_NEAR(E - e * std::sin(E), m, 1e-12 * std::max(1.0, std::abs(m))) << e << " " << m;
    }
  }
  // A value worked by hand: e = 0.5, M = E − 0.5 sin E at E = 2 → M = 1.5453512865.
  EXPECT_NEAR(solveKepler(2.0 - 0.5 * std::sin(2.0), 0.5), 2.0, 1e-13);
}

TEST(Orbit, ElementsTurnTheOrbitIntoTheSceneFrame) {
  OrbitElements o;
  o.semiMajorAxisM = 1.0;
  o.periodS = 4.0;
  o.inclinationRad = kPi / 2.0;  // the orbit stands upright along the line of nodes (+x)
  // A quarter period after periapsis (on +x), the body is at +y in its plane: +z once inclined.
  EXPECT_NEAR(orbitPosition(o, 1.0).z, 1.0, 1e-12);
  o.ascendingNodeRad = kPi / 2.0;  // the line of nodes along +y: periapsis moves there
  EXPECT_NEAR(orbitPosition(o, 0.0).y, 1.0, 1e-12);
  o.inclinationRad = 0.0;
  o.ascendingNodeRad = 0.0;
  o.periapsisArgumentRad = kPi;  // periapsis on −x
  EXPECT_NEAR(orbitPosition(o, 0.0).x, -1.0, 1e-12);
}

TEST(Orbit, PeriodFollowsKeplersThirdLaw) {
  // The Moon around the Earth: a = 384,400 km, GM = 3.986e14 → 27.4 days.
  EXPECT_NEAR(orbitalPeriodS(3.844e8, 3.986004418e14) / 86400.0, 27.45, 0.01);
  EXPECT_EQ(errorOf([] { orbitalPeriodS(1e6, 0.0); }),
            "orbital period needs a > 0 and GM > 0, got a = 1000000 m, GM = 0 m^3/s^2");
}

TEST(Orbit, SpinTurnsAboutTheTiltedPole) {
  SpinElements spin;
  spin.periodS = 100.0;
  spin.tiltRad = kPi / 6.0;
  const glm::dmat3 r0 = bodyToScene(spin, 0.0), r1 = bodyToScene(spin, 25.0), r4 = bodyToScene(spin, 100.0);
  // The pole leans from +z toward −y by the tilt and does not move as the body turns.
  const glm::dvec3 pole = r0 * glm::dvec3(0, 0, 1);
  EXPECT_NEAR(pole.z, std::cos(kPi / 6.0), 1e-12);
  EXPECT_NEAR(pole.y, -std::sin(kPi / 6.0), 1e-12);
  EXPECT_NEAR(glm::length(r1 * glm::dvec3(0, 0, 1) - pole), 0.0, 1e-12);
  // A quarter turn takes the body's +x to where its +y was; a whole turn back to the start.
  EXPECT_NEAR(glm::length(r1 * glm::dvec3(1, 0, 0) - r0 * glm::dvec3(0, 1, 0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(r4 * glm::dvec3(1, 0, 0) - r0 * glm::dvec3(1, 0, 0)), 0.0, 1e-12);
}

TEST(Scene, BuiltInSystemHasAGiantAWorldAndItsMoon) {
  const SceneDescription scene = resolveScene("system");
  ASSERT_EQ(scene.bodies.size(), 3u);
  EXPECT_EQ(scene.bodies[0].name, "Giant");
  EXPECT_EQ(scene.bodies[0].parent, -1);
  EXPECT_EQ(scene.bodies[1].parent, 0);
  EXPECT_EQ(scene.bodies[2].parent, 1);
  EXPECT_EQ(scene.bodies[1].planet.name, "Earth");
  EXPECT_EQ(scene.bodies[2].planet.name, "Moon");
  // The giant's period comes from the sun's GM: 1 au → one year.
  EXPECT_NEAR(scene.bodies[0].orbit.periodS / (365.25 * 86400.0), 1.0, 0.01);
  // The moon's stated period agrees with Kepler's third law around Terra.
  EXPECT_NEAR(scene.bodies[2].orbit.periodS / orbitalPeriodS(6.0e7, 3.986e14), 1.0, 0.01);
  // Positions chain through the parents: the moon is 6e7 m (± e) from Terra at every time.
  for (double t : {0.0, 1e4, 1e6, 3e7}) {
    const std::vector<BodyState> s = sceneStateAt(scene, t);
    const double d = glm::length(s[2].positionM - s[1].positionM);
    EXPECT_GE(d, 6.0e7 * 0.95 - 1.0);
    EXPECT_LE(d, 6.0e7 * 1.05 + 1.0);
    EXPECT_NEAR(glm::length(s[1].positionM - s[0].positionM), 1.0e9, 0.021e9);
  }
  EXPECT_EQ(sceneBodyIndex(scene, "Moon"), 2u);
  EXPECT_EQ(errorOf([&] { sceneBodyIndex(scene, "Pluto"); }),
            "scene 'Three worlds' has no body 'Pluto' (bodies: Giant, Terra, Moon)");
}

constexpr std::string_view kMinimal = R"([scene]
name = "Test"

[[body]]
name = "A"
preset = "moon"
[body.orbit]
semi_major_axis_m = 1e11
)";

std::string sceneError(std::string_view text) {
  return errorOf([&] { parseSceneDescription(text, "s.toml"); });
}

TEST(Scene, BadInputIsOneLineNamingTheFileLineAndValue) {
  EXPECT_NO_THROW(parseSceneDescription(kMinimal, "s.toml"));
  const std::string base(kMinimal);
  EXPECT_EQ(sceneError(""), "s.toml: empty document (expected a [scene] table and [[body]] tables)");
  EXPECT_EQ(sceneError("[scene]\nname = \"x\"\n"), "s.toml: no [[body]] tables: a scene needs at least one body");
  EXPECT_EQ(sceneError(base + "colour = 1\n"), "s.toml:9: unknown key 'colour' in [body.orbit] of body 'A'");
  EXPECT_EQ(sceneError(base + "eccentricity = 1.5\n"), "s.toml:9: eccentricity must be in [0, 0.99], got 1.5");
  EXPECT_EQ(sceneError(base + "[[body]]\nname = \"A\"\npreset = \"moon\"\n"), "s.toml:10: duplicate body name 'A'");
  EXPECT_EQ(sceneError(base + "[[body]]\nname = \"B\"\npreset = \"moon\"\nparent = \"C\"\n"),
            "s.toml:12: parent 'C' of body 'B' is not a body defined before it");
  EXPECT_EQ(sceneError(base + "[[body]]\nname = \"B\"\npreset = \"moon\"\nparent = \"A\"\n[body.orbit]\n"
                              "semi_major_axis_m = 1e8\n"),
            "s.toml:13: the orbit of body 'B' needs period_s: its parent 'A' has no gm_m3_s2");
  EXPECT_EQ(sceneError(base + "[[body]]\nname = \"B\"\npreset = \"moon\"\nparent = \"A\"\n[body.orbit]\n"
                              "semi_major_axis_m = 3e6\nperiod_s = 100\n"),
            "s.toml:13: body 'B' comes within 3e6 m of 'A''s centre, inside it (radii 1737400 + 1737400 m)");
  EXPECT_EQ(sceneError(base + "[[body]]\nname = \"B\"\npreset = \"pluto\"\n"),
            "s.toml:11: unknown planet preset 'pluto' (built-in: earth, moon, mars, giant, faults, mpd; or a FILE.toml)");
  EXPECT_EQ(sceneError(base + "[[body]]\nname = \"B\"\npreset = \"moon\"\n"), "s.toml:9: missing table [body.orbit] in body 'B'");
  // A preset that is not there, named by a multi-line string (the fuzzer's find): the message
  // stays one line, the newline and tab shown as '?'.
  EXPECT_EQ(sceneError(base + "[[body]]\nname = \"B\"\npreset = \"\"\"\nno/\nsuch\tfile\"\"\"\n"),
            "s.toml:11: cannot read 'no/?such?file': No such file or directory");
  EXPECT_EQ(sceneError(base + "[[body]]\nname = \"B\"\npreset = \"plu\\nto\"\n"),
            "s.toml:11: unknown planet preset 'plu?to' (built-in: earth, moon, mars, giant, faults, mpd; or a FILE.toml)");
  EXPECT_EQ(sceneError("body = 3\n[scene]\nname = \"x\"\n"), "s.toml:1: 'body' must be an array of tables [[body]], got integer");
  EXPECT_EQ(sceneError("[scene]\nname = \"x\"\n[planet]\n"), "s.toml:3: unknown table [planet]");
}

TEST(Scene, PresetFilesAreReadRelativeToTheSceneFile) {
  const test::TempDir dir("scene_test");
  std::filesystem::create_directories(dir / "worlds");
  // A copy of the moon preset under another name, next to the scene.
  std::string moon;
  for (const EmbeddedPreset& preset : embeddedPresets())
    if (std::string_view(preset.name) == "moon") moon = preset.text;
  std::ofstream(dir / "worlds" / "rock.toml") << moon;
  std::string scene(kMinimal);
  scene.replace(scene.find("\"moon\""), 6, "\"worlds/rock.toml\"");
  std::ofstream(dir / "scene.toml") << scene;
  const SceneDescription s = loadSceneDescription((dir / "scene.toml").string());
  EXPECT_EQ(s.bodies[0].planet.name, "Moon");
}

}  // namespace
}  // namespace planet

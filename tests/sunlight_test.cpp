// Sunlight by distance from the sun (issue 23, point 3; reference/sunlight.h): the presets' sun
// at 1 au, the inverse-square law, a disc that shrinks as 1 / d with a radiance that does not
// change, and the distance each body of a scene is given.
#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "camera/scene_view.h"
#include "planet/scene_description.h"
#include "reference/sunlight.h"
#include "test_support.h"

namespace planet {
namespace {

constexpr double kAu = kAstronomicalUnitM;

TEST(Sunlight, AtOneAuTheSunIsThePresetsExactly) {
  const Sunlight sun = sunlightAtDistance(kAu);
  EXPECT_EQ(sun.irradianceScale, 1.0);
  EXPECT_EQ(sun.angularRadiusRad, kSunAngularRadiusRad);
}

TEST(Sunlight, IrradianceFallsAsTheInverseSquareOfTheDistance) {
  EXPECT_NEAR(sunlightAtDistance(2.0 * kAu).irradianceScale, 0.25, 1e-12);
  EXPECT_NEAR(sunlightAtDistance(0.5 * kAu).irradianceScale, 4.0, 1e-12);
  EXPECT_NEAR(sunlightAtDistance(5.2 * kAu).irradianceScale, 1.0 / (5.2 * 5.2), 1e-12);  // Jupiter's
  // The built-in system's giant: 1.496e11 m, 0.003 % beyond 1 au.
  EXPECT_NEAR(sunlightAtDistance(1.496e11).irradianceScale, 0.999972, 1e-6);
}

TEST(Sunlight, TheDiscShrinksAsOneOverTheDistanceAndKeepsItsRadiance) {
  // A sphere of radius R seen from d spans sin θ = R / d, and a disc of radiance L gives the
  // irradiance E = L π sin²θ: with E ∝ 1 / d², L stays the same at every distance.
  auto radiance = [](double distanceM) {
    const Sunlight sun = sunlightAtDistance(distanceM);
    return sun.irradianceScale / (std::numbers::pi * std::pow(std::sin(sun.angularRadiusRad), 2));
  };
  const double atOneAu = radiance(kAu);
  for (double au : {0.1, 0.39, 0.72, 1.52, 2.0, 5.2, 30.0}) {
    const Sunlight sun = sunlightAtDistance(au * kAu);
    EXPECT_NEAR(std::sin(sun.angularRadiusRad) * au / std::sin(kSunAngularRadiusRad), 1.0, 1e-12) << au << " au";
    // Small angles: θ itself goes as 1 / d (within 0.1 % from 0.1 au out).
    EXPECT_NEAR(sun.angularRadiusRad * au / kSunAngularRadiusRad, 1.0, 1e-3) << au << " au";
    EXPECT_NEAR(radiance(au * kAu) / atOneAu, 1.0, 1e-12) << au << " au";
  }
}

TEST(Sunlight, NearTheSunTheDiscIsCapped) {
  // 0.03 au and nearer: the cap; the irradiance still follows the inverse square.
  const Sunlight near = sunlightAtDistance(0.01 * kAu);
  EXPECT_EQ(near.angularRadiusRad, kMaxSunAngularRadiusRad);
  EXPECT_NEAR(near.irradianceScale, 1e4, 1e-6);
  EXPECT_LT(sunlightAtDistance(0.031 * kAu).angularRadiusRad, kMaxSunAngularRadiusRad);
}

TEST(Sunlight, ADistanceThatIsNotPositiveIsAnError) {
  for (double d : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    EXPECT_NE(test::errorOf([&] { sunlightAtDistance(d); }).find("distance from the sun must be a number > 0 m"),
              std::string::npos)
        << d;
}

TEST(Sunlight, EverySceneBodyIsGivenItsOwnDistanceFromTheSun) {
  const SceneDescription scene = resolveScene("system");
  const std::vector<BodyState> states = sceneStateAt(scene, 66'500.0);
  const std::vector<SceneBodyView> views = sceneBodyViews(states);
  ASSERT_EQ(views.size(), states.size());
  for (size_t i = 0; i < views.size(); ++i) {
    EXPECT_DOUBLE_EQ(views[i].sunDistanceM, glm::length(states[i].positionM)) << scene.bodies[i].name;
    // Terra and its moon ride 1e9 m around the giant at 1 au: within 1 % of 1 au.
    EXPECT_NEAR(views[i].sunDistanceM / kAu, 1.0, 0.01) << scene.bodies[i].name;
  }
  // A body given without a scene (one planet) is lit as at 1 au.
  EXPECT_EQ(SceneBodyView{}.sunDistanceM, kAu);
}

}  // namespace
}  // namespace planet

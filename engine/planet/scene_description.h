// A scene of several bodies (issue 8, point 1): planets and moons, each a planet preset of its
// own, on Keplerian orbits around the sun at the scene's origin or around another body, each
// turning about its own pole. Read from TOML (engine/planet/scenes/*.toml explains every key)
// and validated like the planet presets: one line naming the file, the line and the bad value.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "planet/orbit.h"
#include "planet/planet_description.h"
#include "planet/ring_description.h"

namespace planet {

inline constexpr size_t kMaxSceneBodies = 8;
inline constexpr Range kOrbitAxisRangeM{1e3, 1e13};
inline constexpr Range kEccentricityRange{0.0, 0.99};
inline constexpr Range kAngleRangeDeg{-360.0, 360.0};
inline constexpr Range kPeriodRangeS{1.0, 1e12};
inline constexpr Range kGmRangeM3S2{1.0, 1e22};
inline constexpr Range kTiltRangeDeg{-180.0, 180.0};
inline constexpr double kSunGmM3S2 = 1.32712440018e20;  // the Sun's gravitational parameter
// The astronomical unit (IAU 2012): a planet preset is lit as at this distance from the sun
// (reference/sunlight.h).
inline constexpr double kAstronomicalUnitM = 1.495978707e11;

struct BodyDescription {
  std::string name;                 // unique in the scene; the viewer and --camera BODY:... use it
  std::string preset;               // as written (an embedded preset's name or a file)
  PlanetDescription planet;         // the preset, read
  int parent = -1;                  // index of the body it orbits (always an earlier one); −1: the sun
  double gmM3S2 = 0.0;              // gravitational parameter (0: unknown; its satellites then need period_s)
  OrbitElements orbit;              // around the parent (its period resolved)
  SpinElements spin;
  std::optional<RingDescription> rings;  // in the body's equatorial plane
};

struct SceneDescription {
  std::string name;
  double sunGmM3S2 = kSunGmM3S2;  // for bodies that orbit the sun without a period_s
  std::vector<BodyDescription> bodies;  // parents before their satellites
};

// Where the bodies are at a time: positions in the scene frame (the sun at the origin) and the
// rotations of their frames, in double.
struct BodyState {
  glm::dvec3 positionM{0.0};
  glm::dmat3 bodyToScene{1.0};
};
std::vector<BodyState> sceneStateAt(const SceneDescription& scene, double timeS);

// The body whose surface is nearest `point` relative to its size, (distance − radius) / radius
// smallest: the camera's own body, whose ground it stands on and whose frame it flies in.
size_t relativelyNearestBody(std::span<const double> radiiM, std::span<const glm::dvec3> centresM,
                             const glm::dvec3& point);
size_t sceneReferenceBody(const SceneDescription& scene, const std::vector<BodyState>& states,
                          const glm::dvec3& point);

// `sourceName` names the text in messages; presets given as relative paths are read from
// `baseDirectory` (the scene file's folder; empty: the working directory).
SceneDescription parseSceneDescription(std::string_view toml, const std::string& sourceName,
                                       const std::string& baseDirectory = "");
SceneDescription loadSceneDescription(const std::string& path);

struct EmbeddedScene {
  const char* name;
  const char* text;
};
std::span<const EmbeddedScene> embeddedScenes();
// An embedded scene's name, or a path to a TOML file (ends in .toml or contains '/').
SceneDescription resolveScene(const std::string& nameOrFile);
// The index of the body of that name; throws planet::Error listing the names.
size_t sceneBodyIndex(const SceneDescription& scene, std::string_view name);

}  // namespace planet

#include "planet/scene_description.h"

#include <filesystem>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "core/error.h"
#include "core/file.h"
#include "planet/toml_reader.h"
#include "scenes/embedded_scenes.h"

namespace planet {
namespace {

using toml_reader::Context;
using toml_reader::formatNumber;
using toml_reader::lineOf;
using toml_reader::optionalTable;
using toml_reader::parseAt;
using toml_reader::shortened;
using toml_reader::TableReader;
using toml_reader::typeName;

constexpr std::string_view kTopKeys[] = {"scene", "body"};
constexpr std::string_view kSceneKeys[] = {"name", "sun_gm_m3_s2"};
constexpr std::string_view kBodyKeys[] = {"name", "preset", "parent", "gm_m3_s2", "orbit", "spin", "rings"};
constexpr std::string_view kOrbitKeys[] = {"semi_major_axis_m",      "eccentricity",     "inclination_deg",
                                           "ascending_node_deg",     "periapsis_argument_deg",
                                           "mean_anomaly_deg",       "period_s"};
constexpr std::string_view kSpinKeys[] = {"period_s", "tilt_deg", "phase_deg"};
// Bodies may not orbit inside the sun (its photosphere's radius).
constexpr double kSunRadiusM = 6.957e8;

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

OrbitElements readOrbit(const Context& context, const toml::table& table, const std::string& where) {
  TableReader reader(context, table, where, kOrbitKeys);
  OrbitElements o;
  o.semiMajorAxisM = reader.requiredNumber("semi_major_axis_m", kOrbitAxisRangeM);
  o.eccentricity = reader.number("eccentricity", kEccentricityRange).value_or(0.0);
  o.inclinationRad = radians(reader.number("inclination_deg", kAngleRangeDeg).value_or(0.0));
  o.ascendingNodeRad = radians(reader.number("ascending_node_deg", kAngleRangeDeg).value_or(0.0));
  o.periapsisArgumentRad = radians(reader.number("periapsis_argument_deg", kAngleRangeDeg).value_or(0.0));
  o.meanAnomalyAtEpochRad = radians(reader.number("mean_anomaly_deg", kAngleRangeDeg).value_or(0.0));
  o.periodS = reader.number("period_s", kPeriodRangeS).value_or(0.0);  // 0: from the parent's GM
  return o;
}

SpinElements readSpin(const Context& context, const toml::table& table, const std::string& where) {
  TableReader reader(context, table, where, kSpinKeys);
  SpinElements s;
  s.periodS = reader.number("period_s", kPeriodRangeS).value_or(0.0);
  s.tiltRad = radians(reader.number("tilt_deg", kTiltRangeDeg).value_or(0.0));
  s.phaseRad = radians(reader.number("phase_deg", kAngleRangeDeg).value_or(0.0));
  return s;
}

std::string presetPath(const std::string& preset, const std::string& baseDirectory) {
  const bool isFile = preset.ends_with(".toml") || preset.find('/') != std::string::npos;
  if (!isFile || baseDirectory.empty() || std::filesystem::path(preset).is_absolute()) return preset;
  return (std::filesystem::path(baseDirectory) / preset).string();
}

BodyDescription readBody(const Context& context, const toml::table& table, size_t index,
                         const std::vector<BodyDescription>& earlier, double sunGm, const std::string& baseDirectory) {
  TableReader reader(context, table, fmt::format("[[body]] {}", index + 1), kBodyKeys);
  BodyDescription b;
  b.name = reader.name("name");
  const uint32_t nameLine = lineOf(*reader.find("name"));
  for (const BodyDescription& other : earlier)
    if (other.name == b.name) context.fail(nameLine, fmt::format("duplicate body name '{}'", shortened(b.name)));
  const std::string where = fmt::format("body '{}'", shortened(b.name));

  b.preset = reader.requiredString("preset");
  b.planet = parseAt(context, lineOf(*reader.find("preset")),
                     [&] { return resolvePreset(presetPath(b.preset, baseDirectory)); });
  b.gmM3S2 = reader.number("gm_m3_s2", kGmRangeM3S2).value_or(0.0);

  double parentGm = sunGm, parentRadius = kSunRadiusM;
  std::string parentName = "the sun";
  if (std::optional<std::string> parent = reader.string("parent")) {
    const uint32_t line = lineOf(*reader.find("parent"));
    auto found = std::find_if(earlier.begin(), earlier.end(), [&](const BodyDescription& o) { return o.name == *parent; });
    if (found == earlier.end())
      context.fail(line, fmt::format("parent '{}' of {} is not a body defined before it", shortened(*parent), where));
    b.parent = int(found - earlier.begin());
    parentGm = found->gmM3S2;
    parentRadius = found->planet.radiusM;
    parentName = fmt::format("'{}'", found->name);
  }

  const toml::table* orbit = optionalTable(context, table, "orbit");
  if (!orbit) context.fail(reader.line(), fmt::format("missing table [body.orbit] in {}", where));
  b.orbit = readOrbit(context, *orbit, fmt::format("[body.orbit] of {}", where));
  if (b.orbit.periodS == 0.0) {
    if (!(parentGm > 0.0))
      context.fail(lineOf(*orbit), fmt::format("the orbit of {} needs period_s: its parent {} has no gm_m3_s2", where,
                                               parentName));
    b.orbit.periodS = orbitalPeriodS(b.orbit.semiMajorAxisM, parentGm);
  }
  const double periapsis = b.orbit.semiMajorAxisM * (1.0 - b.orbit.eccentricity);
  if (periapsis <= parentRadius + b.planet.radiusM)
    context.fail(lineOf(*orbit), fmt::format("{} comes within {} m of {}'s centre, inside it (radii {} + {} m)", where,
                                             formatNumber(periapsis), parentName, formatNumber(parentRadius),
                                             formatNumber(b.planet.radiusM)));
  if (const toml::table* spin = optionalTable(context, table, "spin"))
    b.spin = readSpin(context, *spin, fmt::format("[body.spin] of {}", where));
  if (const toml::table* rings = optionalTable(context, table, "rings")) {
    b.rings = parseRingTable(*rings, context.source());
    if (b.rings->innerRadiusM <= b.planet.radiusM)
      context.fail(lineOf(*rings), fmt::format("the rings of {} start at {} m, inside its radius {} m", where,
                                               formatNumber(b.rings->innerRadiusM), formatNumber(b.planet.radiusM)));
  }
  return b;
}

}  // namespace

std::vector<BodyState> sceneStateAt(const SceneDescription& scene, double timeS) {
  std::vector<BodyState> states(scene.bodies.size());
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDescription& body = scene.bodies[i];
    const glm::dvec3 parent = body.parent >= 0 ? states[size_t(body.parent)].positionM : glm::dvec3(0.0);
    states[i].positionM = parent + orbitPosition(body.orbit, timeS);
    states[i].bodyToScene = bodyToScene(body.spin, timeS);
  }
  return states;
}

size_t relativelyNearestBody(std::span<const double> radiiM, std::span<const glm::dvec3> centresM,
                             const glm::dvec3& point) {
  if (radiiM.empty() || radiiM.size() != centresM.size())
    throw Error(fmt::format("nearest body of {} radii and {} centres", radiiM.size(), centresM.size()));
  size_t best = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < radiiM.size(); ++i) {
    const double relative = (glm::length(point - centresM[i]) - radiiM[i]) / radiiM[i];
    if (relative < nearest) {
      nearest = relative;
      best = i;
    }
  }
  return best;
}

size_t sceneReferenceBody(const SceneDescription& scene, const std::vector<BodyState>& states,
                          const glm::dvec3& point) {
  std::vector<double> radii;
  std::vector<glm::dvec3> centres;
  for (size_t i = 0; i < scene.bodies.size() && i < states.size(); ++i) {
    radii.push_back(scene.bodies[i].planet.radiusM);
    centres.push_back(states[i].positionM);
  }
  return relativelyNearestBody(radii, centres, point);
}

SceneDescription parseSceneDescription(std::string_view text, const std::string& sourceName,
                                       const std::string& baseDirectory) {
  const Context context(sourceName);
  const toml::table root = toml_reader::parseDocument(context, text, "a [scene] table and [[body]] tables");
  for (auto&& [key, value] : root) {
    if (std::find(std::begin(kTopKeys), std::end(kTopKeys), key.str()) != std::end(kTopKeys)) continue;
    context.fail(key.source().begin.line, value.is_table()
                                              ? fmt::format("unknown table [{}]", shortened(key.str()))
                                              : fmt::format("unknown key '{}' at top level", shortened(key.str())));
  }
  SceneDescription scene;
  TableReader header(context, toml_reader::requireTable(context, root, "scene"), "[scene]", kSceneKeys);
  scene.name = header.name("name");
  scene.sunGmM3S2 = header.number("sun_gm_m3_s2", kGmRangeM3S2).value_or(kSunGmM3S2);

  const toml::node* bodies = root.get("body");
  if (!bodies) context.fail(0, "no [[body]] tables: a scene needs at least one body");
  const toml::array* array = bodies->as_array();
  if (!array || !array->is_array_of_tables())
    context.fail(lineOf(*bodies), fmt::format("'body' must be an array of tables [[body]], got {}", typeName(*bodies)));
  if (array->size() > kMaxSceneBodies)
    context.fail(lineOf(*array->get(kMaxSceneBodies)),
                 fmt::format("too many bodies: {} (at most {})", array->size(), kMaxSceneBodies));
  for (size_t i = 0; i < array->size(); ++i)
    scene.bodies.push_back(
        readBody(context, *array->get(i)->as_table(), i, scene.bodies, scene.sunGmM3S2, baseDirectory));
  return scene;
}

SceneDescription loadSceneDescription(const std::string& path) {
  return parseSceneDescription(readFileUpTo(path, kMaxPresetBytes), path,
                               std::filesystem::path(path).parent_path().string());
}

std::span<const EmbeddedScene> embeddedScenes() {
  static const auto scenes = [] {
    std::vector<EmbeddedScene> out;
    for (const auto& scene : scenes::kEmbedded) out.push_back({scene.name, scene.text});
    return out;
  }();
  return scenes;
}

SceneDescription resolveScene(const std::string& nameOrFile) {
  if (nameOrFile.ends_with(".toml") || nameOrFile.find('/') != std::string::npos)
    return loadSceneDescription(nameOrFile);
  for (const EmbeddedScene& scene : embeddedScenes())
    if (nameOrFile == scene.name) return parseSceneDescription(scene.text, nameOrFile + ".toml");
  std::string names;
  for (const EmbeddedScene& scene : embeddedScenes()) names += fmt::format("{}{}", names.empty() ? "" : ", ", scene.name);
  throw Error(fmt::format("unknown scene '{}' (built-in: {}; or a FILE.toml)", nameOrFile, names));
}

size_t sceneBodyIndex(const SceneDescription& scene, std::string_view name) {
  std::string names;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].name == name) return i;
    names += fmt::format("{}{}", names.empty() ? "" : ", ", scene.bodies[i].name);
  }
  throw Error(fmt::format("scene '{}' has no body '{}' (bodies: {})", scene.name, shortened(name), names));
}

}  // namespace planet

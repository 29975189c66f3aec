// Planet descriptions: the built-in presets, every class of bad input as one exact line,
// preset resolution by name and by file, and the description hash.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include "core/error.h"
#include "planet/planet_description.h"
#include "reference/atmosphere_model.h"
#include "shared/exposure_params.h"

namespace planet {
namespace {

// A small valid document; the tests below edit one line of it. Line numbers matter:
// 1 comment, 2 [planet], 4 radius_m, 8 scheme, 10 [[layer]], 13 octaves, 15 amplitude_m.
constexpr std::string_view kMinimal = R"(# test planet
[planet]
name = "Test"
radius_m = 1_000_000
has_ocean = false

[colors]
scheme = "altitude"

[[layer]]
name = "base"
type = "fbm"
octaves = 4
frequency = 1e-6
amplitude_m = 1000
)";

// kMinimal with the first occurrence of `from` replaced by `to` (which must exist).
std::string edit(std::string_view from, std::string_view to, std::string_view text = kMinimal) {
  std::string out(text);
  size_t at = out.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) out.replace(at, from.size(), to);
  return out;
}

using test::errorOf;

// The error of parsing `text` as "x.toml", checked to be a single line.
std::string parseError(std::string_view text, const std::string& source = "x.toml") {
  std::string message = errorOf([&] { parsePlanetDescription(text, source); });
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  return message;
}

// kMinimal without its [[layer]] table.
std::string withoutLayers() { return std::string(kMinimal.substr(0, kMinimal.find("[[layer]]"))); }

// The embedded TOML text of a built-in preset.
std::string presetText(std::string_view name) {
  for (const EmbeddedPreset& preset : embeddedPresets())
    if (name == preset.name) return preset.text;
  ADD_FAILURE() << "no built-in preset " << name;
  return "";
}

bool startsWith(const std::string& text, std::string_view prefix) { return text.starts_with(prefix); }

TEST(PlanetDescription, BuiltInPresetsParseWithTheirRadius) {
  std::vector<std::string> names = presetNames();
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"earth", "faults", "giant", "mars", "moon", "mpd"}));
  EXPECT_EQ(resolvePreset(std::string(kDefaultPresetName)).name, "Earth");
  struct Expected {
    const char* name;
    double radiusM;
    bool hasOcean;
    ColorScheme scheme;
  };
  for (const Expected& e :
       {Expected{"earth", 6371000.0, true, ColorScheme::Earth}, Expected{"moon", 1737400.0, false, ColorScheme::Moon},
        Expected{"mars", 3389500.0, false, ColorScheme::Mars}, Expected{"giant", 5.8e7, false, ColorScheme::Giant},
        Expected{"faults", 6371000.0, true, ColorScheme::Earth}, Expected{"mpd", 6371000.0, true, ColorScheme::Earth}}) {
    PlanetDescription d = resolvePreset(e.name);
    EXPECT_EQ(d.radiusM, e.radiusM) << e.name;
    EXPECT_EQ(d.hasOcean, e.hasOcean) << e.name;
    EXPECT_EQ(d.colors.scheme, e.scheme) << e.name;
    EXPECT_GE(d.layers.size(), 2u) << e.name;
    EXPECT_EQ(d.heightScale, 1.0) << e.name;
  }
}

TEST(PlanetDescription, EarthHasContinentsMountainsAndMetreScaleDetail) {
  PlanetDescription d = resolvePreset("earth");
  EXPECT_EQ(d.name, "Earth");
  EXPECT_EQ(d.seaLevelM, 0.0);
  EXPECT_EQ(d.colors.snowLineM, 3500.0);
  EXPECT_EQ(d.colors.iceCapLatitudeDeg, 70.0);
  ASSERT_EQ(d.layers.size(), 5u);
  const NoiseLayer& continents = d.layers[0];
  const NoiseLayer& belts = d.layers[1];
  const NoiseLayer& mountains = d.layers[2];
  const NoiseLayer& hills = d.layers[3];
  // Continents: thousands of km, through a hypsometry whose sea level leaves 25-35 % land and
  // whose ends are an abyssal plain (-4 km or lower) and a continental platform.
  EXPECT_GT(1.0 / continents.frequency, 1e6);
  ASSERT_GE(continents.hypsometry.size(), 8u);
  double seaFraction = 0.0;
  for (size_t k = 1; k < continents.hypsometry.size(); ++k)
    if (continents.hypsometry[k - 1].y < 0.0 && continents.hypsometry[k].y >= 0.0)
      seaFraction = continents.hypsometry[k].x;
  EXPECT_GT(seaFraction, 0.65);
  EXPECT_LT(seaFraction, 0.75);
  EXPECT_LT(continents.hypsometry.front().y, -4000.0);
  // Belts add no height; they mask the mountains, and are themselves masked by the continents.
  EXPECT_EQ(belts.amplitudeM, 0.0);
  EXPECT_EQ(belts.mask, "continents");
  EXPECT_EQ(mountains.mask, "belts");
  // Mountains: eroded (gullies down the slopes), hundreds of km, a few km high, and rough (H well
  // below 1, so that the km-scale octaves still carry relief).
  EXPECT_EQ(mountains.noise.type, noise::NoiseType::Eroded);
  EXPECT_GT(1.0 / mountains.frequency, 1e5);
  EXPECT_LT(1.0 / mountains.frequency, 1e6);
  EXPECT_GE(mountains.amplitudeM, 1000.0);
  EXPECT_LT(mountains.noise.H, 0.7);
  // Hills: tens of km down to a few metres.
  EXPECT_GT(1.0 / hills.frequency, 1e4);
  EXPECT_LT(1.0 / hills.frequency / std::pow(hills.noise.lacunarity, hills.noise.octaves - 1), 5.0);
  // Ground roughness: plain fBm down to centimetres, so that plains are not glassy at 2 m.
  const NoiseLayer& ground = d.layers[4];
  EXPECT_EQ(ground.noise.type, noise::NoiseType::Fbm);
  EXPECT_LT(1.0 / ground.frequency / std::pow(ground.noise.lacunarity, ground.noise.octaves - 1), 0.02);
}

TEST(PlanetDescription, PresetsAreVisiblyDifferent) {
  PlanetDescription earth = resolvePreset("earth"), moon = resolvePreset("moon"), mars = resolvePreset("mars");
  EXPECT_NE(descriptionHash(earth), descriptionHash(moon));
  EXPECT_NE(descriptionHash(earth), descriptionHash(mars));
  EXPECT_NE(descriptionHash(moon), descriptionHash(mars));
  EXPECT_NE(earth.colors.lowland, mars.colors.lowland);
  EXPECT_GT(mars.colors.highland.x, 2.0f * mars.colors.highland.z);            // red
  for (const glm::vec3& grey : {moon.colors.lowland, moon.colors.highland}) {  // grey, to 10 %
    EXPECT_NEAR(grey.x, grey.y, 0.1f * grey.x);
    EXPECT_NEAR(grey.x, grey.z, 0.1f * grey.x);
  }
}

TEST(PlanetDescription, OptionalKeysTakeTheirDocumentedDefaults) {
  PlanetDescription d = parsePlanetDescription(kMinimal, "x.toml");
  EXPECT_EQ(d.name, "Test");
  EXPECT_EQ(d.seaLevelM, 0.0);
  EXPECT_EQ(d.heightScale, 1.0);
  EXPECT_EQ(d.baseHeightM, 0.0);
  ASSERT_EQ(d.layers.size(), 1u);
  const noise::NoiseSettings& n = d.layers[0].noise;
  EXPECT_EQ(n.type, noise::NoiseType::Fbm);
  EXPECT_EQ(n.octaves, 4);
  EXPECT_EQ(n.lacunarity, 2.0);
  EXPECT_EQ(n.H, 1.0);
  EXPECT_FALSE(n.offset.has_value());
  EXPECT_FALSE(n.gain.has_value());
  EXPECT_EQ(n.seed, 0u);
  EXPECT_EQ(n.hash, noise::NoiseHash::Fast);
  EXPECT_EQ(d.layers[0].frequency, 1e-6);
  EXPECT_EQ(d.layers[0].amplitudeM, 1000.0);
  PlanetColors defaults = defaultColors(ColorScheme::Altitude);
  EXPECT_EQ(d.colors.scheme, ColorScheme::Altitude);
  EXPECT_EQ(d.colors.snow, defaults.snow);
  EXPECT_EQ(d.colors.snowLineM, defaults.snowLineM);
  EXPECT_EQ(d.colors.iceCapLatitudeDeg, 90.0);
}

TEST(PlanetDescription, ExplicitValuesAreRead) {
  std::string text = edit("has_ocean = false", "has_ocean = true\nsea_level_m = -12.5\nheight_scale = 3");
  text = edit("scheme = \"altitude\"", "scheme = \"mars\"\nsnow = [1, 0.5, 0.25]\nice_cap_latitude_deg = 85", text);
  text = edit("frequency = 1e-6", "wavelength_m = 250_000\nseed = 4294967295\nhash = \"reference\"\nH = 0.5", text);
  PlanetDescription d = parsePlanetDescription(text, "x.toml");
  EXPECT_TRUE(d.hasOcean);
  EXPECT_EQ(d.seaLevelM, -12.5);
  EXPECT_EQ(d.heightScale, 3.0);
  EXPECT_EQ(d.colors.scheme, ColorScheme::Mars);
  EXPECT_EQ(d.colors.snow, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(d.colors.iceCapLatitudeDeg, 85.0);
  EXPECT_EQ(d.colors.lowland, defaultColors(ColorScheme::Mars).lowland);
  EXPECT_DOUBLE_EQ(d.layers[0].frequency, 4e-6);
  EXPECT_EQ(d.layers[0].noise.seed, 4294967295u);
  EXPECT_EQ(d.layers[0].noise.hash, noise::NoiseHash::Reference);
  EXPECT_EQ(d.layers[0].noise.H, 0.5);
}

TEST(PlanetDescription, UnknownKeysAndTablesNameTheKeyAndLine) {
  EXPECT_EQ(parseError(edit("radius_m", "radus_m"), "earth.toml"), "earth.toml:4: unknown key 'radus_m' in [planet]");
  EXPECT_EQ(parseError(edit("octaves = 4", "octave = 4")), "x.toml:13: unknown key 'octave' in [[layer]]");
  EXPECT_EQ(parseError(edit("scheme", "schema")), "x.toml:8: unknown key 'schema' in [colors]");
  EXPECT_EQ(parseError(std::string(kMinimal) + "[atmospere]\nheight_m = 1\n"), "x.toml:16: unknown table [atmospere]");
  EXPECT_EQ(parseError(std::string(kMinimal) + "[atmosphere]\nheigth_m = 1\n"),
            "x.toml:17: unknown key 'heigth_m' in [atmosphere]");
  EXPECT_EQ(parseError("seed = 1\n" + std::string(kMinimal)), "x.toml:1: unknown key 'seed' at top level");
  EXPECT_EQ(parseError(edit("[colors]", "[planet.extra]\nx = 1\n[colors]")),
            "x.toml:7: unknown key 'extra' in [planet]");
}

// The sky tables (issue 4): optional, each switches its effect on, with checked values.
TEST(PlanetDescription, SkyTablesAreOptionalAndChecked) {
  const PlanetDescription plain = parsePlanetDescription(kMinimal, "x.toml");
  EXPECT_FALSE(plain.atmosphere.enabled);
  EXPECT_FALSE(plain.clouds.enabled);
  EXPECT_TRUE(plain.stars.enabled);

  const PlanetDescription sky = parsePlanetDescription(
      std::string(kMinimal) +
          "[atmosphere]\nrayleigh_scattering = 1e-5\nmie_scattering = [1e-6, 2e-6, 3e-6]\nmie_g = 0.5\n"
          "[clouds]\ncoverage = 0.7\ntop_m = 9000\n[stars]\nseed = 9\nenabled = false\n",
      "x.toml");
  EXPECT_TRUE(sky.atmosphere.enabled);
  EXPECT_EQ(sky.atmosphere.rayleighScattering, glm::dvec3(1e-5));
  EXPECT_EQ(sky.atmosphere.mieScattering, glm::dvec3(1e-6, 2e-6, 3e-6));
  EXPECT_EQ(sky.atmosphere.mieG, glm::dvec3(0.5));
  EXPECT_TRUE(sky.clouds.enabled);
  EXPECT_EQ(sky.clouds.coverage, 0.7);
  EXPECT_EQ(sky.clouds.topM, 9000.0);
  EXPECT_EQ(sky.stars.seed, 9u);
  EXPECT_FALSE(sky.stars.enabled);
  EXPECT_NE(descriptionHash(plain), descriptionHash(sky));

  const std::string base(kMinimal);
  EXPECT_EQ(parseError(base + "[clouds]\ncoverage = 0.5\n"), "x.toml:16: [clouds] needs an [atmosphere] table");
  EXPECT_EQ(parseError(base + "[atmosphere]\nmie_g = 1.5\n"), "x.toml:17: mie_g must be in [-0.99, 0.99], got 1.5");
  EXPECT_EQ(parseError(base + "[atmosphere]\nmie_scattering = [1e-6, 2e-6]\n"),
            "x.toml:17: 'mie_scattering' must be a number or an array of 3 numbers [r, g, b], got 2 elements");
  EXPECT_EQ(parseError(base + "[atmosphere]\nrayleigh_scattering = [1e-6, -1, 0]\n"),
            "x.toml:17: rayleigh_scattering[1] must be in [0, 0.01], got -1");
  EXPECT_EQ(parseError(base + "[atmosphere]\n[clouds]\nbottom_m = 5000\ntop_m = 4000\n"),
            "x.toml:19: top_m (4000) must be above bottom_m (5000)");
  EXPECT_EQ(parseError(base + "[atmosphere]\nheight_m = 5000\n[clouds]\n"),
            "x.toml:18: clouds top_m (8000) must be below the atmosphere's height_m (5000)");
  EXPECT_EQ(parseError(base + "[water]\nclarity_m = 5\n"), "x.toml:16: [water] needs has_ocean = true");
  EXPECT_EQ(parseError(base + "[stars]\nfaintest_magnitude = nan\n"),
            "x.toml:17: faintest_magnitude must be a finite number, got nan");
  EXPECT_EQ(parseError("atmosphere = 3\n" + base), "x.toml:1: 'atmosphere' must be a table, got integer");
}

// Airglow (issue 21, point 4): off unless asked for; its shell must lie in the air, below its top,
// and its colour must not be black.
TEST(PlanetDescription, AirglowIsOptionalAndChecked) {
  const std::string base(kMinimal);
  const PlanetDescription plain = parsePlanetDescription(base + "[atmosphere]\n", "x.toml");
  EXPECT_EQ(plain.atmosphere.airglowCdM2, 0.0);
  EXPECT_EQ(makeAirglowParams(plain).radiance, glm::vec4(0.0f));
  const PlanetDescription glow = parsePlanetDescription(
      base + "[atmosphere]\nairglow_cd_m2 = 2e-4\nairglow_color = [0.5, 1, 0.5]\nairglow_top_m = 95000\n", "x.toml");
  EXPECT_EQ(glow.atmosphere.airglowCdM2, 2e-4);
  EXPECT_EQ(glow.atmosphere.airglowColor, glm::vec3(0.5f, 1.0f, 0.5f));
  EXPECT_EQ(glow.atmosphere.airglowTopM, 95000.0);
  EXPECT_NE(descriptionHash(plain), descriptionHash(glow));
  // The zenith radiance has the luminance asked for, in the frame's unit.
  const glm::vec4 radiance = makeAirglowParams(glow).radiance;
  EXPECT_NEAR(0.2126 * radiance.r + 0.7152 * radiance.g + 0.0722 * radiance.b, 2e-4 / gpu::kExposureSunCdM2, 1e-15);
  EXPECT_FLOAT_EQ(radiance.r, radiance.b);
  EXPECT_FLOAT_EQ(radiance.w, 1.0f);
  EXPECT_GT(resolvePreset("earth").atmosphere.airglowCdM2, 0.0);
  EXPECT_EQ(resolvePreset("mars").atmosphere.airglowCdM2, 0.0);

  const std::pair<const char*, const char*> errors[] = {
      {"airglow_cd_m2 = 2\n", "x.toml:17: airglow_cd_m2 must be in [0, 1], got 2"},
      {"height_m = 80000\nairglow_cd_m2 = 1e-4\n",
       "x.toml:18: airglow_top_m (97000) must not be above the atmosphere's height_m (80000)"},
      {"airglow_cd_m2 = 1e-4\nairglow_bottom_m = 90000\nairglow_top_m = 90000\n",
       "x.toml:19: airglow_top_m (90000) must be above airglow_bottom_m (90000)"},
      {"airglow_color = [0, 0, 0]\n", "x.toml:17: airglow_color must not be black (airglow_cd_m2 sets how bright)"}};
  for (const auto& [input, message] : errors) EXPECT_EQ(parseError(base + "[atmosphere]\n" + input), message);
}

// The built-in presets differ where the issue asks: Earth has air, clouds and sea; Mars thin
// dusty air; the Moon none of it.
TEST(PlanetDescription, PresetSkiesDiffer) {
  const PlanetDescription earth = resolvePreset("earth");
  const PlanetDescription mars = resolvePreset("mars");
  const PlanetDescription moon = resolvePreset("moon");
  EXPECT_TRUE(earth.atmosphere.enabled && earth.clouds.enabled && earth.hasOcean);
  EXPECT_TRUE(mars.atmosphere.enabled);
  EXPECT_FALSE(mars.clouds.enabled || mars.hasOcean);
  EXPECT_GT(mars.atmosphere.mieScattering.r, mars.atmosphere.mieScattering.b);  // reddish dust
  EXPECT_GT(mars.atmosphere.mieAbsorption.b, mars.atmosphere.mieAbsorption.r);  // that absorbs blue
  EXPECT_FALSE(moon.atmosphere.enabled || moon.clouds.enabled || moon.hasOcean);
  EXPECT_TRUE(moon.stars.enabled);
}

// City lights (issue 14, point 2): Earth has them, Mars and the Moon not; the table's values are
// read, its bad values are one line naming the key, and disabled lights leave the hash alone.
TEST(PlanetDescription, LightsTableIsOptionalReadAndChecked) {
  const PlanetDescription earth = resolvePreset("earth");
  EXPECT_TRUE(earth.lights.enabled);
  EXPECT_GT(earth.lights.radianceNw, 0.0);
  EXPECT_FALSE(resolvePreset("mars").lights.enabled);
  EXPECT_FALSE(resolvePreset("moon").lights.enabled);

  const std::string base(kMinimal);
  const PlanetDescription plain = parsePlanetDescription(base, "x.toml");
  EXPECT_FALSE(plain.lights.enabled);
  const PlanetDescription lit = parsePlanetDescription(
      base + "[lights]\nradiance_nw = 25\ngain = 1000\ncolor = [1, 0.5, 0.25]\ncoverage = 0.4\n"
             "city_size_m = 50_000\nseed = 3\n",
      "x.toml");
  EXPECT_TRUE(lit.lights.enabled);  // the table alone switches them on
  EXPECT_EQ(lit.lights.radianceNw, 25.0);
  EXPECT_EQ(lit.lights.gain, 1000.0);
  EXPECT_EQ(lit.lights.color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(lit.lights.coverage, 0.4);
  EXPECT_EQ(lit.lights.citySizeM, 50000.0);
  EXPECT_EQ(lit.lights.seed, 3u);
  EXPECT_NE(descriptionHash(plain), descriptionHash(lit));
  const PlanetDescription off = parsePlanetDescription(base + "[lights]\nenabled = false\nseed = 5\n", "x.toml");
  EXPECT_FALSE(off.lights.enabled);
  EXPECT_EQ(descriptionHash(plain), descriptionHash(off));

  EXPECT_EQ(parseError(base + "[lights]\nradiance_nw = -1\n"), "x.toml:17: radiance_nw must be in [0, 10000], got -1");
  EXPECT_EQ(parseError(base + "[lights]\ncoverage = 1.5\n"), "x.toml:17: coverage must be in [0, 1], got 1.5");
  EXPECT_EQ(parseError(base + "[lights]\ngain = nan\n"), "x.toml:17: gain must be a finite number, got nan");
  EXPECT_EQ(parseError(base + "[lights]\ncity_size_m = 10\n"),
            "x.toml:17: city_size_m must be in [1000, 1e7], got 10");
  EXPECT_EQ(parseError(base + "[lights]\ncolor = [0, 0, 0]\n"),
            "x.toml:17: color must not be black: [0, 0, 0] has no brightness to scale");
  EXPECT_EQ(parseError(base + "[lights]\ncolor = [1, 2, 0]\n"), "x.toml:17: color[1] must be in [0, 1], got 2");
  EXPECT_EQ(parseError(base + "[lights]\nenabled = 1\n"), "x.toml:17: 'enabled' must be a boolean, got integer");
  EXPECT_EQ(parseError(base + "[lights]\nbrightness = 3\n"), "x.toml:17: unknown key 'brightness' in [lights]");
}

TEST(PlanetDescription, WrongTypesNameTheKeyAndBothTypes) {
  EXPECT_EQ(parseError(edit("octaves = 4", "octaves = \"4\""), "earth.toml"),
            "earth.toml:13: 'octaves' must be an integer, got string");
  EXPECT_EQ(parseError(edit("octaves = 4", "octaves = 4.0")), "x.toml:13: 'octaves' must be an integer, got float");
  EXPECT_EQ(parseError(edit("radius_m = 1_000_000", "radius_m = \"big\"")),
            "x.toml:4: 'radius_m' must be a number, got string");
  EXPECT_EQ(parseError(edit("has_ocean = false", "has_ocean = 0")),
            "x.toml:5: 'has_ocean' must be a boolean, got integer");
  EXPECT_EQ(parseError(edit("name = \"Test\"", "name = 7")), "x.toml:3: 'name' must be a string, got integer");
  EXPECT_EQ(parseError(edit("scheme = \"altitude\"", "scheme = \"altitude\"\nsnow = [1, 1]")),
            "x.toml:9: 'snow' must be an array of 3 numbers [r, g, b], got 2 elements");
  EXPECT_EQ(parseError(edit("scheme = \"altitude\"", "scheme = \"altitude\"\nsnow = \"white\"")),
            "x.toml:9: 'snow' must be an array of 3 numbers [r, g, b], got string");
  EXPECT_EQ(parseError(edit("scheme = \"altitude\"", "scheme = \"altitude\"\nsnow = [1, \"x\", 1]")),
            "x.toml:9: snow[1] must be a number, got string");
  EXPECT_EQ(parseError("colors = 3\n" + edit("[colors]\nscheme = \"altitude\"\n", "")),
            "x.toml:1: 'colors' must be a table, got integer");
  EXPECT_EQ(parseError("layer = 5\n" + withoutLayers()),
            "x.toml:1: 'layer' must be an array of tables ([[layer]]), got integer");
  EXPECT_EQ(parseError("layer = [1, 2]\n" + withoutLayers()),
            "x.toml:1: 'layer' must be an array of tables ([[layer]]), got an array of values");
  EXPECT_EQ(parseError(edit("type = \"fbm\"", "type = \"fbn\"")),
            "x.toml:12: unknown noise type 'fbn' (expected simplex, fbm, ridged, hybrid, hetero, cascade, craters, "
            "damped, eroded, faults, mpd or mpd_ico)");
  EXPECT_EQ(parseError(edit("scheme = \"altitude\"", "scheme = \"venus\"")),
            "x.toml:8: unknown color scheme 'venus' (expected one of earth, altitude, moon, mars, giant, "
            "altitude_perturbed, noise, altitude_noise, turbulence, earth_like, gradient, moon_like)");
}

TEST(PlanetDescription, OutOfRangeValuesNameKeyLineRangeAndValue) {
  EXPECT_EQ(parseError(edit("radius_m = 1_000_000", "radius_m = -5"), "moon.toml"),
            "moon.toml:4: radius_m must be in [1000, 1e8], got -5");
  EXPECT_EQ(parseError(edit("radius_m = 1_000_000", "radius_m = 2.5e8")),
            "x.toml:4: radius_m must be in [1000, 1e8], got 2.5e8");
  EXPECT_EQ(parseError(edit("octaves = 4", "octaves = 40")), "x.toml:13: octaves must be in [1, 32], got 40");
  EXPECT_EQ(parseError(edit("octaves = 4", "octaves = 0")), "x.toml:13: octaves must be in [1, 32], got 0");
  EXPECT_EQ(parseError(edit("octaves = 4", "octaves = 4\nseed = -1")),
            "x.toml:14: seed must be in [0, 4294967295], got -1");
  EXPECT_EQ(parseError(edit("frequency = 1e-6", "frequency = 0")), "x.toml:14: frequency must be in [1e-9, 10], got 0");
  EXPECT_EQ(parseError(edit("frequency = 1e-6", "wavelength_m = 0.01")),
            "x.toml:14: wavelength_m must be in [0.1, 1e9], got 0.01");
  EXPECT_EQ(parseError(edit("amplitude_m = 1000", "amplitude_m = 1e6")),
            "x.toml:15: amplitude_m must be in [-1e5, 1e5], got 1e6");
  EXPECT_EQ(parseError(edit("scheme = \"altitude\"", "scheme = \"altitude\"\nice_cap_latitude_deg = 91")),
            "x.toml:9: ice_cap_latitude_deg must be in [0, 90], got 91");
  EXPECT_EQ(parseError(edit("scheme = \"altitude\"", "scheme = \"altitude\"\nsnow = [1, 1.5, 0]")),
            "x.toml:9: snow[1] must be in [0, 1], got 1.5");
  EXPECT_EQ(parseError(edit("has_ocean = false", "has_ocean = false\nheight_scale = -1")),
            "x.toml:6: height_scale must be in [0, 100], got -1");
}

TEST(PlanetDescription, NoiseRangesComeFromNoiseSettingsAtTheLayerLine) {
  EXPECT_EQ(parseError(edit("octaves = 4", "octaves = 4\nlacunarity = 0.5")),
            "x.toml:10: layer 'base': lacunarity must be in (1, 8], got 0.5");
  EXPECT_EQ(parseError(edit("octaves = 4", "octaves = 4\nH = -1")),
            "x.toml:10: layer 'base': H must be in [0, 4], got -1");
  EXPECT_EQ(parseError(edit("octaves = 4", "octaves = 4\ngain = 17")),
            "x.toml:10: layer 'base': gain must be in [0, 16], got 17");
}

TEST(PlanetDescription, CrossKeyRulesAreEnforced) {
  EXPECT_EQ(parseError(edit("has_ocean = false", "has_ocean = false\nsea_level_m = 10")),
            "x.toml:6: sea_level_m needs has_ocean = true");
  EXPECT_EQ(parseError(edit("frequency = 1e-6", "frequency = 1e-6\nwavelength_m = 1e6")),
            "x.toml:15: give either frequency or wavelength_m in [[layer]], not both");
  std::string layer(kMinimal.substr(kMinimal.find("[[layer]]")));
  EXPECT_EQ(parseError(std::string(kMinimal) + layer), "x.toml:16: duplicate layer name 'base' (first at line 10)");
  std::string many(kMinimal);
  for (int i = 1; i <= kMaxLayers; ++i) many += edit("name = \"base\"", "name = \"l" + std::to_string(i) + "\"", layer);
  EXPECT_EQ(parseError(many), "x.toml:58: at most 8 [[layer]] tables, got 9");
  EXPECT_EQ(parseError(edit("name = \"Test\"", "name = \"\"")), "x.toml:3: name must be 1 to 64 bytes long, got 0");
  EXPECT_EQ(parseError(edit("name = \"Test\"", "name = \"a\\tb\"")),
            "x.toml:3: name must not contain control characters");
  EXPECT_EQ(parseError("layer = []\n" + withoutLayers()), "x.toml:1: at least one [[layer]] is required");
}

TEST(PlanetDescription, MissingKeysNameTheKeyAndTable) {
  EXPECT_EQ(parseError(edit("radius_m = 1_000_000\n", "")), "x.toml:2: missing key 'radius_m' in [planet]");
  EXPECT_EQ(parseError(edit("has_ocean = false\n", "")), "x.toml:2: missing key 'has_ocean' in [planet]");
  EXPECT_EQ(parseError(edit("octaves = 4\n", "")), "x.toml:10: missing key 'octaves' in [[layer]]");
  EXPECT_EQ(parseError(edit("amplitude_m = 1000\n", "")), "x.toml:10: missing key 'amplitude_m' in [[layer]]");
  EXPECT_EQ(parseError(edit("frequency = 1e-6\n", "")),
            "x.toml:10: missing key 'frequency' (or 'wavelength_m') in [[layer]]");
  EXPECT_EQ(parseError(edit("scheme = \"altitude\"\n", "")), "x.toml:7: missing key 'scheme' in [colors]");
  EXPECT_EQ(parseError(edit("[colors]\nscheme = \"altitude\"\n", "")), "x.toml: missing table [colors]");
  EXPECT_EQ(parseError(withoutLayers()), "x.toml: missing table [[layer]] (at least one noise layer)");
  EXPECT_EQ(parseError("# only a comment\n"), "x.toml: missing table [planet]");
}

TEST(PlanetDescription, SyntaxErrorsGiveLineColumnAndTheParsersMessage) {
  std::string message = parseError(edit("octaves = 4", "octaves = "));
  EXPECT_TRUE(startsWith(message, "x.toml:13:11: ")) << message;
  EXPECT_GT(message.size(), std::string("x.toml:13:11: ").size());
  message = parseError(edit("[colors]", "[colors"));
  EXPECT_TRUE(startsWith(message, "x.toml:7:")) << message;
  message = parseError(std::string(kMinimal) + "[planet]\n");
  EXPECT_TRUE(startsWith(message, "x.toml:16:")) << message;
  EXPECT_NE(message.find("planet"), std::string::npos) << message;
}

TEST(PlanetDescription, NanAndInfinityAreRejected) {
  EXPECT_EQ(parseError(edit("radius_m = 1_000_000", "radius_m = nan")),
            "x.toml:4: radius_m must be a finite number, got nan");
  EXPECT_EQ(parseError(edit("amplitude_m = 1000", "amplitude_m = -inf")),
            "x.toml:15: amplitude_m must be a finite number, got -inf");
  EXPECT_EQ(parseError(edit("octaves = 4", "octaves = 4\nlacunarity = inf")),
            "x.toml:10: layer 'base': lacunarity must be a finite number, got inf");
  EXPECT_EQ(parseError(edit("scheme = \"altitude\"", "scheme = \"altitude\"\nsnow = [nan, 0, 0]")),
            "x.toml:9: snow[0] must be in [0, 1], got nan");
}

TEST(PlanetDescription, HugeNumbersAreRejected) {
  // Beyond double or int64: the TOML parser's own message, with the line.
  EXPECT_TRUE(startsWith(parseError(edit("radius_m = 1_000_000", "radius_m = 1e400")), "x.toml:4:"));
  EXPECT_TRUE(startsWith(parseError(edit("octaves = 4", "octaves = 99999999999999999999")), "x.toml:13:"));
  // Representable but absurd: the range check (an int64 octave count is not truncated to int).
  EXPECT_EQ(parseError(edit("octaves = 4", "octaves = 9223372036854775807")),
            "x.toml:13: octaves must be in [1, 32], got 9223372036854775807");
  EXPECT_EQ(parseError(edit("octaves = 4", "octaves = 4294967300")),
            "x.toml:13: octaves must be in [1, 32], got 4294967300");
  EXPECT_EQ(parseError(edit("radius_m = 1_000_000", "radius_m = 1.7e308")),
            "x.toml:4: radius_m must be in [1000, 1e8], got 1.7e308");
}

TEST(PlanetDescription, EmptyInputIsRejected) {
  const std::string expected = "x.toml: empty document (expected [planet], [colors] and [[layer]] tables)";
  EXPECT_EQ(parseError(""), expected);
  EXPECT_EQ(parseError(" \n\t\r\n"), expected);
}

TEST(PlanetDescription, BinaryAndNonUtf8InputIsRejected) {
  EXPECT_EQ(parseError(std::string("\0\0\0\0", 4)), "x.toml:1:1: not TOML text (control byte 0x00)");
  EXPECT_EQ(parseError(edit("\"Test\"", std::string("\"Te\0st\"", 7))),
            "x.toml:3:11: not TOML text (control byte 0x00)");
  EXPECT_EQ(parseError(edit("\"Test\"", "\"Te\xffst\"")), "x.toml:3:11: not UTF-8 text (invalid byte 0xff)");
  EXPECT_EQ(parseError("\x89PNG\r\n\x1a\n"), "x.toml:1:1: not UTF-8 text (invalid byte 0x89)");
  EXPECT_EQ(parseError("\xc0\xaf"), "x.toml:1:1: not UTF-8 text (invalid byte 0xc0)");          // overlong '/'
  EXPECT_EQ(parseError("\xed\xa0\x80"), "x.toml:1:1: not UTF-8 text (invalid byte 0xed)");      // surrogate
  EXPECT_EQ(parseError("a = \"\xe2\x82\""), "x.toml:1:6: not UTF-8 text (invalid byte 0xe2)");  // truncated
  // Valid multi-byte UTF-8 is accepted, and columns count characters.
  EXPECT_EQ(parsePlanetDescription(edit("\"Test\"", "\"Terre \xc3\xa9\xe2\x82\xac\""), "x.toml").name,
            "Terre \xc3\xa9\xe2\x82\xac");
  // ... in strings and comments only: elsewhere TOML is ASCII (and toml++ 3.3 misbehaves on it,
  // found by the fuzzer: tests/fuzz/corpus/preset/toml_unreachable_*).
  const std::string outside = "x.toml:1: a non-ASCII character outside a string or a comment";
  EXPECT_EQ(parseError("\xc3\xa9 = 1").substr(0, outside.size()), outside);
  EXPECT_EQ(parseError("[a.\xc2\xa7]").substr(0, outside.size()), outside);
  EXPECT_EQ(parseError("name = \xc3\xa9").substr(0, outside.size()), outside);
  EXPECT_EQ(parseError(edit("\"Test\"", "\"Test\" # Terre \xc3\xa9")).find("non-ASCII"), std::string::npos);
  EXPECT_EQ(parseError("s = \"\"\"\\\n\xc2\xa7\"\"\"\n").substr(0, 69),
            "x.toml:2: a non-ASCII character after a backslash in a string: not a ");
  EXPECT_NE(parseError("name = \"a\\\xc3\xa9\"").find("x.toml:1: a non-ASCII character after a backslash"),
            std::string::npos);
  EXPECT_NE(parseError("name = \"\"\"a\\ \xef\xba\xbf\"\"\"").find("x.toml:1: a non-ASCII character after a backslash"),
            std::string::npos);
  std::mt19937 random(7);
  std::string garbage(4096, '\0');
  for (char& c : garbage) c = char(random());
  std::string message = parseError(garbage);
  EXPECT_TRUE(startsWith(message, "x.toml:")) << message;
  EXPECT_NE(message.find("not UTF-8 text"), std::string::npos) << message;
}

// Any byte sequence either parses or throws planet::Error with one line: truncations and
// random byte changes of the largest preset.
TEST(PlanetDescription, DamagedPresetsOnlyEverThrowOneLineErrors) {
  std::string earth = presetText("earth");
  int failures = 0;
  for (size_t length = 0; length < earth.size(); length += 7) {
    std::string message = errorOf([&] { parsePlanetDescription(earth.substr(0, length), "e.toml"); });
    failures += !message.empty();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  std::mt19937 random(11);
  for (int trial = 0; trial < 400; ++trial) {
    std::string damaged = earth;
    for (int k = 0; k < 3; ++k) damaged[random() % damaged.size()] = char(random());
    std::string message = errorOf([&] { parsePlanetDescription(damaged, "e.toml"); });
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_GT(failures, 0);
}

TEST(PlanetDescription, ResolvePresetByNameAndByFile) {
  EXPECT_EQ(resolvePreset("moon").name, "Moon");
  EXPECT_EQ(errorOf([] { resolvePreset("venus"); }),
            "unknown planet preset 'venus' (built-in: earth, moon, mars, giant, faults, mpd; or a FILE.toml)");

  const test::TempDir dir("description_test");
  auto write = [&](const std::string& fileName, const std::string& text) {
    std::string path = (dir / fileName).string();
    std::FILE* file = std::fopen(path.c_str(), "wb");
    EXPECT_NE(file, nullptr);
    if (file) {
      std::fwrite(text.data(), 1, text.size(), file);
      std::fclose(file);
    }
    return path;
  };
  std::string good = write("custom.toml", edit("\"Earth\"", "\"Custom\"", presetText("earth")));
  PlanetDescription custom = resolvePreset(good);
  EXPECT_EQ(custom.name, "Custom");
  EXPECT_EQ(custom.radiusM, 6371000.0);
  EXPECT_EQ(custom.layers.size(), resolvePreset("earth").layers.size());
  // A path without the .toml extension is a file too (it contains '/'); its errors name it.
  std::string bad = write("bad", edit("radius_m = 1_000_000", "radius_m = -5"));
  EXPECT_EQ(errorOf([&] { resolvePreset(bad); }), bad + ":4: radius_m must be in [1000, 1e8], got -5");
  // A built-in's errors would name NAME.toml, and a missing file names its path.
  EXPECT_EQ(errorOf([] { resolvePreset("no_such_planet.toml"); }),
            "cannot read 'no_such_planet.toml': No such file or directory");
  EXPECT_EQ(errorOf([&] { loadPlanetDescription(dir.string()); }),
            "cannot read '" + dir.string() + "': Is a directory");
}

// Hostile preset text (issue 7): one case per kind of bad input. Each is a planet::Error with
// one line, at most a few hundred bytes, that starts with the source name and says `says`; no
// input crashes the parser or makes it run for long.
TEST(PlanetDescription, HostileTextGivesOneShortLineNamingTheProblem) {
  const std::string base(kMinimal);
  const std::string planetTable = base.substr(0, base.find("[colors]"));
  auto repeated = [](std::string_view piece, size_t count) {
    std::string out;
    for (size_t i = 0; i < count; ++i) out += piece;
    return out;
  };
  std::mt19937 random(3);
  std::string binary(2048, '\0');
  for (char& c : binary) c = char(random());
  struct Case {
    const char* what;
    std::string text;
    std::string says;
  } cases[] = {
      {"empty", "", "x.toml: empty document"},
      {"blank", "\n \t\r\n", "x.toml: empty document"},
      {"only comments", "# a preset\n# with nothing in it\n", "x.toml: missing table [planet]"},
      {"unknown key", edit("has_ocean", "has_oceans"), "x.toml:5: unknown key 'has_oceans' in [planet]"},
      {"unknown key at top", "colour = 1\n" + base, "x.toml:1: unknown key 'colour' at top level"},
      {"unknown table", base + "[oceans]\n", "x.toml:16: unknown table [oceans]"},
      {"unknown dotted key", edit("has_ocean = false", "has_ocean = false\nextra.more = 1"),
       "x.toml:6: unknown key 'extra' in [planet]"},
      {"string for a number", edit("1_000_000", "\"1e6\""), "x.toml:4: 'radius_m' must be a number, got string"},
      {"table for a number", edit("1_000_000", "{ m = 1 }"), "x.toml:4: 'radius_m' must be a number, got table"},
      {"array for a number", edit("1_000_000", "[1e6]"), "x.toml:4: 'radius_m' must be a number, got array"},
      {"date for a number", edit("1_000_000", "1979-05-27"), "x.toml:4: 'radius_m' must be a number, got date"},
      {"number for a string", edit("\"fbm\"", "3"), "x.toml:12: 'type' must be a string, got integer"},
      {"table for an array", edit("scheme = \"altitude\"", "scheme = \"altitude\"\nsnow = { r = 1 }"),
       "x.toml:9: 'snow' must be an array of 3 numbers [r, g, b], got table"},
      {"array for a table", "planet = [1]\n" + base.substr(base.find("[colors]")),
       "x.toml:1: 'planet' must be a table, got array"},
      {"float for an integer", edit("octaves = 4", "octaves = 4.5"),
       "x.toml:13: 'octaves' must be an integer, got float"},
      {"nan", edit("1_000_000", "nan"), "x.toml:4: radius_m must be a finite number, got nan"},
      {"inf", edit("amplitude_m = 1000", "amplitude_m = inf"),
       "x.toml:15: amplitude_m must be a finite number, got inf"},
      {"-inf", edit("frequency = 1e-6", "frequency = -inf"), "x.toml:14: frequency must be a finite number, got -inf"},
      {"negative radius", edit("1_000_000", "-6e6"), "x.toml:4: radius_m must be in [1000, 1e8], got -6e6"},
      {"huge radius", edit("1_000_000", "1e300"), "x.toml:4: radius_m must be in [1000, 1e8], got 1e300"},
      {"huge height", edit("has_ocean = false", "has_ocean = false\nbase_height_m = 1e12"),
       "x.toml:6: base_height_m must be in [-1e5, 1e5], got 1e12"},
      {"negative height scale", edit("has_ocean = false", "has_ocean = false\nheight_scale = -2"),
       "x.toml:6: height_scale must be in [0, 100], got -2"},
      {"1000 octaves", edit("octaves = 4", "octaves = 1000"), "x.toml:13: octaves must be in [1, 32], got 1000"},
      {"negative octaves", edit("octaves = 4", "octaves = -4"), "x.toml:13: octaves must be in [1, 32], got -4"},
      {"int64 octaves", edit("octaves = 4", "octaves = -9223372036854775808"),
       "x.toml:13: octaves must be in [1, 32], got -9223372036854775808"},
      {"beyond double", edit("1_000_000", "1e999"), "x.toml:4:"},
      {"duplicate key", edit("has_ocean = false", "has_ocean = false\nradius_m = 2e6"), "x.toml:6:"},
      {"duplicate table", base + "[colors]\n", "x.toml:16:"},
      {"cut mid-table", base.substr(0, base.find("[colors]") + 4), "x.toml:7:"},
      {"cut mid-string", base.substr(0, base.find("\"Test\"") + 3), "x.toml:3:"},
      {"cut mid-array", base.substr(0, base.find("\n\n[[layer]]")) + "\nsnow = [1, 0", "x.toml:9:"},
      {"cut mid-key", base.substr(0, base.find("radius_m") + 3), "x.toml:4:"},
      {"binary garbage", binary, "x.toml:"},
      {"png header", "\x89PNG\r\n\x1a\n" + binary, "x.toml:1:1: not UTF-8 text (invalid byte 0x89)"},
      {"NUL byte", edit("Test", std::string("Te\0st", 5)), "x.toml:3:11: not TOML text (control byte 0x00)"},
      {"latin-1 in a string", edit("Test", "Caf\xe9"), "x.toml:3:12: not UTF-8 text (invalid byte 0xe9)"},
      {"latin-1 in a key", edit("radius_m", std::string("r") + char(0xe4) + "dius_m"),
       "x.toml:4:2: not UTF-8 text (invalid byte 0xe4)"},
      {"multi-megabyte", base + "# " + std::string(3 << 20, 'x') + "\n",
       "x.toml: too large (" + std::to_string(base.size() + (3 << 20) + 3) + " bytes, limit 1048576)"},
      {"deep table header", "[" + repeated("a.", 40000) + "a]\n",
       "x.toml:1: a key path of 40001 parts nests too deep (at most 8)"},
      {"deep array of tables", base + "[[" + repeated("layer.", 20000) + "x]]\n",
       "x.toml:16: a key path of 20001 parts nests too deep"},
      {"deep dotted key", edit("has_ocean = false", "has_ocean = false\n" + repeated("b . ", 40000) + "b = 1"),
       "x.toml:6: a key path of 40001 parts nests too deep"},
      {"deep quoted key", repeated("\"q\".", 20000) + "'q' = 1\n", "x.toml:1: a key path of 20001 parts"},
      {"deep key in an inline table", "x = { y = 1, " + repeated("z.", 30000) + "z = 2 }\n",
       "x.toml:1: a key path of 30001 parts"},
      {"deep arrays", "x = " + repeated("[", 100000), "x.toml:1:"},
      {"deep inline tables", "x = " + repeated("{ y = ", 100000), "x.toml:1:"},
      {"huge key", "\"" + std::string(900000, 'k') + "\" = 1\n", "x.toml:1: unknown key 'kkkkkkkkkk"},
      {"key with a newline escape", "\"a\\nb\" = 1\n" + base, "x.toml:1: unknown key 'a?b' at top level"},
      {"huge value", edit("\"altitude\"", "\"" + std::string(500000, 'v') + "\""),
       "x.toml:8: unknown color scheme 'vvvvvvvvvv"},
      {"huge name", edit("\"Test\"", "\"" + std::string(500000, 'n') + "\""),
       "x.toml:3: name must be 1 to 64 bytes long, got 500000"},
  };
  for (const Case& c : cases) {
    const auto start = std::chrono::steady_clock::now();
    const std::string message = parseError(c.text);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_TRUE(startsWith(message, c.says)) << c.what << "\n got: " << message.substr(0, 300);
    EXPECT_LT(message.size(), 400u) << c.what;
    // Not a speed claim: a bound that quadratic work on these inputs (minutes) would break, loose
    // enough for an AddressSanitizer build sharing the machine with another test (CTest runs two).
    EXPECT_LT(seconds, 5.0) << c.what;
  }
  // Dots, brackets and braces inside strings and comments are not key paths.
  const PlanetDescription d = parsePlanetDescription(
      edit("name = \"Test\"", "name = \"[a.a.a.a.a.a.a.a.a.a]\" # [b.b.b.b.b.b.b.b.b.b]\n# c.c.c.c.c.c.c.c.c.c = 1",
           edit("scheme = \"altitude\"",
                "scheme = '''altitude'''\nsnow = [\n  0.5, # x.x.x.x.x.x.x.x.x.x\n  0.5,\n  0.5,\n]")),
      "x.toml");
  EXPECT_EQ(d.name, "[a.a.a.a.a.a.a.a.a.a]");
  EXPECT_EQ(d.colors.snow, glm::vec3(0.5f));
  // A dotted key of two parts is as good as its table.
  EXPECT_EQ(
      parsePlanetDescription("colors.scheme = \"moon\"\n" + edit("[colors]\nscheme = \"altitude\"\n", ""), "x.toml")
          .colors.scheme,
      ColorScheme::Moon);
}

// The file front door: what cannot be read is one line naming the path and the reason.
TEST(PlanetDescription, UnreadableFilesAreOneLineNamingThePath) {
  const test::TempDir dir("description_files");
  std::filesystem::create_directories(dir / "sub.toml");
  const std::string missing = (dir / "missing.toml").string();
  EXPECT_EQ(errorOf([&] { loadPlanetDescription(missing); }),
            "cannot read '" + missing + "': No such file or directory");
  const std::string directory = (dir / "sub.toml").string();
  EXPECT_EQ(errorOf([&] { loadPlanetDescription(directory); }), "cannot read '" + directory + "': Is a directory");
  const std::string big = (dir / "big.toml").string();
  {
    std::FILE* file = std::fopen(big.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    const std::string chunk(1 << 16, '#');
    for (int i = 0; i < 64; ++i) std::fwrite(chunk.data(), 1, chunk.size(), file);  // 4 MiB
    std::fclose(file);
  }
  // Only the limit and one byte more are read: the size in the message is that, not the file's.
  EXPECT_EQ(errorOf([&] { loadPlanetDescription(big); }), big + ": too large (1048577 bytes, limit 1048576)");
  if (::geteuid() != 0) {  // root reads any file
    const std::string locked = (dir / "locked.toml").string();
    std::FILE* file = std::fopen(locked.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    std::fclose(file);
    std::filesystem::permissions(locked, std::filesystem::perms::none);
    EXPECT_EQ(errorOf([&] { loadPlanetDescription(locked); }), "cannot read '" + locked + "': Permission denied");
  }
}

TEST(PlanetDescription, DescriptionHashIsStableAndSeesEveryChange) {
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ull);  // published FNV-1a 64 test vectors
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ull);

  PlanetDescription earth = resolvePreset("earth");
  EXPECT_EQ(descriptionHash(earth), descriptionHash(resolvePreset("earth")));
  EXPECT_EQ(descriptionHash(earth), fnv1a64(canonicalForm(earth)));
  // Equal meaning, equal hash: a default written out equals the default left out.
  EXPECT_EQ(
      descriptionHash(parsePlanetDescription(kMinimal, "x.toml")),
      descriptionHash(parsePlanetDescription(edit("octaves = 4", "octaves = 4\noffset = 0\ngain = 2"), "y.toml")));

  const uint64_t base = descriptionHash(earth);
  auto changed = [&](auto change) {
    PlanetDescription d = earth;
    change(d);
    return descriptionHash(d);
  };
  EXPECT_NE(changed([](PlanetDescription& d) { d.radiusM += 1.0; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.hasOcean = false; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.seaLevelM = 1.0; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.heightScale = 2.0; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.baseHeightM += 0.5; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.colors.snow.x *= 0.5f; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.colors.scheme = ColorScheme::Altitude; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.layers[2].noise.seed += 1; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.layers[2].noise.octaves -= 1; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.layers[1].noise.gain = 2.5; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.layers[1].frequency *= 1.0 + 1e-15; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.layers[0].amplitudeM = -d.layers[0].amplitudeM; }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { std::swap(d.layers[0], d.layers[1]); }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.layers.pop_back(); }), base);
  EXPECT_NE(changed([](PlanetDescription& d) { d.name = "Earth2"; }), base);
}

}  // namespace
}  // namespace planet

// Presets written back (planet/preset_writer.h): every built-in preset, edited ones and
// random descriptions the parser could have produced read back with the same canonical form;
// the text is deterministic and laid out like the presets; saving is whole or not at all.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include "core/error.h"
#include "core/file.h"
#include "planet/planet_description.h"
#include "planet/preset_writer.h"

namespace planet {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

PlanetDescription reparse(const PlanetDescription& d) {
  return parsePlanetDescription(formatPlanetDescription(d), "saved.toml");
}

// parse(format(d)) has the canonical form and hash of d, and formatting it again gives the same text.
void expectRoundTrip(const PlanetDescription& d) {
  std::string text = formatPlanetDescription(d);
  PlanetDescription back;
  std::string error = errorOf([&] { back = parsePlanetDescription(text, "saved.toml"); });
  ASSERT_EQ(error, "") << text;
  EXPECT_EQ(canonicalForm(back), canonicalForm(d)) << text;
  EXPECT_EQ(descriptionHash(back), descriptionHash(d));
  EXPECT_EQ(formatPlanetDescription(back), text);
}

PlanetDescription preset(const std::string& name) { return resolvePreset(name); }

// The text of the [[layer]] table named `name` in a formatted preset.
std::string layerText(const std::string& text, const std::string& name) {
  size_t begin = text.find("[[layer]]\nname = \"" + name + "\"\n");
  EXPECT_NE(begin, std::string::npos) << name;
  if (begin == std::string::npos) return "";
  size_t end = text.find("[[layer]]", begin + 1);
  return text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

TEST(PresetWriter, EveryEmbeddedPresetRoundTripsWithTheSameCanonicalFormAndHash) {
  ASSERT_FALSE(embeddedPresets().empty());
  for (const EmbeddedPreset& embedded : embeddedPresets()) {
    SCOPED_TRACE(embedded.name);
    PlanetDescription original = parsePlanetDescription(embedded.text, std::string(embedded.name) + ".toml");
    PlanetDescription back = reparse(original);
    EXPECT_EQ(descriptionHash(back), descriptionHash(original));
    EXPECT_EQ(canonicalForm(back), canonicalForm(original));
  }
}

TEST(PresetWriter, EditedEarthWithoutAirOceanOrCloudsAndWithAnExtraLayerRoundTrips) {
  PlanetDescription d = preset("earth");
  d.name = "Edited \"Earth\" \\ Terre \xc3\xa9t\xc3\xa9";  // quotes, a backslash, UTF-8
  d.radiusM = 1234567.891;
  d.heightScale = 2.5;
  d.baseHeightM = -123.456;
  d.layers[0].noise.type = noise::NoiseType::Hetero;
  d.layers[0].noise.octaves = 32;
  d.layers[0].noise.seed = 4294967295u;
  d.layers[0].amplitudeM = -3333.3;
  d.layers[1].noise.type = noise::NoiseType::Simplex;
  d.layers[1].noise.octaves = 1;
  d.layers[1].noise.offset.reset();  // resolves to the simplex default
  d.layers[1].noise.gain = 0.0;
  d.layers[2].noise.hash = noise::NoiseHash::Reference;
  d.layers[2].frequency = 1.0 / 3.0;
  d.layers[3].noise.lacunarity = std::nextafter(1.0, 2.0);
  d.layers[3].noise.H = 4.0;
  NoiseLayer extra;
  extra.name = "extra";
  extra.noise.type = noise::NoiseType::Cascade;
  extra.noise.octaves = 5;
  extra.noise.offset = -10.0;
  extra.noise.seed = 99;
  extra.frequency = 7.3e-8;
  extra.amplitudeM = 1e5;
  extra.transfer = {{-1.5, -2.0}, {0.25, 0.125}, {1e5, 3.0}};
  extra.mask = "hills";
  extra.maskCurve = {{-1e5, 1.0}, {1e-3, 0.0}};
  d.layers.push_back(extra);
  d.layers[0].hypsometry = {{0.0, -1e5}, {0.1, -5.5}, {1.0, 1e5}};
  d.layers[1].mask.clear();  // the belts unmasked: the mountains' mask stays
  d.layers[1].maskCurve.clear();
  d.colors.scheme = ColorScheme::Altitude;
  d.colors.lowland = {0.1f, 0.2f, 0.3f};
  d.colors.snow = {1.0f, 0.0f, 1.0f / 3.0f};
  d.colors.beachHeightM = 0.0;
  d.hasOcean = false;  // what the parser gives without an ocean, [water] and [atmosphere]
  d.seaLevelM = 0.0;
  d.water = {};
  d.atmosphere = {};
  d.clouds = {};
  d.stars.enabled = false;
  expectRoundTrip(d);

  std::string text = formatPlanetDescription(d);
  for (const char* absent : {"[atmosphere]", "[clouds]", "[water]", "sea_level_m"})
    EXPECT_EQ(text.find(absent), std::string::npos) << absent;
  PlanetDescription back = reparse(d);
  EXPECT_FALSE(back.atmosphere.enabled);
  EXPECT_FALSE(back.clouds.enabled);
  EXPECT_FALSE(back.hasOcean);
  EXPECT_FALSE(back.stars.enabled);
  ASSERT_EQ(back.layers.size(), 6u);
  EXPECT_EQ(back.name, d.name);
  EXPECT_EQ(back.layers[5].transfer, d.layers[5].transfer);
  EXPECT_EQ(back.layers[5].mask, "hills");
  EXPECT_EQ(back.layers[5].maskCurve, d.layers[5].maskCurve);
  EXPECT_EQ(back.layers[0].hypsometry, d.layers[0].hypsometry);
  EXPECT_TRUE(back.layers[1].mask.empty());
  EXPECT_EQ(back.layers[2].mask, "belts");
  EXPECT_EQ(back.layers[1].noise.offset, noise::defaultOffset(noise::NoiseType::Simplex));
}

TEST(PresetWriter, EditedMoonWithAirCloudsAndAnOceanRoundTrips) {
  PlanetDescription d = preset("moon");
  d.hasOcean = true;
  d.seaLevelM = -250.5;
  d.water = {12.5, 3.25, 0.5};
  d.atmosphere.enabled = true;
  d.atmosphere.heightM = 60'000.0;
  d.atmosphere.rayleighScattering = {1e-6, 2e-6, 3.3e-6};
  d.atmosphere.mieScattering = glm::dvec3(7e-6);  // written as one number
  d.atmosphere.mieAbsorption = {0.0, 1e-7, std::numeric_limits<double>::denorm_min()};
  d.atmosphere.mieG = glm::dvec3(-0.99);
  d.atmosphere.ozoneAbsorption = {0.0, 0.0, 0.0};
  d.atmosphere.ozoneWidthM = 0.0;
  d.clouds.enabled = true;
  d.clouds.bottomM = 0.0;
  d.clouds.topM = 60'000.0;  // at the atmosphere's top: allowed
  d.clouds.octaves = 16;
  d.clouds.seed = 0;
  d.clouds.windMps = -1e3;
  d.colors.deepWater = {0.0f, 7.038531e-26f, 1e-45f};  // 7.038531e-26 double-rounds wrongly as float text
  expectRoundTrip(d);
  std::string text = formatPlanetDescription(d);
  EXPECT_NE(text.find("mie_scattering = 7e-6\n"), std::string::npos) << text;
  EXPECT_NE(text.find("sea_level_m = -250.5\n"), std::string::npos) << text;
}

// Random descriptions within every range and rule the parser enforces, bounds and their
// neighbours included: values it could have produced.
class RandomPlanet {
 public:
  explicit RandomPlanet(uint64_t seed) : rng_(seed) {}

  PlanetDescription next() {
    PlanetDescription d;
    d.name = name(0);
    d.radiusM = value(kRadiusRangeM);
    d.hasOcean = coin();
    if (d.hasOcean && coin()) d.seaLevelM = value(kSeaLevelRangeM);
    d.heightScale = value(kHeightScaleRange);
    d.baseHeightM = value(kBaseHeightRangeM);
    d.colors = defaultColors(ColorScheme(integer(0, 3)));
    d.colors.beachHeightM = value(kBeachHeightRangeM);
    d.colors.snowLineM = value(kSnowLineRangeM);
    d.colors.iceCapLatitudeDeg = value(kIceCapLatitudeRangeDeg);
    for (glm::vec3* c : {&d.colors.deepWater, &d.colors.shallowWater, &d.colors.beach, &d.colors.lowland,
                         &d.colors.highland, &d.colors.cliff, &d.colors.snow})
      if (coin()) *c = {colorComponent(), colorComponent(), colorComponent()};
    int layers = int(integer(1, kMaxLayers));
    for (int i = 0; i < layers; ++i) d.layers.push_back(layer(i));
    // Faults and MPD sample the unit sphere: the parser gives them no other frequency.
    for (NoiseLayer& l : d.layers)
      if (noise::isGenerator(l.noise.type)) l.frequency = 1.0 / d.radiusM;
    if (coin()) d.atmosphere = atmosphere();
    if (d.atmosphere.enabled && coin()) d.clouds = clouds(d.atmosphere.heightM);
    if (d.hasOcean && coin()) d.water = {value(kClarityRangeM), value(kWaveWavelengthRangeM), value(kWaveSlopeRange)};
    if (coin())
      d.stars = {coin(), uint32_t(integer(0, 4294967295)), value(kMagnitudeRange), value(kStarBrightnessRange)};
    if (coin()) {
      d.lights.enabled = true;
      d.lights.radianceNw = value(kLightsRadianceRangeNw);
      d.lights.gain = value(kLightsGainRange);
      d.lights.color = {colorComponent(), colorComponent(), 1.0f};  // never black (an error)
      d.lights.coverage = value(kUnitRange);
      d.lights.citySizeM = value(kCitySizeRangeM);
      d.lights.seed = uint32_t(integer(0, 4294967295));
    }
    return d;
  }

 private:
  bool coin() { return std::uniform_int_distribution<int>(0, 1)(rng_) == 1; }
  int64_t integer(int64_t min, int64_t max) { return std::uniform_int_distribution<int64_t>(min, max)(rng_); }

  // A bound, a bound's neighbour, -0, the smallest subnormal, or a uniform or log-uniform value.
  double value(Range r) { return std::clamp(anyValue(r), r.min, r.max); }
  double anyValue(Range r) {
    const double inf = std::numeric_limits<double>::infinity();
    switch (integer(0, 15)) {
      case 0: return r.min;
      case 1: return r.max;
      case 2: return std::nextafter(r.min, inf);
      case 3: return std::nextafter(r.max, -inf);
      case 4: return r.min <= 0.0 && r.max >= 0.0 ? -0.0 : r.min;
      case 5: return r.min <= 0.0 ? std::numeric_limits<double>::denorm_min() : r.max;
      case 6:
      case 7:
        if (r.min > 0.0)
          return std::exp(std::uniform_real_distribution<double>(std::log(r.min), std::log(r.max))(rng_));
        [[fallthrough]];
      default: return std::uniform_real_distribution<double>(r.min, r.max)(rng_);
    }
  }

  // Any float in [0, 1], subnormals included: the parser rounds any double in range to one.
  float colorComponent() {
    auto bits = uint32_t(integer(0, 0x3f800000));
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  }

  // 1 to 64 bytes without control characters, unique by their leading index; quotes and UTF-8 included.
  std::string name(int index) {
    static const std::vector<std::string> kPieces = {
        "a", "Z", " ", "\"", "\\", "'", "#", "=", "[", "]", "\xc3\xa9", "\xe2\x82\xac", "\xf0\x9f\x8c\x8d", "~"};
    std::string out = std::to_string(index);
    size_t length = size_t(integer(1, int64_t(kMaxNameBytes)));
    while (true) {
      const std::string& piece = kPieces[size_t(integer(0, int64_t(kPieces.size()) - 1))];
      if (out.size() + piece.size() > length) return out;
      out += piece;
    }
  }

  NoiseLayer layer(int index) {
    NoiseLayer l;
    l.name = name(index);
    l.noise.type = noise::NoiseType(integer(0, int64_t(gpu::kNoiseTypeCount) - 1));
    l.noise.octaves = int(integer(noise::kMinOctaves, noise::kMaxOctaves));
    if (l.noise.type == noise::NoiseType::Faults) {  // no octaves: a count and a ramp width
      l.noise.octaves = 1;
      l.noise.faults = int(integer(noise::kMinFaults, noise::kMaxFaults));
      l.noise.width = coin() ? 0.0 : value({0.0, noise::kMaxFaultWidth});
    } else if (noise::isMpd(l.noise.type)) {  // octaves are levels
      l.noise.octaves = int(integer(noise::kMinMpdLevels, noise::kMaxMpdLevels));
      l.noise.multifractal = coin();
    }
    l.noise.lacunarity = value({std::nextafter(1.0, 2.0), 8.0});
    l.noise.H = value({noise::kMinH, noise::kMaxH});
    if (coin())  // craters' offset is a rim perturbation with a narrower range
      l.noise.offset = l.noise.type == noise::NoiseType::Craters ? value({0.0, noise::kMaxCraterPerturbation})
                                                                 : value({-noise::kMaxOffset, noise::kMaxOffset});
    if (coin()) l.noise.gain = value({0.0, noise::kMaxGain});
    l.noise.seed = uint32_t(integer(0, 4294967295));
    l.noise.hash = noise::NoiseHash(integer(0, 1));
    // Keys the parser refuses for these types keep their defaults.
    if (noise::isGenerator(l.noise.type)) {
      const noise::NoiseSettings defaults;
      l.noise.lacunarity = defaults.lacunarity;
      l.noise.offset.reset();
      l.noise.hash = defaults.hash;
      if (l.noise.type == noise::NoiseType::Faults) {
        l.noise.H = defaults.H;
        l.noise.gain.reset();
      }
    }
    // From a frequency key or from a wavelength_m key (1 / wavelength).
    l.frequency = coin() ? value(kFrequencyRange) : 1.0 / value(kWavelengthRangeM);
    l.amplitudeM = value(kAmplitudeRangeM);
    return l;
  }

  glm::dvec3 coefficients() {
    if (coin()) return glm::dvec3(value(kScatteringRange));
    return {value(kScatteringRange), value(kScatteringRange), value(kScatteringRange)};
  }

  AtmosphereDescription atmosphere() {
    AtmosphereDescription a;
    a.enabled = true;
    a.heightM = value(kAtmosphereHeightRangeM);
    a.rayleighScattering = coefficients();
    a.rayleighScaleHeightM = value(kScaleHeightRangeM);
    a.mieScattering = coefficients();
    a.mieExtinctionRatio = value(kMieExtinctionRatioRange);
    a.mieAbsorption = coefficients();
    a.mieScaleHeightM = value(kScaleHeightRangeM);
    a.mieG = glm::dvec3(value(kMieGRange), value(kMieGRange), value(kMieGRange));
    a.ozoneAbsorption = coefficients();
    a.ozoneCenterM = value(kOzoneAltitudeRangeM);
    a.ozoneWidthM = value(kOzoneAltitudeRangeM);
    if (a.ozoneWidthM <= 0.0 && a.ozoneAbsorption != glm::dvec3(0.0)) a.ozoneWidthM = 1.0;
    return a;
  }

  CloudDescription clouds(double atmosphereHeightM) {
    CloudDescription c;
    c.enabled = true;
    double ceiling = std::min(atmosphereHeightM, kCloudAltitudeRangeM.max);
    c.bottomM = value({0.0, std::nextafter(ceiling, 0.0)});
    c.topM = value({std::nextafter(c.bottomM, ceiling), ceiling});
    c.coverage = value(kUnitRange);
    c.sharpness = value(kSharpnessRange);
    c.wavelengthM = value(kCloudWavelengthRangeM);
    c.octaves = int(integer(1, 16));
    c.seed = uint32_t(integer(0, 4294967295));
    c.windMps = value(kWindRangeMps);
    c.evolvePeriodS = value(kEvolvePeriodRangeS);
    c.opacity = value(kCloudOpacityRange);
    return c;
  }

  std::mt19937_64 rng_;
};

TEST(PresetWriter, AnyDescriptionTheParserCouldProduceFormatsToTextItParsesBackEqual) {
  RandomPlanet random(20240601);
  for (int i = 0; i < 1000; ++i) {
    SCOPED_TRACE("random description " + std::to_string(i));
    expectRoundTrip(random.next());
    if (testing::Test::HasFailure()) break;  // one description's failure is enough to read
  }
}

TEST(PresetWriter, FormattingIsDeterministic) {
  for (const std::string& name : presetNames()) {
    PlanetDescription d = preset(name);
    std::string first = formatPlanetDescription(d);
    EXPECT_EQ(formatPlanetDescription(d), first);
    EXPECT_EQ(formatPlanetDescription(preset(name)), first);
  }
}

TEST(PresetWriter, TextHasThePresetLayoutWithEveryKeyAndResolvedDefaults) {
  std::string text = formatPlanetDescription(preset("earth"));
  size_t at = 0;
  for (const char* line : {"[planet]\n",
                           "name = \"Earth\"\n",
                           "radius_m = 6_371_000\n",
                           "has_ocean = true\n",
                           "sea_level_m = 0\n",
                           "height_scale = 1\n",
                           "base_height_m = 0\n",
                           "[colors]\n",
                           "scheme = \"earth\"\n",
                           "deep_water = [0.004, 0.016, 0.045]\n",
                           "[atmosphere]\n",
                           "height_m = 100_000\n",
                           "rayleigh_scattering = [5.8e-6, 1.35e-5, 3.31e-5]\n",
                           "mie_scattering = 2.1e-5\n",
                           "mie_absorption = 0\n",
                           "[clouds]\n",
                           "octaves = 9\n",
                           "[water]\n",
                           "clarity_m = 30\n",
                           "[stars]\n",
                           "enabled = true\n",
                           "[[layer]]\n",
                           "name = \"continents\"\n",
                           "type = \"fbm\"\n",
                           "octaves = 9\n",
                           "lacunarity = 2.03\n",
                           "H = 0.85\n",
                           "offset = 0\n",  // the fbm default, resolved
                           "gain = 2\n",
                           "seed = 23\n",
                           "hash = \"fast\"\n",
                           "wavelength_m = 6_500_000\n",
                           "amplitude_m = 1\n",
                           "hypsometry = [[0, -6_300], [0.02, -5_500], ",
                           "[1, 1_200]]\n",
                           "[[layer]]\n",
                           "name = \"belts\"\n",
                           "amplitude_m = 0\n",
                           "transfer = [[-0.3, 0], ",
                           "mask = \"continents\"\n",
                           "mask_curve = [[-2_500, 0], ",
                           "[[layer]]\n",
                           "name = \"mountains\"\n",
                           "wavelength_m = 400_000\n",
                           "mask = \"belts\"\n",
                           "[[layer]]\n",
                           "name = \"hills\"\n",
                           "wavelength_m = 20_000\n",
                           "[[layer]]\n",
                           "name = \"ground\"\n",
                           "wavelength_m = 3_000\n"}) {
    size_t found = text.find(line, at);
    ASSERT_NE(found, std::string::npos) << "missing or out of order: " << line << text;
    at = found + std::strlen(line);
  }
  std::string moon = formatPlanetDescription(preset("moon"));
  for (const char* absent : {"[atmosphere]", "[clouds]", "[water]", "sea_level_m"})
    EXPECT_EQ(moon.find(absent), std::string::npos) << absent;
  EXPECT_NE(moon.find("offset = 0.8\n"), std::string::npos);  // the cascade default, resolved
}

TEST(PresetWriter, SchemaGapsReadBackAsTheParsersDefaults) {
  // A viewer may switch an effect off and keep its settings; the preset has no place for them.
  PlanetDescription d = preset("earth");
  d.atmosphere.enabled = false;  // clouds stay enabled but are not drawn without air
  d.hasOcean = false;
  d.seaLevelM = 12.0;
  PlanetDescription back = reparse(d);
  EXPECT_FALSE(back.atmosphere.enabled);
  EXPECT_FALSE(back.clouds.enabled);
  EXPECT_EQ(back.seaLevelM, 0.0);
  PlanetDescription expected = d;
  expected.atmosphere = {};
  expected.clouds = {};
  expected.seaLevelM = 0.0;
  expected.water = {};
  EXPECT_EQ(canonicalForm(back), canonicalForm(expected));
}

TEST(PresetWriter, LayerScaleIsAWavelengthWhenOneReadsBackExactlyElseAFrequency) {
  PlanetDescription d = preset("moon");
  d.layers[0].frequency = 1.0 / 200'000.0;  // 5e-6: as few digits either way
  EXPECT_NE(layerText(formatPlanetDescription(d), "basins").find("wavelength_m = 200_000\n"), std::string::npos);
  d.layers[0].frequency = 1.2345e-5;  // 1 / f = 81004.45524503848...: the frequency reads better
  EXPECT_NE(layerText(formatPlanetDescription(d), "basins").find("frequency = 1.2345e-5\n"), std::string::npos);
  expectRoundTrip(d);
  int wavelengths = 0, frequencies = 0;
  std::mt19937_64 rng(7);
  for (int i = 0; i < 500 && !testing::Test::HasFailure(); ++i) {
    d.layers[0].frequency = std::exp(std::uniform_real_distribution<double>(std::log(1e-9), std::log(10.0))(rng));
    std::string layer = layerText(formatPlanetDescription(d), "basins");
    wavelengths += layer.find("wavelength_m = ") != std::string::npos;
    frequencies += layer.find("frequency = ") != std::string::npos;
    expectRoundTrip(d);
  }
  EXPECT_GT(wavelengths, 0);
  EXPECT_GT(frequencies, 0);
}

// Each test gets an empty directory of its own.
class PresetWriterFile : public testing::Test {
 protected:
  void SetUp() override {
    const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("planet_preset_writer_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
};

TEST_F(PresetWriterFile, SavedPresetLoadsBackEqualAndNoTemporaryFileRemains) {
  for (const std::string& name : presetNames()) {
    PlanetDescription d = preset(name);
    std::string target = path(name + ".toml");
    savePlanetDescription(d, target);
    EXPECT_EQ(readFileUpTo(target, kMaxPresetBytes), formatPlanetDescription(d));
    PlanetDescription back = loadPlanetDescription(target);
    EXPECT_EQ(canonicalForm(back), canonicalForm(d));
    EXPECT_EQ(canonicalForm(resolvePreset(target)), canonicalForm(d));
  }
  EXPECT_EQ(files(), (std::vector<std::string>{"earth.toml", "faults.toml", "giant.toml", "mars.toml", "moon.toml",
                                               "mpd.toml"}));
}

TEST_F(PresetWriterFile, SaveReplacesAnExistingFileWhole) {
  std::string target = path("planet.toml");
  savePlanetDescription(preset("earth"), target);
  savePlanetDescription(preset("moon"), target);
  EXPECT_EQ(canonicalForm(loadPlanetDescription(target)), canonicalForm(preset("moon")));
  EXPECT_EQ(files(), std::vector<std::string>{"planet.toml"});
}

TEST_F(PresetWriterFile, SaveToAMissingDirectoryThrowsNamingThePathAndLeavesNothing) {
  std::string target = path("no-such-dir/planet.toml");
  std::string error = errorOf([&] { savePlanetDescription(preset("earth"), target); });
  EXPECT_NE(error.find("'" + target + "'"), std::string::npos) << error;
  EXPECT_NE(error.find("No such file or directory"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_TRUE(files().empty());
}

TEST_F(PresetWriterFile, SaveOverADirectoryThrowsNamingThePathAndRemovesItsTemporaryFile) {
  fs::create_directory(dir_ / "taken.toml");
  std::string error = errorOf([&] { savePlanetDescription(preset("mars"), path("taken.toml")); });
  EXPECT_NE(error.find("'" + path("taken.toml") + "'"), std::string::npos) << error;
  EXPECT_EQ(files(), std::vector<std::string>{"taken.toml"});
}

TEST_F(PresetWriterFile, SaveRefusesADescriptionThatWouldNotLoadAndKeepsTheOldFile) {
  std::string target = path("planet.toml");
  savePlanetDescription(preset("earth"), target);
  PlanetDescription bad = preset("earth");
  bad.clouds.topM = 200'000.0;  // above the atmosphere's top
  std::string error = errorOf([&] { savePlanetDescription(bad, target); });
  EXPECT_NE(error.find(target), std::string::npos) << error;
  EXPECT_NE(error.find("must be below the atmosphere's height_m"), std::string::npos) << error;
  PlanetDescription empty = preset("moon");
  empty.layers.clear();
  EXPECT_NE(errorOf([&] { savePlanetDescription(empty, target); }).find(target), std::string::npos);
  EXPECT_EQ(canonicalForm(loadPlanetDescription(target)), canonicalForm(preset("earth")));
  EXPECT_EQ(files(), std::vector<std::string>{"planet.toml"});
}

}  // namespace
}  // namespace planet

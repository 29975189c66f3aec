#include "planet/planet_description.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/error.h"
#include "core/file.h"
#include "planet/toml_reader.h"

namespace planet {
namespace {

using toml_reader::Context;
using toml_reader::formatNumber;
using toml_reader::formatRange;
using toml_reader::lineOf;
using toml_reader::optionalTable;
using toml_reader::parseAt;
using toml_reader::requireTable;
using toml_reader::shortened;
using toml_reader::TableReader;
using toml_reader::typeName;

constexpr std::string_view kTopKeys[] = {"planet",     "colors", "materials", "layer",
                                         "atmosphere", "clouds", "water",     "stars",
                                         "lights"};
constexpr std::string_view kMaterialKeys[] = {
    "equator_temperature_c", "pole_temperature_drop_c", "lapse_rate_k_per_km", "snow_temperature_c",
    "moisture",              "moisture_noise",          "coastal_height_m",    "dry_belt",
    "regional_noise",
    "rock_slope_deg",        "snow_slope_deg",          "detail_relief",       "detail_contrast",
    "conifer",               "forest",                  "grass",               "dry_grass",
    "desert",                "tundra",                  "scree"};
constexpr std::string_view kAtmosphereKeys[] = {"height_m",
                                                "rayleigh_scattering",
                                                "rayleigh_scale_height_m",
                                                "mie_scattering",
                                                "mie_extinction_ratio",
                                                "mie_absorption",
                                                "mie_scale_height_m",
                                                "mie_g",
                                                "ozone_absorption",
                                                "ozone_center_m",
                                                "ozone_width_m",
                                                "airglow_cd_m2",
                                                "airglow_color",
                                                "airglow_bottom_m",
                                                "airglow_top_m"};
constexpr std::string_view kCloudKeys[] = {
    "bottom_m", "top_m",   "coverage", "sharpness",        "wavelength_m", "octaves", "seed",       "wind_mps",
    "evolve_period_s", "opacity", "climate", "cyclones", "cyclone_radius_m", "swirl", "shear", "warp", "resolution"};
constexpr std::string_view kWaterKeys[] = {"clarity_m", "wave_wavelength_m", "wave_slope", "wind_mps"};
constexpr std::string_view kStarKeys[] = {"enabled", "seed", "faintest_magnitude", "brightness"};
constexpr std::string_view kLightsKeys[] = {"enabled", "radiance_nw", "gain", "color", "coverage", "city_size_m", "seed"};
constexpr std::string_view kPlanetKeys[] = {"name",        "radius_m",     "has_ocean",
                                            "sea_level_m", "height_scale", "base_height_m"};
constexpr std::string_view kColorKeys[] = {"scheme",     "beach_height_m",     "snow_line_m",  "ice_cap_latitude_deg",
                                           "deep_water", "shallow_water",      "beach",        "lowland",
                                           "highland",   "cliff",              "snow",         "palette",
                                           "polar_caps", "noise_wavelength_m", "perturbation"};
constexpr std::string_view kLayerKeys[] = {"name", "type", "octaves",   "lacunarity",   "H",          "offset", "gain",
                                           "seed", "hash", "frequency", "wavelength_m", "amplitude_m",
                                           "transfer", "hypsometry", "mask", "mask_curve",
                                           "count", "width", "levels", "multifractal"};

struct SchemeName {
  ColorScheme scheme;
  const char* name;
};
constexpr SchemeName kSchemeNames[] = {
    {ColorScheme::Earth, "earth"},
    {ColorScheme::Altitude, "altitude"},
    {ColorScheme::Moon, "moon"},
    {ColorScheme::Mars, "mars"},
    {ColorScheme::Giant, "giant"},
    {ColorScheme::AltitudePerturbed, "altitude_perturbed"},
    {ColorScheme::Noise, "noise"},
    {ColorScheme::AltitudeNoise, "altitude_noise"},
    {ColorScheme::Turbulence, "turbulence"},
    {ColorScheme::EarthLike, "earth_like"},
    {ColorScheme::Gradient, "gradient"},
    {ColorScheme::MoonLike, "moon_like"},
};
constexpr ColorScheme kSchemes[] = {
    ColorScheme::Earth,      ColorScheme::Altitude,      ColorScheme::Moon,       ColorScheme::Mars,
    ColorScheme::Giant,      ColorScheme::AltitudePerturbed, ColorScheme::Noise,  ColorScheme::AltitudeNoise,
    ColorScheme::Turbulence, ColorScheme::EarthLike,     ColorScheme::Gradient,   ColorScheme::MoonLike,
};
static_assert(std::size(kSchemes) == std::size(kSchemeNames));

// palette = [[r, g, b], ...]: exactly the scheme's paletteSize colours.
void readPalette(const Context& context, const TableReader& reader, PlanetColors& colors) {
  const toml::node* node = reader.find("palette");
  if (!node) return;
  const size_t size = paletteSize(colors.scheme);
  if (size == 0)
    context.fail(lineOf(*node), fmt::format("palette is not used by scheme '{}' (only by the schemes of seed 000)",
                                            colorSchemeName(colors.scheme)));
  const toml::array* array = node->as_array();
  if (!array || array->size() != size)
    context.fail(lineOf(*node),
                 fmt::format("palette of scheme '{}' must be an array of {} colours [r, g, b], got {}",
                             colorSchemeName(colors.scheme), size,
                             array ? fmt::format("{} elements", array->size()) : typeName(*node)));
  for (size_t i = 0; i < size; ++i) {
    const toml::node& item = *array->get(i);
    const toml::array* rgb = item.as_array();
    if (!rgb || rgb->size() != 3)
      context.fail(lineOf(item), fmt::format("palette[{}] must be an array of 3 numbers [r, g, b], got {}", i,
                                             rgb ? fmt::format("{} elements", rgb->size()) : typeName(item)));
    for (size_t k = 0; k < 3; ++k)
      colors.palette[i][int(k)] =
          float(reader.element(*rgb->get(k), fmt::format("palette[{}][{}]", i, k), kColorComponentRange));
  }
}

PlanetColors readColors(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[colors]", kColorKeys);
  std::string schemeName = reader.requiredString("scheme");
  PlanetColors colors =
      defaultColors(parseAt(context, lineOf(*reader.find("scheme")), [&] { return parseColorScheme(schemeName); }));
  colors.beachHeightM = reader.number("beach_height_m", kBeachHeightRangeM).value_or(colors.beachHeightM);
  colors.snowLineM = reader.number("snow_line_m", kSnowLineRangeM).value_or(colors.snowLineM);
  colors.iceCapLatitudeDeg =
      reader.number("ice_cap_latitude_deg", kIceCapLatitudeRangeDeg).value_or(colors.iceCapLatitudeDeg);
  struct ColorKey {
    std::string_view key;
    glm::vec3 PlanetColors::*member;
  };
  const ColorKey colorKeys[] = {
      {"deep_water", &PlanetColors::deepWater},
      {"shallow_water", &PlanetColors::shallowWater},
      {"beach", &PlanetColors::beach},
      {"lowland", &PlanetColors::lowland},
      {"highland", &PlanetColors::highland},
      {"cliff", &PlanetColors::cliff},
      {"snow", &PlanetColors::snow},
  };
  for (const ColorKey& c : colorKeys)
    if (auto value = reader.color(c.key)) colors.*c.member = *value;
  readPalette(context, reader, colors);
  colors.noiseWavelengthM =
      reader.number("noise_wavelength_m", kColorNoiseWavelengthRangeM).value_or(colors.noiseWavelengthM);
  colors.perturbation = reader.number("perturbation", kPerturbationRange).value_or(colors.perturbation);
  colors.polarCaps = reader.boolean("polar_caps").value_or(colors.polarCaps);
  // Caps without a latitude of their own start at seed 004's polar circle (its POLAR_CIRCLE,
  // sin 66.5° = 0.917).
  if (colors.polarCaps && !reader.find("ice_cap_latitude_deg")) colors.iceCapLatitudeDeg = kPolarCircleDeg;
  return colors;
}

MaterialDescription readMaterials(const Context& context, const toml::table& table, ColorScheme scheme) {
  TableReader reader(context, table, "[materials]", kMaterialKeys);
  MaterialDescription m = defaultMaterials(scheme);
  struct NumberKey {
    std::string_view key;
    double MaterialDescription::*member;
    Range range;
  };
  const NumberKey numberKeys[] = {
      {"equator_temperature_c", &MaterialDescription::equatorTemperatureC, kTemperatureRangeC},
      {"pole_temperature_drop_c", &MaterialDescription::poleTemperatureDropC, kTemperatureDropRangeC},
      {"lapse_rate_k_per_km", &MaterialDescription::lapseRateKPerKm, kLapseRangeKPerKm},
      {"snow_temperature_c", &MaterialDescription::snowTemperatureC, kTemperatureRangeC},
      {"moisture", &MaterialDescription::moisture, kUnitRange},
      {"moisture_noise", &MaterialDescription::moistureNoise, kMaterialKnobRange},
      {"regional_noise", &MaterialDescription::regionalNoise, kMaterialKnobRange},
      {"coastal_height_m", &MaterialDescription::coastalHeightM, kCoastalHeightRangeM},
      {"dry_belt", &MaterialDescription::dryBelt, kMaterialKnobRange},
      {"rock_slope_deg", &MaterialDescription::rockSlopeDeg, kSlopeRangeDeg},
      {"snow_slope_deg", &MaterialDescription::snowSlopeDeg, kSlopeRangeDeg},
      {"detail_relief", &MaterialDescription::detailRelief, kMaterialKnobRange},
      {"detail_contrast", &MaterialDescription::detailContrast, kMaterialKnobRange},
  };
  for (const NumberKey& k : numberKeys) m.*k.member = reader.number(k.key, k.range).value_or(m.*k.member);
  struct ColorKey {
    std::string_view key;
    glm::vec3 MaterialDescription::*member;
  };
  const ColorKey colorKeys[] = {
      {"conifer", &MaterialDescription::conifer}, {"forest", &MaterialDescription::forest},
      {"grass", &MaterialDescription::grass},     {"dry_grass", &MaterialDescription::dryGrass},
      {"desert", &MaterialDescription::desert},   {"tundra", &MaterialDescription::tundra},
      {"scree", &MaterialDescription::scree},
  };
  for (const ColorKey& c : colorKeys)
    if (auto value = reader.color(c.key)) m.*c.member = *value;
  return m;
}

AtmosphereDescription readAtmosphere(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[atmosphere]", kAtmosphereKeys);
  AtmosphereDescription a;
  a.enabled = true;
  a.heightM = reader.number("height_m", kAtmosphereHeightRangeM).value_or(a.heightM);
  a.rayleighScattering = reader.vector3("rayleigh_scattering", kScatteringRange, true).value_or(a.rayleighScattering);
  a.rayleighScaleHeightM =
      reader.number("rayleigh_scale_height_m", kScaleHeightRangeM).value_or(a.rayleighScaleHeightM);
  a.mieScattering = reader.vector3("mie_scattering", kScatteringRange, true).value_or(a.mieScattering);
  a.mieExtinctionRatio = reader.number("mie_extinction_ratio", kMieExtinctionRatioRange).value_or(a.mieExtinctionRatio);
  a.mieAbsorption = reader.vector3("mie_absorption", kScatteringRange, true).value_or(a.mieAbsorption);
  a.mieScaleHeightM = reader.number("mie_scale_height_m", kScaleHeightRangeM).value_or(a.mieScaleHeightM);
  a.mieG = reader.vector3("mie_g", kMieGRange, true).value_or(a.mieG);
  a.ozoneAbsorption = reader.vector3("ozone_absorption", kScatteringRange, true).value_or(a.ozoneAbsorption);
  a.ozoneCenterM = reader.number("ozone_center_m", kOzoneAltitudeRangeM).value_or(a.ozoneCenterM);
  a.ozoneWidthM = reader.number("ozone_width_m", kOzoneAltitudeRangeM).value_or(a.ozoneWidthM);
  if (a.ozoneWidthM <= 0.0 && a.ozoneAbsorption != glm::dvec3(0.0))
    context.fail(lineOf(*reader.find("ozone_width_m")), "ozone_width_m must be above 0 when ozone_absorption is set");
  a.airglowCdM2 = reader.number("airglow_cd_m2", kAirglowRangeCdM2).value_or(a.airglowCdM2);
  if (auto color = reader.color("airglow_color")) {
    if (*color == glm::vec3(0.0f))
      context.fail(lineOf(*reader.find("airglow_color")),
                   "airglow_color must not be black (airglow_cd_m2 sets how bright)");
    a.airglowColor = *color;
  }
  a.airglowBottomM = reader.number("airglow_bottom_m", kOzoneAltitudeRangeM).value_or(a.airglowBottomM);
  a.airglowTopM = reader.number("airglow_top_m", kOzoneAltitudeRangeM).value_or(a.airglowTopM);
  if (a.airglowCdM2 > 0.0) {
    // The shell is drawn where the air is (the compose covers the atmosphere's extent on screen).
    const toml::node* node = reader.find("airglow_top_m") ? reader.find("airglow_top_m") : reader.find("airglow_cd_m2");
    if (!(a.airglowTopM > a.airglowBottomM))
      context.fail(lineOf(*node), fmt::format("airglow_top_m ({}) must be above airglow_bottom_m ({})",
                                              formatNumber(a.airglowTopM), formatNumber(a.airglowBottomM)));
    if (a.airglowTopM > a.heightM)
      context.fail(lineOf(*node), fmt::format("airglow_top_m ({}) must not be above the atmosphere's height_m ({})",
                                              formatNumber(a.airglowTopM), formatNumber(a.heightM)));
  }
  return a;
}

CloudDescription readClouds(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[clouds]", kCloudKeys);
  CloudDescription c;
  c.enabled = true;
  c.bottomM = reader.number("bottom_m", kCloudAltitudeRangeM).value_or(c.bottomM);
  c.topM = reader.number("top_m", kCloudAltitudeRangeM).value_or(c.topM);
  if (!(c.topM > c.bottomM)) {
    const toml::node* node = reader.find("top_m") ? reader.find("top_m") : reader.find("bottom_m");
    context.fail(node ? lineOf(*node) : reader.line(),
                 fmt::format("top_m ({}) must be above bottom_m ({})", formatNumber(c.topM), formatNumber(c.bottomM)));
  }
  c.coverage = reader.number("coverage", kUnitRange).value_or(c.coverage);
  c.sharpness = reader.number("sharpness", kSharpnessRange).value_or(c.sharpness);
  c.wavelengthM = reader.number("wavelength_m", kCloudWavelengthRangeM).value_or(c.wavelengthM);
  c.octaves = int(reader.integer("octaves", kCloudOctavesRange).value_or(c.octaves));
  c.seed = uint32_t(reader.integer("seed", kSeedRange).value_or(c.seed));
  c.windMps = reader.number("wind_mps", kWindRangeMps).value_or(c.windMps);
  c.evolvePeriodS = reader.number("evolve_period_s", kEvolvePeriodRangeS).value_or(c.evolvePeriodS);
  c.opacity = reader.number("opacity", kCloudOpacityRange).value_or(c.opacity);
  c.climate = reader.number("climate", kCloudClimateRange).value_or(c.climate);
  c.cyclones = int(reader.integer("cyclones", kCloudCyclonesRange).value_or(c.cyclones));
  c.cycloneRadiusM = reader.number("cyclone_radius_m", kCloudWavelengthRangeM).value_or(c.cycloneRadiusM);
  c.swirl = reader.number("swirl", kCloudSwirlRange).value_or(c.swirl);
  c.shear = reader.number("shear", kCloudShearRange).value_or(c.shear);
  c.warp = reader.number("warp", kUnitRange).value_or(c.warp);
  c.resolution = int(reader.integer("resolution", kCloudResolutionRange).value_or(c.resolution));
  return c;
}

WaterDescription readWater(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[water]", kWaterKeys);
  WaterDescription w;
  w.clarityM = reader.number("clarity_m", kClarityRangeM).value_or(w.clarityM);
  w.waveWavelengthM = reader.number("wave_wavelength_m", kWaveWavelengthRangeM).value_or(w.waveWavelengthM);
  w.waveSlope = reader.number("wave_slope", kWaveSlopeRange).value_or(w.waveSlope);
  w.windMps = reader.number("wind_mps", kSeaWindRangeMps).value_or(w.windMps);
  return w;
}

StarDescription readStars(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[stars]", kStarKeys);
  StarDescription s;
  s.enabled = reader.boolean("enabled").value_or(s.enabled);
  s.seed = uint32_t(reader.integer("seed", kSeedRange).value_or(s.seed));
  s.faintestMagnitude = reader.number("faintest_magnitude", kMagnitudeRange).value_or(s.faintestMagnitude);
  s.brightness = reader.number("brightness", kStarBrightnessRange).value_or(s.brightness);
  return s;
}

LightsDescription readLights(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[lights]", kLightsKeys);
  LightsDescription l;
  l.enabled = reader.boolean("enabled").value_or(true);
  l.radianceNw = reader.number("radiance_nw", kLightsRadianceRangeNw).value_or(l.radianceNw);
  l.gain = reader.number("gain", kLightsGainRange).value_or(l.gain);
  l.color = reader.color("color").value_or(l.color);
  if (l.color == glm::vec3(0.0f))
    context.fail(lineOf(*reader.find("color")), "color must not be black: [0, 0, 0] has no brightness to scale");
  l.coverage = reader.number("coverage", kUnitRange).value_or(l.coverage);
  l.citySizeM = reader.number("city_size_m", kCitySizeRangeM).value_or(l.citySizeM);
  l.seed = uint32_t(reader.integer("seed", kSeedRange).value_or(l.seed));
  return l;
}

// [[x, y], ...]: 2 to maxPoints points, x strictly increasing and in xRange, y in kCurveValueRange.
std::vector<CurvePoint> readCurve(const Context& context, const TableReader& reader, std::string_view key,
                                  Range xRange, size_t maxPoints) {
  const toml::node* node = reader.find(key);
  if (!node) return {};
  const toml::array* array = node->as_array();
  if (!array || array->size() < 2 || array->size() > maxPoints)
    context.fail(lineOf(*node), fmt::format("'{}' must be an array of 2 to {} points [x, y], got {}", key, maxPoints,
                                            array ? fmt::format("{} elements", array->size()) : typeName(*node)));
  std::vector<CurvePoint> points;
  for (size_t i = 0; i < array->size(); ++i) {
    const toml::node& element = *array->get(i);
    const toml::array* pair = element.as_array();
    if (!pair || pair->size() != 2)
      context.fail(lineOf(element), fmt::format("{}[{}] must be a point [x, y], got {}", key, i,
                                                pair ? fmt::format("{} elements", pair->size()) : typeName(element)));
    CurvePoint point{reader.element(*pair->get(0), fmt::format("{}[{}][0]", key, i), xRange),
                     reader.element(*pair->get(1), fmt::format("{}[{}][1]", key, i), kCurveValueRange)};
    if (!points.empty() && !(point.x > points.back().x))
      context.fail(lineOf(element), fmt::format("{}[{}][0] must be above the point before ({}), got {}", key, i,
                                                formatNumber(points.back().x), formatNumber(point.x)));
    points.push_back(point);
  }
  return points;
}

NoiseLayer readLayer(const Context& context, const toml::table& table) {
  TableReader reader(context, table, "[[layer]]", kLayerKeys);
  NoiseLayer layer;
  layer.name = reader.name("name");
  std::string type = reader.requiredString("type");
  layer.noise.type = parseAt(context, lineOf(*reader.find("type")), [&] {
    return noise::parseNoiseType(shortened(type));  // the cut is for the message: no type name is that long
  });
  // Keys that belong to some types only: a key given to a type it does not apply to is an error,
  // not silently ignored (faults have no octaves, mpd counts levels, fractals have neither).
  const bool faults = layer.noise.type == noise::NoiseType::Faults;
  const bool mpd = noise::isMpd(layer.noise.type);
  auto onlyFor = [&](std::string_view key, bool applies, const char* types) {
    if (!applies && reader.find(key))
      context.fail(lineOf(*reader.find(key)), fmt::format("'{}' applies to {} layers only, not to type '{}'", key,
                                                          types, noise::noiseTypeName(layer.noise.type)));
  };
  onlyFor("octaves", !faults && !mpd, "fractal (not faults, mpd or mpd_ico)");
  onlyFor("count", faults, "faults");
  onlyFor("width", faults, "faults");
  onlyFor("levels", mpd, "mpd and mpd_ico");
  onlyFor("multifractal", mpd, "mpd and mpd_ico");
  onlyFor("lacunarity", !faults && !mpd, "fractal (each MPD level halves the edges)");
  onlyFor("offset", !faults && !mpd, "fractal (not faults, mpd or mpd_ico)");
  onlyFor("hash", !faults && !mpd, "fractal (faults and MPD hash each fault or vertex with the integer hash)");
  onlyFor("H", !faults, "fractal, mpd and mpd_ico");
  onlyFor("gain", !faults, "fractal, mpd and mpd_ico (k of the multifractal)");
  onlyFor("frequency", !faults && !mpd, "fractal (faults, mpd and mpd_ico sample the unit sphere)");
  onlyFor("wavelength_m", !faults && !mpd, "fractal (faults, mpd and mpd_ico sample the unit sphere)");
  if (faults) {
    std::optional<int64_t> count = reader.integer("count", {noise::kMinFaults, noise::kMaxFaults});
    if (!count) reader.missing("count");
    layer.noise.faults = int(*count);
    layer.noise.width = reader.number("width", Range{0.0, noise::kMaxFaultWidth}).value_or(0.0);
    layer.noise.octaves = 1;
  } else if (mpd) {
    std::optional<int64_t> levels = reader.integer("levels", {noise::kMinMpdLevels, noise::kMaxMpdLevels});
    if (!levels) reader.missing("levels");
    layer.noise.octaves = int(*levels);
    layer.noise.multifractal = reader.boolean("multifractal").value_or(false);
  } else {
    std::optional<int64_t> octaves = reader.integer("octaves", {noise::kMinOctaves, noise::kMaxOctaves});
    if (!octaves) reader.missing("octaves");
    layer.noise.octaves = int(*octaves);
  }
  layer.noise.lacunarity = reader.number("lacunarity").value_or(layer.noise.lacunarity);
  layer.noise.H = reader.number("H").value_or(layer.noise.H);
  layer.noise.offset = reader.number("offset");
  layer.noise.gain = reader.number("gain");
  layer.noise.seed = uint32_t(reader.integer("seed", kSeedRange).value_or(0));
  if (auto hash = reader.string("hash"))
    layer.noise.hash =
        parseAt(context, lineOf(*reader.find("hash")), [&] { return noise::parseNoiseHash(shortened(*hash)); });

  std::optional<double> frequency = reader.number("frequency", kFrequencyRange);
  std::optional<double> wavelength = reader.number("wavelength_m", kWavelengthRangeM);
  if (frequency && wavelength)
    context.fail(lineOf(*reader.find("wavelength_m")), "give either frequency or wavelength_m in [[layer]], not both");
  if (!frequency && !wavelength && !faults && !mpd)
    context.fail(reader.line(), "missing key 'frequency' (or 'wavelength_m') in [[layer]]");
  // Generators: 1 / radius, set once the radius is known (readLayers' caller).
  layer.frequency = frequency ? *frequency : wavelength ? 1.0 / *wavelength : 1.0;
  layer.amplitudeM = reader.requiredNumber("amplitude_m", kAmplitudeRangeM);
  layer.transfer = readCurve(context, reader, "transfer", kCurveValueRange, kMaxCurvePoints);
  layer.hypsometry = readCurve(context, reader, "hypsometry", kUnitRange, kMaxCurvePoints);
  if (!layer.transfer.empty() && !layer.hypsometry.empty())
    context.fail(lineOf(*reader.find("hypsometry")), "give either transfer or hypsometry in [[layer]], not both");
  for (size_t i = 1; i < layer.hypsometry.size(); ++i)
    if (layer.hypsometry[i].y < layer.hypsometry[i - 1].y)
      context.fail(lineOf(*reader.find("hypsometry")),
                   fmt::format("hypsometry values must not decrease with the area fraction, got {} after {}",
                               formatNumber(layer.hypsometry[i].y), formatNumber(layer.hypsometry[i - 1].y)));
  if (auto mask = reader.string("mask")) layer.mask = *mask;
  layer.maskCurve = readCurve(context, reader, "mask_curve", kCurveValueRange, kMaxMaskCurvePoints);
  if (!layer.maskCurve.empty() && layer.mask.empty())
    context.fail(lineOf(*reader.find("mask_curve")), "mask_curve needs a mask (the name of an earlier layer)");

  try {
    noise::validateNoiseSettings(layer.noise);
  } catch (const Error& e) {
    context.fail(reader.line(), fmt::format("layer '{}': {}", layer.name, e.what()));
  }
  return layer;
}

std::vector<NoiseLayer> readLayers(const Context& context, const toml::table& root) {
  const toml::node* node = root.get("layer");
  if (!node) context.fail(0, "missing table [[layer]] (at least one noise layer)");
  const toml::array* array = node->as_array();
  if (array && array->empty()) context.fail(lineOf(*node), "at least one [[layer]] is required");
  if (!array || !array->is_array_of_tables())
    context.fail(lineOf(*node), fmt::format("'layer' must be an array of tables ([[layer]]), got {}",
                                            array ? "an array of values" : typeName(*node)));
  if (array->size() > size_t(kMaxLayers))
    context.fail(lineOf(*array->get(size_t(kMaxLayers))),
                 fmt::format("at most {} [[layer]] tables, got {}", kMaxLayers, array->size()));
  std::vector<NoiseLayer> layers;
  std::vector<uint32_t> lines;
  for (const toml::node& element : *array) {
    layers.push_back(readLayer(context, *element.as_table()));
    lines.push_back(lineOf(element));
    for (size_t i = 0; i + 1 < layers.size(); ++i)
      if (layers[i].name == layers.back().name)
        context.fail(lines.back(),
                     fmt::format("duplicate layer name '{}' (first at line {})", layers[i].name, lines[i]));
    const std::string& mask = layers.back().mask;
    if (!mask.empty() && std::none_of(layers.begin(), layers.end() - 1, [&](const NoiseLayer& earlier) {
          return earlier.name == mask;
        }))
      context.fail(lineOf(*element.as_table()->get("mask")),
                   fmt::format("mask '{}' must name an earlier layer", shortened(mask)));
  }
  return layers;
}


}  // namespace

const char* colorSchemeName(ColorScheme scheme) {
  for (const SchemeName& s : kSchemeNames)
    if (s.scheme == scheme) return s.name;
  return "unknown";
}

std::span<const ColorScheme> colorSchemes() { return kSchemes; }

ColorScheme parseColorScheme(std::string_view name) {
  for (const SchemeName& s : kSchemeNames)
    if (name == s.name) return s.scheme;
  std::string names;
  for (const SchemeName& s : kSchemeNames) names += fmt::format("{}{}", names.empty() ? "" : ", ", s.name);
  throw Error(fmt::format("unknown color scheme '{}' (expected one of {})", shortened(name), names));
}

size_t paletteSize(ColorScheme scheme) {
  switch (scheme) {
    case ColorScheme::Noise:
    case ColorScheme::Turbulence:
    case ColorScheme::Gradient: return 2;
    case ColorScheme::MoonLike: return 4;
    case ColorScheme::AltitudeNoise: return 8;
    case ColorScheme::EarthLike: return 12;
    default: return 0;
  }
}

// The default palettes of seed 000's schemes (README.md lists what each colour is for).
static std::array<glm::vec3, kMaxPaletteColors> schemePalette(ColorScheme scheme) {
  std::array<glm::vec3, kMaxPaletteColors> p{};
  switch (scheme) {
    case ColorScheme::Noise:  // green <-> brown (seed: "green", "brown")
      p[0] = {0.060f, 0.200f, 0.030f};
      p[1] = {0.280f, 0.150f, 0.050f};
      break;
    case ColorScheme::Turbulence:  // black -> red (seed: "black and red", "fire-like")
      p[0] = {0.000f, 0.000f, 0.000f};
      p[1] = {0.800f, 0.030f, 0.000f};
      break;
    case ColorScheme::Gradient:  // flat -> steep (seed: two unnamed colours): light grass, dark rock
      p[0] = {0.100f, 0.220f, 0.050f};
      p[1] = {0.100f, 0.070f, 0.050f};
      break;
    case ColorScheme::MoonLike:  // maria: two dark greys; land: brighter greys low -> high
      p[0] = {0.035f, 0.035f, 0.035f};
      p[1] = {0.065f, 0.062f, 0.058f};
      p[2] = {0.110f, 0.110f, 0.105f};
      p[3] = {0.200f, 0.195f, 0.190f};
      break;
    case ColorScheme::AltitudeNoise:  // two sets of lowlands, highlands, mountains, snowy tops
      p[0] = {0.040f, 0.150f, 0.020f};
      p[1] = {0.150f, 0.160f, 0.050f};
      p[2] = {0.220f, 0.130f, 0.060f};
      p[3] = {0.850f, 0.870f, 0.900f};
      p[4] = {0.130f, 0.180f, 0.040f};
      p[5] = {0.320f, 0.240f, 0.110f};
      p[6] = {0.190f, 0.180f, 0.170f};
      p[7] = {0.750f, 0.800f, 0.880f};
      break;
    case ColorScheme::EarthLike:
      // Two latitude splines (equator, 22.5°, 45°, 67.5°, pole: rainforest, desert, temperate
      // forest, tundra, ice; seed 000 §2.1.1), then the mountain colours: rock and snow.
      p[0] = {0.030f, 0.110f, 0.020f};
      p[1] = {0.420f, 0.320f, 0.160f};
      p[2] = {0.070f, 0.140f, 0.040f};
      p[3] = {0.170f, 0.170f, 0.130f};
      p[4] = {0.850f, 0.870f, 0.900f};
      p[5] = {0.050f, 0.140f, 0.030f};
      p[6] = {0.460f, 0.280f, 0.100f};
      p[7] = {0.100f, 0.160f, 0.050f};
      p[8] = {0.210f, 0.200f, 0.160f};
      p[9] = {0.780f, 0.820f, 0.880f};
      p[10] = {0.200f, 0.180f, 0.160f};
      p[11] = {0.880f, 0.890f, 0.920f};
      break;
    default:
      break;
  }
  return p;
}

PlanetColors defaultColors(ColorScheme scheme) {
  PlanetColors c;
  c.scheme = scheme;
  switch (scheme) {
    case ColorScheme::Earth:
      c.beachHeightM = 20.0;
      c.snowLineM = 3500.0;
      c.iceCapLatitudeDeg = 70.0;
      c.deepWater = {0.004f, 0.016f, 0.045f};
      c.shallowWater = {0.015f, 0.080f, 0.100f};
      c.beach = {0.480f, 0.400f, 0.240f};
      c.lowland = {0.050f, 0.110f, 0.020f};
      c.highland = {0.170f, 0.130f, 0.070f};
      c.cliff = {0.200f, 0.180f, 0.160f};  // granite to weathered mixed rock (ECOSTRESS)
      c.snow = {0.850f, 0.870f, 0.900f};
      break;
    case ColorScheme::Altitude:
      c.deepWater = {0.0f, 0.0f, 0.3f};
      c.shallowWater = {0.0f, 0.3f, 0.6f};
      c.beach = {0.8f, 0.8f, 0.2f};
      c.lowland = {0.0f, 0.4f, 0.0f};
      c.highland = {0.6f, 0.3f, 0.0f};
      c.cliff = {0.3f, 0.3f, 0.3f};
      c.snow = {1.0f, 1.0f, 1.0f};
      break;
    case ColorScheme::Moon:
      c.deepWater = c.shallowWater = {0.0f, 0.0f, 0.0f};
      c.lowland = c.beach = {0.045f, 0.045f, 0.043f};
      c.highland = c.snow = {0.160f, 0.155f, 0.150f};
      c.cliff = {0.100f, 0.100f, 0.100f};
      break;
    case ColorScheme::Giant:
      // Belts (lowland), zones (highland), the fine bands' tint (beach), the polar hoods (cliff).
      c.iceCapLatitudeDeg = 90.0;
      c.snowLineM = 1000.0;  // the height that shifts a band by about a twentieth of its width
      c.deepWater = c.shallowWater = {0.0f, 0.0f, 0.0f};
      c.lowland = {0.200f, 0.125f, 0.070f};
      c.highland = {0.320f, 0.280f, 0.215f};
      c.beach = {0.340f, 0.210f, 0.110f};
      c.cliff = {0.200f, 0.190f, 0.170f};
      c.snow = c.highland;
      break;
    case ColorScheme::AltitudePerturbed:
    case ColorScheme::Noise:
    case ColorScheme::AltitudeNoise:
    case ColorScheme::Turbulence:
    case ColorScheme::EarthLike:
    case ColorScheme::Gradient:
    case ColorScheme::MoonLike:
      // Seed 000 names its colours but gives no values (its §4.7: "green", "brown", "black and
      // red", "dark grey"); these are this project's choices. The named colours below are the
      // altitude scheme's (altitude_perturbed's ramp, the sea floor and the water).
      c = defaultColors(ColorScheme::Altitude);
      c.scheme = scheme;
      c.snowLineM = 4000.0;  // the top of the altitude ramps
      c.palette = schemePalette(scheme);
      break;
    case ColorScheme::Mars:
      c.iceCapLatitudeDeg = 80.0;
      c.deepWater = c.shallowWater = {0.0f, 0.0f, 0.0f};
      c.beach = {0.300f, 0.130f, 0.060f};
      c.lowland = {0.100f, 0.045f, 0.025f};
      c.highland = {0.380f, 0.160f, 0.070f};
      c.cliff = {0.200f, 0.100f, 0.060f};
      c.snow = {0.800f, 0.780f, 0.750f};
      break;
  }
  return c;
}

PlanetDescription parsePlanetDescription(std::string_view text, const std::string& sourceName) {
  const Context context(sourceName);
  const toml::table root = parseDocument(context, text, "[planet], [colors] and [[layer]] tables");
  for (auto&& [key, value] : root) {
    if (std::find(std::begin(kTopKeys), std::end(kTopKeys), key.str()) != std::end(kTopKeys)) continue;
    context.fail(key.source().begin.line, value.is_table()
                                              ? fmt::format("unknown table [{}]", shortened(key.str()))
                                              : fmt::format("unknown key '{}' at top level", shortened(key.str())));
  }

  PlanetDescription d;
  TableReader planet(context, requireTable(context, root, "planet"), "[planet]", kPlanetKeys);
  d.name = planet.name("name");
  d.radiusM = planet.requiredNumber("radius_m", kRadiusRangeM);
  std::optional<bool> hasOcean = planet.boolean("has_ocean");
  if (!hasOcean) planet.missing("has_ocean");
  d.hasOcean = *hasOcean;
  if (std::optional<double> seaLevel = planet.number("sea_level_m", kSeaLevelRangeM)) {
    if (!d.hasOcean) context.fail(lineOf(*planet.find("sea_level_m")), "sea_level_m needs has_ocean = true");
    d.seaLevelM = *seaLevel;
  }
  d.heightScale = planet.number("height_scale", kHeightScaleRange).value_or(1.0);
  d.baseHeightM = planet.number("base_height_m", kBaseHeightRangeM).value_or(0.0);
  d.colors = readColors(context, requireTable(context, root, "colors"));
  d.materials = defaultMaterials(d.colors.scheme);
  if (const toml::table* table = optionalTable(context, root, "materials"))
    d.materials = readMaterials(context, *table, d.colors.scheme);
  d.layers = readLayers(context, root);
  // Faults and MPD are functions of the direction: they sample the unit sphere (and the octave
  // budget measures their levels in radii).
  for (NoiseLayer& layer : d.layers)
    if (noise::isGenerator(layer.noise.type)) layer.frequency = 1.0 / d.radiusM;
  if (const toml::table* table = optionalTable(context, root, "atmosphere"))
    d.atmosphere = readAtmosphere(context, *table);
  if (const toml::table* table = optionalTable(context, root, "clouds")) {
    if (!d.atmosphere.enabled) context.fail(lineOf(*table), "[clouds] needs an [atmosphere] table");
    d.clouds = readClouds(context, *table);
    if (d.clouds.topM > d.atmosphere.heightM)
      context.fail(lineOf(*table), fmt::format("clouds top_m ({}) must be below the atmosphere's height_m ({})",
                                               formatNumber(d.clouds.topM), formatNumber(d.atmosphere.heightM)));
  }
  if (const toml::table* table = optionalTable(context, root, "water")) {
    if (!d.hasOcean) context.fail(lineOf(*table), "[water] needs has_ocean = true");
    d.water = readWater(context, *table);
  }
  if (const toml::table* table = optionalTable(context, root, "stars")) d.stars = readStars(context, *table);
  if (const toml::table* table = optionalTable(context, root, "lights")) d.lights = readLights(context, *table);
  return d;
}

PlanetDescription loadPlanetDescription(const std::string& path) {
  // One byte past the limit tells "too large" (parsePlanetDescription says so) from "exactly at it".
  return parsePlanetDescription(readFileUpTo(path, kMaxPresetBytes), path);
}

std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  for (const EmbeddedPreset& preset : embeddedPresets()) names.emplace_back(preset.name);
  return names;
}

PlanetDescription resolvePreset(const std::string& nameOrFile) {
  if (nameOrFile.ends_with(".toml") || nameOrFile.find('/') != std::string::npos)
    return loadPlanetDescription(nameOrFile);
  for (const EmbeddedPreset& preset : embeddedPresets())
    if (nameOrFile == preset.name) return parsePlanetDescription(preset.text, nameOrFile + ".toml");
  std::string names;
  for (const EmbeddedPreset& preset : embeddedPresets())
    names += fmt::format("{}{}", names.empty() ? "" : ", ", preset.name);
  throw Error(fmt::format("unknown planet preset '{}' (built-in: {}; or a FILE.toml)", shortened(nameOrFile), names));
}

MaterialDescription defaultMaterials(ColorScheme scheme) {
  // Reflectances: band means (red 620-700 nm, green 500-570, blue 450-500) of the ECOSTRESS
  // spectral library (Meerdink et al. 2019, formerly ASTER: vegetation, soil, rock spectra) and
  // MODIS white-sky albedo for canopies; the presets repeat them with their sources.
  MaterialDescription m;
  m.conifer = {0.030f, 0.050f, 0.025f};
  m.forest = {0.040f, 0.080f, 0.030f};
  m.grass = {0.065f, 0.110f, 0.045f};
  m.dryGrass = {0.250f, 0.210f, 0.120f};
  m.desert = {0.420f, 0.300f, 0.160f};
  m.tundra = {0.110f, 0.110f, 0.070f};
  m.scree = {0.240f, 0.220f, 0.200f};
  m.regionalNoise = 0.5;
  switch (scheme) {
    case ColorScheme::Mars:
      // Mean annual surface temperatures of the Mars Climate Database: about −50 °C at the
      // equator, −125 °C (the CO₂ frost point) at the residual caps; a 2.5 K/km lapse rate.
      m.equatorTemperatureC = -50.0;
      m.poleTemperatureDropC = 75.0;
      m.lapseRateKPerKm = 2.5;
      m.snowTemperatureC = -122.0;
      m.moisture = 0.0;
      m.moistureNoise = 0.0;
      m.regionalNoise = 0.6;
      m.dryBelt = 0.0;
      m.rockSlopeDeg = 35.0;
      m.scree = {0.220f, 0.110f, 0.060f};
      break;
    case ColorScheme::Moon:
      m.equatorTemperatureC = 0.0;
      m.poleTemperatureDropC = 0.0;
      m.lapseRateKPerKm = 0.0;
      m.snowTemperatureC = -273.0;  // no frost in the sunlit regolith
      m.moisture = 0.0;
      m.moistureNoise = 0.0;
      m.regionalNoise = 0.3;
      m.dryBelt = 0.0;
      m.rockSlopeDeg = 35.0;
      m.scree = {0.140f, 0.135f, 0.130f};
      break;
    default:
      break;
  }
  return m;
}

std::string canonicalForm(const PlanetDescription& d) {
  auto color = [](const glm::vec3& c) {
    return fmt::format("{},{},{}", formatNumber(c.x), formatNumber(c.y), formatNumber(c.z));
  };
  // Names carry their length, so no name can imitate the lines that follow it.
  std::string out = "planet-description v1\n";
  out += fmt::format("name={}:{}\nradius_m={}\nhas_ocean={}\nsea_level_m={}\nheight_scale={}\nbase_height_m={}\n",
                     d.name.size(), d.name, formatNumber(d.radiusM), d.hasOcean, formatNumber(d.seaLevelM),
                     formatNumber(d.heightScale), formatNumber(d.baseHeightM));
  const PlanetColors& c = d.colors;
  out +=
      fmt::format("scheme={}\nbeach_height_m={}\nsnow_line_m={}\nice_cap_latitude_deg={}\n", colorSchemeName(c.scheme),
                  formatNumber(c.beachHeightM), formatNumber(c.snowLineM), formatNumber(c.iceCapLatitudeDeg));
  out += fmt::format("deep_water={}\nshallow_water={}\nbeach={}\nlowland={}\nhighland={}\ncliff={}\nsnow={}\n",
                     color(c.deepWater), color(c.shallowWater), color(c.beach), color(c.lowland), color(c.highland),
                     color(c.cliff), color(c.snow));
  // Seed 000's schemes and seed 004's caps add lines only where they are used, so the hashes of
  // the planets from before them stay as they were.
  const bool seedScheme = paletteSize(c.scheme) > 0 || c.scheme == ColorScheme::AltitudePerturbed;
  if (seedScheme || c.polarCaps) {
    out += fmt::format("noise_wavelength_m={}\nperturbation={}\npolar_caps={}\npalette=",
                       formatNumber(c.noiseWavelengthM), formatNumber(c.perturbation), c.polarCaps);
    for (size_t i = 0; i < paletteSize(c.scheme); ++i) out += color(c.palette[i]) + ";";
    out += "\n";
  }
  const MaterialDescription& m = d.materials;
  out += fmt::format(
      "materials.temperature_c={},{},{},{}\nmaterials.moisture={},{},{},{}\nmaterials.regional_noise={}\n"
      "materials.slopes_deg={},{}\n"
      "materials.detail={},{}\n",
      formatNumber(m.equatorTemperatureC), formatNumber(m.poleTemperatureDropC), formatNumber(m.lapseRateKPerKm),
      formatNumber(m.snowTemperatureC), formatNumber(m.moisture), formatNumber(m.moistureNoise),
      formatNumber(m.coastalHeightM), formatNumber(m.dryBelt), formatNumber(m.regionalNoise),
      formatNumber(m.rockSlopeDeg),
      formatNumber(m.snowSlopeDeg), formatNumber(m.detailRelief), formatNumber(m.detailContrast));
  out += fmt::format("materials.colors={};{};{};{};{};{};{}\n", color(m.conifer), color(m.forest), color(m.grass),
                     color(m.dryGrass), color(m.desert), color(m.tundra), color(m.scree));
  auto vector = [](const glm::dvec3& v) {
    return fmt::format("{},{},{}", formatNumber(v.x), formatNumber(v.y), formatNumber(v.z));
  };
  const AtmosphereDescription& a = d.atmosphere;
  out += fmt::format(
      "atmosphere={}\natmosphere.height_m={}\natmosphere.rayleigh_scattering={}\n"
      "atmosphere.rayleigh_scale_height_m={}\natmosphere.mie_scattering={}\natmosphere.mie_extinction_ratio={}\n"
      "atmosphere.mie_absorption={}\n"
      "atmosphere.mie_scale_height_m={}\natmosphere.mie_g={}\natmosphere.ozone_absorption={}\n"
      "atmosphere.ozone_center_m={}\natmosphere.ozone_width_m={}\natmosphere.airglow_cd_m2={}\n"
      "atmosphere.airglow_color={}\natmosphere.airglow_bottom_m={}\natmosphere.airglow_top_m={}\n",
      a.enabled, formatNumber(a.heightM), vector(a.rayleighScattering), formatNumber(a.rayleighScaleHeightM),
      vector(a.mieScattering), formatNumber(a.mieExtinctionRatio), vector(a.mieAbsorption),
      formatNumber(a.mieScaleHeightM), vector(a.mieG), vector(a.ozoneAbsorption), formatNumber(a.ozoneCenterM),
      formatNumber(a.ozoneWidthM), formatNumber(a.airglowCdM2), color(a.airglowColor), formatNumber(a.airglowBottomM),
      formatNumber(a.airglowTopM));
  const CloudDescription& cl = d.clouds;
  out += fmt::format(
      "clouds={}\nclouds.bottom_m={}\nclouds.top_m={}\nclouds.coverage={}\nclouds.sharpness={}\n"
      "clouds.wavelength_m={}\nclouds.octaves={}\nclouds.seed={}\nclouds.wind_mps={}\nclouds.evolve_period_s={}\n"
      "clouds.opacity={}\nclouds.climate={}\nclouds.cyclones={}\nclouds.cyclone_radius_m={}\nclouds.swirl={}\n"
      "clouds.shear={}\nclouds.warp={}\nclouds.resolution={}\n",
      cl.enabled, formatNumber(cl.bottomM), formatNumber(cl.topM), formatNumber(cl.coverage),
      formatNumber(cl.sharpness), formatNumber(cl.wavelengthM), cl.octaves, cl.seed, formatNumber(cl.windMps),
      formatNumber(cl.evolvePeriodS), formatNumber(cl.opacity), formatNumber(cl.climate), cl.cyclones,
      formatNumber(cl.cycloneRadiusM), formatNumber(cl.swirl), formatNumber(cl.shear), formatNumber(cl.warp),
      cl.resolution);
  out += fmt::format("water.clarity_m={}\nwater.wave_wavelength_m={}\nwater.wave_slope={}\nwater.wind_mps={}\n",
                     formatNumber(d.water.clarityM), formatNumber(d.water.waveWavelengthM),
                     formatNumber(d.water.waveSlope), formatNumber(d.water.windMps));
  out += fmt::format("stars={}\nstars.seed={}\nstars.faintest_magnitude={}\nstars.brightness={}\n", d.stars.enabled,
                     d.stars.seed, formatNumber(d.stars.faintestMagnitude), formatNumber(d.stars.brightness));
  // Only planets with lights add lines, so the hashes of the others stay as they were.
  if (const LightsDescription& l = d.lights; l.enabled)
    out += fmt::format("lights.radiance_nw={}\nlights.gain={}\nlights.color={}\nlights.coverage={}\n"
                       "lights.city_size_m={}\nlights.seed={}\n",
                       formatNumber(l.radianceNw), formatNumber(l.gain), color(l.color), formatNumber(l.coverage),
                       formatNumber(l.citySizeM), l.seed);
  for (size_t i = 0; i < d.layers.size(); ++i) {
    const NoiseLayer& l = d.layers[i];
    const noise::NoiseSettings& n = l.noise;
    out += fmt::format(
        "layer.{0}.name={1}:{2}\nlayer.{0}.type={3}\nlayer.{0}.octaves={4}\nlayer.{0}.lacunarity={5}\n"
        "layer.{0}.H={6}\nlayer.{0}.offset={7}\nlayer.{0}.gain={8}\nlayer.{0}.seed={9}\nlayer.{0}.hash={10}\n"
        "layer.{0}.frequency={11}\nlayer.{0}.amplitude_m={12}\n",
        i, l.name.size(), l.name, noise::noiseTypeName(n.type), n.octaves, formatNumber(n.lacunarity),
        formatNumber(n.H), formatNumber(n.offset.value_or(noise::defaultOffset(n.type))),
        formatNumber(n.gain.value_or(noise::kDefaultGain)), n.seed, noise::noiseHashName(n.hash),
        formatNumber(l.frequency), formatNumber(l.amplitudeM));
    // Only generator layers add these lines, so the hashes of other planets stay as they were.
    if (n.type == noise::NoiseType::Faults)
      out += fmt::format("layer.{0}.count={1}\nlayer.{0}.width={2}\n", i, n.faults, formatNumber(n.width));
    if (noise::isMpd(n.type)) out += fmt::format("layer.{}.multifractal={}\n", i, n.multifractal);
    // Only shaped layers add lines, so the hashes of unshaped planets stay as they were.
    auto curve = [&](const char* key, const std::vector<CurvePoint>& points) {
      if (points.empty()) return;
      out += fmt::format("layer.{}.{}=", i, key);
      for (const CurvePoint& point : points) out += fmt::format("{},{};", formatNumber(point.x), formatNumber(point.y));
      out += "\n";
    };
    curve("transfer", l.transfer);
    curve("hypsometry", l.hypsometry);
    if (!l.mask.empty()) out += fmt::format("layer.{}.mask={}:{}\n", i, l.mask.size(), l.mask);
    curve("mask_curve", l.maskCurve);
  }
  return out;
}

uint64_t fnv1a64(std::string_view bytes) {
  uint64_t hash = 14695981039346656037ull;  // FNV-1a 64-bit offset basis
  for (char c : bytes) {
    hash ^= uint8_t(c);
    hash *= 1099511628211ull;  // FNV 64-bit prime
  }
  return hash;
}

uint64_t descriptionHash(const PlanetDescription& description) { return fnv1a64(canonicalForm(description)); }

}  // namespace planet

// A planet: its radius, ocean, the stack of noise layers that forms its heights, and its
// colours, read from TOML presets (engine/planet/presets/*.toml) and validated strictly, so
// that a typo or a wild value is one clear line naming the file, the line and the key.
//
// How a height is formed (the renderer's compute shaders and any CPU reference follow this):
//   d          unit direction from the planet's centre (planet frame)
//   p          = radiusM * d, the point on the radius sphere in metres
//   n_l        = noise_l(p * frequency_l), the fractal of layer l (noise::NoiseSettings)
//   height(d)  = heightScale * (baseHeightM + sum over layers of amplitudeM_l * n_l)
//   surface    = (radiusM + height(d)) * d
// Noise is sampled on the radius sphere, not on the displaced surface, so a height depends on
// the direction only. With an ocean the water surface is the sphere of radius
// radiusM + seaLevelM; the ground is under water where height(d) < seaLevelM.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "noise/noise_settings.h"

namespace planet {

// A point of a layer's curve (shared/terrain_params.h): x strictly increasing along a curve.
struct CurvePoint {
  double x = 0.0;
  double y = 0.0;
  bool operator==(const CurvePoint&) const = default;
};

// A layer's shaping (terrain_height.glsl): its value is curve(noise) · mask, and amplitudeM
// times that value is its term of the height. With neither curve nor mask the value is the noise.
struct NoiseLayer {
  std::string name;            // unique within a planet, shown in logs and reports
  noise::NoiseSettings noise;  // type, octaves, lacunarity, H, offset, gain, seed, hash
  double frequency = 1.0;      // noise cycles per metre at octave 0 (noise input = p * frequency)
  double amplitudeM = 1.0;     // metres of height per unit of the layer's value (negative inverts)
  // Transfer curve, one of two kinds or none: `transfer` maps noise values to values directly;
  // `hypsometry` gives (fraction of the sphere's area below, value) and the noise values are
  // that seed's quantiles (planet/terrain_shape.h), so the layer has the same area statistics
  // at every seed. Values non-decreasing in a hypsometry.
  std::vector<CurvePoint> transfer;
  std::vector<CurvePoint> hypsometry;
  std::string mask;                   // name of an earlier layer whose value multiplies this one; empty: none
  std::vector<CurvePoint> maskCurve;  // (that layer's value, factor); empty: the value itself
};

// How the renderer colours the ground; each scheme has its own default palette (defaultColors).
// The values are the shader's scheme numbers (shaders/common/color_schemes.glsl): append only.
enum class ColorScheme {
  Earth,     // water, beach, vegetation to bare highland by height, rock on slopes, snow, ice caps
  Altitude,  // seed 000 #1: lowland -> highland -> snow, piecewise linear by height up to the snow line
  Moon,      // grey regolith: dark maria low, bright highlands high
  Mars,      // red dust and dark basalt, polar caps
  Giant,     // a gas giant's belts and zones by latitude, warped by the heights (the layers' turbulence)
  // Seed 000's other colouring schemes (its §4.7; shaders/common/color_schemes.glsl):
  AltitudePerturbed,  // #2: the altitude ramp of a height moved by the colour noise
  Noise,              // #3: green <-> brown by the colour noise
  AltitudeNoise,      // #4: two four-colour altitude ramps blended by the colour noise
  Turbulence,         // #5: black -> red by |colour noise|
  EarthLike,          // #6: vegetation zones by perturbed latitude, toward mountain colours by height
  Gradient,           // #7: flat -> steep colour by the slope
  MoonLike,           // #8: maria (two greys by noise) below sea level, brighter greys by height above
};

// Colours of the palette a scheme of seed 000 uses (PlanetColors::palette), at most this many.
inline constexpr size_t kMaxPaletteColors = 12;

// Colours are linear RGB in [0, 1] (not sRGB: a picker's 0.5 is about 0.21 here).
struct PlanetColors {
  ColorScheme scheme = ColorScheme::Earth;
  double beachHeightM = 0.0;        // ground up to this height above sea level is beach (0: none)
  double snowLineM = 1e5;           // ground above this height is snow (the range's top: none)
  double iceCapLatitudeDeg = 90.0;  // ice poleward of this latitude (90: no caps)
  glm::vec3 deepWater{0.0f};        // ocean far below sea level (unused without an ocean)
  glm::vec3 shallowWater{0.0f};     // ocean near the coast (unused without an ocean)
  glm::vec3 beach{0.0f};            // the band between sea level and beachHeightM
  glm::vec3 lowland{0.0f};          // low ground (vegetation, maria, basalt)
  glm::vec3 highland{0.0f};         // high ground
  glm::vec3 cliff{0.0f};            // steep slopes at any height
  glm::vec3 snow{0.0f};             // snow above the snow line and ice caps
  // Seed 000's schemes (paletteSize(scheme) colours, each scheme's meaning in README.md):
  std::array<glm::vec3, kMaxPaletteColors> palette{};
  double noiseWavelengthM = 300'000.0;  // largest octave of their per-pixel colour noise
  double perturbation = 0.3;            // how far the noise moves a zone edge: × snow line, × 45° of latitude
  // Seed 004's polar caps: ice on land and sea poleward of iceCapLatitudeDeg, over any scheme,
  // the edge moved by the colour noise as `perturbation` says.
  bool polarCaps = false;
  bool operator==(const PlanetColors&) const = default;
};

// Ground materials from climate and terrain (issue 20; shaders/terrain_material.glsl): the earth
// and mars schemes pick the material from temperature, moisture and slope; every scheme but
// altitude and giant gets the per-pixel ground detail. Colours are linear RGB reflectances
// (the preset names their source); rock is PlanetColors::cliff, sand ::beach, snow ::snow.
struct MaterialDescription {
  double equatorTemperatureC = 30.0;   // mean annual sea-level temperature at the equator
  double poleTemperatureDropC = 45.0;  // sea-level temperature = equator − drop · sin²(latitude)
  double lapseRateKPerKm = 6.5;        // temperature falls this much per km of height
  double snowTemperatureC = -10.0;     // snow (frost) lies where the mean annual temperature is below this
  double moisture = 0.55;              // mean moisture, 0 (desert) .. 1 (rainforest)
  double moistureNoise = 0.6;          // how much the colour noise moves it
  double regionalNoise = 0.0;          // weight of continent-scale octaves in the colour noise (regions)
  double coastalHeightM = 300.0;       // land below about this height is near the sea, so wetter
  double dryBelt = 0.45;               // how much drier the subtropical belts (about 15–35°) are
  double rockSlopeDeg = 40.0;          // bare rock on slopes steeper than this (scree just below)
  double snowSlopeDeg = 50.0;          // snow does not hold on slopes steeper than this
  double detailRelief = 1.0;           // slope scale of the ground detail below the vertex spacing (0: smooth)
  double detailContrast = 1.0;         // albedo variation of the ground detail (0: none)
  glm::vec3 conifer{0.0f};             // boreal forest canopy
  glm::vec3 forest{0.0f};              // broadleaf forest canopy
  glm::vec3 grass{0.0f};               // green grassland
  glm::vec3 dryGrass{0.0f};            // steppe and savanna
  glm::vec3 desert{0.0f};              // desert sand and soil
  glm::vec3 tundra{0.0f};              // moss, lichen and dwarf shrubs
  glm::vec3 scree{0.0f};               // loose rock below cliffs
};

// The sky of a planet (issue 4): optional tables of the preset. A table that is left out turns
// its effect off (an airless moon has no [atmosphere], a dry one no ocean, and so on).

// Single scattering by air molecules (Rayleigh) and aerosols (Mie) in an exponential
// atmosphere, plus an optional ozone layer that only absorbs (Bruneton & Neyret 2008 and the
// parameters of its 2017 reference implementation). Coefficients are per metre at the ground.
struct AtmosphereDescription {
  bool enabled = false;
  double heightM = 100'000.0;                               // top of the atmosphere above the radius sphere
  glm::dvec3 rayleighScattering{5.8e-6, 13.5e-6, 33.1e-6};  // β_R (red, green, blue)
  double rayleighScaleHeightM = 8'000.0;
  glm::dvec3 mieScattering{21e-6, 21e-6, 21e-6};  // β_M (grey for Earth; coloured dust for Mars)
  double mieExtinctionRatio = 1.11;               // Mie extinction / scattering (aerosols absorb a little)
  glm::dvec3 mieAbsorption{0.0, 0.0, 0.0};        // extra, coloured absorption by aerosols (Mars dust eats blue)
  double mieScaleHeightM = 1'200.0;
  glm::dvec3 mieG{0.76};                      // Cornette-Shanks asymmetry per channel: forward scattering
  glm::dvec3 ozoneAbsorption{0.0, 0.0, 0.0};  // at the layer's peak; Earth: 0.65, 1.881, 0.085 ·10⁻⁶
  double ozoneCenterM = 25'000.0;             // the ozone density is a tent around this altitude
  double ozoneWidthM = 30'000.0;              // full width of the tent
  // Airglow (issue 21, point 4: the night sky): light the upper air emits by itself at night
  // (oxygen's green line, OH, sodium), from a shell between two altitudes; 0 for none.
  double airglowCdM2 = 0.0;                   // luminance looking straight up through the shell
  glm::vec3 airglowColor{0.6f, 1.0f, 0.25f};  // linear RGB, scaled to that luminance
  double airglowBottomM = 87'000.0;
  double airglowTopM = 97'000.0;
};

// A cloud shell (seed 001 §4.4): three noise images cross-faded over time (its eq. 4.2) and
// Hugo Elias's cover function d = 1 − S^max(0, v − (1 − coverage)) (its eq. 4.1), drawn as a
// layer between two altitudes that is lit by the sun and shadows the ground.
struct CloudDescription {
  bool enabled = false;
  double bottomM = 2'000.0;          // base of the layer above the radius sphere
  double topM = 8'000.0;             // top of the layer
  double coverage = 0.3;             // 0: clear sky, 1: overcast
  double sharpness = 0.01;           // S: smaller gives denser, harder-edged clouds
  double wavelengthM = 3'000'000.0;  // largest weather systems
  int octaves = 9;                   // of the fBm that forms the cover (the last ones reach its texels)
  uint32_t seed = 7;
  double windMps = 20.0;           // drift of the whole layer eastward
  double evolvePeriodS = 7'200.0;  // one cycle of the three-image cross-fade
  double opacity = 3.0;            // optical depth of a full-density column through the layer
  // Weather (issue 20): what shapes the cover from orbit.
  double climate = 1.0;               // 0 .. 2: strength of the latitude bands (ITCZ, dry subtropics, storm tracks)
  int cyclones = 10;                  // 0 .. 48: cyclones per hemisphere (a fifth of them tropical)
  double cycloneRadiusM = 900'000.0;  // e-folding radius of a mid-latitude cyclone's twist
  double swirl = 0.6;                 // 0 .. 5: turns of a cyclone's spiral arms at its centre
  double shear = 0.35;                // 0 .. 3: longitude (rad) the zonal winds carry the cover at their peak
  double warp = 0.05;                 // 0 .. 1: displacement of the domain warp (planet radii)
  int resolution = 512;               // 64 .. 2048: texels per cube face side of the cover images
};

struct WaterDescription {
  double clarityM = 30.0;         // depth at which the sea floor has faded out of sight
  double waveWavelengthM = 40.0;  // largest ripples of the animated normal perturbation
  double waveSlope = 0.06;        // their steepness (0: a mirror)
  double windMps = 7.0;           // wind 10 m above the sea: the glint's width (Cox–Munk slope variance)
};

// The starfield behind everything (engine/render/star_pass.h).
struct StarDescription {
  bool enabled = true;
  uint32_t seed = 1;
  double faintestMagnitude = 7.0;  // stars down to this apparent magnitude
  double brightness = 0.4;         // HDR flux of a magnitude-0 star (engine/reference/star_catalogue.h)
};

// City lights on the night side (issue 14, point 2; shaders/common/city_lights.glsl): clustered
// into cities and towns on low, gentle, mild, watered land, densest along coasts and valleys,
// switched on through dusk. Radiance in VIIRS Day/Night Band units, so values can be read off
// NASA's Black Marble; the gain stands for the night exposure no daylight-calibrated one reaches.
struct LightsDescription {
  bool enabled = false;
  double radianceNw = 60.0;  // nW cm⁻² sr⁻¹ (VIIRS DNB, 500–900 nm) of a fully lit city core
  double gain = 3e4;         // multiplies the radiance: the longer exposure of a night photograph
  glm::vec3 color{1.0f, 0.358f, 0.053f};  // linear RGB (a 2,400 K blackbody), scaled by the renderer to luminance 1
  double coverage = 0.15;               // lit share of the most habitable land of a settled region
  double citySizeM = 120'000.0;         // wavelength of the cities' largest octave (a metropolis)
  uint32_t seed = 11;
};

struct PlanetDescription {
  std::string name;
  double radiusM = 0.0;            // radius of the sphere the heights are measured from
  bool hasOcean = false;           // false for airless or dry bodies: no water is drawn
  double seaLevelM = 0.0;          // water surface above the radius sphere (0 without an ocean)
  double heightScale = 1.0;        // vertical exaggeration: multiplies every height (1: true scale)
  double baseHeightM = 0.0;        // constant added to the layer sum (moves the coastline)
  std::vector<NoiseLayer> layers;  // summed; at least one
  PlanetColors colors;
  MaterialDescription materials;  // [materials]; its defaults are the scheme's (defaultMaterials)
  AtmosphereDescription atmosphere;
  CloudDescription clouds;
  WaterDescription water;  // used when hasOcean
  StarDescription stars;
  LightsDescription lights;  // [lights]; absent: none
};

// A closed interval [min, max]; every bound the parser checks is one of the constants below.
struct Range {
  double min;
  double max;
};
inline constexpr Range kRadiusRangeM{1e3, 1e8};
inline constexpr Range kSeaLevelRangeM{-2e4, 2e4};
inline constexpr Range kHeightScaleRange{0.0, 100.0};
inline constexpr Range kBaseHeightRangeM{-1e5, 1e5};
inline constexpr Range kFrequencyRange{1e-9, 10.0};  // cycles per metre
inline constexpr Range kWavelengthRangeM{0.1, 1e9};  // 1 / kFrequencyRange
inline constexpr Range kAmplitudeRangeM{-1e5, 1e5};
inline constexpr Range kSeedRange{0.0, 4294967295.0};
inline constexpr Range kBeachHeightRangeM{0.0, 1e3};
inline constexpr Range kSnowLineRangeM{-1e5, 1e5};
inline constexpr Range kIceCapLatitudeRangeDeg{0.0, 90.0};
inline constexpr Range kColorNoiseWavelengthRangeM{1.0, 1e9};
inline constexpr Range kPerturbationRange{0.0, 2.0};
inline constexpr double kPolarCircleDeg = 66.5;  // seed 004's polar caps when a preset names no latitude
inline constexpr Range kColorComponentRange{0.0, 1.0};
inline constexpr Range kTemperatureRangeC{-273.0, 1000.0};
inline constexpr Range kTemperatureDropRangeC{-500.0, 500.0};
inline constexpr Range kLapseRangeKPerKm{-50.0, 50.0};
inline constexpr Range kSlopeRangeDeg{0.0, 90.0};
inline constexpr Range kMaterialKnobRange{0.0, 10.0};
inline constexpr Range kCoastalHeightRangeM{0.0, 1e5};
inline constexpr Range kAtmosphereHeightRangeM{1e3, 1e7};
inline constexpr Range kScatteringRange{0.0, 1e-2};  // per metre
inline constexpr Range kScaleHeightRangeM{10.0, 1e6};
inline constexpr Range kMieExtinctionRatioRange{1.0, 10.0};
inline constexpr Range kMieGRange{-0.99, 0.99};
inline constexpr Range kOzoneAltitudeRangeM{0.0, 1e6};
inline constexpr Range kAirglowRangeCdM2{0.0, 1.0};  // the night sky is ~2e-4 cd/m²; 1 is twilight
inline constexpr Range kCloudAltitudeRangeM{0.0, 1e6};
inline constexpr Range kUnitRange{0.0, 1.0};
inline constexpr Range kSharpnessRange{1e-6, 1.0};
inline constexpr Range kCloudWavelengthRangeM{1e3, 1e9};
inline constexpr Range kCloudOctavesRange{1.0, 16.0};
inline constexpr Range kWindRangeMps{-1e3, 1e3};
inline constexpr Range kEvolvePeriodRangeS{1.0, 1e9};
inline constexpr Range kCloudOpacityRange{0.0, 100.0};
inline constexpr Range kCloudClimateRange{0.0, 2.0};
inline constexpr Range kCloudCyclonesRange{0.0, 48.0};
inline constexpr Range kCloudSwirlRange{0.0, 5.0};
inline constexpr Range kCloudShearRange{0.0, 3.0};
inline constexpr Range kCloudResolutionRange{64.0, 2048.0};
inline constexpr Range kClarityRangeM{0.1, 1e4};
inline constexpr Range kWaveWavelengthRangeM{0.01, 1e4};
inline constexpr Range kWaveSlopeRange{0.0, 1.0};
inline constexpr Range kSeaWindRangeMps{0.0, 40.0};  // Cox & Munk measured up to ~14 m/s; beyond, extrapolated
inline constexpr Range kMagnitudeRange{0.0, 9.0};
inline constexpr Range kLightsRadianceRangeNw{0.0, 1e4};  // nW cm⁻² sr⁻¹
inline constexpr Range kLightsGainRange{0.0, 1e9};
inline constexpr Range kCitySizeRangeM{1e3, 1e7};
inline constexpr Range kStarBrightnessRange{0.0, 1e3};
inline constexpr int kMaxLayers = 8;                 // the height shader's fixed layer array
inline constexpr size_t kMaxCurvePoints = 16;        // transfer and hypsometry points (gpu::kTerrainCurveKnots)
inline constexpr size_t kMaxMaskCurvePoints = 8;     // mask curve points (gpu::kTerrainMaskKnots)
inline constexpr Range kCurveValueRange{-1e5, 1e5};  // x and y of transfer and mask curves, y of hypsometries
inline constexpr size_t kMaxNameBytes = 64;          // planet and layer names
inline constexpr size_t kMaxPresetBytes = 1 << 20;   // a preset file larger than this is an error

inline constexpr std::string_view kDefaultPresetName = "earth";

const char* colorSchemeName(ColorScheme scheme);
// Every scheme, in the enum's order.
std::span<const ColorScheme> colorSchemes();
// "earth", "altitude", ...; throws planet::Error naming the bad value and listing the valid ones.
ColorScheme parseColorScheme(std::string_view name);
// How many colours of PlanetColors::palette the scheme uses (0: none, it uses the named colours).
size_t paletteSize(ColorScheme scheme);
// The palette and bands a scheme uses when a preset leaves them out.
PlanetColors defaultColors(ColorScheme scheme);
// The climate, detail and biome palette a scheme uses when a preset leaves [materials] out.
MaterialDescription defaultMaterials(ColorScheme scheme);

// Parse a TOML document; `sourceName` starts every message ("earth.toml:12: ..."). Throws
// planet::Error with a single-line message for any syntax error, unknown or missing key,
// wrong type, non-finite or out-of-range value, non-UTF-8 or empty input.
PlanetDescription parsePlanetDescription(std::string_view toml, const std::string& sourceName);
// Reads and parses a file; messages start with `path`.
PlanetDescription loadPlanetDescription(const std::string& path);

// A preset compiled into the binary (the files of engine/planet/presets).
struct EmbeddedPreset {
  const char* name;  // "earth"
  const char* text;  // the whole TOML file
};
std::span<const EmbeddedPreset> embeddedPresets();
// Names of the built-in presets, in embedding order.
std::vector<std::string> presetNames();
// A FILE (ends in ".toml" or contains '/') is loaded; anything else is a built-in NAME, whose
// messages are attributed to "NAME.toml".
PlanetDescription resolvePreset(const std::string& nameOrFile);

// Deterministic text of every field (offset and gain resolved to the values used), one
// "key=value" per line, numbers in shortest round-trip form: the input of descriptionHash.
std::string canonicalForm(const PlanetDescription& description);
// 64-bit FNV-1a of canonicalForm: equal for descriptions that render the same terrain and
// colours (and carry the same names), stable across runs, compilers and machines.
uint64_t descriptionHash(const PlanetDescription& description);
uint64_t fnv1a64(std::string_view bytes);

}  // namespace planet

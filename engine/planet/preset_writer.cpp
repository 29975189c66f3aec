#include "planet/preset_writer.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

#include <fmt/format.h>

#include "core/error.h"
#include "core/file.h"

namespace planet {
namespace {

// "1.5e-06" -> "1.5e-6", "1e+08" -> "1e8": the compact exponent planet_description.cpp prints.
std::string compactExponent(std::string text) {
  size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  bool negative = exponent[0] == '-';
  size_t digits = exponent.find_first_not_of("+-0");
  return text.substr(0, e + 1) + (negative ? "-" : "") +
         (digits == std::string::npos ? std::string("0") : exponent.substr(digits));
}

// "6371000" -> "6_371_000", as the presets write whole numbers from 1000 up.
std::string groupThousands(const std::string& integer) {
  size_t first = integer[0] == '-' ? 1 : 0;
  size_t digits = integer.size() - first;
  if (digits < 4) return integer;
  std::string out = integer.substr(0, first);
  for (size_t i = 0; i < digits; ++i) {
    if (i > 0 && (digits - i) % 3 == 0) out += '_';
    out += integer[first + i];
  }
  return out;
}

// std::to_chars's shortest round-trip text of `value` (-0 as 0, so equal values give equal text).
std::string shortest(double value) {
  if (value == 0.0) value = 0.0;
  char buffer[64];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

// Digits that carry information in a shortest text: "4000000" has 1, "0.00012" 2, "1.5e-6" 2.
size_t significantDigits(const std::string& text) {
  std::string mantissa = text.substr(0, text.find('e'));
  std::string digits;
  for (char c : mantissa)
    if (c >= '0' && c <= '9') digits += c;
  size_t begin = digits.find_first_not_of('0');
  if (begin == std::string::npos) return 1;
  return digits.find_last_not_of('0') - begin + 1;
}

// A TOML number that reads back to exactly `value`. Whole numbers below 1e15 are TOML integers
// in full ("100_000", not "1e5", as the presets write them; the parser takes an integer wherever
// it takes a number), everything else the shortest round-trip text.
std::string number(double value) {
  if (value == std::trunc(value) && std::abs(value) < 1e15) return groupThousands(std::to_string(int64_t(value)));
  std::string text = shortest(value);
  if (text.find_first_not_of("-0123456789") != std::string::npos) return compactExponent(text);
  // A whole number of 16+ digits: as a float, since a TOML integer must fit in 64 bits.
  char buffer[64];
  return compactExponent(
      std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::scientific).ptr));
}

// A colour component: the parser reads a double and rounds it to float, so the shortest float
// text is used only when that double rounding gives `value` back (it does not for a few floats,
// e.g. 7.038531e-26), else the double text of the float (exact).
std::string colorComponent(float value) {
  if (value == 0.0f) value = 0.0f;
  char buffer[64];
  std::string text(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
  double back = 0.0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), back);
  if (error == std::errc() && end == text.data() + text.size() && float(back) == value) return compactExponent(text);
  return number(double(value));
}

std::string color(const glm::vec3& c) {
  return fmt::format("[{}, {}, {}]", colorComponent(c.x), colorComponent(c.y), colorComponent(c.z));
}

// [x, y, z], or one number for all three (the atmosphere's coefficients accept both).
std::string vector3(const glm::dvec3& v) {
  if (v.x == v.y && v.y == v.z) return number(v.x);
  return fmt::format("[{}, {}, {}]", number(v.x), number(v.y), number(v.z));
}

// A TOML basic string: quotes, backslashes and control characters escaped, other UTF-8 as is.
std::string quoted(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (uint8_t(c) < 0x20 || c == 0x7f) {
      out += fmt::format("\\u{:04X}", uint8_t(c));
    } else {
      out += c;
    }
  }
  return out + '"';
}

// The wavelength_m that reads back (as 1 / wavelength_m) to exactly `frequency`, if one exists:
// 1 / frequency or one of its neighbours a few ulps away, among which is any wavelength the
// parser turned into this frequency. The one with the fewest significant digits wins.
std::optional<double> exactWavelength(double frequency) {
  if (!(frequency > 0.0) || !std::isfinite(frequency)) return std::nullopt;
  double guess = 1.0 / frequency;
  double candidates[7] = {guess};
  double below = guess, above = guess;
  for (int step = 1; step <= 3; ++step) {
    below = std::nextafter(below, 0.0);
    above = std::nextafter(above, std::numeric_limits<double>::infinity());
    candidates[2 * step - 1] = below;
    candidates[2 * step] = above;
  }
  std::optional<double> best;
  for (double wavelength : candidates) {
    if (!(wavelength >= kWavelengthRangeM.min && wavelength <= kWavelengthRangeM.max)) continue;
    if (1.0 / wavelength != frequency) continue;
    if (!best || significantDigits(shortest(wavelength)) < significantDigits(shortest(*best))) best = wavelength;
  }
  return best;
}

class Writer {
 public:
  void comment(std::string_view text) { out_ += fmt::format("# {}\n", text); }
  void table(std::string_view header) { out_ += fmt::format("\n{}\n", header); }
  void key(std::string_view key, const std::string& value) { out_ += fmt::format("{} = {}\n", key, value); }
  void key(std::string_view key, double value) { this->key(key, number(value)); }
  void integer(std::string_view key, int64_t value) { this->key(key, std::to_string(value)); }
  void boolean(std::string_view key, bool value) { this->key(key, std::string(value ? "true" : "false")); }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

void writeLayer(Writer& w, const NoiseLayer& layer) {
  const noise::NoiseSettings& n = layer.noise;
  w.table("[[layer]]");
  w.key("name", quoted(layer.name));
  w.key("type", quoted(noise::noiseTypeName(n.type)));
  const bool faults = n.type == noise::NoiseType::Faults;
  const bool mpd = noise::isMpd(n.type);
  if (faults) {
    w.integer("count", n.faults);
    w.key("width", n.width);
  } else if (mpd) {
    w.integer("levels", n.octaves);
    w.boolean("multifractal", n.multifractal);
  } else {
    w.integer("octaves", n.octaves);
  }
  // The parser refuses the keys a type does not use (planet_description.cpp, readLayer).
  if (!faults && !mpd) w.key("lacunarity", n.lacunarity);
  if (!faults) w.key("H", n.H);
  if (!faults && !mpd) w.key("offset", n.offset.value_or(noise::defaultOffset(n.type)));
  if (!faults) w.key("gain", n.gain.value_or(noise::kDefaultGain));
  w.integer("seed", n.seed);
  if (!faults && !mpd) w.key("hash", quoted(noise::noiseHashName(n.hash)));
  // The presets give most layers a wavelength; a frequency that no wavelength reproduces
  // exactly, or that reads better as itself (1.5e-6 rather than 666_666.6666666666), stays one.
  // Generators sample the unit sphere (frequency 1 / radius, set by the parser): no key.
  std::optional<double> wavelength = exactWavelength(layer.frequency);
  if (!faults && !mpd) {
    if (wavelength && significantDigits(shortest(*wavelength)) <= significantDigits(shortest(layer.frequency)))
      w.key("wavelength_m", *wavelength);
    else
      w.key("frequency", layer.frequency);
  }
  w.key("amplitude_m", layer.amplitudeM);
  auto curve = [&](std::string_view key, const std::vector<CurvePoint>& points) {
    if (points.empty()) return;
    std::string text = "[";
    for (size_t i = 0; i < points.size(); ++i)
      text += fmt::format("{}[{}, {}]", i ? ", " : "", number(points[i].x), number(points[i].y));
    w.key(key, text + "]");
  };
  curve("transfer", layer.transfer);
  curve("hypsometry", layer.hypsometry);
  if (!layer.mask.empty()) w.key("mask", quoted(layer.mask));
  curve("mask_curve", layer.maskCurve);
}

}  // namespace

std::string formatPlanetDescription(const PlanetDescription& d) {
  Writer w;
  w.comment(fmt::format("Planet preset {}, saved by planet (engine/planet/preset_writer.h).", quoted(d.name)));
  w.comment("earth.toml explains every key. Lengths are metres, angles degrees, colours linear RGB.");

  w.table("[planet]");
  w.key("name", quoted(d.name));
  w.key("radius_m", d.radiusM);
  w.boolean("has_ocean", d.hasOcean);
  if (d.hasOcean) w.key("sea_level_m", d.seaLevelM);
  w.key("height_scale", d.heightScale);
  w.key("base_height_m", d.baseHeightM);

  const PlanetColors& c = d.colors;
  w.table("[colors]");
  w.key("scheme", quoted(colorSchemeName(c.scheme)));
  w.key("beach_height_m", c.beachHeightM);
  w.key("snow_line_m", c.snowLineM);
  w.key("ice_cap_latitude_deg", c.iceCapLatitudeDeg);
  w.key("deep_water", color(c.deepWater));
  w.key("shallow_water", color(c.shallowWater));
  w.key("beach", color(c.beach));
  w.key("lowland", color(c.lowland));
  w.key("highland", color(c.highland));
  w.key("cliff", color(c.cliff));
  w.key("snow", color(c.snow));
  if (const size_t size = paletteSize(c.scheme)) {
    std::string text = "[";
    for (size_t i = 0; i < size; ++i) text += (i ? ", " : "") + color(c.palette[i]);
    w.key("palette", text + "]");
  }
  w.key("noise_wavelength_m", c.noiseWavelengthM);
  w.key("perturbation", c.perturbation);
  w.boolean("polar_caps", c.polarCaps);

  const MaterialDescription& m = d.materials;
  w.table("[materials]");
  w.key("equator_temperature_c", m.equatorTemperatureC);
  w.key("pole_temperature_drop_c", m.poleTemperatureDropC);
  w.key("lapse_rate_k_per_km", m.lapseRateKPerKm);
  w.key("snow_temperature_c", m.snowTemperatureC);
  w.key("moisture", m.moisture);
  w.key("moisture_noise", m.moistureNoise);
  w.key("regional_noise", m.regionalNoise);
  w.key("coastal_height_m", m.coastalHeightM);
  w.key("dry_belt", m.dryBelt);
  w.key("rock_slope_deg", m.rockSlopeDeg);
  w.key("snow_slope_deg", m.snowSlopeDeg);
  w.key("detail_relief", m.detailRelief);
  w.key("detail_contrast", m.detailContrast);
  w.key("conifer", color(m.conifer));
  w.key("forest", color(m.forest));
  w.key("grass", color(m.grass));
  w.key("dry_grass", color(m.dryGrass));
  w.key("desert", color(m.desert));
  w.key("tundra", color(m.tundra));
  w.key("scree", color(m.scree));

  const AtmosphereDescription& a = d.atmosphere;
  if (a.enabled) {
    w.table("[atmosphere]");
    w.key("height_m", a.heightM);
    w.key("rayleigh_scattering", vector3(a.rayleighScattering));
    w.key("rayleigh_scale_height_m", a.rayleighScaleHeightM);
    w.key("mie_scattering", vector3(a.mieScattering));
    w.key("mie_extinction_ratio", a.mieExtinctionRatio);
    w.key("mie_absorption", vector3(a.mieAbsorption));
    w.key("mie_scale_height_m", a.mieScaleHeightM);
    w.key("mie_g", vector3(a.mieG));
    w.key("ozone_absorption", vector3(a.ozoneAbsorption));
    w.key("ozone_center_m", a.ozoneCenterM);
    w.key("ozone_width_m", a.ozoneWidthM);
    w.key("airglow_cd_m2", a.airglowCdM2);
    w.key("airglow_color", color(a.airglowColor));
    w.key("airglow_bottom_m", a.airglowBottomM);
    w.key("airglow_top_m", a.airglowTopM);
  }

  const CloudDescription& cl = d.clouds;
  if (cl.enabled && a.enabled) {
    w.table("[clouds]");
    w.key("bottom_m", cl.bottomM);
    w.key("top_m", cl.topM);
    w.key("coverage", cl.coverage);
    w.key("sharpness", cl.sharpness);
    w.key("wavelength_m", cl.wavelengthM);
    w.integer("octaves", cl.octaves);
    w.integer("seed", cl.seed);
    w.key("wind_mps", cl.windMps);
    w.key("evolve_period_s", cl.evolvePeriodS);
    w.key("opacity", cl.opacity);
    w.key("climate", cl.climate);
    w.integer("cyclones", cl.cyclones);
    w.key("cyclone_radius_m", cl.cycloneRadiusM);
    w.key("swirl", cl.swirl);
    w.key("shear", cl.shear);
    w.key("warp", cl.warp);
    w.integer("resolution", cl.resolution);
  }

  if (d.hasOcean) {
    w.table("[water]");
    w.key("clarity_m", d.water.clarityM);
    w.key("wave_wavelength_m", d.water.waveWavelengthM);
    w.key("wave_slope", d.water.waveSlope);
    w.key("wind_mps", d.water.windMps);
  }

  w.table("[stars]");
  w.boolean("enabled", d.stars.enabled);
  w.integer("seed", d.stars.seed);
  w.key("faintest_magnitude", d.stars.faintestMagnitude);
  w.key("brightness", d.stars.brightness);

  if (d.lights.enabled) {
    w.table("[lights]");
    w.key("radiance_nw", d.lights.radianceNw);
    w.key("gain", d.lights.gain);
    w.key("color", color(d.lights.color));
    w.key("coverage", d.lights.coverage);
    w.key("city_size_m", d.lights.citySizeM);
    w.integer("seed", d.lights.seed);
  }

  for (const NoiseLayer& layer : d.layers) writeLayer(w, layer);
  return w.take();
}

void savePlanetDescription(const PlanetDescription& planet, const std::string& path) {
  std::string text = formatPlanetDescription(planet);
  try {
    parsePlanetDescription(text, path);
  } catch (const Error& e) {
    throw Error(fmt::format("cannot save planet preset: {}", e.what()));
  }
  writeFileAtomic(path, text);
}

}  // namespace planet

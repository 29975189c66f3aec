// planet sky (issue 21, point 9): one view ray through a preset's atmosphere, for headless checks
// of the model in the spirit of planet validate. For the model's three wavelengths: the
// transmittance along the view to the top of the atmosphere (or to the ground), and the
// single-scattered and the total (single and multiple) sky radiance per steradian for a
// top-of-atmosphere solar irradiance of 1, from one of three evaluations of the shared source
// (shaders/common/atmosphere.glsl).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "core/error.h"
#include "core/file.h"
#include "reference/atmosphere_model.h"
#include "render/sky_pass.h"
#include "render/sky_tables.h"

namespace planet::cli {
namespace {

// The model's channels: the presets' Rayleigh coefficients (Bruneton & Neyret 2008's Earth
// values, 5.8, 13.5, 33.1 ·10⁻⁶ m⁻¹) are those of 680, 550 and 440 nm (β_R ∝ λ⁻⁴).
constexpr int kWavelengthsNm[3] = {680, 550, 440};

// Samples along the ray: the CPU reference's (and its sun transmittance's), the reference sky
// pass's default per-pixel march (SkySettings::viewSamples), and the tables' march.
constexpr uint32_t kCpuSteps = 256;
const uint32_t kReferenceSteps = SkySettings{}.viewSamples;
constexpr uint32_t kTableSteps = 64;
constexpr double kMaxAltitudeM = 1e9;

struct SkyCommand {
  std::string preset{kDefaultPresetName};
  double altitudeM = 0.0;
  double sunElevationDeg = 0.0;
  double viewElevationDeg = 0.0;
  double viewAzimuthDeg = 0.0;
  std::string backend = "cpu";
  std::string json;
};

struct SkyResult {
  glm::dvec3 transmittance{1.0};
  glm::dvec3 single{0.0};
  glm::dvec3 total{0.0};
  std::string method;    // what computed it, one line
  double tableMs = 0.0;  // building the tables this backend reads
};

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

void checkElevation(const char* option, double degrees) {
  if (!(degrees >= -90.0 && degrees <= 90.0))
    throw UsageError(fmt::format("{} must be in -90..90 degrees, got {}", option, degrees));
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

nlohmann::ordered_json triple(const glm::dvec3& v) { return {v.r, v.g, v.b}; }

nlohmann::ordered_json modelJson(const PlanetDescription& planet, const gpu::AtmosphereParams& p) {
  const AtmosphereDescription& a = planet.atmosphere;
  return {{"radius_m", planet.radiusM},
          {"atmosphere", a.enabled},
          {"top_m", a.heightM},
          {"rayleigh_scattering_per_m", triple(a.rayleighScattering)},
          {"rayleigh_scale_height_m", a.rayleighScaleHeightM},
          {"mie_scattering_per_m", triple(a.mieScattering)},
          {"mie_extinction_per_m", triple(glm::dvec3(glm::vec3(p.mieExtinction)))},
          {"mie_scale_height_m", a.mieScaleHeightM},
          {"mie_g", triple(a.mieG)},
          {"mie_phase", "Cornette-Shanks"},
          {"ozone_absorption_per_m", triple(a.ozoneAbsorption)},
          {"ozone_center_m", a.ozoneCenterM},
          {"ozone_width_m", a.ozoneWidthM},
          {"ground_albedo_multiple_scattering", gpu::kMultiScatteringGroundAlbedo}};
}

int runSky(const GlobalOptions& global, const SkyCommand& cmd, const CLI::App& sub) {
  if (!(cmd.altitudeM >= 0.0 && cmd.altitudeM <= kMaxAltitudeM))
    throw UsageError(fmt::format("--altitude must be in 0..{:g} m, got {}", kMaxAltitudeM, cmd.altitudeM));
  checkElevation("--sun-elevation", cmd.sunElevationDeg);
  checkElevation("--view-elevation", cmd.viewElevationDeg);
  if (!std::isfinite(cmd.viewAzimuthDeg))
    throw UsageError(fmt::format("--view-azimuth must be a number of degrees, got {}", cmd.viewAzimuthDeg));
  if (cmd.backend != "cpu" && cmd.backend != "gpu" && cmd.backend != "reference")
    throw UsageError(fmt::format("--backend must be cpu, gpu or reference, got '{}'", cmd.backend));
  if (sub.count("--json")) checkOutputFile("--json", cmd.json);
  PlanetDescription planet;
  try {
    planet = resolvePreset(cmd.preset);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  planet.clouds.enabled = false;  // the clear sky: the tables do not need the cloud cover

  const gpu::AtmosphereParams params = makeAtmosphereParams(planet);
  const double mu = std::sin(radians(cmd.viewElevationDeg));
  const double muS = std::sin(radians(cmd.sunElevationDeg));
  const double nu =
      std::clamp(mu * muS + std::cos(radians(cmd.viewElevationDeg)) * std::cos(radians(cmd.sunElevationDeg)) *
                                std::cos(radians(cmd.viewAzimuthDeg)),
                 -1.0, 1.0);

  SkyResult result;
  std::unique_ptr<vk::Context> context;
  if (cmd.backend == "cpu") {
    const auto start = std::chrono::steady_clock::now();
    const MultipleScatteringTable table = multipleScatteringTable(params);
    result.tableMs = millisecondsSince(start);
    const SkySample sample = skyRadiance(params, cmd.altitudeM, mu, muS, nu, kCpuSteps, kCpuSteps, &table);
    result = {sample.transmittance, sample.radiance, sample.total,
              fmt::format("cpu: the double reference, {} steps, the sun's transmittance integrated ({} steps); "
                          "multiple scattering from the CPU's {}x{} table",
                          kCpuSteps, kCpuSteps, gpu::kMultiScatteringSize, gpu::kMultiScatteringSize),
              result.tableMs};
  } else {
    context = openContext(global);
    SkyTables tables(*context, planet);
    const auto start = std::chrono::steady_clock::now();
    const SkyTables::RayQuery query{cmd.altitudeM, mu, muS, nu};
    // The first call builds the tables; a second one times the ray alone.
    tables.evaluateRays({&query, 1}, kReferenceSteps, kTableSteps);
    result.tableMs = millisecondsSince(start);
    const SkyTables::RayResult ray = tables.evaluateRays({&query, 1}, kReferenceSteps, kTableSteps).front();
    if (cmd.backend == "gpu") {
      result.transmittance = ray.transmittance;
      result.single = ray.single;
      result.total = ray.single + ray.multiple;
      result.method =
          fmt::format("gpu: the tables ({}x{} transmittance, {}x{} multiple scattering), {} steps (sky_ray.comp) on {}",
                      gpu::kTransmittanceWidth, gpu::kTransmittanceHeight, gpu::kMultiScatteringSize,
                      gpu::kMultiScatteringSize, kTableSteps, context->info.name);
    } else {
      result.transmittance = ray.referenceTransmittance;
      result.single = ray.reference;
      result.total = ray.referenceTotal;
      result.method = fmt::format(
          "reference: the sky pass's per-pixel march (--sky reference), {} samples, multiple scattering from the "
          "GPU's table, run for this ray by sky_ray.comp on {}",
          kReferenceSteps, context->info.name);
    }
  }

  const double sunIrradiance = params.ozoneSun.y;  // the radiances are per unit sun irradiance
  result.single /= sunIrradiance;
  result.total /= sunIrradiance;
  const double viewSunDeg = std::acos(nu) * 180.0 / std::numbers::pi;
  fmt::memory_buffer out;
  auto line = [&out](const std::string& text) { fmt::format_to(std::back_inserter(out), "{}\n", text); };
  line(
      fmt::format("{} (preset {}): altitude {:g} m, sun elevation {:g}°, view elevation {:g}°, view azimuth {:g}° "
                  "from the sun's ({:.2f}° from the sun)",
                  planet.name, cmd.preset, cmd.altitudeM, cmd.sunElevationDeg, cmd.viewElevationDeg, cmd.viewAzimuthDeg,
                  viewSunDeg));
  line(result.method);
  line("radiance: per steradian, for a top-of-atmosphere solar irradiance of 1 (normal to the sun)");
  line(fmt::format("{:<12}{:>15}{:>15}{:>15}", "wavelength", "transmittance", "single", "total"));
  for (int c = 0; c < 3; ++c)
    line(fmt::format("{:<12}{:>15.6g}{:>15.6g}{:>15.6g}", fmt::format("{} nm", kWavelengthsNm[c]),
                     result.transmittance[c], result.single[c], result.total[c]));
  line(fmt::format("tables built in {:.3f} s{}", result.tableMs / 1000.0,
                   cmd.backend == "cpu" ? " (CPU, double)" : " (with the first ray, GPU)"));
  std::fwrite(out.data(), 1, out.size(), stdout);
  std::fflush(stdout);

  if (!cmd.json.empty()) {
    nlohmann::ordered_json j;
    j["format"] = "planet-sky";
    j["version"] = 1;
    j["generator"] = "planet sky";
    j["preset"] = cmd.preset;
    j["planet"] = planet.name;
    j["backend"] = cmd.backend;
    j["method"] = result.method;
    j["altitude_m"] = cmd.altitudeM;
    j["sun_elevation_deg"] = cmd.sunElevationDeg;
    j["view_elevation_deg"] = cmd.viewElevationDeg;
    j["view_azimuth_deg"] = cmd.viewAzimuthDeg;
    j["view_sun_angle_deg"] = viewSunDeg;
    j["units"] = "radiance per steradian for a top-of-atmosphere solar irradiance of 1; transmittance unitless";
    j["wavelengths_nm"] = {kWavelengthsNm[0], kWavelengthsNm[1], kWavelengthsNm[2]};
    j["transmittance"] = triple(result.transmittance);
    j["single"] = triple(result.single);
    j["total"] = triple(result.total);
    j["tables_ms"] = result.tableMs;
    j["model"] = modelJson(planet, params);
    writeFileAtomic(cmd.json, j.dump(2) + "\n");
  }
  return context ? finishWithValidation(*context, 0) : 0;
}

}  // namespace

void addSkyCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
  auto cmd = std::make_shared<SkyCommand>();
  CLI::App* sub = app.add_subcommand(
      "sky",
      "One view ray through the atmosphere: for each of the model's wavelengths (680, 550, 440 nm) the "
      "transmittance along the view and the single-scattered and total (single + multiple) sky radiance per "
      "steradian for a top-of-atmosphere solar irradiance of 1");
  sub->add_option("--preset", cmd->preset, "Built-in preset (earth, moon, mars, giant, faults, mpd) or a .toml file")
      ->capture_default_str();
  sub->add_option("--altitude", cmd->altitudeM, "Viewpoint altitude above the planet's radius (m, >= 0)")->required();
  sub->add_option("--sun-elevation", cmd->sunElevationDeg, "Sun elevation above the horizon (degrees, -90..90)")
      ->required();
  sub->add_option("--view-elevation", cmd->viewElevationDeg, "View elevation above the horizon (degrees, -90..90)")
      ->required();
  sub->add_option("--view-azimuth", cmd->viewAzimuthDeg, "View azimuth measured from the sun's (degrees)")->required();
  sub->add_option("--backend", cmd->backend,
                  "cpu: the double reference with its multiple-scattering table (no GPU); gpu: the GPU's "
                  "transmittance and multiple-scattering tables; reference: the sky pass's per-pixel march "
                  "(planet render --sky reference, 64 samples) run on the GPU for this ray")
      ->capture_default_str();
  sub->add_option("--json", cmd->json, "Also write the results and the model's parameters as JSON to FILE");
  checkNumbersAsText(*sub);
  sub->callback([&global, &exitCode, cmd, sub] { exitCode = runSky(global, *cmd, *sub); });
}

}  // namespace planet::cli

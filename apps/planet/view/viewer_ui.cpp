#include "view/viewer_ui.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <imgui.h>

namespace planet::view {
namespace {

// ImGui edits floats; the description holds doubles. Returns true when the edit finished
// (slider released or value typed), so a rebuild happens once per edit, not per drag step.
bool editDouble(const char* label, double& value, double min, double max, const char* format = "%.3g",
                ImGuiSliderFlags flags = 0) {
  float f = float(value);
  ImGui::SliderFloat(label, &f, float(min), float(max), format, flags | ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemEdited()) value = double(f);
  return ImGui::IsItemDeactivatedAfterEdit();
}

bool editInt(const char* label, int& value, int min, int max) {
  ImGui::SliderInt(label, &value, min, max, "%d", ImGuiSliderFlags_AlwaysClamp);
  return ImGui::IsItemDeactivatedAfterEdit();
}

bool editColor(const char* label, glm::vec3& color) {
  float c[3] = {color.x, color.y, color.z};
  ImGui::ColorEdit3(label, c, ImGuiColorEditFlags_Float);
  if (ImGui::IsItemEdited()) color = glm::vec3(c[0], c[1], c[2]);
  return ImGui::IsItemDeactivatedAfterEdit();
}

// The generators of issue 22 (faults, mpd, mpd_ico) have parameters of their own. Faults get
// seed 000's "Step" (one more fault) and "Run" (keep adding faults, redrawing after each: the
// count grows by about 5 % a step, so a run from 1 to 10,000 takes some 190 rebuilds; on
// lavapipe each takes seconds, on a GPU a fraction of one). `playing` says whether this layer runs.
bool editGenerator(noise::NoiseSettings& n, bool& playing) {
  bool done = false;
  if (n.type == noise::NoiseType::Faults) {
    ImGui::SliderInt("faults", &n.faults, noise::kMinFaults, noise::kMaxFaults, "%d",
                     ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_Logarithmic);
    done |= ImGui::IsItemDeactivatedAfterEdit();
    if (ImGui::Button("step") && n.faults < noise::kMaxFaults) {
      ++n.faults;
      done = true;
    }
    ImGui::SameLine();
    if (ImGui::Button(playing ? "stop" : "run")) playing = !playing;
    if (playing) {
      if (n.faults >= noise::kMaxFaults) {
        playing = false;
      } else {
        n.faults = std::min(noise::kMaxFaults, n.faults + std::max(1, n.faults / 20));
        done = true;
      }
    }
    done |= editDouble("step width (rad)", n.width, 0.0, noise::kMaxFaultWidth, "%.4f",
                       ImGuiSliderFlags_Logarithmic);
  } else {
    playing = false;
    done |= editInt("levels", n.octaves, noise::kMinMpdLevels, noise::kMaxMpdLevels);
    done |= editDouble("H", n.H, noise::kMinH, noise::kMaxH);
    if (ImGui::Checkbox("multifractal", &n.multifractal)) done = true;
    if (n.multifractal) {
      double gain = n.gain.value_or(noise::kDefaultGain);
      if (editDouble("gain", gain, 0.0, noise::kMaxGain)) done = true;
      if (gain != n.gain.value_or(noise::kDefaultGain)) n.gain = gain;
    }
  }
  int seed = int(std::min<uint32_t>(n.seed, 1u << 30));
  if (ImGui::InputInt("seed", &seed, 1, 100, ImGuiInputTextFlags_EnterReturnsTrue)) {
    n.seed = uint32_t(std::max(seed, 0));
    done = true;
  }
  return done;
}

bool editLayer(NoiseLayer& layer, double radiusM, bool& playing) {
  bool done = false;
  noise::NoiseSettings& n = layer.noise;
  static constexpr noise::NoiseType kTypes[] = {
      noise::NoiseType::Simplex, noise::NoiseType::Fbm,    noise::NoiseType::Ridged, noise::NoiseType::Hybrid,
      noise::NoiseType::Hetero,  noise::NoiseType::Cascade, noise::NoiseType::Craters, noise::NoiseType::Damped,
      noise::NoiseType::Eroded,  noise::NoiseType::Faults,  noise::NoiseType::Mpd,     noise::NoiseType::MpdIco};
  if (ImGui::BeginCombo("type", noise::noiseTypeName(n.type))) {
    for (noise::NoiseType t : kTypes)
      if (ImGui::Selectable(noise::noiseTypeName(t), t == n.type) && t != n.type) {
        const bool wasGenerator = noise::isGenerator(n.type);
        n.type = t;
        n.offset.reset();  // the new type's default
        // The generators sample the unit sphere and refuse the fractals' keys; a fractal coming
        // back from one gets its defaults.
        if (noise::isGenerator(t)) {
          layer.frequency = 1.0 / radiusM;  // functions of the direction (the parser's rule)
          n.lacunarity = 2.0;
          n.hash = noise::NoiseHash::Fast;
          if (t == noise::NoiseType::Faults) {
            n.octaves = 1;
            n.gain.reset();
          } else {
            n.octaves = std::clamp(n.octaves, noise::kMinMpdLevels, noise::kMaxMpdLevels);
          }
        } else if (wasGenerator) {
          layer.frequency = 1e-6;  // a 1,000 km wavelength to start from
          n.octaves = 8;
          n.H = 1.0;
          n.gain.reset();
        }
        done = true;
      }
    ImGui::EndCombo();
  }
  if (noise::isGenerator(n.type)) {
    done |= editGenerator(n, playing);
    done |= editDouble("amplitude (m)", layer.amplitudeM, -10000.0, 10000.0, "%.0f");
    return done;
  }
  playing = false;
  done |= editInt("octaves", n.octaves, noise::kMinOctaves, noise::kMaxOctaves);
  done |= editDouble("lacunarity", n.lacunarity, 1.01, 8.0);
  done |= editDouble("H", n.H, noise::kMinH, noise::kMaxH);
  double offset = n.offset.value_or(noise::defaultOffset(n.type));
  // Craters' offset is the rim perturbation, valid in [0, 0.5] only; eroded's the number of
  // octaves of plain fBm under the gullies (a whole number); damped has none.
  const bool craters = n.type == noise::NoiseType::Craters;
  const bool damped = n.type == noise::NoiseType::Damped;
  const bool eroded = n.type == noise::NoiseType::Eroded;
  if (eroded) {
    const int shown = std::clamp(int(std::floor(offset)), 1, n.octaves);
    int baseOctaves = shown;
    if (editInt("base octaves (fBm under the gullies)", baseOctaves, 1, n.octaves)) done = true;
    if (baseOctaves != shown) offset = double(baseOctaves);  // unmoved, a fractional offset stays
  } else if (!damped && editDouble(craters ? "rim perturbation" : "offset", offset, craters ? 0.0 : -2.0,
                                   craters ? noise::kMaxCraterPerturbation : 2.0)) {
    done = true;
  }
  if (offset != n.offset.value_or(noise::defaultOffset(n.type))) n.offset = offset;
  double gain = n.gain.value_or(noise::kDefaultGain);
  // Ridged: how a crest sharpens the next octave; damped: how much steep ground smooths the finer
  // octaves; eroded: the depth of the gullies.
  const char* gainLabel = damped ? "slope damping (gain)" : eroded ? "gully depth (gain)" : "gain";
  if (editDouble(gainLabel, gain, 0.0, noise::kMaxGain)) done = true;
  if (gain != n.gain.value_or(noise::kDefaultGain)) n.gain = gain;
  int seed = int(std::min<uint32_t>(n.seed, 1u << 30));
  if (ImGui::InputInt("seed", &seed, 1, 100, ImGuiInputTextFlags_EnterReturnsTrue)) {
    n.seed = uint32_t(std::max(seed, 0));
    done = true;
  }
  bool reference = n.hash == noise::NoiseHash::Reference;
  if (ImGui::Checkbox("reference hash (Perlin's table)", &reference)) {
    n.hash = reference ? noise::NoiseHash::Reference : noise::NoiseHash::Fast;
    done = true;
  }
  done |= editDouble("amplitude (m)", layer.amplitudeM, -10000.0, 10000.0, "%.0f");
  // Shown as a wavelength; the frequency is written only when the slider moved (1 / (1 / f)
  // need not give f back, and the planet must not change by looking at it).
  double wavelength = 1.0 / layer.frequency;
  if (editDouble("wavelength (m)", wavelength, 1.0, 1e8, "%.4g", ImGuiSliderFlags_Logarithmic)) done = true;
  if (ImGui::IsItemEdited()) layer.frequency = 1.0 / std::max(wavelength, 1.0);
  return done;
}

}  // namespace

const char* viewerKeyHelp() {
  return "Mouse: right button held looks around (free flight) or turns and tilts the view (orbit);\n"
         "  left drag in orbit moves over the ground; the wheel multiplies the height by 0.85 a step\n"
         "W/S forward/back, A/D left/right, E/Space up, Q/C down; Shift 4x faster, Alt 4x slower\n"
         "Tab switches orbit / free flight; G flies to the go-to point of the panel\n"
         "T (planet view --scene) travels to the next body of the scene; looking around takes over\n"
         "F1 this help, F2 hides the panel, F12 or P saves a screenshot (without the panel), Esc quits";
}

void ViewerUi::draw(ViewerSettings& settings, const HudData& hud, UiRequests& requests) {
  drawHud(hud);
  if (showPanel_) drawPanel(settings, requests);
  if (showHelp_) drawHelp();
}

void ViewerUi::drawHud(const HudData& hud) {
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.55f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove;
  if (ImGui::Begin("HUD", nullptr, flags)) {
    ImGui::Text("%s", hud.device.c_str());
    ImGui::Text("%.1f fps  (%ux%u render)", hud.fps, hud.renderWidth, hud.renderHeight);
    if (hud.frameTimesMs && !hud.frameTimesMs->empty()) {
      std::vector<float> times(hud.frameTimesMs->begin(), hud.frameTimesMs->end());
      const float top = *std::max_element(times.begin(), times.end());
      ImGui::PlotLines("##frame", times.data(), int(times.size()), 0, fmt::format("frame ms (max {:.1f})", top).c_str(),
                       0.0f, top * 1.1f, ImVec2(260, 50));
    }
    for (const vk::GpuTiming& pass : hud.passes) ImGui::Text("  %-10s %7.2f ms", pass.name.c_str(), pass.milliseconds);
    if (hud.exposure && hud.exposure->exposure > 0.0)
      ImGui::Text("exposure %.3g (auto, toward %.3g)", hud.exposure->exposure, hud.exposure->target);
    ImGui::Separator();
    ImGui::Text("lat %.4f  lon %.4f", hud.latitudeDeg, hud.longitudeDeg);
    if (hud.altitudeM >= 1e4)
      ImGui::Text("altitude %.1f km, %.1f km above ground", hud.altitudeM / 1e3, hud.heightAboveGroundM / 1e3);
    else
      ImGui::Text("altitude %.1f m, %.1f m above ground", hud.altitudeM, hud.heightAboveGroundM);
    ImGui::Text("%.4g m per vertex at the nadir", hud.metresPerVertex);
    ImGui::Text("%llu triangles", static_cast<unsigned long long>(hud.triangles));
    ImGui::Text("%s, %.3g m/s%s", hud.mode == FlightMode::Orbit ? "orbit" : "free flight", hud.speedMps,
                hud.pathPlaying ? ", playing path" : "");
    if (!hud.status.empty()) ImGui::TextWrapped("%s", hud.status.c_str());
    ImGui::TextDisabled("F1: keys");
  }
  ImGui::End();
}

void ViewerUi::drawPanel(ViewerSettings& s, UiRequests& r) {
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(viewport->Size.x - 8, 8), ImGuiCond_FirstUseEver, ImVec2(1, 0));
  ImGui::SetNextWindowSize(ImVec2(340, std::min(viewport->Size.y - 16, 640.0f)), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("planet", nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::End();
    return;
  }
  ImGui::PushItemWidth(150);
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
    int quality = int(s.quality);
    const char* names[kViewQualityCount];
    for (int i = 0; i < kViewQualityCount; ++i) names[i] = viewQualityName(ViewQuality(i));
    ImGui::SliderInt("quality", &quality, 0, kViewQualityCount - 1, names[quality], ImGuiSliderFlags_AlwaysClamp);
    if (ImGui::IsItemDeactivatedAfterEdit() && quality != int(s.quality)) {
      s.quality = ViewQuality(quality);
      s.mesh = qualityPreset(s.quality).mesh;
      r.rebuild = true;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", describeQuality(ViewQuality(quality)).c_str());
    // The spherical clipmap (Clasen & Hege): levels halve theta, rings per level, vertices per ring.
    int levels = int(s.mesh.levels), rings = int(s.mesh.ringsPerLevel), numPhi = int(s.mesh.numPhi);
    if (editInt("mesh levels", levels, 8, int(kClipmapMaxLevels))) r.rebuild = true;
    if (editInt("rings per level", rings, 2, 64)) r.rebuild = true;
    if (editInt("vertices per ring", numPhi, 16, 1024)) r.rebuild = true;
    s.mesh = ClipmapParams{uint32_t(levels), uint32_t(rings), uint32_t(numPhi)};
    r.rebuild |= editDouble("field of view", s.fovDeg, 10.0, 120.0, "%.0f deg");
    r.terrainToggles |= ImGui::Checkbox("water", &s.water);
    if (s.planet.lights.enabled) r.terrainToggles |= ImGui::Checkbox("city lights", &s.lights);
    r.skyChanged |= ImGui::Checkbox("clouds", &s.clouds);
    if (ImGui::Checkbox("atmosphere", &s.planet.atmosphere.enabled)) r.rebuild = true;
    if (ImGui::Checkbox("stars", &s.planet.stars.enabled)) r.rebuild = true;
    r.terrainToggles |= ImGui::Checkbox("wireframe", &s.wireframe);
    ImGui::SameLine();
    r.terrainToggles |= ImGui::Checkbox("freeze LOD", &s.freezeLod);
    if (ImGui::Checkbox("patch textures", &s.patches)) r.rebuild = true;
    if (!qualityPreset(s.quality).patches) {
      ImGui::SameLine();
      ImGui::TextDisabled("(off at this quality)");
    }
    r.skyChanged |= ImGui::Checkbox("auto exposure", &s.autoExposure);
    ImGui::BeginDisabled(s.autoExposure);
    editDouble("exposure", s.exposure, 0.5, 100.0, "%.2f", ImGuiSliderFlags_Logarithmic);
    r.skyChanged |= ImGui::IsItemEdited();
    ImGui::EndDisabled();
  }
  if (ImGui::CollapsingHeader("Sun and time", ImGuiTreeNodeFlags_DefaultOpen)) {
    // Local solar time at the camera: noon where the sun stands over the camera's meridian.
    double hours = 12.0 + std::remainder(s.cameraLongitudeDeg - s.sunLongitudeDeg, 360.0) / 15.0;
    float h = float(hours);
    ImGui::SliderFloat("time of day", &h, 0.0f, 24.0f, "%.2f h", ImGuiSliderFlags_AlwaysClamp);
    if (ImGui::IsItemEdited())
      s.sunLongitudeDeg = std::remainder(s.cameraLongitudeDeg - (double(h) - 12.0) * 15.0, 360.0);
    editDouble("sun latitude", s.sunLatitudeDeg, -90.0, 90.0, "%.1f deg");
    editDouble("sun longitude", s.sunLongitudeDeg, -180.0, 180.0, "%.1f deg");
    ImGui::Checkbox("sun moves", &s.sunMoves);
    ImGui::SameLine();
    ImGui::Checkbox("animate", &s.animate);
    editDouble("day length", s.dayLengthS, 10.0, 86400.0, "%.0f s", ImGuiSliderFlags_Logarithmic);
  }
  if (ImGui::CollapsingHeader("Terrain")) {
    PlanetDescription& p = s.planet;
    r.rebuild |= editDouble("height scale", p.heightScale, 0.0, 10.0);
    r.rebuild |= editDouble("base height (m)", p.baseHeightM, -5000.0, 5000.0, "%.0f");
    if (p.hasOcean) r.rebuild |= editDouble("sea level (m)", p.seaLevelM, -5000.0, 5000.0, "%.0f");
    for (size_t i = 0; i < p.layers.size(); ++i) {
      ImGui::PushID(int(i));
      if (ImGui::TreeNode("layer", "layer %zu: %s (%s)", i, p.layers[i].name.c_str(),
                          noise::noiseTypeName(p.layers[i].noise.type))) {
        bool playing = faultsPlaying_ == int(i);
        r.rebuild |= editLayer(p.layers[i], p.radiusM, playing);
        if (playing) faultsPlaying_ = int(i);
        else if (faultsPlaying_ == int(i)) faultsPlaying_ = -1;
        ImGui::TreePop();
      }
      ImGui::PopID();
    }
  }
  if (ImGui::CollapsingHeader("Colours")) {
    PlanetColors& c = s.planet.colors;
    if (ImGui::BeginCombo("scheme", colorSchemeName(c.scheme))) {
      for (ColorScheme scheme : colorSchemes())
        if (ImGui::Selectable(colorSchemeName(scheme), scheme == c.scheme) && scheme != c.scheme) {
          c = defaultColors(scheme);
          s.planet.materials = defaultMaterials(scheme);
          r.rebuild = true;
        }
      ImGui::EndCombo();
    }
    r.rebuild |= editDouble("beach (m)", c.beachHeightM, 0.0, 1000.0, "%.0f");
    r.rebuild |= editDouble("snow line (m)", c.snowLineM, -2000.0, 10000.0, "%.0f");
    r.rebuild |= editDouble("ice caps from", c.iceCapLatitudeDeg, 0.0, 90.0, "%.1f deg");
    // Seed 004's polar caps over any scheme, and seed 000's colour noise.
    if (ImGui::Checkbox("polar caps", &c.polarCaps)) {
      if (c.polarCaps && c.iceCapLatitudeDeg >= 90.0) c.iceCapLatitudeDeg = kPolarCircleDeg;
      r.rebuild = true;
    }
    r.rebuild |= editDouble("colour noise", c.noiseWavelengthM, 1e3, 1e7, "%.0f m", ImGuiSliderFlags_Logarithmic);
    r.rebuild |= editDouble("perturbation", c.perturbation, kPerturbationRange.min, kPerturbationRange.max, "%.2f");
    for (size_t i = 0; i < paletteSize(c.scheme); ++i) {
      ImGui::PushID(int(i));
      r.rebuild |= editColor(fmt::format("palette {}", i).c_str(), c.palette[i]);
      ImGui::PopID();
    }
    r.rebuild |= editColor("lowland", c.lowland);
    r.rebuild |= editColor("highland", c.highland);
    r.rebuild |= editColor("cliff", c.cliff);
    r.rebuild |= editColor("snow", c.snow);
    r.rebuild |= editColor("beach", c.beach);
    r.rebuild |= editColor("shallow water", c.shallowWater);
    r.rebuild |= editColor("deep water", c.deepWater);
    // The sea's roughness (Cox & Munk): a stronger wind spreads the sun's glint wider and dimmer.
    if (s.planet.hasOcean)
      r.rebuild |=
          editDouble("sea wind", s.planet.water.windMps, kSeaWindRangeMps.min, kSeaWindRangeMps.max, "%.1f m/s");
  }
  if (ImGui::CollapsingHeader("Materials")) {
    // The climate that picks the ground's material (earth and mars schemes) and the per-pixel
    // ground detail (every scheme but altitude and giant): shaders/terrain_material.glsl.
    MaterialDescription& m = s.planet.materials;
    r.rebuild |= editDouble("equator (sea level)", m.equatorTemperatureC, -150.0, 60.0, "%.1f C");
    r.rebuild |= editDouble("pole drop", m.poleTemperatureDropC, 0.0, 150.0, "%.1f C");
    r.rebuild |= editDouble("lapse rate", m.lapseRateKPerKm, 0.0, 12.0, "%.2f K/km");
    r.rebuild |= editDouble("snow below", m.snowTemperatureC, -150.0, 10.0, "%.1f C");
    r.rebuild |= editDouble("moisture", m.moisture, 0.0, 1.0, "%.2f");
    r.rebuild |= editDouble("moisture noise", m.moistureNoise, 0.0, 3.0, "%.2f");
    r.rebuild |= editDouble("regional noise", m.regionalNoise, 0.0, 3.0, "%.2f");
    r.rebuild |= editDouble("coastal height", m.coastalHeightM, 0.0, 3000.0, "%.0f m");
    r.rebuild |= editDouble("dry belts", m.dryBelt, 0.0, 2.0, "%.2f");
    r.rebuild |= editDouble("rock from slope", m.rockSlopeDeg, 5.0, 89.0, "%.0f deg");
    r.rebuild |= editDouble("snow up to slope", m.snowSlopeDeg, 5.0, 89.0, "%.0f deg");
    r.rebuild |= editDouble("detail relief", m.detailRelief, 0.0, 3.0, "%.2f");
    r.rebuild |= editDouble("detail contrast", m.detailContrast, 0.0, 3.0, "%.2f");
    r.rebuild |= editColor("conifer", m.conifer);
    r.rebuild |= editColor("forest", m.forest);
    r.rebuild |= editColor("grass", m.grass);
    r.rebuild |= editColor("dry grass", m.dryGrass);
    r.rebuild |= editColor("desert", m.desert);
    r.rebuild |= editColor("tundra", m.tundra);
    r.rebuild |= editColor("scree", m.scree);
  }
  if (ImGui::CollapsingHeader("Atmosphere")) {
    AtmosphereDescription& a = s.planet.atmosphere;
    r.rebuild |= editDouble("top (m)", a.heightM, 1e4, 1e6, "%.0f", ImGuiSliderFlags_Logarithmic);
    double rayleigh = a.rayleighScattering.z * 1e6;
    if (editDouble("Rayleigh blue (1e-6/m)", rayleigh, 0.0, 200.0, "%.1f")) r.rebuild = true;
    if (rayleigh != a.rayleighScattering.z * 1e6)  // scaled (keeps the colour); from 0, air's λ^-4 ratios
      a.rayleighScattering = a.rayleighScattering.z > 0.0
                                 ? a.rayleighScattering * (rayleigh * 1e-6 / a.rayleighScattering.z)
                                 : AtmosphereDescription{}.rayleighScattering * (rayleigh * 1e-6 / 33.1e-6);
    r.rebuild |= editDouble("Rayleigh scale height", a.rayleighScaleHeightM, 100.0, 50000.0, "%.0f m");
    double mie = a.mieScattering.x * 1e6;
    if (editDouble("Mie (1e-6/m)", mie, 0.0, 500.0, "%.1f")) r.rebuild = true;
    if (mie != a.mieScattering.x * 1e6)  // scaled, which keeps the dust's colour; grey from 0
      a.mieScattering =
          a.mieScattering.x > 0.0 ? a.mieScattering * (mie * 1e-6 / a.mieScattering.x) : glm::dvec3(mie * 1e-6);
    r.rebuild |= editDouble("Mie scale height", a.mieScaleHeightM, 100.0, 20000.0, "%.0f m");
    double mieG = a.mieG.y;  // green's; the others move with it (a preset's spread across channels stays)
    if (editDouble("Mie g", mieG, 0.0, 0.95, "%.2f")) r.rebuild = true;
    if (mieG != a.mieG.y) a.mieG = glm::clamp(a.mieG + (mieG - a.mieG.y), glm::dvec3(-0.99), glm::dvec3(0.99));
    CloudDescription& cl = s.planet.clouds;
    r.rebuild |= editDouble("cloud cover", cl.coverage, 0.0, 1.0, "%.2f");
    r.rebuild |= editDouble("cloud climate bands", cl.climate, 0.0, 2.0, "%.2f");
    r.rebuild |= editDouble("cyclone swirl", cl.swirl, 0.0, 5.0, "%.2f turns");
    r.rebuild |= editDouble("wind shear", cl.shear, 0.0, 3.0, "%.2f rad");
    r.rebuild |= editDouble("cloud warp", cl.warp, 0.0, 1.0, "%.3f");
    r.rebuild |= editDouble("cloud opacity", cl.opacity, 0.0, 100.0, "%.0f");
  }
  if (ImGui::CollapsingHeader("Go to and presets", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::InputFloat3("lat, lon, alt m", goTo_, "%.5g");
    if (ImGui::Button("Go (G)")) {
      r.goTo = true;
      r.goToLatDeg = goTo_[0];
      r.goToLonDeg = goTo_[1];
      r.goToAltitudeM = goTo_[2];
    }
    ImGui::SameLine();
    if (ImGui::Button("orbit / free (Tab)")) r.toggleMode = true;
    ImGui::InputText("preset file", presetPath_, sizeof(presetPath_));
    if (ImGui::Button("Load")) r.loadPreset = presetPath_;
    ImGui::SameLine();
    if (ImGui::Button("Save")) r.savePreset = presetPath_;
    ImGui::SameLine();
    if (ImGui::Button("Screenshot (F12)")) r.screenshot = true;
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

void ViewerUi::drawHelp() {
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (ImGui::Begin("Keys (F1)", &showHelp_, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings))
    ImGui::TextUnformatted(viewerKeyHelp());
  ImGui::End();
}

}  // namespace planet::view

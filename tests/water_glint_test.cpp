// The sun's glint on the sea (issue 20, point 3): from orbit it must have the width Cox & Munk
// (1954) measured for the preset's wind, grow with the wind, and stay below the tonemapper's
// white. The width is measured on the rendered HDR frame along the image row through the
// glint: the brightness above the background (a smooth fit over the row's sea) has a full width
// at half maximum, which the view geometry turns into facet tilts (the angle between the sea's
// normal and the half vector of sun and camera at each pixel); the same is done on the model
// profile with Cox–Munk's slope variance. Plus the formula and the preset key on the CPU.
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "camera/camera.h"
#include "core/error.h"
#include "core/image_file.h"
#include "gpu_fixture.h"
#include "planet/planet_description.h"
#include "planet/terrain_height.h"
#include "render/renderer.h"
#include "render/water_pass.h"
#include "test_support.h"

namespace planet::test {
namespace {

constexpr double kPi = std::numbers::pi;

// Cox & Munk's clean-surface fit, written out here rather than taken from the renderer.
double coxMunkVariance(double windMps) { return 0.003 + 0.00512 * windMps; }

// Unpolarised Fresnel reflectance of water (n = 1.333) at incidence cosine c.
double fresnelWater(double c) {
  const double n = 1.333;
  const double g = std::sqrt(n * n - 1.0 + c * c);
  const double a = (g - c) / (g + c);
  const double b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

// What the view geometry gives at one pixel of the sea-level sphere.
struct Facet {
  glm::dvec3 ground;  // unit direction of the point seen
  double tilt = 0.0;  // angle between the sphere's normal and the half vector of sun and camera
  double cosView = 0.0;
  double cosHalfSun = 0.0;  // the half vector against the sun: Fresnel's incidence
};

// The frame as the renderer sets it up (camera.h: right-handed view space, screen up = basis up,
// row 0 at the top), intersected with the sphere of radius `seaRadiusM`.
std::optional<Facet> facetAt(const CameraBasis& basis, const glm::dvec3& sun, double seaRadiusM, double fovYRad,
                             uint32_t width, uint32_t height, double px, double py) {
  const double tanHalf = std::tan(0.5 * fovYRad);
  const double aspect = double(width) / double(height);
  const glm::dvec3 right = glm::normalize(glm::cross(basis.forward, basis.up));
  const double x = (2.0 * px / width - 1.0) * tanHalf * aspect;
  const double y = (1.0 - 2.0 * py / height) * tanHalf;
  const glm::dvec3 ray = glm::normalize(basis.forward + x * right + y * basis.up);
  const double b = glm::dot(basis.position, ray);
  const double c = glm::dot(basis.position, basis.position) - seaRadiusM * seaRadiusM;
  const double discriminant = b * b - c;
  if (discriminant <= 0.0) return std::nullopt;
  const glm::dvec3 hit = basis.position + (-b - std::sqrt(discriminant)) * ray;
  Facet facet;
  facet.ground = glm::normalize(hit);
  const glm::dvec3 toCamera = -ray;
  const glm::dvec3 halfway = glm::normalize(sun + toCamera);
  facet.tilt = std::acos(std::clamp(glm::dot(facet.ground, halfway), -1.0, 1.0));
  facet.cosView = glm::dot(facet.ground, toCamera);
  facet.cosHalfSun = glm::dot(halfway, sun);
  return facet;
}

// The glint's radiance per unit sun irradiance for total mean square slope m2 (Beckmann / Cox–Munk
// facets, Fresnel; the shadowing term is 1 within 60° of the nadir at these slopes).
double modelGlint(const Facet& f, double m2) {
  const double c = std::cos(f.tilt);
  const double tan2 = std::tan(f.tilt) * std::tan(f.tilt);
  const double distribution = std::exp(-tan2 / m2) / (kPi * m2 * c * c * c * c);
  return fresnelWater(f.cosHalfSun) * distribution / (4.0 * f.cosView);
}

double luminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Solves the symmetric system a·x = b (n ≤ 5) by Gaussian elimination with partial pivoting.
template <size_t N>
std::array<double, N> solve(std::array<std::array<double, N>, N> a, std::array<double, N> b) {
  for (size_t col = 0; col < N; ++col) {
    size_t pivot = col;
    for (size_t row = col + 1; row < N; ++row)
      if (std::abs(a[row][col]) > std::abs(a[pivot][col])) pivot = row;
    std::swap(a[col], a[pivot]);
    std::swap(b[col], b[pivot]);
    for (size_t row = col + 1; row < N; ++row) {
      const double factor = a[row][col] / a[col][col];
      for (size_t k = col; k < N; ++k) a[row][k] -= factor * a[col][k];
      b[row] -= factor * b[col];
    }
  }
  std::array<double, N> x{};
  for (size_t i = N; i-- > 0;) {
    double sum = b[i];
    for (size_t k = i + 1; k < N; ++k) sum -= a[i][k] * x[k];
    x[i] = sum / a[i][i];
  }
  return x;
}

// Full width at half maximum of `profile` (samples along the row) around its largest value, in
// facet tilt: the tilts where it falls to half, interpolated between pixels, on either side of
// the peak (the row passes through the specular point, where the tilt is ~0, so the width is
// their sum). 0 when a side never falls to half.
double fwhmTilt(const std::vector<double>& profile, const std::vector<double>& tilt) {
  const size_t peak = size_t(std::max_element(profile.begin(), profile.end()) - profile.begin());
  const double half = 0.5 * profile[peak];
  auto crossing = [&](int direction) -> double {
    for (int i = int(peak); i + direction >= 0 && i + direction < int(profile.size()); i += direction) {
      const int j = i + direction;
      if (profile[j] < half) {
        const double t = (profile[i] - half) / (profile[i] - profile[j]);
        return tilt[i] + t * (tilt[j] - tilt[i]);
      }
    }
    return -1.0;
  };
  const double left = crossing(-1), right = crossing(1);
  return left < 0.0 || right < 0.0 ? 0.0 : left + right;
}

struct GlintMeasure {
  double measuredFwhm = 0.0;   // facet tilt, radians
  double predictedFwhm = 0.0;  // the same on the Cox–Munk model profile
  int peakColumn = 0, predictedPeakColumn = 0, row = 0;
  int maxByte = 0;  // largest 8-bit channel within the glint (tilt below the Cox–Munk σ)
};

using WaterGlint = GpuTest;

constexpr uint32_t kWidth = 480, kHeight = 270;
// Over the earth preset's widest open sea (5° N 130° E: 93 % of the 56° around it is sea at
// seed 0), 8,000 km up, looking straight down; the sun 68° high toward the north-east, so the
// specular point is off the image centre in both axes.
constexpr CameraPose kOrbit{5.0, 130.0, 8.0e6, 0.0, -90.0};
constexpr SunPose kSun{60.0, 68.0};

PlanetDescription seaEarth(double windMps) {
  PlanetDescription earth = resolvePreset("earth");
  earth.clouds.enabled = false;  // the glint, not the weather
  earth.water.windMps = windMps;
  return earth;
}

RenderSettings glintSettings() {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.terrain.patchSettings.resolution = 128;
  settings.terrain.patchSettings.levelCount = 3;
  return settings;
}

GlintMeasure measureGlint(vk::Context& context, double windMps, const std::string& picture) {
  const PlanetDescription earth = seaEarth(windMps);
  Renderer renderer(context, earth, glintSettings());
  const RenderResult result = renderer.render(kOrbit, kSun, 0.0, true);
  writePng((testOutputDir() / picture).string(), result.image);

  const double seaRadius = earth.radiusM + earth.seaLevelM;
  const CameraBasis basis = cameraBasis(kOrbit, earth.radiusM);
  const glm::dvec3 sun = sunDirection(kSun, kOrbit);
  const double fovY = glintSettings().fovYDeg * kPi / 180.0;
  const double m2 = coxMunkVariance(windMps);
  auto facet = [&](uint32_t x, uint32_t y) {
    return facetAt(basis, sun, seaRadius, fovY, kWidth, kHeight, x + 0.5, y + 0.5);
  };

  GlintMeasure m;
  // The specular point: the pixel of least tilt.
  double least = 10.0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x)
      if (const std::optional<Facet> f = facet(x, y); f && f->tilt < least) {
        least = f->tilt;
        m.predictedPeakColumn = int(x);
        m.row = int(y);
      }
  // The row through it, where the sea is seen within 60° of its zenith (beyond, the air's path
  // grows too fast for a smooth background).
  std::vector<double> data, model, tilt, inverseCos, column;
  for (uint32_t x = 0; x < kWidth; ++x) {
    const std::optional<Facet> f = facet(x, uint32_t(m.row));
    if (!f || f->cosView < 0.5) continue;
    const double groundM = terrainHeightM(earth, f->ground);
    EXPECT_LT(groundM, earth.seaLevelM - 50.0) << "column " << x << " of row " << m.row << " is not open sea";
    data.push_back(luminance(result.hdr[size_t(m.row) * kWidth + x]));
    model.push_back(modelGlint(*f, m2));
    tilt.push_back(f->tilt);
    inverseCos.push_back(1.0 / f->cosView);
    column.push_back(double(x));
  }
  EXPECT_GT(data.size(), kWidth / 3) << "too little sea on the row";
  if (data.size() < 20) return m;

  // Background: a + b·s + c·s² + d/cos θv (the sea's own light, the air's path radiance) fitted
  // together with a glint of the model's shape at the best slope variance on a grid (only to
  // separate the two; the width below is read off the data minus this background).
  const double s0 = column.front(), s1 = column.back();
  auto basisAt = [&](size_t i, const std::vector<double>& glint) {
    const double s = (column[i] - s0) / (s1 - s0) * 2.0 - 1.0;
    return std::array<double, 5>{1.0, s, s * s, inverseCos[i], glint[i]};
  };
  double bestResidual = 1e300;
  std::array<double, 5> best{};
  for (double scale = 0.2; scale <= 5.0; scale *= 1.02) {
    std::vector<double> glint(data.size());
    for (size_t i = 0; i < data.size(); ++i) {
      const std::optional<Facet> f = facet(uint32_t(column[i]), uint32_t(m.row));
      glint[i] = modelGlint(*f, m2 * scale);
    }
    std::array<std::array<double, 5>, 5> normal{};
    std::array<double, 5> rhs{};
    for (size_t i = 0; i < data.size(); ++i) {
      const std::array<double, 5> row = basisAt(i, glint);
      for (size_t j = 0; j < 5; ++j) {
        rhs[j] += row[j] * data[i];
        for (size_t k = 0; k < 5; ++k) normal[j][k] += row[j] * row[k];
      }
    }
    const std::array<double, 5> coefficients = solve(normal, rhs);
    double residual = 0.0;
    for (size_t i = 0; i < data.size(); ++i) {
      const std::array<double, 5> row = basisAt(i, glint);
      double fit = 0.0;
      for (size_t j = 0; j < 5; ++j) fit += coefficients[j] * row[j];
      residual += (fit - data[i]) * (fit - data[i]);
    }
    if (residual < bestResidual) {
      bestResidual = residual;
      best = coefficients;
    }
  }
  std::vector<double> excess(data.size());
  for (size_t i = 0; i < data.size(); ++i) {
    const std::array<double, 5> row = basisAt(i, model);
    excess[i] = data[i] - (best[0] * row[0] + best[1] * row[1] + best[2] * row[2] + best[3] * row[3]);
  }
  m.measuredFwhm = fwhmTilt(excess, tilt);
  m.predictedFwhm = fwhmTilt(model, tilt);
  m.peakColumn = int(column[size_t(std::max_element(excess.begin(), excess.end()) - excess.begin())]);

  // The brightest display value within the glint (tilt below σ), on every row.
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x)
      if (const std::optional<Facet> f = facet(x, y); f && f->tilt < std::sqrt(m2)) {
        const uint8_t* p = &result.image.pixels[(size_t(y) * kWidth + x) * 4];
        m.maxByte = std::max({m.maxByte, int(p[0]), int(p[1]), int(p[2])});
      }
  return m;
}

// From 8,000 km the glint is a soft spot of the width Cox–Munk give the preset's wind (7 m/s:
// σ² = 0.0388, a half-maximum width of 2σ√ln 2 ≈ 0.33 rad of facet tilt, ~1,500 km on the sea),
// twice the wind widens it by √(σ²(14)/σ²(7)) ≈ 1.39, and it stays below the display's white.
TEST_F(WaterGlint, OrbitGlintHasCoxMunkWidthForTheWindAndIsNotClipped) {
  const double presetWind = resolvePreset("earth").water.windMps;
  EXPECT_EQ(presetWind, 7.0);
  const GlintMeasure calm = measureGlint(context(), presetWind, "water_glint_7mps.png");
  const GlintMeasure windy = measureGlint(context(), 2.0 * presetWind, "water_glint_14mps.png");
  for (const GlintMeasure* m : {&calm, &windy}) {
    const double wind = m == &calm ? presetWind : 2.0 * presetWind;
    std::cout << fmt::format(
        "wind {} m/s: glint FWHM {:.4f} rad of facet tilt, Cox-Munk {:.4f} (ratio {:.3f}); "
        "peak at column {} (predicted {}) of row {}; brightest byte {}\n",
        wind, m->measuredFwhm, m->predictedFwhm, m->measuredFwhm / m->predictedFwhm, m->peakColumn,
        m->predictedPeakColumn, m->row, m->maxByte);
    ASSERT_GT(m->predictedFwhm, 0.0);
    EXPECT_NEAR(m->measuredFwhm / m->predictedFwhm, 1.0, 0.3) << "wind " << wind;
    // Where the geometry puts the specular point (a check of the measurement's geometry too).
    EXPECT_NEAR(m->peakColumn, m->predictedPeakColumn, 0.02 * kWidth) << "wind " << wind;
    EXPECT_LT(m->maxByte, 250) << "the glint is clipped at the display's white, wind " << wind;
  }
  const double predictedRatio = std::sqrt(coxMunkVariance(2.0 * presetWind) / coxMunkVariance(presetWind));
  const double measuredRatio = windy.measuredFwhm / calm.measuredFwhm;
  EXPECT_NEAR(measuredRatio, predictedRatio, 0.15 * predictedRatio) << "the glint's width ignores the wind";
}

// The CPU side: the formula the shader's slope variance comes from, and the preset key.
TEST(WaterGlintSettings, CoxMunkVarianceAndTheWindKey) {
  EXPECT_DOUBLE_EQ(coxMunkSlopeVariance(0.0), 0.003);
  EXPECT_DOUBLE_EQ(coxMunkSlopeVariance(10.0), 0.003 + 0.0512);
  const PlanetDescription earth = resolvePreset("earth");
  EXPECT_FLOAT_EQ(waterUniform(earth.water, true).w, float(0.003 + 0.00512 * earth.water.windMps));

  // The [water] key: read, defaulted, and refused out of range with one line naming it.
  auto preset = [](const std::string& water) {
    return "[planet]\nname = \"Sea\"\nradius_m = 1_000_000\nhas_ocean = true\n\n[colors]\nscheme = \"altitude\"\n\n"
           "[[layer]]\nname = \"base\"\ntype = \"fbm\"\noctaves = 4\nfrequency = 1e-6\namplitude_m = "
           "1000\n\n[water]\n" +
           water;
  };
  EXPECT_EQ(parsePlanetDescription(preset("wind_mps = 12.5\n"), "x.toml").water.windMps, 12.5);
  EXPECT_EQ(parsePlanetDescription(preset("clarity_m = 5\n"), "x.toml").water.windMps, 7.0);
  EXPECT_EQ(errorOf([&] { parsePlanetDescription(preset("wind_mps = -1\n"), "x.toml"); }),
            "x.toml:17: wind_mps must be in [0, 40], got -1");
  EXPECT_EQ(errorOf([&] { parsePlanetDescription(preset("wind_mps = 41\n"), "x.toml"); }),
            "x.toml:17: wind_mps must be in [0, 40], got 41");
}

}  // namespace
}  // namespace planet::test

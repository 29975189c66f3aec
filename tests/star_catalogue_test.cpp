// The star catalogue on the CPU (issue 4, point 4): deterministic per seed, uniform directions,
// the count-versus-magnitude law, Pogson fluxes, colour by temperature, the polynomial
// transcendentals of shaders/common/stars.glsl, and settings validation.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "planet/planet_description.h"
#include "reference/atmosphere_model.h"
#include "reference/star_catalogue.h"
#include "render/star_pass.h"
#include "reference/star_kernel.h"
#include "test_support.h"

namespace planet::test {
namespace {

using gpu::StarRecord;

glm::vec3 directionOf(const StarRecord& s) { return glm::vec3(s.direction.x, s.direction.y, s.direction.z); }
double luminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// How many standard deviations `observed` lies from the binomial expectation n·p.
double sigmas(double observed, double n, double p) { return (observed - n * p) / std::sqrt(n * p * (1.0 - p)); }

std::vector<StarRecord> catalogue(uint32_t seed, uint32_t count, float faintest = 7.0f) {
  StarSettings settings;
  settings.seed = seed;
  settings.count = count;
  settings.faintestMagnitude = faintest;
  return starCatalogueCpu(settings);
}

TEST(StarCatalogue, SameSeedGivesTheSameBytes) {
  const std::vector<StarRecord> a = catalogue(7, 5000);
  const std::vector<StarRecord> b = catalogue(7, 5000);
  ASSERT_EQ(a.size(), 5000u);
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(StarRecord)), 0);
}

TEST(StarCatalogue, DifferentSeedsShareNoStars) {
  const std::vector<StarRecord> a = catalogue(1, 4000);
  std::set<std::pair<float, float>> positions;
  for (const StarRecord& s : a) positions.insert({s.direction.x, s.direction.y});
  for (uint32_t other : {2u, 3u, 1000u, 0xffffffffu}) {
    // No star of one catalogue appears anywhere in the other (not even at a shifted index).
    size_t shared = 0;
    for (const StarRecord& s : catalogue(other, 4000)) shared += positions.count({s.direction.x, s.direction.y});
    EXPECT_EQ(shared, 0u) << "seed " << other;
  }
}

TEST(StarCatalogue, DirectionsAreUnitVectors) {
  for (const StarRecord& s : catalogue(3, 20000)) ASSERT_NEAR(glm::length(directionOf(s)), 1.0f, 1e-6f);
}

TEST(StarCatalogue, DirectionsAreUniformOverTheSphere) {
  const uint32_t n = 200000;
  const std::vector<StarRecord> stars = catalogue(11, n);
  glm::dvec3 mean(0.0);
  double octants[8] = {};
  double zBands[20] = {}, sectors[32] = {};
  double corner = 0.0, faceCentre = 0.0;
  const glm::dvec3 cornerAxis = glm::normalize(glm::dvec3(1.0, 1.0, 1.0));
  const double capCos = std::cos(10.0 * std::numbers::pi / 180.0);
  for (const StarRecord& s : stars) {
    const glm::dvec3 d(directionOf(s));
    mean += d;
    octants[(d.x > 0) + 2 * (d.y > 0) + 4 * (d.z > 0)] += 1;
    zBands[std::min(19, int((d.z + 1.0) * 10.0))] += 1;
    const double phi = std::atan2(d.y, d.x) + std::numbers::pi;
    sectors[std::min(31, int(phi / (2.0 * std::numbers::pi) * 32.0))] += 1;
    corner += glm::dot(d, cornerAxis) > capCos ? 1 : 0;
    faceCentre += d.x > capCos ? 1 : 0;
  }
  mean /= double(n);
  // Each component of a uniform unit vector has variance 1/3: the mean's sd is sqrt(1/(3n)).
  EXPECT_LT(glm::length(mean), 5.0 * std::sqrt(1.0 / (3.0 * n)));
  // Equal-area cells hold n·p stars each, within 5 binomial standard deviations.
  for (double c : octants) EXPECT_LT(std::abs(sigmas(c, n, 1.0 / 8.0)), 5.0);
  for (double c : zBands) EXPECT_LT(std::abs(sigmas(c, n, 1.0 / 20.0)), 5.0);   // z uniform (hat-box theorem)
  for (double c : sectors) EXPECT_LT(std::abs(sigmas(c, n, 1.0 / 32.0)), 5.0);  // azimuth, across the quadrant seams
  // Normalised cube points would crowd the cube's corners: 10° caps at a corner and at a face
  // centre hold the same share, (1 − cos 10°)/2.
  const double capShare = (1.0 - capCos) / 2.0;
  EXPECT_LT(std::abs(sigmas(corner, n, capShare)), 5.0);
  EXPECT_LT(std::abs(sigmas(faceCentre, n, capShare)), 5.0);
}

TEST(StarCatalogue, StarsAreOrderedBySkyTileInEqualShares) {
  stars::StarKernel kernel;
  for (uint32_t count : {1u, 100u, 511u, 512u, 513u, 16000u, gpu::kStarMaxCount}) {
    ASSERT_EQ(starTileFirstIndex(0, count), 0u);
    ASSERT_EQ(starTileFirstIndex(gpu::kStarTileCount, count), count);
    for (uint32_t t = 0; t < gpu::kStarTileCount; ++t) {
      const uint32_t first = starTileFirstIndex(t, count), end = starTileFirstIndex(t + 1, count);
      ASSERT_LE(end - first, count / gpu::kStarTileCount + 1) << count << " stars, tile " << t;
      ASSERT_GE(end - first, count / gpu::kStarTileCount) << count << " stars, tile " << t;
      // The shader's tile of each index agrees with the CPU's table (both ends of the range).
      if (end > first) {
        ASSERT_EQ(kernel.starTileOf(first, count), t) << count;
        ASSERT_EQ(kernel.starTileOf(end - 1, count), t) << count;
      }
    }
  }
}

TEST(StarCatalogue, EveryStarLiesInItsTilesCap) {
  const uint32_t n = 100000;
  const std::vector<StarRecord> stars = catalogue(12, n);
  for (uint32_t t = 0; t < gpu::kStarTileCount; ++t) {
    const StarTileCap cap = starTileCap(t);
    const uint32_t band = t / gpu::kStarTileSectors;
    const double zTop = 1.0 - 2.0 * band / gpu::kStarTileBands, zBottom = zTop - 2.0 / gpu::kStarTileBands;
    double farthest = 0.0;
    for (uint32_t i = starTileFirstIndex(t, n); i < starTileFirstIndex(t + 1, n); ++i) {
      const glm::dvec3 d(directionOf(stars[i]));
      ASSERT_LE(d.z, zTop + 1e-6) << "tile " << t;
      ASSERT_GE(d.z, zBottom - 1e-6) << "tile " << t;
      farthest = std::max(farthest, std::acos(std::clamp(glm::dot(d, cap.axis), -1.0, 1.0)));
    }
    ASSERT_LE(farthest, cap.radiusRad) << "tile " << t;
    // The cap is tight: its ~195 stars reach most of the way to its edge (less in the polar
    // tiles, whose farthest point is the thin tip at the pole).
    const bool polar = band == 0 || band == gpu::kStarTileBands - 1;
    ASSERT_GT(farthest, (polar ? 0.6 : 0.8) * cap.radiusRad) << "tile " << t;
  }
  EXPECT_NE(errorOf([] { starTileCap(gpu::kStarTileCount); }).find("sky tile 512"), std::string::npos);
}

TEST(StarCatalogue, CountsFollowTheMagnitudeLawInHalfMagnitudeBins) {
  // N(< m) = count · 10^(0.5 (m − faintest)), so the bin [a, b) holds count · (10^(0.5(b − f)) −
  // 10^(0.5(a − f))). Tolerance: 5 binomial standard deviations per bin, and 3 % for bins
  // expecting more than 5,000 stars.
  const uint32_t n = 400000;
  const float faintest = 9.0f;
  const std::vector<StarRecord> stars = catalogue(5, n, faintest);
  std::vector<double> bins(22, 0.0);  // [−1.5, −1), [−1, −0.5), ..., [9, 9.5)
  for (const StarRecord& s : stars) {
    const float m = s.direction.w;
    ASSERT_GE(m, gpu::kStarBrightestMagnitude);
    ASSERT_LE(m, faintest);
    bins[size_t((m + 1.5f) * 2.0f)] += 1;
  }
  auto below = [&](double m) { return std::min(1.0, std::pow(10.0, 0.5 * (m - faintest))); };
  for (size_t b = 1; b + 1 < bins.size(); ++b) {  // the first bin also holds the clamped stars
    const double lo = -1.5 + 0.5 * b, hi = lo + 0.5;
    const double p = below(hi) - below(lo);
    EXPECT_LT(std::abs(sigmas(bins[b], n, p)), 5.0) << "bin [" << lo << ", " << hi << ")";
    if (n * p > 5000) {
      EXPECT_NEAR(bins[b] / (n * p), 1.0, 0.03) << "bin [" << lo << ", " << hi << ")";
    }
  }
}

TEST(StarCatalogue, DefaultSettingsGiveTheRealSkysStarCounts) {
  // About 9,000 stars brighter than 6.5 (the Yale Bright Star Catalogue), ~500 brighter than 4,
  // ~16 brighter than 1.
  EXPECT_EQ(realisticStarCount(6.5f), 9000u);
  EXPECT_EQ(realisticStarCount(7.0f), 16005u);
  const StarSettings defaults;
  EXPECT_NEAR(double(defaults.count), double(realisticStarCount(defaults.faintestMagnitude)), 0.01 * defaults.count);
  const std::vector<StarRecord> stars = starCatalogueCpu(defaults);
  auto brighterThan = [&](float m) {
    return double(std::count_if(stars.begin(), stars.end(), [&](const StarRecord& s) { return s.direction.w < m; }));
  };
  EXPECT_NEAR(brighterThan(6.5f), 9000.0, 300.0);
  EXPECT_NEAR(brighterThan(4.0f), 506.0, 70.0);
  EXPECT_NEAR(brighterThan(1.0f), 16.0, 12.0);
}

TEST(StarCatalogue, FluxIsPogsonsLawAndTheColourCarriesIt) {
  for (const StarRecord& s : catalogue(9, 20000)) {
    const double flux = std::pow(10.0, -0.4 * double(s.direction.w));
    // The colour is scaled to luminance 1 before the flux (the sRGB matrix's 4 decimals leave
    // ~1e-4), and no component is negative.
    ASSERT_NEAR(luminance(s.color) / flux, 1.0, 2e-3) << "magnitude " << s.direction.w << ", T " << s.color.w;
    ASSERT_GE(std::min({s.color.r, s.color.g, s.color.b}), 0.0f);
  }
}

TEST(StarCatalogue, CoolStarsAreRedderThanHotStars) {
  stars::StarKernel kernel;
  // Along the temperature range the colour's red/blue ratio falls strictly.
  double previous = std::numeric_limits<double>::infinity();
  for (double t = gpu::kStarMinTemperatureK; t <= gpu::kStarMaxTemperatureK; t += 250.0) {
    const glm::vec3 c = kernel.starColor(float(1000.0 / t));
    const double ratio = c.r / c.b;
    EXPECT_LT(ratio, previous) << t << " K";
    previous = ratio;
  }
  const glm::vec3 cool = kernel.starColor(1000.0f / 3000.0f);
  const glm::vec3 sunlike = kernel.starColor(1000.0f / 6500.0f);
  const glm::vec3 hot = kernel.starColor(1000.0f / 20000.0f);
  EXPECT_GT(cool.r, cool.g);
  EXPECT_GT(cool.g, cool.b);
  EXPECT_GT(hot.b, hot.g);
  EXPECT_GT(hot.g, hot.r);
  // 6,500 K is close to sRGB's D65 white.
  EXPECT_NEAR(sunlike.r / sunlike.g, 1.0, 0.1);
  EXPECT_NEAR(sunlike.b / sunlike.g, 1.0, 0.1);
  // In a catalogue, the stars below 4,000 K are on average redder than those above 10,000 K.
  double coolRatio = 0.0, hotRatio = 0.0, coolCount = 0.0, hotCount = 0.0;
  for (const StarRecord& s : catalogue(4, 20000)) {
    ASSERT_GE(s.color.w, gpu::kStarMinTemperatureK - 1.0f);
    ASSERT_LE(s.color.w, gpu::kStarMaxTemperatureK + 1.0f);
    if (s.color.w < 4000.0f) coolRatio += s.color.r / s.color.b, coolCount += 1;
    if (s.color.w > 10000.0f) hotRatio += s.color.r / s.color.b, hotCount += 1;
  }
  EXPECT_GT(coolRatio / coolCount, 3.0 * (hotRatio / hotCount));
}

TEST(StarCatalogue, TemperaturesLeanTowardCoolStars) {
  // Uniform in 1000 K / T: median 1000 / 0.18667 = 5,357 K, 20.5 % above 10,000 K, 28.4 % below 4,000 K.
  const uint32_t n = 100000;
  std::vector<float> t;
  for (const StarRecord& s : catalogue(8, n)) t.push_back(s.color.w);
  std::nth_element(t.begin(), t.begin() + n / 2, t.end());
  EXPECT_NEAR(t[n / 2], 5357.0, 60.0);
  const double hot = double(std::count_if(t.begin(), t.end(), [](float x) { return x > 10000.0f; }));
  const double cool = double(std::count_if(t.begin(), t.end(), [](float x) { return x < 4000.0f; }));
  EXPECT_LT(std::abs(sigmas(hot, n, 0.06 / 0.29333)), 5.0);
  EXPECT_LT(std::abs(sigmas(cool, n, (1.0 / 3.0 - 0.25) / 0.29333)), 5.0);
}

TEST(StarCatalogue, PolynomialTranscendentalsMatchTheLibraryWithinTheirStatedError) {
  stars::StarKernel kernel;
  // log2 of k · 2^−24 for k = 1, 2^24 and a spread of values between.
  double worstLog = 0.0;
  for (uint32_t k : {1u, 2u, 3u, 0xb504f3u, 0xb504f4u, 1u << 23, (1u << 24) - 1, 1u << 24}) {
    worstLog = std::max(worstLog, std::abs(kernel.starLog2Unit(k) - (std::log2(double(k)) - 24.0)));
  }
  for (uint32_t i = 0; i < 100000; ++i) {
    const uint32_t k = (kernel.pcgHash(i) >> 8) + 1;
    worstLog = std::max(worstLog, std::abs(kernel.starLog2Unit(k) - (std::log2(double(k)) - 24.0)));
  }
  // A few float roundings of values up to 24 in size: 24 · 2^−24 = 1.4e-6.
  EXPECT_LT(worstLog, 4e-6);
  double worstExp = 0.0;
  for (double y = -20.0; y <= 3.0; y += 0.001)
    worstExp = std::max(worstExp, std::abs(kernel.starExp2(float(y)) / std::exp2(double(float(y))) - 1.0));
  EXPECT_LT(worstExp, 1e-6);
  double worstTrig = 0.0;
  for (int i = 0; i < 4096; ++i) {
    const float a = float(i) / 4096.0f;
    const glm::vec2 cs = kernel.starCosSinQuarter(a);
    const double angle = double(a) * std::numbers::pi / 2.0;
    worstTrig = std::max({worstTrig, std::abs(cs.x - std::cos(angle)), std::abs(cs.y - std::sin(angle))});
  }
  EXPECT_LT(worstTrig, 5e-7);
  std::printf("polynomials vs library: log2 %.2e, exp2 (relative) %.2e, cos/sin %.2e\n", worstLog, worstExp, worstTrig);
}

TEST(StarCatalogue, BrighterStarsGetLargerAndBrighterSprites) {
  stars::StarKernel kernel;
  double previousPeak = std::numeric_limits<double>::infinity();
  double previousDiameter = 3.0;
  for (float m = gpu::kStarBrightestMagnitude; m <= kStarMaxFaintestMagnitude; m += 0.01f) {
    const float d = kernel.starSpriteDiameter(m);
    EXPECT_GE(d, 1.0f);
    EXPECT_LE(d, 3.0f);
    EXPECT_LE(d, previousDiameter);
    // The share of the Gaussian (σ = d/4) on a pixel centred on the star: its brightest pixel.
    const double centreShare = std::erf(0.5 / (gpu::kStarSpriteSigma * d * std::numbers::sqrt2));
    const double peak = kernel.starFlux(m) * centreShare * centreShare;
    EXPECT_LT(peak, previousPeak) << "magnitude " << m;
    previousPeak = peak;
    previousDiameter = d;
  }
  EXPECT_EQ(kernel.starSpriteDiameter(-1.0f), 3.0f);
  EXPECT_EQ(kernel.starSpriteDiameter(4.0f), 1.0f);
}

TEST(StarCatalogue, ValidationNamesTheBadValue) {
  auto check = [](StarSettings s) { return errorOf([&] { validateStarSettings(s); }); };
  EXPECT_EQ(check(StarSettings{}), "");
  StarSettings s;
  s.count = 0;
  EXPECT_NE(check(s).find("star count 0"), std::string::npos) << check(s);
  s.count = gpu::kStarMaxCount + 1;
  EXPECT_NE(check(s).find("star count 1048577"), std::string::npos) << check(s);
  s = StarSettings{};
  s.faintestMagnitude = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(check(s).find("magnitude nan"), std::string::npos) << check(s);
  s.faintestMagnitude = 13.0f;
  EXPECT_NE(check(s).find("magnitude 13"), std::string::npos) << check(s);
  s.faintestMagnitude = -1.0f;
  EXPECT_NE(check(s).find("magnitude -1"), std::string::npos) << check(s);
  s = StarSettings{};
  s.brightness = 0.0f;
  EXPECT_NE(check(s).find("brightness 0"), std::string::npos) << check(s);
  s.brightness = std::numeric_limits<float>::infinity();
  EXPECT_NE(check(s).find("brightness inf"), std::string::npos) << check(s);
  s.brightness = 2000.0f;
  EXPECT_NE(check(s).find("brightness 2000"), std::string::npos) << check(s);
  // The CPU reference validates too.
  s = StarSettings{};
  s.count = 0;
  EXPECT_NE(errorOf([&] { starCatalogueCpu(s); }).find("star count 0"), std::string::npos);
}

// Which stars the eye sees against the sky (issue 21, point 4; common/star_visibility.glsl):
// magnitude 6.5 under a dark sky of 2e-4 cd/m² (the naked eye's limit), none of the catalogue by
// day, only the brightest (brighter than magnitude 0) at sunset, about magnitude 3 against the zenith with the sun 6°
// down (the end of civil twilight, when the brightest stars are out) and 5 at 12° (the end of nautical twilight), the
// sky's radiance from the CPU reference of the atmosphere; the share fades in over ±0.5 magnitude.
TEST(StarVisibility, TheEyeSeesFainterStarsAsTheSkyDarkens) {
  const double darkSky = 2e-4 / double(gpu::kStarSunLux);  // 2e-4 cd/m² in the frame's units
  EXPECT_NEAR(starLimitingMagnitude(darkSky), 6.5, 0.2);
  const gpu::AtmosphereParams params = makeAtmosphereParams(resolvePreset("earth"));
  const MultipleScatteringTable table = multipleScatteringTable(params);
  auto zenith = [&](double sunElevationDeg) {
    const double muS = std::sin(sunElevationDeg * std::numbers::pi / 180.0);
    const glm::dvec3 c = skyRadiance(params, 2.0, 1.0, muS, muS, 256, 256, &table).total;
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
  };
  const double noon = starLimitingMagnitude(zenith(50.0));
  const double sunset = starLimitingMagnitude(zenith(0.0));
  const double civil = starLimitingMagnitude(zenith(-6.0));
  const double nautical = starLimitingMagnitude(zenith(-12.0));
  std::printf("[ measured ] faintest star at the zenith: noon %.2f, sunset %.2f, sun -6: %.2f, sun -12: %.2f\n", noon,
              sunset, civil, nautical);
  EXPECT_LT(noon, gpu::kStarBrightestMagnitude - 0.5f);
  EXPECT_LT(sunset, 0.0);  // the sun on the horizon: at most the few brightest, at the zenith
  EXPECT_GT(civil, 2.0);
  EXPECT_LT(civil, 4.0);
  EXPECT_GT(nautical, 4.5);
  EXPECT_LT(nautical, starLimitingMagnitude(darkSky));
  // The fade: half a magnitude above the limit a star shows whole, half below not at all.
  auto flux = [](double magnitude) { return std::pow(10.0, -0.4 * magnitude); };
  EXPECT_NEAR(starVisibleShare(flux(civil - 0.55), zenith(-6.0)), 1.0, 1e-6);
  EXPECT_NEAR(starVisibleShare(flux(civil), zenith(-6.0)), 0.5, 0.02);
  EXPECT_NEAR(starVisibleShare(flux(civil + 0.55), zenith(-6.0)), 0.0, 1e-6);
}

}  // namespace
}  // namespace planet::test

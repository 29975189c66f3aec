// planet sky as a user runs it (issue 21, point 9): the three backends agree, twilight shows the
// multiple scattering, and bad input is one line with exit code 2.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace planet::test {
namespace {

std::filesystem::path skyTempDir() { return processTempDir("sky_cli_test"); }

ShellRun planetSky(const std::string& args) { return runShell(PLANET_EXE, "sky " + args, "", skyTempDir()); }

bool noDevice(const ShellRun& run) { return run.err.find("no Vulkan") != std::string::npos; }

// One backend's JSON for a view.
nlohmann::json skyJson(const std::string& view, const std::string& backend) {
  const std::filesystem::path json = skyTempDir() / ("sky_" + backend + ".json");
  const ShellRun run = planetSky(view + " --backend " + backend + " --json " + json.string());
  if (noDevice(run)) return nullptr;
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("550 nm"), std::string::npos) << run.out;
  return nlohmann::json::parse(readFileBytes(json));
}

double relative(double actual, double expected) {
  return std::abs(actual - expected) / std::max(std::abs(expected), 1e-12);
}

// cpu (double, 256 steps) against gpu (the tables, 64 steps): single and total within 5 %, the
// transmittance within 1 %. reference (the reference sky pass's march, 64 equal steps each
// integrated in closed form, multiple scattering from the GPU's table) against cpu: single and
// total within 5 %, the transmittance within 1 %.
TEST(SkyCli, TheThreeBackendsAgree) {
  for (const std::string view :
       {"--altitude 0 --sun-elevation 45 --view-elevation 30 --view-azimuth 90",
        "--altitude 10000 --sun-elevation -4 --view-elevation 60 --view-azimuth 0",
        "--preset mars --altitude 0 --sun-elevation 60 --view-elevation 40 --view-azimuth 120"}) {
    const nlohmann::json cpu = skyJson(view, "cpu");
    const nlohmann::json gpu = skyJson(view, "gpu");
    const nlohmann::json reference = skyJson(view, "reference");
    if (gpu.is_null()) GTEST_SKIP() << "no Vulkan device";
    ASSERT_EQ(cpu["wavelengths_nm"], nlohmann::json({680, 550, 440}));
    for (int c = 0; c < 3; ++c) {
      EXPECT_LT(relative(gpu["single"][c], cpu["single"][c]), 0.05) << view << " channel " << c;
      EXPECT_LT(relative(gpu["total"][c], cpu["total"][c]), 0.05) << view << " channel " << c;
      EXPECT_LT(relative(gpu["transmittance"][c], cpu["transmittance"][c]), 0.01) << view;
      EXPECT_LT(relative(reference["single"][c], cpu["single"][c]), 0.05) << view << " channel " << c;
      EXPECT_LT(relative(reference["total"][c], cpu["total"][c]), 0.05) << view << " channel " << c;
      EXPECT_LT(relative(reference["transmittance"][c], cpu["transmittance"][c]), 0.01) << view;
      // The reference march has multiple scattering.
      EXPECT_GT(reference["total"][c], reference["single"][c]) << view << " channel " << c;
    }
  }
}

// Sun 4° below the horizon, 10 km up, looking straight up: the single scattering is faint, the
// total (with the multiple scattering) brighter and bluer than red, on the CPU and the GPU.
TEST(SkyCli, TwilightZenithIsLitAndBlueByMultipleScattering) {
  const std::string view = "--altitude 10000 --sun-elevation -4 --view-elevation 90 --view-azimuth 0";
  for (const char* backend : {"cpu", "gpu"}) {
    const nlohmann::json sky = skyJson(view, backend);
    if (sky.is_null()) continue;  // no Vulkan device: the CPU's result stands alone
    const double red = sky["total"][0], green = sky["total"][1], blue = sky["total"][2];
    EXPECT_GT(green, 0.0) << backend;
    EXPECT_GT(blue, red) << backend;
    EXPECT_GT(blue, 1.3 * double(sky["single"][2])) << backend;
  }
}

TEST(SkyCli, PrintsTheWavelengthsAndUnits) {
  const ShellRun run = planetSky("--altitude 0 --sun-elevation 90 --view-elevation 90 --view-azimuth 0");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  for (const char* text : {"680 nm", "550 nm", "440 nm", "per steradian", "irradiance of 1", "transmittance"})
    EXPECT_NE(run.out.find(text), std::string::npos) << text << "\n" << run.out;
}

TEST(SkyCli, BadInputIsOneLineWithExitCode2) {
  const std::string rest = " --view-azimuth 0";
  const std::pair<std::string, std::string> cases[] = {
      {"--altitude 0 --sun-elevation 91 --view-elevation 0" + rest, "91"},
      {"--altitude 0 --sun-elevation 0 --view-elevation -90.5" + rest, "-90.5"},
      {"--altitude -1 --sun-elevation 0 --view-elevation 0" + rest, "-1"},
      {"--altitude nan --sun-elevation 0 --view-elevation 0" + rest, "nan"},
      {"--altitude 0 --sun-elevation 0 --view-elevation 0 --backend opengl" + rest, "opengl"},
      {"--altitude 0 --sun-elevation 0 --view-elevation 0 --preset nowhere" + rest, "nowhere"},
      {"--altitude 0 --sun-elevation 0 --view-elevation 0", "--view-azimuth"},
  };
  for (const auto& [args, named] : cases) {
    const ShellRun run = planetSky(args);
    EXPECT_EQ(run.exitCode, 2) << args << "\n" << run.err;
    EXPECT_EQ(run.out, "") << args;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << "\n" << run.err;
    EXPECT_NE(run.err.find(named), std::string::npos) << args << "\n" << run.err;
  }
}

}  // namespace
}  // namespace planet::test

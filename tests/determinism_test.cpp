// Determinism across processes: the same preset and seed give byte-identical images and
// heights from two separate runs of `planet` (nothing depends on addresses, time, thread
// scheduling or uninitialised memory), and a different seed gives a different planet.
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image_file.h"
#include "core/subprocess.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

fs::path tempDir() { return planet::test::processTempDir("determinism_test"); }
std::string readBytes(const fs::path& path) { return planet::test::readFileBytes(path); }

planet::ProcessResult planetRun(std::vector<std::string> args) {
  args.insert(args.begin(), PLANET_EXE);
  return planet::runProcess(args, "");
}

bool noDevice(const planet::ProcessResult& run) { return run.err.find("no Vulkan") != std::string::npos; }

// A view where the seed decides what is seen: from 9 km over land that seed 3 puts at 2.3 km
// above the sea and seed 4 3 km under the ocean.
std::vector<std::string> renderArgs(const fs::path& out, const std::string& seed) {
  return {"render", "--size", "96x54", "--camera", "38.75,130.75,9000,45,-20", "--seed", seed, "--out", out.string()};
}

TEST(Determinism, TwoProcessesRenderTheSameBytesAndAnotherSeedAnotherPlanet) {
  const fs::path a = tempDir() / "a.png", b = tempDir() / "b.png", c = tempDir() / "c.png";
  const planet::ProcessResult first = planetRun(renderArgs(a, "3"));
  if (noDevice(first)) GTEST_SKIP() << first.err;
  ASSERT_EQ(first.exitCode, 0) << first.err;
  const planet::ProcessResult second = planetRun(renderArgs(b, "3"));
  ASSERT_EQ(second.exitCode, 0) << second.err;
  const planet::ProcessResult other = planetRun(renderArgs(c, "4"));
  ASSERT_EQ(other.exitCode, 0) << other.err;
  const std::string bytesA = readBytes(a), bytesB = readBytes(b), bytesC = readBytes(c);
  ASSERT_GT(bytesA.size(), 1000u);
  EXPECT_TRUE(bytesA == bytesB) << "two runs with seed 3 wrote different images: " << a << " " << b;
  // Another planet, not a few pixels of noise: most of the picture below the horizon changes.
  const planet::Rgba8Image imageA = planet::readPng(a.string()), imageC = planet::readPng(c.string());
  ASSERT_EQ(imageA.pixels.size(), imageC.pixels.size());
  size_t changed = 0;
  for (size_t i = 0; i < imageA.pixels.size(); i += 4)
    changed += std::abs(int(imageA.pixels[i]) - int(imageC.pixels[i])) + std::abs(int(imageA.pixels[i + 1]) - int(imageC.pixels[i + 1])) +
                   std::abs(int(imageA.pixels[i + 2]) - int(imageC.pixels[i + 2])) > 12;
  EXPECT_GT(changed, imageA.pixels.size() / 4 / 10) << "seed 4 changed only " << changed << " pixels: " << c;
}

// The earth preset with every terrain layer's seed moved by `shift`: another planet of the
// same kind, through a preset file as a user would write one.
fs::path shiftedEarth(int shift) {
  std::ifstream in(std::string(PLANET_SOURCE_DIR) + "/engine/planet/presets/earth.toml");
  const std::string text(std::istreambuf_iterator<char>(in), {});
  const std::regex seedLine(R"(seed = (\d+))");
  std::string out;
  std::sregex_iterator it(text.begin(), text.end(), seedLine, std::regex_constants::match_default), end;
  size_t last = 0;
  for (; it != end; ++it) {
    out += text.substr(last, size_t(it->position()) - last);
    out += "seed = " + std::to_string(std::stoi((*it)[1].str()) + shift);
    last = size_t(it->position() + it->length());
  }
  out += text.substr(last);
  const fs::path path = tempDir() / ("earth_shift" + std::to_string(shift) + ".toml");
  std::ofstream(path) << out;
  return path;
}

std::vector<std::string> heightArgs(const std::string& preset, const std::string& backend) {
  return {"height", "--preset", preset, "--at", "12.5,-40.25", "--bearing", "30", "--step-m", "250",
          "--count", "400", "--backend", backend};
}

TEST(Determinism, TwoProcessesPrintTheSameHeightsAndAnotherSeedOtherHeights) {
  const fs::path shifted = shiftedEarth(11);
  for (const char* backend : {"cpu", "gpu"}) {
    const planet::ProcessResult first = planetRun(heightArgs("earth", backend));
    if (backend == std::string("gpu") && noDevice(first)) GTEST_SKIP() << first.err;
    ASSERT_EQ(first.exitCode, 0) << first.err;
    const planet::ProcessResult second = planetRun(heightArgs("earth", backend));
    ASSERT_EQ(second.exitCode, 0) << second.err;
    EXPECT_EQ(first.out, second.out) << backend << ": two runs printed different heights";
    EXPECT_EQ(std::count(first.out.begin(), first.out.end(), '\n'), 400) << first.out;

    const planet::ProcessResult other = planetRun(heightArgs(shifted.string(), backend));
    ASSERT_EQ(other.exitCode, 0) << other.err;
    // Different seeds: different terrain almost everywhere, not just somewhere.
    std::istringstream x(first.out), y(other.out);
    int differ = 0, total = 0;
    for (double hx, hy; x >> hx && y >> hy; ++total) differ += hx != hy;
    EXPECT_EQ(total, 400);
    EXPECT_GT(differ, 390) << backend << ": the shifted seeds changed only " << differ << " of 400 heights";
  }
}

}  // namespace

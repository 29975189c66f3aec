// `planet render --path FILE --out VIDEO` as a user runs it (issue 23, point 5): a video with the
// frames and size asked for, the same frames every run, the path's first frame as the still of
// the same camera, scene flights, and every bad input (or a missing ffmpeg) as one line with no
// file left behind. The videos are small (96x54, a few frames): seconds on lavapipe.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image_file.h"
#include "test_support.h"

namespace planet::test {
namespace {

std::filesystem::path tempDir() { return processTempDir("video_cli_test"); }

ShellRun planet(const std::string& args, const std::string& environment = "") {
  return runShell(environment + PLANET_EXE, args, "", tempDir());
}

// ffmpeg and ffprobe themselves (tools/setup.sh installs them), run through the shell.
ShellRun tool(const std::string& command) { return runShell(command, "", "", tempDir() / "tool"); }

bool haveFfmpeg() { return std::system("ffmpeg -version > /dev/null 2>&1 && ffprobe -version > /dev/null 2>&1") == 0; }

bool noDevice(const ShellRun& run) { return run.err.find("no Vulkan") != std::string::npos; }

// A descent straight down over the default render's point (20 N, 30 W), from 2e7 m to 1e6 m
// above the ground in 10 s: its first frame is the camera of a plain `planet render`.
std::filesystem::path writeDescent() {
  const std::filesystem::path path = tempDir() / "descent.path";
  std::ofstream(path) << "# time_s lat lon height_m heading pitch\n0 20 -30 2e7 0 -90\n10 20 -30 1e6 0 -90\n";
  return path;
}

struct Probe {
  std::string codec;
  int width = 0, height = 0, frames = 0;
};

// What ffprobe reads from the file: the first video stream's codec and size, and its frames
// counted by decoding them all.
Probe probe(const std::filesystem::path& video) {
  const ShellRun run = tool(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=codec_name,width,height,nb_read_frames -of json '" +
      video.string() + "'");
  EXPECT_EQ(run.exitCode, 0) << run.err;
  Probe p;
  const nlohmann::json j = nlohmann::json::parse(run.out, nullptr, false);
  if (j.is_discarded() || !j.contains("streams") || j["streams"].empty()) {
    ADD_FAILURE() << "ffprobe printed no stream: " << run.out;
    return p;
  }
  const nlohmann::json& s = j["streams"][0];
  p.codec = s.value("codec_name", "");
  p.width = s.value("width", 0);
  p.height = s.value("height", 0);
  p.frames = std::stoi(s.value("nb_read_frames", std::string("0")));
  return p;
}

// One line per decoded frame: its number, timing and the MD5 of its pixels (ffmpeg's framemd5).
std::vector<std::string> frameMd5s(const std::filesystem::path& video) {
  const ShellRun run = tool("ffmpeg -v error -i '" + video.string() + "' -f framemd5 -");
  EXPECT_EQ(run.exitCode, 0) << run.err;
  std::vector<std::string> frames;
  std::istringstream lines(run.out);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && line[0] != '#') frames.push_back(line);
  return frames;
}

// The image at half size, each pixel the mean of a 2x2 block: what 4:2:0 chroma keeps of colour.
Rgba8Image halved(const Rgba8Image& image) {
  Rgba8Image half;
  half.width = image.width / 2;
  half.height = image.height / 2;
  half.pixels.resize(size_t(half.width) * half.height * 4);
  for (uint32_t y = 0; y < half.height; ++y)
    for (uint32_t x = 0; x < half.width; ++x)
      for (uint32_t c = 0; c < 4; ++c) {
        uint32_t sum = 0;
        for (uint32_t dy = 0; dy < 2; ++dy)
          for (uint32_t dx = 0; dx < 2; ++dx) sum += image.pixels[((2 * y + dy) * image.width + 2 * x + dx) * 4 + c];
        half.pixels[(size_t(y) * half.width + x) * 4 + c] = uint8_t((sum + 2) / 4);
      }
  return half;
}

class VideoCli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::filesystem::create_directories(tempDir() / "tool");
    if (!haveFfmpeg()) GTEST_SKIP() << "ffmpeg and ffprobe are not installed (tools/setup.sh installs them)";
  }
};

TEST_F(VideoCli, AFlightIsAnMp4OfTheFramesAskedAndTheSameEveryRun) {
  const std::filesystem::path path = writeDescent();
  std::vector<std::string> md5s[2];
  std::string bytes[2];
  for (int run = 0; run < 2; ++run) {
    const std::filesystem::path out = tempDir() / ("flight" + std::to_string(run) + ".mp4");
    const ShellRun r = planet("render --path " + path.string() + " --frames 6 --size 96x54 --out " + out.string());
    if (noDevice(r)) GTEST_SKIP() << "no Vulkan device";
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("wrote " + out.string() + " (6 frames, 96x54 at 30 fps: 0.20 s of video"), std::string::npos)
        << r.out;
    const Probe p = probe(out);
    EXPECT_EQ(p.codec, "h264");
    EXPECT_EQ(p.width, 96);
    EXPECT_EQ(p.height, 54);
    EXPECT_EQ(p.frames, 6);
    md5s[run] = frameMd5s(out);
    bytes[run] = readFileBytes(out);
    // Nothing but the video: no temporary twin left beside it.
    size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(tempDir()))
      files += entry.path().filename().string().starts_with("flight" + std::to_string(run)) ? 1 : 0;
    EXPECT_EQ(files, 1u);
  }
  ASSERT_EQ(md5s[0].size(), 6u);
  EXPECT_EQ(md5s[0], md5s[1]) << "the decoded frames differ between two runs";
  EXPECT_TRUE(bytes[0] == bytes[1]) << "the files differ between two runs (bit-exact encoding)";
  // A descent: the frames change from first to last (not one picture repeated).
  EXPECT_NE(md5s[0].front().substr(md5s[0].front().rfind(',')), md5s[0].back().substr(md5s[0].back().rfind(',')));
}

// The video's first frame is the path's first key: the camera of a plain `planet render` (20 N,
// 30 W, 2e7 m, looking down), the sun placed the same way. At 96x54 the planet's detail is near
// pixel size and 4:2:0 chroma (one colour per 2x2 block) costs most of the error: compared at
// half size, where that averages out, H.264 at crf 20 keeps the frame at about 35 dB (measured);
// a wrong camera, sun or colour matrix falls far below the 32 dB asked.
TEST_F(VideoCli, TheFirstFrameIsTheStillOfTheSameCamera) {
  const std::filesystem::path path = writeDescent();
  const std::filesystem::path video = tempDir() / "first.mp4", still = tempDir() / "still.png",
                              decoded = tempDir() / "decoded.png";
  const ShellRun r = planet("render --path " + path.string() + " --frames 2 --size 96x54 --out " + video.string());
  if (noDevice(r)) GTEST_SKIP() << "no Vulkan device";
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const ShellRun s = planet("render --size 96x54 --out " + still.string());
  ASSERT_EQ(s.exitCode, 0) << s.err;
  const ShellRun d = tool("ffmpeg -v error -i '" + video.string() + "' -frames:v 1 '" + decoded.string() + "'");
  ASSERT_EQ(d.exitCode, 0) << d.err;
  const double psnr = psnrRgb(halved(readPng(still.string())), halved(readPng(decoded.string())));
  EXPECT_GT(psnr, 32.0);
}

// A flight over the built-in system's moon, as VP9 in WebM (the GIF and WebM encoders
// themselves: video_file_test.cpp): it names its body, and the frames and size are those asked.
TEST_F(VideoCli, ASceneFlightOverAnotherBodyIsAWebm) {
  const std::filesystem::path path = tempDir() / "moon.path";
  std::ofstream(path) << "0 10 20 5e5 0 -90\n4 10 20 1e4 90 -30\n";
  const std::filesystem::path out = tempDir() / "moon.webm";
  const ShellRun r = planet("render --scene system --path-body Moon --path " + path.string() +
                            " --frames 3 --size 64x36 --time 66500 --out " + out.string());
  if (noDevice(r)) GTEST_SKIP() << "no Vulkan device";
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("the path flies over Moon"), std::string::npos) << r.out;
  const Probe p = probe(out);
  EXPECT_EQ(p.codec, "vp9");
  EXPECT_EQ(p.width, 64);
  EXPECT_EQ(p.height, 36);
  EXPECT_EQ(p.frames, 3);
}

// Without ffmpeg the command says so in one line before any rendering, and writes nothing.
TEST_F(VideoCli, AMissingFfmpegIsOneLineBeforeAnyWork) {
  const std::filesystem::path path = writeDescent();
  const std::filesystem::path out = tempDir() / "none.mp4";
  for (const std::string environment : {"PATH=/nonexistent ", "PLANET_FFMPEG=/nonexistent/ffmpeg "}) {
    const ShellRun r = planet("render --path " + path.string() + " --out " + out.string(), environment);
    EXPECT_EQ(r.exitCode, 1) << environment;
    EXPECT_NE(r.err.find("writing a .mp4 video needs the ffmpeg program"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("install ffmpeg"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

// Every bad input is one line naming the value, exit code 2, and no file (nor a temporary one).
TEST_F(VideoCli, BadInputIsOneLineNamingTheValueAndLeavesNoFile) {
  const std::filesystem::path path = writeDescent();
  const std::filesystem::path bad = tempDir() / "bad.path";
  std::ofstream(bad) << "0 20 -30 2e7 0 -90\n0 20 -30 1e6 0 -90\n";
  const std::string p = path.string(), out = (tempDir() / "v.mp4").string();
  const struct {
    std::string args, message;
  } cases[] = {
      {"--path " + p + " --frames 0 --out " + out, "--frames must be in 1..108000, got 0"},
      {"--path " + p + " --frames -3 --out " + out, "--frames must be in 1..108000, got -3"},
      {"--path " + p + " --fps 0 --out " + out, "--fps must be in 1..240, got 0"},
      {"--path " + p + " --out " + (tempDir() / "v.avi").string(), "--out with --path must end in .mp4, .webm or .gif"},
      {"--path " + p + " --out " + (tempDir() / "v.png").string(), "--out with --path must end in .mp4, .webm or .gif"},
      {"--path " + p + " --size 95x54 --out " + out, "--size 95x54: a .mp4 video needs an even width and height"},
      {"--path " + bad.string() + " --out " + out, "bad.path"},
      {"--path " + (tempDir() / "missing.path").string() + " --out " + out, "cannot read"},
      {"--path '' --out " + out, "--path must name a file"},
      {"--path " + p + " --camera 1,2,3 --out " + out, "--camera and --path exclude each other"},
      {"--path " + p + " --path-body Moon --out " + out, "--path-body needs --scene"},
      {"--scene system --path " + p + " --path-body Pluto --out " + out, "Pluto"},
      {"--frames 5 --out " + out, "--frames needs --path"},
      {"--out " + out, "names a video: give the camera path to fly with --path FILE"},
  };
  for (const auto& c : cases) {
    const ShellRun r = planet("render " + c.args);
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << "\n" << r.err;
    for (const auto& entry : std::filesystem::directory_iterator(tempDir()))
      EXPECT_FALSE(entry.path().filename().string().starts_with("v.")) << c.args << ": " << entry.path();
  }
}

}  // namespace
}  // namespace planet::test

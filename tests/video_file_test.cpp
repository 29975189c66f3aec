// Video files (export/video_file.h) without a GPU: formats by extension, colours that survive
// the encoder's YUV conversion, and an ffmpeg that fails or vanishes midway leaving no file.
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/image_file.h"
#include "core/subprocess.h"
#include "export/video_file.h"
#include "test_support.h"

namespace planet {
namespace {

bool haveFfmpeg() { return std::system("ffmpeg -version > /dev/null 2>&1") == 0; }

Rgba8Image solid(uint32_t width, uint32_t height, uint8_t r, uint8_t g, uint8_t b) {
  Rgba8Image image;
  image.width = width;
  image.height = height;
  for (uint32_t i = 0; i < width * height; ++i) image.pixels.insert(image.pixels.end(), {r, g, b, 255});
  return image;
}

// Nothing in `dir` but `keep`: no output, no temporary twin.
size_t filesIn(const std::filesystem::path& dir) {
  size_t n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) n += entry.is_regular_file() ? 1 : 0;
  return n;
}

TEST(VideoFile, TheFormatFollowsTheExtension) {
  EXPECT_EQ(videoFormatOf("flight.mp4"), VideoFormat::Mp4);
  EXPECT_EQ(videoFormatOf("a/b/FLIGHT.WebM"), VideoFormat::Webm);
  EXPECT_EQ(videoFormatOf("x.gif"), VideoFormat::Gif);
  for (const char* other : {"flight.png", "flight", "mp4", "dir.mp4/flight", "flight.mp4.tmp", ".mp4x"})
    EXPECT_EQ(videoFormatOf(other), std::nullopt) << other;
  EXPECT_TRUE(videoNeedsEvenSize(VideoFormat::Mp4));
  EXPECT_FALSE(videoNeedsEvenSize(VideoFormat::Gif));
}

// Flat colours through H.264 and VP9 at 4:2:0 and back: the BT.709 matrix the encoder is told to
// use and the one the stream declares agree, so a decoder gives the colour back within the
// rounding of 8-bit limited-range YUV (a BT.601 decode of a BT.709 stream moves this orange by
// 10 to 14 levels).
TEST(VideoFile, FlatColoursComeBackFromTheVideo) {
  if (!haveFfmpeg()) GTEST_SKIP() << "ffmpeg is not installed (tools/setup.sh installs it)";
  test::TempDir dir("video_file");
  for (VideoFormat format : {VideoFormat::Mp4, VideoFormat::Webm, VideoFormat::Gif}) {
    const std::string path = (dir / (std::string("flat") + videoExtension(format))).string();
    VideoWriter video(findFfmpeg(format), path, {32, 16, 10.0, format});
    for (int i = 0; i < 3; ++i) video.addFrame(solid(32, 16, 230, 120, 40));
    video.finish();
    EXPECT_EQ(video.frames(), 3u);
    const std::string png = (dir / "frame.png").string();
    const ProcessResult decode = runProcess({"ffmpeg", "-v", "error", "-y", "-i", path, "-frames:v", "1", png}, "");
    ASSERT_EQ(decode.exitCode, 0) << decode.err;
    const Rgba8Image frame = readPng(png);
    const uint8_t* p = &frame.pixels[(8 * 32 + 16) * 4];
    EXPECT_NEAR(p[0], 230, 3) << videoExtension(format);
    EXPECT_NEAR(p[1], 120, 3) << videoExtension(format);
    EXPECT_NEAR(p[2], 40, 3) << videoExtension(format);
  }
}

// An "ffmpeg" that passes the encoder check, then reads one frame's worth and fails the way a
// full disk would: the error names the file and repeats ffmpeg's last line; nothing is left.
TEST(VideoFile, AnEncoderThatFailsLeavesNoFileAndSaysWhy) {
  test::TempDir dir("video_file");
  const std::filesystem::path fake = dir / "ffmpeg";
  std::ofstream(fake) << "#!/bin/sh\n"
                         "case \"$*\" in *-encoders*) echo ' V....D libx264 H.264'; exit 0;; esac\n"
                         "head -c 2048 > /dev/null\n"
                         "echo 'first line' >&2\n"
                         "echo 'Error writing trailer: No space left on device' >&2\n"
                         "exit 1\n";
  ::chmod(fake.c_str(), 0755);
  ::setenv("PLANET_FFMPEG", fake.c_str(), 1);
  const std::string ffmpeg = findFfmpeg(VideoFormat::Mp4);
  ::unsetenv("PLANET_FFMPEG");
  EXPECT_EQ(ffmpeg, fake.string());
  const std::string path = (dir / "out.mp4").string();
  const std::string error = test::errorOf([&] {
    VideoWriter video(ffmpeg, path, {64, 64, 30.0, VideoFormat::Mp4});
    for (int i = 0; i < 100; ++i) video.addFrame(solid(64, 64, 1, 2, 3));  // it stops reading after 2 kB
    video.finish();
  });
  EXPECT_NE(error.find("cannot write '" + path + "'"), std::string::npos) << error;
  EXPECT_NE(error.find("No space left on device"), std::string::npos) << error;
  EXPECT_EQ(filesIn(dir.path()), 1u) << "only the fake ffmpeg should remain";

  // An encoder without the format's encoder is refused before any frame.
  ::setenv("PLANET_FFMPEG", fake.c_str(), 1);
  const std::string noVp9 = test::errorOf([] { findFfmpeg(VideoFormat::Webm); });
  ::unsetenv("PLANET_FFMPEG");
  EXPECT_NE(noVp9.find("libvpx-vp9"), std::string::npos) << noVp9;
}

TEST(VideoFile, BadSettingsAndFramesAreErrors) {
  test::TempDir dir("video_file");
  const std::string path = (dir / "v.mp4").string();
  EXPECT_NE(test::errorOf([&] {
              VideoWriter("ffmpeg", path, {33, 16, 30.0, VideoFormat::Mp4});
            }).find("needs an even width and height"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] {
              VideoWriter("ffmpeg", path, {32, 16, 0.5, VideoFormat::Mp4});
            }).find("frame rate must be in 1..240, got 0.5"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] {
              VideoWriter("/nonexistent/ffmpeg", path, {32, 16, 30.0, VideoFormat::Gif});
            }).find("cannot run '/nonexistent/ffmpeg'"),
            std::string::npos);
  if (haveFfmpeg()) {
    const std::string wrongSize = test::errorOf([&] {
      VideoWriter video("ffmpeg", path, {32, 16, 30.0, VideoFormat::Gif});
      video.addFrame(solid(16, 16, 0, 0, 0));
    });
    EXPECT_NE(wrongSize.find("frame 1 is 16x16"), std::string::npos) << wrongSize;
    const std::string empty = test::errorOf([&] {
      VideoWriter("ffmpeg", path, {32, 16, 30.0, VideoFormat::Gif}).finish();
    });
    EXPECT_NE(empty.find("no frames"), std::string::npos) << empty;
  }
  EXPECT_EQ(filesIn(dir.path()), 0u);
}

}  // namespace
}  // namespace planet

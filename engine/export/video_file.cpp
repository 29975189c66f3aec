#include "export/video_file.h"

#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "core/subprocess.h"

namespace planet {
namespace {

constexpr const char* kInstallHint = "install ffmpeg (tools/setup.sh does) or set PLANET_FFMPEG to one";

// The encoder each format needs, as `ffmpeg -encoders` names it.
const char* encoderOf(VideoFormat format) {
  switch (format) {
    case VideoFormat::Mp4: return "libx264";
    case VideoFormat::Webm: return "libvpx-vp9";
    case VideoFormat::Gif: return "gif";
  }
  return "";
}

// The last non-empty line of a program's error output (ffmpeg ends with the reason it stopped).
std::string lastLine(const std::string& text) {
  const size_t end = text.find_last_not_of(" \n\r\t");
  if (end == std::string::npos) return "no message";
  const size_t newline = text.find_last_of("\r\n", end);
  const size_t start = newline == std::string::npos ? 0 : newline + 1;
  return printable(text.substr(start, end - start + 1));
}

// Everything after the input: how each format is encoded. The frames arrive as sRGB-encoded
// RGBA; the 4:2:0 formats convert with the BT.709 matrix and say so (and that the transfer is
// sRGB's) in the stream, so that players do not guess another matrix and shift the colours.
std::vector<std::string> encoderArguments(VideoFormat format) {
  const std::vector<std::string> yuv = {"-vf",
                                        "scale=out_color_matrix=bt709:out_range=tv,format=yuv420p",
                                        "-colorspace",
                                        "bt709",
                                        "-color_primaries",
                                        "bt709",
                                        "-color_trc",
                                        "iec61966-2-1",
                                        "-color_range",
                                        "tv"};
  std::vector<std::string> args;
  switch (format) {
    case VideoFormat::Mp4:
      // crf 20: visually clean flights at a few hundred kB per second of 960x540.
      args = {"-c:v", "libx264", "-preset", "medium", "-crf", "20"};
      args.insert(args.end(), yuv.begin(), yuv.end());
      args.insert(args.end(), {"-movflags", "+faststart", "-f", "mp4"});
      break;
    case VideoFormat::Webm:
      // Constant quality (crf with no bitrate cap); row threading is bit-exact in libvpx.
      args = {"-c:v", "libvpx-vp9", "-crf", "32", "-b:v", "0", "-deadline", "good", "-cpu-used", "2", "-row-mt", "1"};
      args.insert(args.end(), yuv.begin(), yuv.end());
      args.insert(args.end(), {"-f", "webm"});
      break;
    case VideoFormat::Gif:
      // One palette for the whole clip (palettegen sees every frame first), so colours do not
      // flicker from frame to frame; ordered (Bayer) dithering compresses far better than error
      // diffusion and does not crawl between frames. Alpha is dropped: no transparent pixels.
      args = {"-vf",
              "format=rgb24,split[a][b];[a]palettegen=reserve_transparent=0[p];[b][p]paletteuse=dither=bayer:"
              "bayer_scale=3",
              "-loop",
              "0",
              "-f",
              "gif"};
      break;
  }
  return args;
}

}  // namespace

std::optional<VideoFormat> videoFormatOf(std::string_view path) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string_view::npos || path.find('/', dot) != std::string_view::npos) return std::nullopt;
  std::string extension(path.substr(dot));
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (VideoFormat format : {VideoFormat::Mp4, VideoFormat::Webm, VideoFormat::Gif})
    if (extension == videoExtension(format)) return format;
  return std::nullopt;
}

const char* videoExtension(VideoFormat format) {
  switch (format) {
    case VideoFormat::Mp4: return ".mp4";
    case VideoFormat::Webm: return ".webm";
    case VideoFormat::Gif: return ".gif";
  }
  return "";
}

bool videoNeedsEvenSize(VideoFormat format) { return format != VideoFormat::Gif; }

std::string findFfmpeg(VideoFormat format) {
  const char* chosen = std::getenv("PLANET_FFMPEG");
  const bool fromEnvironment = chosen && *chosen;
  const std::string ffmpeg = fromEnvironment ? chosen : "ffmpeg";
  const std::string what = fmt::format("writing a {} video needs the ffmpeg program", videoExtension(format));
  const ProcessResult probe = runProcess({ffmpeg, "-hide_banner", "-encoders"}, "");
  if (!probe.started)
    throw Error(fmt::format("{}: {} was not found{}; {}", what, quotedPath(ffmpeg),
                            fromEnvironment ? " (PLANET_FFMPEG)" : " in PATH", kInstallHint));
  if (probe.exitCode != 0)
    throw Error(fmt::format("{}: {} -encoders failed (exit {}): {}", what, quotedPath(ffmpeg), probe.exitCode,
                            lastLine(probe.err)));
  const std::string encoder = encoderOf(format);
  if (probe.out.find(" " + encoder + " ") == std::string::npos)
    throw Error(
        fmt::format("{} with the {} encoder; {} has none: {}", what, encoder, quotedPath(ffmpeg), kInstallHint));
  return ffmpeg;
}

VideoWriter::VideoWriter(const std::string& ffmpeg, const std::string& path, const VideoSettings& settings)
    : path_(path), temporary_(path + ".tmp-" + std::to_string(::getpid())), settings_(settings) {
  if (settings.width == 0 || settings.height == 0)
    throw Error(fmt::format("video size {}x{} is empty", settings.width, settings.height));
  if (videoNeedsEvenSize(settings.format) && (settings.width % 2 || settings.height % 2))
    throw Error(fmt::format("a {} video needs an even width and height (4:2:0 chroma), got {}x{}",
                            videoExtension(settings.format), settings.width, settings.height));
  if (!(settings.fps >= kVideoMinFps && settings.fps <= kVideoMaxFps))
    throw Error(fmt::format("video frame rate must be in {}..{}, got {}", kVideoMinFps, kVideoMaxFps, settings.fps));
  std::vector<std::string> argv = {ffmpeg, "-hide_banner", "-nostats", "-loglevel", "error", "-y",
                                   // The input: raw frames on standard input.
                                   "-f", "rawvideo", "-pixel_format", "rgba", "-video_size",
                                   fmt::format("{}x{}", settings.width, settings.height), "-framerate",
                                   fmt::format("{}", settings.fps), "-i", "pipe:0",
                                   // The same frames give the same bytes: no version strings or dates.
                                   "-map_metadata", "-1", "-fflags", "+bitexact", "-flags:v", "+bitexact"};
  const std::vector<std::string> encoder = encoderArguments(settings.format);
  argv.insert(argv.end(), encoder.begin(), encoder.end());
  argv.push_back(temporary_);
  ffmpeg_ = std::make_unique<FedProcess>(argv);
  if (!ffmpeg_->started()) {
    ffmpeg_.reset();
    throw Error(fmt::format("cannot write {}: cannot run {}", quotedPath(path_), quotedPath(ffmpeg)));
  }
}

VideoWriter::~VideoWriter() {
  if (finished_) return;
  ffmpeg_.reset();  // kills it if it still runs
  std::remove(temporary_.c_str());
}

void VideoWriter::fail(const std::string& reason) {
  std::string errors = ffmpeg_ ? ffmpeg_->errorOutput() : std::string();
  ffmpeg_.reset();
  std::remove(temporary_.c_str());
  finished_ = true;  // nothing left to clean up
  throw Error(
      fmt::format("cannot write {}: {}{}", quotedPath(path_), reason, errors.empty() ? "" : ": " + lastLine(errors)));
}

void VideoWriter::addFrame(const Rgba8Image& frame) {
  if (finished_) throw Error(fmt::format("cannot write {}: a frame after the video was finished", quotedPath(path_)));
  if (frame.width != settings_.width || frame.height != settings_.height ||
      frame.pixels.size() != size_t(frame.width) * frame.height * 4)
    fail(fmt::format("frame {} is {}x{} ({} bytes), the video {}x{}", frames_ + 1, frame.width, frame.height,
                     frame.pixels.size(), settings_.width, settings_.height));
  const std::string_view bytes(reinterpret_cast<const char*>(frame.pixels.data()), frame.pixels.size());
  if (!ffmpeg_->write(bytes)) {
    const int status = ffmpeg_->finish();
    fail(fmt::format("ffmpeg stopped at frame {} (exit {})", frames_ + 1, status));
  }
  ++frames_;
}

void VideoWriter::finish() {
  if (finished_) throw Error(fmt::format("cannot write {}: the video was finished already", quotedPath(path_)));
  if (frames_ == 0) fail("no frames");
  const int status = ffmpeg_->finish();
  if (status != 0) fail(fmt::format("ffmpeg failed (exit {})", status));
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) fail(std::strerror(errno));
  finished_ = true;
}

}  // namespace planet

// Video files of rendered frames (issue 23, point 5: flights as video). The frames go to the
// ffmpeg program as raw RGBA through a pipe while they are rendered, so a long flight never
// holds more than one frame in memory; ffmpeg writes a temporary twin of the output, renamed over
// it only when the encoder finished cleanly (as core/file.h does for every other output).
//
// Formats, chosen by the output's extension: .mp4 (H.264, libx264, 4:2:0), .webm (VP9, libvpx,
// 4:2:0) and .gif (one 256-colour palette for the whole clip, ordered dithering: small enough for
// a README). The encoders run with ffmpeg's bit-exact flags and no metadata, so that the same
// frames give the same file.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "core/image_file.h"

namespace planet {

class FedProcess;

enum class VideoFormat { Mp4, Webm, Gif };

inline constexpr double kVideoMinFps = 1.0;
inline constexpr double kVideoMaxFps = 240.0;

// The format `path` asks for by its extension (case-insensitive), or nullopt.
std::optional<VideoFormat> videoFormatOf(std::string_view path);
// ".mp4", ".webm", ".gif".
const char* videoExtension(VideoFormat format);
// 4:2:0 chroma (mp4, webm) needs an even width and height; gif takes any size.
bool videoNeedsEvenSize(VideoFormat format);

// The ffmpeg to run: $PLANET_FFMPEG, else `ffmpeg` from PATH, checked to start and to have the
// encoder `format` needs. Throws planet::Error (one line, naming what was tried and how to
// install it) otherwise. Call it before any rendering: a missing encoder is found at once.
std::string findFfmpeg(VideoFormat format);

struct VideoSettings {
  uint32_t width = 0, height = 0;
  double fps = 30.0;
  VideoFormat format = VideoFormat::Mp4;
};

// One video being encoded. Frames are added in order; finish() completes the file. Destroyed
// without a successful finish() (an error, an exception while rendering), it stops ffmpeg and
// removes the temporary file: the output is then left as it was before.
class VideoWriter {
 public:
  // Starts `ffmpeg` (findFfmpeg's answer) writing the temporary twin of `path`. Throws
  // planet::Error for bad settings (a size or rate out of range, an odd size for a 4:2:0
  // format) or when ffmpeg cannot be started.
  VideoWriter(const std::string& ffmpeg, const std::string& path, const VideoSettings& settings);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // Throws planet::Error for a frame of another size, or when ffmpeg stopped reading (with the
  // last line it wrote to its error output).
  void addFrame(const Rgba8Image& frame);
  // Closes ffmpeg's input, waits for it and renames the file into place. Throws planet::Error
  // (nothing left behind) when there are no frames, ffmpeg failed, or the rename failed.
  void finish();
  uint32_t frames() const { return frames_; }

 private:
  // Stops ffmpeg and removes the temporary file; the error names `path_` and `reason`.
  [[noreturn]] void fail(const std::string& reason);

  std::string path_, temporary_;
  VideoSettings settings_;
  std::unique_ptr<FedProcess> ffmpeg_;
  uint32_t frames_ = 0;
  bool finished_ = false;
};

}  // namespace planet

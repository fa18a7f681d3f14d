// Video files from rendered frames, encoded by piping raw 8-bit sRGB frames to Debian's
// ffmpeg: H.264 in MP4 (yuv420p, tagged BT.709), VP9 in WebM, or an animated GIF.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

enum class VideoFormat { kMp4, kWebm, kGif };

// The format a video file's name asks for (.mp4, .webm, .gif, any case), if any.
std::optional<VideoFormat> video_format_of(const std::filesystem::path& file);

// The full path of `program` on PATH; InputError naming it (and its Debian package) if absent.
std::string require_program(const std::string& program, const std::string& needed_for);

// Checks everything a video needs before any frame is rendered: the name's format, the
// frame size (even, for the yuv420p of MP4 and WebM), the rate and quality, the target and
// ffmpeg. Throws InputError naming `option`.
void check_video(const std::string& option, const std::filesystem::path& file, int width,
                 int height, double fps, int crf);

// One video being written: frames go to ffmpeg as they come; the file appears under its name
// only when finish() succeeds (a failure leaves the previous file, if any, untouched).
class VideoWriter {
 public:
  VideoWriter(const std::filesystem::path& file, int width, int height, double fps, int crf);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // A display image (tone-mapped) of the video's size, as its PNG would store it.
  void add(const Image& display);
  void finish();

 private:
  void close_pipe();
  std::filesystem::path file_, temp_;
  int width_, height_;
  int pipe_ = -1;
  pid_t child_ = -1;
  bool finished_ = false;
};

}  // namespace lightcone

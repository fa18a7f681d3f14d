// Video files from rendered frames, encoded by piping raw 8-bit sRGB frames to Debian's
// ffmpeg: H.264 in MP4 (yuv420p, tagged BT.709), VP9 in WebM, or an animated GIF.
//
// A video is whole or absent: ffmpeg's exit status is not trusted alone (it can report
// success after "No space left on device"), so every finished file is read back with ffprobe
// and must hold every frame sent before it is renamed into place. ffmpeg and ffprobe run under
// a watchdog: no progress for kVideoWatchdogSeconds (or LIGHTCONE_VIDEO_WATCHDOG_SECONDS) is a
// failure.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

enum class VideoFormat { kMp4, kWebm, kGif };

inline constexpr double kVideoWatchdogSeconds = 30;

// The format a video file's name asks for (.mp4, .webm, .gif, any case), if any.
std::optional<VideoFormat> video_format_of(const std::filesystem::path& file);

// The full path of `program` on PATH; InputError naming it (and its Debian package) if absent.
std::string require_program(const std::string& program, const std::string& needed_for);

// Checks everything a video needs before any frame is rendered: the name's format, the frame
// size (even, for the yuv420p of MP4 and WebM), the rate (0.01 to 1000 frames a second; a GIF,
// whose delays are whole hundredths of a second, 0.01 to 50), the quality, the target, ffmpeg
// and ffprobe; then encodes one black frame with the same settings beside the target and reads
// it back, so that whatever ffmpeg would refuse is refused now. Throws InputError naming
// `option`.
void check_video(const std::string& option, const std::filesystem::path& file, int width,
                 int height, double fps, int crf, int gif_width);

// One video being written: frames go to ffmpeg as they come; the file appears under its name
// only when finish() has read back every frame from it (a failure, or destruction before
// finish(), leaves the previous file, if any, untouched and removes the temporary one).
class VideoWriter {
 public:
  // `crf`: MP4 and WebM quality; `gif_width`: a GIF's frames are scaled down to this width
  // when wider (the height in proportion), so that slides' GIFs stay small.
  VideoWriter(const std::filesystem::path& file, int width, int height, double fps, int crf,
              int gif_width);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // A display image (tone-mapped) of the video's size, as its PNG would store it. Throws when
  // ffmpeg stops taking frames, takes none for the watchdog's time, or a stop signal arrives.
  void add(const Image& display);
  // Ends the stream, waits for ffmpeg, checks the file and renames it into place.
  void finish();

 private:
  // Ends the stream and checks the temporary file: ffmpeg's status, then what ffprobe reads.
  void complete();
  void stop_child();
  std::filesystem::path file_, temp_;
  int width_, height_;
  double fps_;
  long long frames_ = 0;
  int pipe_ = -1;
  pid_t child_ = -1;
  bool finished_ = false;
  friend void check_video(const std::string&, const std::filesystem::path&, int, int, double, int,
                          int);
};

}  // namespace lightcone

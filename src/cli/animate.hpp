// `lightcone animate`: a frame sequence at successive moments of the camera's own clock (or of
// world time), to image files and/or a video; `lightcone encode`: a video from frame files.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lightcone/io/scene_file.hpp"

namespace lightcone {

struct AnimateArgs {
  std::string scene;
  std::optional<std::string> output, exr, video, frames;
  std::optional<std::string> animation;  // the whole animation's frames, A-B (default: the run's)
  std::optional<double> duration;
  double fps = 30;
  std::string clock = "proper", renderer = "trace", tessellation = "auto";
  std::optional<int> width, height, samples;
  std::optional<double> scale;
  int threads = 0, crf = 18, gif_width = 640;
  std::uint64_t seed = 0;
  std::vector<std::string> overrides;
  SceneLoadOptions scene_options;  // --allow-outside
  bool resume = false, quiet = false;
};
int run_animate(const AnimateArgs& args);

struct EncodeArgs {
  std::string pattern, output;
  std::optional<std::string> frames;
  double fps = 30;
  int crf = 18, gif_width = 640;
  bool quiet = false, allow_gaps = false;
};
int run_encode(const EncodeArgs& args);

// The most frames one `animate` run renders (longer animations are split with --frames).
inline constexpr long long kMaxFramesPerRun = 1'000'000;

// A printf-style frame file name with one integer conversion (%d, %04d, ...; %% is a percent
// sign), checked: InputError naming `option` otherwise.
class FramePattern {
 public:
  FramePattern(const std::string& option, const std::string& pattern);
  std::string name(long long frame) const;
  // The frame number whose name this is, if any (name(n) == name).
  std::optional<long long> frame_of(const std::string& name) const;
  const std::string& text() const { return text_; }
  // Whether the frame number is in the file's name (not a folder's), and the folder part of
  // every name ("frames/" for frames/shot-%04d.png; empty for a name without a folder).
  bool number_in_file_name() const { return after_.find('/') == std::string::npos; }
  std::string folder_prefix() const { return before_.substr(0, before_.rfind('/') + 1); }

 private:
  std::string text_, before_, after_;
  int width_ = 0;
  bool zero_ = false;
};

// "A-B" (inclusive, 0 <= A <= B), or InputError naming `option`.
std::pair<long long, long long> parse_frame_range(const std::string& option,
                                                  const std::string& text);

}  // namespace lightcone

// `lightcone animate`: a frame sequence at successive moments of the camera's own clock (or of
// world time), to image files and/or a video; `lightcone encode`: a video from frame files.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace lightcone {

struct AnimateArgs {
  std::string scene;
  std::optional<std::string> output, exr, video, frames;
  std::optional<double> duration;
  double fps = 30;
  std::string clock = "proper", renderer = "trace", tessellation = "auto";
  std::optional<int> width, height, samples;
  int threads = 0, crf = 18;
  std::uint64_t seed = 0;
  std::vector<std::string> overrides;
  bool resume = false, quiet = false;
};
int run_animate(const AnimateArgs& args);

struct EncodeArgs {
  std::string pattern, output;
  std::optional<std::string> frames;
  double fps = 30;
  int crf = 18;
  bool quiet = false;
};
int run_encode(const EncodeArgs& args);

// A printf-style frame file name with one integer conversion (%d, %04d, ...; %% is a percent
// sign), checked: InputError naming `option` otherwise.
class FramePattern {
 public:
  FramePattern(const std::string& option, const std::string& pattern);
  std::string name(long long frame) const;

 private:
  std::string before_, after_;
  int width_ = 0;
  bool zero_ = false;
};

// "A-B" (inclusive, 0 <= A <= B), or InputError naming `option`.
std::pair<long long, long long> parse_frame_range(const std::string& option,
                                                  const std::string& text);

}  // namespace lightcone

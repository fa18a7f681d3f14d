#include "viewer/frame_rate.hpp"

#include <fmt/format.h>

namespace lightcone {

bool FrameRateProbe::frame(double seconds_since_start) {
  if (measured_) return false;
  ++frames_;
  if (frames_ == kWarmUpFrames) start_ = seconds_since_start;
  if (frames_ <= kWarmUpFrames || seconds_since_start - start_ < kSeconds) return false;
  measured_ = (frames_ - kWarmUpFrames) / (seconds_since_start - start_);
  return true;
}

std::optional<std::string> slow_viewer_advice(double fps, int width, int height, bool on_gpu,
                                              bool gpu_available, bool split) {
  if (!(fps < kSmoothFramesPerSecond)) return std::nullopt;
  std::string advice = fmt::format(
      "the viewer draws {:.1f} frames a second here, below {:.0f}: a smaller window draws "
      "faster (now {}x{}; --width and --height set it)",
      fps, kSmoothFramesPerSecond, width, height);
  if (!on_gpu && gpu_available) advice += "; --tessellation gpu cuts the bodies' edges on the GPU";
  if (split) advice += "; the classical | relativistic split (C) draws the scene twice";
  return advice;
}

}  // namespace lightcone

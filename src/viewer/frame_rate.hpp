// The viewer's first impression: the frame rate it reaches on this machine, measured once over
// its first seconds (after the first frames, which compile the GL programs), and what to lower
// when it is too slow to fly smoothly.
#pragma once

#include <optional>
#include <string>

namespace lightcone {

// Below this a flight stutters: the viewer warns, once.
inline constexpr double kSmoothFramesPerSecond = 20;

class FrameRateProbe {
 public:
  // Frames skipped before measuring, and the time measured over.
  static constexpr int kWarmUpFrames = 3;
  static constexpr double kSeconds = 2;

  // Called once a frame with the time since the viewer started; true on the frame at which the
  // measurement ends (measured() is then set).
  bool frame(double seconds_since_start);
  std::optional<double> measured() const { return measured_; }

 private:
  int frames_ = 0;
  double start_ = 0;
  std::optional<double> measured_;
};

// The advice for a measured rate below kSmoothFramesPerSecond, naming what to lower: the window
// (its size now), the tessellation where edges are cut on the CPU though a hardware GPU could
// (`gpu_available`), and the split view, which draws the scene twice; none at or above it.
std::optional<std::string> slow_viewer_advice(double fps, int width, int height, bool on_gpu,
                                              bool gpu_available, bool split);

}  // namespace lightcone

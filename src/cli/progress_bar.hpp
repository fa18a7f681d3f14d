// A progress bar on stderr for long renders: it fits the terminal and shows the elapsed time and
// an estimate of the time left; silent when stderr is not a terminal.
#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>

namespace lightcone {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  ~ProgressBar();
  // Thread-safe; redraws at most ten times a second and at the end.
  void update(std::size_t done, std::size_t total);

 private:
  bool enabled_;
  std::mutex mutex_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace lightcone

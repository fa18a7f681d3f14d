// A progress bar on stderr for long renders; silent when stderr is not a terminal.
#pragma once

#include <cstddef>
#include <mutex>

namespace lightcone {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  ~ProgressBar();
  // Thread-safe; redraws only when the shown percentage changes.
  void update(std::size_t done, std::size_t total);

 private:
  bool enabled_;
  std::mutex mutex_;
  int shown_percent_ = -1;
};

}  // namespace lightcone

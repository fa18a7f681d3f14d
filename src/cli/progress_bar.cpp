#include "progress_bar.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace lightcone {
namespace {

int terminal_columns() {
  winsize w{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
  return 80;
}

std::string clock_text(double seconds) {
  const auto s = static_cast<long>(std::max(0.0, seconds) + 0.5);
  char text[32];
  if (s >= 3600)
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
  return text;
}

}  // namespace

ProgressBar::ProgressBar(bool enabled)
    : enabled_(enabled), start_(std::chrono::steady_clock::now()), last_(start_) {}

ProgressBar::~ProgressBar() {
  if (enabled_ && drawn_) std::fputc('\n', stderr);
}

void ProgressBar::update(std::size_t done, std::size_t total) {
  if (!enabled_ || total == 0) return;
  std::lock_guard lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  if (done < total && drawn_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  drawn_ = true;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fraction = static_cast<double>(done) / total;
  const std::string times =
      " " + clock_text(elapsed) +
      (done < total && done > 0 ? " elapsed, " + clock_text(elapsed / fraction - elapsed) + " left"
                                : " elapsed");
  char percent[16];
  std::snprintf(percent, sizeof percent, " %3d%%", static_cast<int>(100 * fraction));
  // Every redraw is exactly the terminal's width, so that it covers the last one (no erase
  // sequence: at the last column it would erase the line's last character); the bar takes what
  // the text leaves, and a terminal too narrow for the text gets its beginning.
  const std::string label = "rendering [", tail = std::string("]") + percent + times;
  const int columns = terminal_columns();
  const int width = std::max(0, columns - static_cast<int>(label.size() + tail.size()));
  const int filled = static_cast<int>(fraction * width);
  std::string line = label + std::string(filled, '#') + std::string(width - filled, '.') + tail;
  line.resize(static_cast<std::size_t>(columns), ' ');
  std::fprintf(stderr, "\r%s", line.c_str());
  std::fflush(stderr);
}

}  // namespace lightcone

#include "video.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "cli_common.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"

extern char** environ;

namespace fs = std::filesystem;

namespace lightcone {

std::optional<VideoFormat> video_format_of(const fs::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".mp4") return VideoFormat::kMp4;
  if (extension == ".webm") return VideoFormat::kWebm;
  if (extension == ".gif") return VideoFormat::kGif;
  return std::nullopt;
}

std::string require_program(const std::string& program, const std::string& needed_for) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "/usr/bin:/bin");
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    const fs::path candidate = fs::path(folder.empty() ? "." : folder) / program;
    if (::access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate))
      return candidate.string();
  }
  throw InputError(
      fmt::format("{} needs {}, which is not installed (on Debian: apt-get install "
                  "{}); nothing written",
                  needed_for, program, program));
}

void check_video(const std::string& option, const fs::path& file, int width, int height, double fps,
                 int crf) {
  const std::optional<VideoFormat> format = video_format_of(file);
  if (!format)
    throw InputError(option + " " + file.string() +
                     ": unknown video format (the name must end in .mp4, .webm or .gif)");
  if (*format != VideoFormat::kGif && (width % 2 != 0 || height % 2 != 0))
    throw InputError(fmt::format(
        "{} {}: {}x{} frames: MP4 and WebM (yuv420p) need an even width and height (set "
        "--width and --height)",
        option, file.string(), width, height));
  if (!(fps > 0) || !std::isfinite(fps))
    throw InputError(fmt::format("--fps {}: must be greater than 0", fps));
  if (crf < 0 || crf > 63) throw InputError(fmt::format("--crf {}: must be from 0 to 63", crf));
  require_writable_target(option, file.string());
  require_program("ffmpeg", option);
}

VideoWriter::VideoWriter(const fs::path& file, int width, int height, double fps, int crf)
    : file_(file), width_(width), height_(height) {
  const VideoFormat format = *video_format_of(file);
  temp_ = file_;
  temp_ += fmt::format(".partial-{}", ::getpid());
  const std::string size = fmt::format("{}x{}", width, height);
  const std::string rate = fmt::format("{:.17g}", fps);
  const std::string quality = std::to_string(crf);
  std::vector<std::string> args = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-nostdin", "-y",
                                   "-f",     "rawvideo",     "-pix_fmt",  "rgb24", "-s",       size,
                                   "-r",     rate,           "-i",        "-"};
  // The frames are sRGB (Rec. 709 primaries): tagged as BT.709 for players.
  const std::vector<std::string> bt709 = {"-colorspace", "bt709", "-color_primaries", "bt709",
                                          "-color_trc",  "bt709", "-color_range",     "tv"};
  if (format == VideoFormat::kMp4) {
    args.insert(args.end(), {"-c:v", "libx264", "-preset", "medium", "-crf", quality, "-pix_fmt",
                             "yuv420p", "-vf", "scale=out_color_matrix=bt709:out_range=tv"});
    args.insert(args.end(), bt709.begin(), bt709.end());
    args.insert(args.end(), {"-movflags", "+faststart", "-f", "mp4"});
  } else if (format == VideoFormat::kWebm) {
    args.insert(args.end(), {"-c:v", "libvpx-vp9", "-crf", quality, "-b:v", "0", "-pix_fmt",
                             "yuv420p", "-vf", "scale=out_color_matrix=bt709:out_range=tv"});
    args.insert(args.end(), bt709.begin(), bt709.end());
    args.insert(args.end(), {"-f", "webm"});
  } else {
    // One palette for the whole animation, dithered.
    args.insert(args.end(), {"-vf", "split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse",
                             "-f", "gif"});
  }
  args.push_back(temp_.string());

  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("cannot create a pipe to ffmpeg");
  ::fcntl(fds[1], F_SETFD, FD_CLOEXEC);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string program = require_program("ffmpeg", "--video");
  const int spawned =
      posix_spawn(&child_, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[0]);
  if (spawned != 0) {
    ::close(fds[1]);
    throw std::runtime_error(fmt::format("cannot run ffmpeg: {}", std::strerror(spawned)));
  }
  pipe_ = fds[1];
  // A dying ffmpeg must make writes fail, not kill this process.
  std::signal(SIGPIPE, SIG_IGN);
}

VideoWriter::~VideoWriter() {
  if (finished_) return;
  close_pipe();
  std::error_code ec;
  fs::remove(temp_, ec);
}

void VideoWriter::close_pipe() {
  if (pipe_ >= 0) ::close(pipe_);
  pipe_ = -1;
  if (child_ > 0) {
    int status = 0;
    while (::waitpid(child_, &status, 0) < 0 && errno == EINTR) {
    }
    child_ = -1;
  }
}

void VideoWriter::add(const Image& display) {
  if (display.width != width_ || display.height != height_)
    throw std::runtime_error(fmt::format("a {}x{} frame for a {}x{} video", display.width,
                                         display.height, width_, height_));
  const std::vector<unsigned char> bytes = display_rgb8(display);
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(pipe_, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw std::runtime_error(fmt::format("{}: ffmpeg stopped taking frames ({})", file_.string(),
                                           std::strerror(errno)));
    written += static_cast<std::size_t>(n);
  }
}

void VideoWriter::finish() {
  ::close(pipe_);
  pipe_ = -1;
  int status = 0;
  while (::waitpid(child_, &status, 0) < 0 && errno == EINTR) {
  }
  child_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(fmt::format("{}: ffmpeg failed (status {}); nothing written",
                                         file_.string(),
                                         WIFEXITED(status) ? WEXITSTATUS(status) : -1));
  std::error_code ec;
  fs::rename(temp_, file_, ec);
  if (ec) throw std::runtime_error(fmt::format("{}: {}", file_.string(), ec.message()));
  finished_ = true;
}

}  // namespace lightcone

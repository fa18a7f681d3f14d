#include "video.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "cli_common.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"

extern char** environ;

namespace fs = std::filesystem;

namespace lightcone {

namespace {

using SteadyClock = std::chrono::steady_clock;

// The watchdog's time: LIGHTCONE_VIDEO_WATCHDOG_SECONDS if set to a positive number (tests
// use a short one), else kVideoWatchdogSeconds.
double watchdog_seconds() {
  if (const char* text = std::getenv("LIGHTCONE_VIDEO_WATCHDOG_SECONDS")) {
    char* end = nullptr;
    const double seconds = std::strtod(text, &end);
    if (end != text && *end == '\0' && seconds > 0 && std::isfinite(seconds)) return seconds;
  }
  return kVideoWatchdogSeconds;
}

double seconds_since(SteadyClock::time_point t) {
  return std::chrono::duration<double>(SteadyClock::now() - t).count();
}

struct Child {
  pid_t pid = -1;
  int input = -1;   // our end of its standard input, if piped
  int output = -1;  // our end of its standard output, if piped
};

// Starts `args` (args[0] found on PATH) with its standard input and/or output piped to us;
// our ends are non-blocking and closed on exec.
Child spawn(const std::string& program, std::vector<std::string> args, bool pipe_input,
            bool pipe_output) {
  int in[2] = {-1, -1}, out[2] = {-1, -1};
  if ((pipe_input && ::pipe2(in, O_CLOEXEC) != 0) || (pipe_output && ::pipe2(out, O_CLOEXEC) != 0))
    throw std::runtime_error(fmt::format("cannot create a pipe to {}", args[0]));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (pipe_input) posix_spawn_file_actions_adddup2(&actions, in[0], STDIN_FILENO);
  if (pipe_output) posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // This process ignores SIGPIPE (a dying ffmpeg must make writes fail, not kill it); the
  // child gets the default back.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
  Child child;
  const int spawned =
      posix_spawn(&child.pid, program.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  for (const int fd : {in[0], out[1]})
    if (fd >= 0) ::close(fd);
  if (spawned != 0) {
    for (const int fd : {in[1], out[0]})
      if (fd >= 0) ::close(fd);
    throw std::runtime_error(fmt::format("cannot run {}: {}", args[0], std::strerror(spawned)));
  }
  child.input = in[1];
  child.output = out[0];
  for (const int fd : {child.input, child.output})
    if (fd >= 0) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
  return child;
}

void kill_and_reap(pid_t pid) {
  ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
}

// Waits for `pid` to end and returns its wait status. `progress` is a number that grows while
// the child works (the bytes it has written); if it stays the same for the watchdog's time, or
// a stop signal arrives, the child is killed and this throws.
int wait_watched(pid_t pid, const std::string& what,
                 const std::function<std::uintmax_t()>& progress) {
  const double limit = watchdog_seconds();
  std::uintmax_t last = progress();
  SteadyClock::time_point since = SteadyClock::now();
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) return status;
    if (done < 0 && errno != EINTR) throw std::runtime_error(fmt::format("{}: lost", what));
    if (interrupted) {
      kill_and_reap(pid);
      throw Stopped(what + ": stopped");
    }
    const std::uintmax_t now = progress();
    if (now != last) {
      last = now;
      since = SteadyClock::now();
    } else if (seconds_since(since) > limit) {
      kill_and_reap(pid);
      throw std::runtime_error(
          fmt::format("{} made no progress for {:g} s and was stopped", what, limit));
    }
    ::poll(nullptr, 0, 20);
  }
}

std::uintmax_t size_of(const fs::path& file) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  return ec ? 0 : size;
}

struct Probe {
  long long frames = 0;
  double duration = 0;
};

// What ffprobe reads from a video file: the packets of its first video stream (one a frame)
// and its duration. Throws when it cannot read the file as a video.
Probe probe(const fs::path& file) {
  const std::string program = require_program("ffprobe", "--video");
  Child child =
      spawn(program,
            {"ffprobe", "-v", "error", "-count_packets", "-select_streams", "v:0", "-show_entries",
             "stream=nb_read_packets:format=duration", "-of", "json", file.string()},
            false, true);
  std::string text;
  std::uintmax_t received = 0;
  const auto drain = [&] {
    char buffer[4096];
    for (;;) {
      const ssize_t n = ::read(child.output, buffer, sizeof buffer);
      if (n <= 0) break;
      if (text.size() < (1u << 20)) text.append(buffer, static_cast<std::size_t>(n));
      received += static_cast<std::uintmax_t>(n);
    }
    return received;
  };
  int status = 0;
  try {
    status = wait_watched(child.pid, "ffprobe", drain);
  } catch (...) {
    ::close(child.output);
    throw;
  }
  drain();
  ::close(child.output);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("ffprobe cannot read it as a video");
  Probe p;
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    const auto& streams = j.at("streams");
    if (streams.empty()) throw std::runtime_error("no video stream");
    p.frames = std::stoll(streams.at(0).at("nb_read_packets").get<std::string>());
    p.duration = std::stod(j.at("format").at("duration").get<std::string>());
  } catch (const std::exception&) {
    throw std::runtime_error("ffprobe finds no video stream with frames and a duration in it");
  }
  return p;
}

// The rates a format plays as asked: a GIF's frame delays are whole hundredths of a second,
// and players stretch delays under two of them.
double max_rate(VideoFormat format) {
  return format == VideoFormat::kGif ? 50 : 1000;
}
constexpr double kMinRate = 0.01;

}  // namespace

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
                  "ffmpeg); nothing written",
                  needed_for, program));
}

void check_video(const std::string& option, const fs::path& file, int width, int height, double fps,
                 int crf, int gif_width) {
  const std::optional<VideoFormat> format = video_format_of(file);
  if (!format)
    throw InputError(option + " " + file.string() +
                     ": unknown video format (the name must end in .mp4, .webm or .gif)");
  if (*format != VideoFormat::kGif && (width % 2 != 0 || height % 2 != 0))
    throw InputError(fmt::format(
        "{} {}: {}x{} frames: MP4 and WebM (yuv420p) need an even width and height (set "
        "--width and --height)",
        option, file.string(), width, height));
  if (!(fps >= kMinRate && fps <= max_rate(*format)))
    throw InputError(fmt::format("--fps {}: {} {} plays from {:g} to {:g} frames a second", fps,
                                 option, file.string(), kMinRate, max_rate(*format)));
  const int max_crf = *format == VideoFormat::kMp4 ? 51 : 63;
  if (crf < 0 || crf > max_crf)
    throw InputError(fmt::format("--crf {}: must be from 0 to {} for {}", crf, max_crf,
                                 file.extension().string()));
  require_writable_target(option, file.string());
  require_program("ffmpeg", option);
  require_program("ffprobe", option);
  // One black frame with the same settings, read back: whatever ffmpeg would refuse after
  // the last frame is refused before the first.
  try {
    VideoWriter trial(file, width, height, fps, crf, gif_width);
    Image black;
    black.width = width;
    black.height = height;
    black.rgb.assign(3 * static_cast<std::size_t>(width) * height, 0.0f);
    trial.add(black);
    trial.complete();
  } catch (const Stopped&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(
        fmt::format("{} {}: ffmpeg cannot make a {}x{} video at {:g} fps here ({}); "
                    "nothing rendered",
                    option, file.string(), width, height, fps, e.what()));
  }
}

VideoWriter::VideoWriter(const fs::path& file, int width, int height, double fps, int crf,
                         int gif_width)
    : file_(file), width_(width), height_(height), fps_(fps) {
  static std::atomic<unsigned> counter{0};
  const VideoFormat format = *video_format_of(file);
  temp_ = file_;
  temp_ += fmt::format(".partial-{}-{}", ::getpid(), counter++);
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
    // Scaled down to gif_width where wider; one palette for the whole animation, dithered.
    // (ffmpeg spreads the frame delays, whole hundredths of a second, so that they add up to
    // the rate asked for: 3, 4, 3, ... at 30 fps.)
    const std::string scale =
        width > gif_width ? fmt::format("scale={}:-1:flags=lanczos,", gif_width) : "";
    args.insert(args.end(),
                {"-vf", scale + "split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse",
                 "-f", "gif"});
  }
  args.push_back(temp_.string());
  std::signal(SIGPIPE, SIG_IGN);
  const Child child = spawn(require_program("ffmpeg", "--video"), args, true, false);
  child_ = child.pid;
  pipe_ = child.input;
}

VideoWriter::~VideoWriter() {
  if (finished_) return;
  stop_child();
  std::error_code ec;
  fs::remove(temp_, ec);
}

void VideoWriter::stop_child() {
  if (pipe_ >= 0) ::close(pipe_);
  pipe_ = -1;
  if (child_ > 0) kill_and_reap(child_);
  child_ = -1;
}

void VideoWriter::add(const Image& display) {
  if (display.width != width_ || display.height != height_)
    throw std::runtime_error(fmt::format("a {}x{} frame for a {}x{} video", display.width,
                                         display.height, width_, height_));
  const std::vector<unsigned char> bytes = display_rgb8(display);
  const double limit = watchdog_seconds();
  std::size_t written = 0;
  SteadyClock::time_point progress = SteadyClock::now();
  while (written < bytes.size()) {
    if (interrupted) throw Stopped(file_.string() + ": stopped");
    pollfd ready{pipe_, POLLOUT, 0};
    if (::poll(&ready, 1, 100) <= 0) {
      if (seconds_since(progress) > limit) {
        stop_child();
        throw std::runtime_error(fmt::format(
            "{}: ffmpeg took no frame data for {:g} s and was stopped", file_.string(), limit));
      }
      continue;
    }
    const ssize_t n = ::write(pipe_, bytes.data() + written, bytes.size() - written);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n <= 0)
      throw std::runtime_error(fmt::format("{}: ffmpeg stopped taking frames ({})", file_.string(),
                                           std::strerror(errno)));
    written += static_cast<std::size_t>(n);
    progress = SteadyClock::now();
  }
  ++frames_;
}

void VideoWriter::complete() {
  ::close(pipe_);
  pipe_ = -1;
  const pid_t child = child_;
  child_ = -1;
  const int status = wait_watched(child, "ffmpeg", [&] { return size_of(temp_); });
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(
        fmt::format("ffmpeg failed (status {})", WIFEXITED(status) ? WEXITSTATUS(status) : -1));
  // On disk, not only in the page cache: a full disk can show up only here.
  const int fd = ::open(temp_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const std::string reason = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    throw std::runtime_error("ffmpeg's file cannot be stored (" + reason + ")");
  }
  ::close(fd);
  const Probe p = probe(temp_);
  if (p.frames != frames_ || !(p.duration > 0))
    throw std::runtime_error(
        fmt::format("ffmpeg's file holds {} of the {} frames sent", p.frames, frames_));
}

void VideoWriter::finish() {
  try {
    complete();
  } catch (const Stopped&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(
        fmt::format("{}: {}; no video written (any earlier file of that name is untouched)",
                    file_.string(), e.what()));
  }
  std::error_code ec;
  fs::rename(temp_, file_, ec);
  if (ec) throw std::runtime_error(fmt::format("{}: {}", file_.string(), ec.message()));
  finished_ = true;
}

}  // namespace lightcone

#include "cli_common.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <utility>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/scene_file.hpp"

namespace fs = std::filesystem;

namespace lightcone {

std::atomic<bool> interrupted{false};

namespace {

volatile std::sig_atomic_t first_stop_signal = 0;
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void on_stop_signal(int signal) {
  if (first_stop_signal == 0) first_stop_signal = signal;
  interrupted = true;
}

}  // namespace

StopSignals::StopSignals() {
  for (const int s : kStopSignals) std::signal(s, on_stop_signal);
}

StopSignals::~StopSignals() {
  for (const int s : kStopSignals) std::signal(s, SIG_DFL);
}

int StopSignals::received() {
  return first_stop_signal;
}

std::string StopSignals::name() {
  switch (first_stop_signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "a signal";
  }
}

int StopSignals::exit_status() {
  return 128 + (first_stop_signal != 0 ? static_cast<int>(first_stop_signal) : SIGINT);
}

Scene load(const std::string& file, const std::vector<std::string>& overrides,
           const SceneLoadOptions& options) {
  SceneLoadReport report;
  Scene scene = load_scene_file(file, overrides, report, options);
  for (const std::string& w : tangent_warnings(scene)) report.warnings.push_back(w);
  for (const std::string& w : report.warnings)
    std::fprintf(stderr, "lightcone: warning: %s\n", w.c_str());
  return scene;
}

// Checked before rendering: the target is a regular file or absent (a symbolic link counts as
// the file it points to, which is then written and the link kept), and its folder exists and
// is writable, so that nothing but a regular file is ever replaced and a render is never lost
// to a bad output name.
void require_writable_target(const std::string& option, const std::string& path) {
  std::error_code ec;
  const fs::path target = fs::weakly_canonical(fs::absolute(path), ec);
  const fs::file_status status = fs::status(ec ? fs::path(path) : target, ec);
  if (fs::is_directory(status)) throw InputError(option + " " + path + ": is a folder, not a file");
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw InputError(option + " " + path +
                     ": is not a regular file (a device, a FIFO or a socket); it is not replaced");
  const fs::path parent = (ec ? fs::absolute(path) : target).parent_path();
  if (!fs::is_directory(parent) && !fs::create_directories(parent, ec) && !fs::is_directory(parent))
    throw InputError(option + " " + path + ": folder " + parent.string() +
                     " does not exist and cannot be made (" + ec.message() + ")");
  if (::access(parent.c_str(), W_OK) != 0)
    throw InputError(option + " " + path + ": folder " + parent.string() + " is not writable");
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  const fs::path pa = fs::weakly_canonical(fs::absolute(a), ec);
  const fs::path pb = fs::weakly_canonical(fs::absolute(b), ec);
  return pa == pb;
}

void scale_image_size(Camera& camera, double factor) {
  const double width = std::round(camera.width * factor),
               height = std::round(camera.height * factor);
  if (!(factor > 0) || !(width <= 16384 && height <= 16384))
    throw InputError(
        fmt::format("--scale {}: must be above 0 and make at most 16384 pixels a side "
                    "(the scene is {}x{})",
                    factor, camera.width, camera.height));
  camera.width = std::max(1, static_cast<int>(width));
  camera.height = std::max(1, static_cast<int>(height));
}

std::string resize_keeping_field(Camera& camera, std::optional<int> width,
                                 std::optional<int> height) {
  for (const auto& [option, size] : {std::pair{"--width", width}, std::pair{"--height", height}})
    if (size && !(*size >= 1 && *size <= kMaxCameraSide))
      throw InputError(fmt::format("{}: must be an integer from 1 to {}, got {}", option,
                                   kMaxCameraSide, *size));
  const int new_width = width.value_or(camera.width), new_height = height.value_or(camera.height);
  if (std::int64_t{new_width} * new_height > kMaxCameraPixels)
    throw InputError(fmt::format("{}: {} x {} pixels is more than the limit of {} (2^27)",
                                 width ? "--width" : "--height", new_width, new_height,
                                 kMaxCameraPixels));
  const double old_aspect = double(camera.width) / camera.height,
               new_aspect = double(new_width) / new_height;
  camera.width = new_width;
  camera.height = new_height;
  if (new_aspect == old_aspect) return "";
  const double half_tan = std::tan(camera.fov_degrees * std::numbers::pi / 360);
  const auto degrees = [](double half_tangent) {
    return 360 / std::numbers::pi * std::atan(half_tangent);
  };
  if (new_aspect > old_aspect)
    return fmt::format(
        "{}x{} is wider than the scene: its vertical field of {:.4g} degrees is "
        "kept, the horizontal one widens from {:.4g} to {:.4g}",
        new_width, new_height, camera.fov_degrees, degrees(half_tan * old_aspect),
        degrees(half_tan * new_aspect));
  const double horizontal = degrees(half_tan * old_aspect);
  const double old_vertical = camera.fov_degrees;
  camera.fov_degrees = degrees(half_tan * old_aspect / new_aspect);
  return fmt::format(
      "{}x{} is narrower than the scene: its horizontal field of {:.4g} degrees "
      "is kept, the vertical one widens from {:.4g} to {:.4g}",
      new_width, new_height, horizontal, old_vertical, camera.fov_degrees);
}

std::unique_ptr<tbb::global_control> thread_limit(int threads) {
  if (threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               static_cast<std::size_t>(threads));
}

std::string counted(std::size_t count, const std::string& noun) {
  return fmt::format("{} {}{}", count, noun, count == 1 ? "" : "s");
}

std::string partial_name(const std::string& path) {
  const fs::path p(path);
  fs::path partial = p.parent_path() / p.stem();
  partial += ".partial";
  partial += p.extension();
  return partial.string();
}

CLI::Validator library_rule(std::optional<std::string> (*refused)(std::string_view),
                            const std::string& names) {
  return CLI::Validator([refused](std::string& value) { return refused(value).value_or(""); },
                        names);
}

std::vector<double> parse_numbers(const std::string& option, const std::string& text,
                                  std::size_t count, bool integers, const std::string& what) {
  std::vector<double> v;
  std::stringstream in(text);
  std::string part;
  const InputError error(option + " " + text + ": expected " + what);
  while (std::getline(in, part, ',')) {
    std::size_t used = 0;
    double x = 0;
    try {
      x = integers ? static_cast<double>(std::stol(part, &used)) : std::stod(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != part.size() || part.empty() || !std::isfinite(x)) throw error;
    v.push_back(x);
  }
  if (count != 0 && v.size() != count) throw error;
  return v;
}

}  // namespace lightcone

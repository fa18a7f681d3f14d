// What the commands share: loading a scene with its warnings, checking output targets, the
// stop signals and the exit statuses.
#pragma once

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "lightcone/io/scene_file.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

constexpr int kBadInput = 2;

// Set when SIGINT (Ctrl-C), SIGTERM (`timeout`, Slurm's scancel) or SIGHUP (a closed terminal)
// arrives while StopSignals is installed; a render then stops at its next tile.
extern std::atomic<bool> interrupted;

// Thrown where work ends early because a stop signal arrived.
struct Stopped : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// While alive, the three stop signals set `interrupted` instead of ending the process, so that
// a command can keep its whole frames, remove its temporaries and say what it kept.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  // The first stop signal received (0 if none), its name ("SIGTERM") and the exit status a
  // shell reports for it (128 + its number: 130, 143, 129).
  static int received();
  static std::string name();
  static int exit_status();
};

// Loads a scene file with --set overrides, printing its warnings (and the tangent
// approximation's) to stderr. Throws InputError.
Scene load(const std::string& file, const std::vector<std::string>& overrides,
           const SceneLoadOptions& options = {});

// The help of --allow-outside, which sets SceneLoadOptions::mesh.allow_outside.
inline constexpr const char* kAllowOutsideHelp =
    "Let a mesh file (glTF) read files outside its own folder";

// Checked before rendering: the target is a regular file or absent, and its folder exists (made,
// with its parents, if missing) and is writable (InputError naming `option` otherwise).
void require_writable_target(const std::string& option, const std::string& path);

// Whether two paths name the same file.
bool same_file(const std::string& a, const std::string& b);

// --scale F: the camera's width and height times F (rounded, at least 1), the same view (the
// vertical field of view is kept, and the aspect as nearly as whole pixels allow). F must be
// above 0 and make at most 16384 pixels a side (InputError otherwise).
void scale_image_size(Camera& camera, double factor);

// --width W and --height H: the picture at that size shows at least the scene's own field of
// view both ways. A wider picture than the scene's keeps the vertical field (camera.fov) and
// shows more at the sides; a narrower one keeps the horizontal field and shows more above and
// below. Returns a line saying which was kept (empty where the aspect is the scene's); sizes
// outside the camera's limits are InputErrors naming the option.
std::string resize_keeping_field(Camera& camera, std::optional<int> width,
                                 std::optional<int> height);

// "1 sample", "4 samples": a count and its noun, singular or plural.
std::string counted(std::size_t count, const std::string& noun);

// --threads N (N > 0) bounds the whole command, while the returned limit lives: the render,
// and the tone mapping and image encoding around it, which are parallel too.
std::unique_ptr<tbb::global_control> thread_limit(int threads);

// Where an interrupted render's image goes, beside its target: out.png -> out.partial.png.
std::string partial_name(const std::string& path);

// A CLI11 check of an option's value by one of the library's name rules (renderer_refused,
// tessellation_refused): the option is refused with the library's message.
CLI::Validator library_rule(std::optional<std::string> (*refused)(std::string_view),
                            const std::string& names);

// `count` comma-separated finite numbers (any number of them for 0; integers if `integers`), or
// an error that says so: "OPTION TEXT: expected WHAT".
std::vector<double> parse_numbers(const std::string& option, const std::string& text,
                                  std::size_t count, bool integers, const std::string& what);

}  // namespace lightcone

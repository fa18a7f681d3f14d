// The web page's entry points: the real-time renderer of the native viewer drawing into the
// page's canvas (WebGL 2), a scene read from the page's files with the same reader and the same
// messages as `lightcone`, and the viewer's flight. web/page.js calls these through ccall; each
// returns its result as text (JSON where it has fields), and none throws into JavaScript.
#include <emscripten/emscripten.h>
#include <emscripten/html5.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/color/sigmoid_polynomial.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/pixel_probe.hpp"
#include "lightcone/frame/request_rules.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/locate_json.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/io/star_catalogue.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/scene/speed_text.hpp"
#include "page_images.hpp"
#include "viewer/flight.hpp"
#include "viewer/frame_loop.hpp"
#include "viewer/probe_text.hpp"

namespace lightcone {
namespace {

struct Page {
  EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context = 0;
  std::unique_ptr<RasterRenderer> renderer;
  std::unique_ptr<DisplayPass> display;
  std::unique_ptr<FloatTarget> relativistic, classical;
  // The scene as loaded (from `path`), and as drawn (the flight's camera): each kept with its
  // emission tables.
  std::string path;
  std::unique_ptr<Scene> scene;
  Scene frame, still;
  std::unique_ptr<EmissionTable> frame_emission, still_emission;
  std::unique_ptr<Flight> flight;
  bool split = false;
  double proper_time = 0;  // the camera's clock
  ExposureFollower meter;
  std::vector<PixelProbe> probes;  // the clicked points' (lc_probe), at most two
  std::string result;              // what the last call returns to JavaScript
};

Page& page() {
  static Page p;
  return p;
}

const char* answer(std::string text) {
  page().result = std::move(text);
  return page().result.c_str();
}

// The error as every door shows it (printable: a 10 MB key cut, control characters escaped).
const char* failure(const std::string& message) {
  return answer(nlohmann::json{{"error", printable(message)}}.dump());
}

}  // namespace
}  // namespace lightcone

using namespace lightcone;

extern "C" {

// Makes the WebGL 2 context on the page's <canvas id="canvas">. Returns {} or {"error"}.
EMSCRIPTEN_KEEPALIVE const char* lc_start() {
  EmscriptenWebGLContextAttributes attributes;
  emscripten_webgl_init_context_attributes(&attributes);
  attributes.majorVersion = 2;
  attributes.minorVersion = 0;
  attributes.antialias = false;
  attributes.depth = false;
  attributes.alpha = false;
  attributes.preserveDrawingBuffer = true;  // for the screenshot button
  Page& p = page();
  p.context = emscripten_webgl_create_context("#canvas", &attributes);
  if (p.context <= 0) return failure("this browser has no WebGL 2");
  emscripten_webgl_make_context_current(p.context);
  // Float colour targets (the frame's linear radiance) and filtered float tables.
  for (const char* extension : {"EXT_color_buffer_float", "OES_texture_float_linear"})
    if (!emscripten_webgl_enable_extension(p.context, extension))
      return failure(fmt::format("this browser's WebGL 2 lacks {}", extension));
  // The star catalogue the page's data carries (web/CMakeLists.txt): the reader would look
  // beside the program, which a page does not have.
  set_star_catalogue_folder("/data");
  try {
    p.renderer = std::make_unique<RasterRenderer>();
    p.display = std::make_unique<DisplayPass>();
  } catch (const std::exception& e) {
    return failure(e.what());
  }
  return answer(nlohmann::json{{"gl", gl_description()}}.dump());
}

// Reads the scene file at `path` (in the page's file system) with `overrides` ("key.path=value"
// lines, as --set takes them). With `keep_flight`, and the same file as before, the camera
// stays where the flight has taken it (a switch changed); else it starts at the scene's camera.
// On failure the previous scene stays. Returns {"warnings", "differences", "beta", "time_scale"}
// (the native viewer's clock for it: flight.hpp's default_time_scale); {"images"}
// when the scene names an image the browser has not decoded yet (decode it and call again: one
// image a call); or {"error"}.
EMSCRIPTEN_KEEPALIVE const char* lc_load(const char* path, const char* overrides, int keep_flight) {
  std::vector<std::string> sets;
  std::istringstream lines(overrides);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) sets.push_back(line);
  try {
    SceneLoadReport report;
    auto scene = std::make_unique<Scene>(load_scene_file(path, sets, report));
    // The rules the program and the Python module check, with their message.
    if (const auto refused = scene_refused(*scene)) return failure(*refused);
    Page& p = page();
    const bool keep = keep_flight && p.flight && p.path == path;
    p.path = path;
    p.scene = std::move(scene);
    p.frame = p.still = *p.scene;
    p.frame_emission.reset();
    p.probes.clear();
    p.still_emission.reset();
    if (!keep) {
      p.flight = std::make_unique<Flight>(p.scene->camera);
      p.proper_time = p.scene->camera.motion.proper_time;
    }
    p.meter.reset();
    return answer(nlohmann::json{{"warnings", report.warnings},
                                 {"differences", raster_differences(*p.scene)},
                                 {"beta", p.flight->speed},
                                 {"time_scale", default_time_scale(*p.scene)}}
                      .dump());
  } catch (const ImageNotDecoded& image) {
    return answer(nlohmann::json{{"images", nlohmann::json::array({image.path})}}.dump());
  } catch (const std::exception& e) {
    return failure(e.what());
  }
}

// Flight: a boost to `speed` (|speed| < 1) along the view, `steps` tenths of rapidity, a turn.
EMSCRIPTEN_KEEPALIVE void lc_set_speed(double speed) {
  if (page().flight && std::abs(speed) < 1) page().flight->set_speed(speed);
}
EMSCRIPTEN_KEEPALIVE void lc_change_speed(int steps) {
  if (page().flight) page().flight->change_speed(steps);
}
EMSCRIPTEN_KEEPALIVE void lc_turn(double yaw, double pitch) {
  if (page().flight) page().flight->turn(yaw, pitch);
}
EMSCRIPTEN_KEEPALIVE void lc_set_split(int split) {
  page().split = split != 0;
}
// Advances the flight by `seconds` of the camera's proper time without drawing (a link's "tau").
EMSCRIPTEN_KEEPALIVE void lc_fly(double seconds) {
  Page& p = page();
  if (!p.flight || !p.scene) return;
  p.flight->advance(seconds, p.scene->black_hole ? &*p.scene->black_hole : nullptr);
  p.proper_time += seconds;
}

// Probes image point (x, y) of the frame as last drawn (what `lightcone locate --pixel` answers
// there, by the same function), as the next of at most two probes (a third starts again).
// Returns {"probe": locate --pixel's JSON, "lines": the readouts of the probes kept, as the
// native viewer's panel shows them} or {"error"} (a point off the picture: the library's rule).
EMSCRIPTEN_KEEPALIVE const char* lc_probe(double x, double y) {
  Page& p = page();
  if (!p.scene) return failure("no scene");
  if (const auto refused = probe_refused(p.frame, x, y)) return failure(*refused);
  try {
    const PixelProbe probe = probe_pixel(p.frame, x, y);
    if (p.probes.size() >= 2) p.probes.clear();
    p.probes.push_back(probe);
    return answer(nlohmann::json{{"probe", nlohmann::json::parse(probe_json(probe, p.frame))},
                                 {"lines", probe_lines(p.probes, p.frame)}}
                      .dump());
  } catch (const std::exception& e) {
    return failure(e.what());
  }
}

// Forgets the probes.
EMSCRIPTEN_KEEPALIVE void lc_clear_probes() {
  page().probes.clear();
}

// Advances the flight by `flown` of the camera's proper time and draws a frame of `width` x
// `height` pixels into the canvas, `seconds` after the last (the exposure follows in those).
// Returns the numbers the page shows.
EMSCRIPTEN_KEEPALIVE const char* lc_frame(double flown, double seconds, int width, int height) {
  Page& p = page();
  if (!p.scene || !p.renderer) return failure("no scene");
  try {
    const BlackHole* hole = p.scene->black_hole ? &*p.scene->black_hole : nullptr;
    p.flight->advance(flown, hole);
    p.proper_time += flown;
    if (!p.relativistic || p.relativistic->width() != width || p.relativistic->height() != height) {
      p.relativistic = std::make_unique<FloatTarget>(width, height);
      p.classical = std::make_unique<FloatTarget>(width, height);
    }
    p.frame.camera = p.flight->camera;
    p.frame.camera.width = width;
    p.frame.camera.height = height;
    const FrameDraw seen =
        draw_scene(*p.renderer, p.frame, *p.relativistic, false, p.frame_emission);
    const bool split = p.split && !p.scene->black_hole;
    if (split) {
      p.still.camera = p.frame.camera;
      p.still.render.relativity = false;
      draw_scene(*p.renderer, p.still, *p.classical, false, p.still_emission);
    }
    const RenderSettings& render = p.scene->render;
    const double exposure = render.auto_exposure
                                ? p.meter.follow(*p.relativistic, render.tonemap, seconds)
                                : render.exposure;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    p.display->draw(*p.relativistic, split ? p.classical.get() : nullptr, exposure, render.tonemap);
    const Camera& camera = p.flight->camera;
    const double beta = length(camera.world_line.velocity);
    return answer(nlohmann::json{
        {"beta", beta},
        {"beta_text", speed_text(beta, 3)},  // never 1 below c (the program's rule)
        {"gamma", 1 / std::sqrt(std::max(0.0, 1 - beta * beta))},
        {"doppler", {seen.doppler_min, seen.doppler_max}},
        {"proper_time", p.proper_time},
        {"exposure",
         exposure}}.dump());
  } catch (const std::exception& e) {
    return failure(e.what());
  }
}

// `lightcone view --benchmark FRAMES` in the page: the same scripted flight through the current
// scene, drawn `frames` times at width x height with the GL finished after each frame, for the
// comparison with the native viewer. Returns {"frames", "seconds", "fps", "triangles"}.
EMSCRIPTEN_KEEPALIVE const char* lc_benchmark(int frames, int width, int height) {
  Page& p = page();
  if (!p.scene || !p.renderer) return failure("no scene");
  try {
    const FloatTarget target(width, height);
    const FlightBenchmark run = benchmark_flight(*p.renderer, *p.scene, target, frames, false);
    return answer(nlohmann::json{{"frames", frames},
                                 {"seconds", run.seconds},
                                 {"fps", frames / std::max(run.seconds, 1e-9)},
                                 {"triangles", run.triangles}}
                      .dump());
  } catch (const std::exception& e) {
    return failure(e.what());
  }
}

// Table l's column (j, i) of RGB-to-spectrum coefficients as the page fits them (64 nodes of
// 3), for the test that compares them with the native build's table.
EMSCRIPTEN_KEEPALIVE const char* lc_table_column(int l, int j, int i) {
  constexpr int res = kRgbToSpectrumRes;
  if (l < 0 || l > 2 || j < 0 || j > res - 2 || i < 0 || i > res - 2) return failure("no column");
  const float* table = detail::rgb_to_spectrum_table(l, j, i);
  std::vector<float> column;
  for (int k = 0; k < res; ++k)
    for (int n = 0; n < 3; ++n) column.push_back(table[rgb_to_spectrum_cell(l, k, j, i, res) + n]);
  return answer(nlohmann::json(column).dump());
}

}  // extern "C"

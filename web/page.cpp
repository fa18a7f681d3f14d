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
#include <vector>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "viewer/flight.hpp"

namespace lightcone {
namespace {

// As the native viewer: the emission tables are kept while they serve the frames, and the
// automatic exposure is metered on every 4th pixel of every 4th row and followed with a time
// constant of half a second.
constexpr double kEmissionMargin = 0.25;
constexpr int kMeteringStep = 4;
constexpr double kMeteringTime = 0.5;

struct Page {
  EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context = 0;
  std::unique_ptr<RasterRenderer> renderer;
  std::unique_ptr<DisplayPass> display;
  std::unique_ptr<FloatTarget> relativistic, classical;
  // The scene as loaded, and as drawn (the flight's camera): each kept with its emission tables.
  std::unique_ptr<Scene> scene;
  Scene frame, still;
  std::unique_ptr<EmissionTable> frame_emission, still_emission;
  std::unique_ptr<Flight> flight;
  bool split = false;
  double proper_time = 0;  // the camera's clock
  double metered = 0;
  bool metered_yet = false;
  std::vector<float> subject;
  std::string result;  // what the last call returns to JavaScript
};

Page& page() {
  static Page p;
  return p;
}

const char* answer(std::string text) {
  page().result = std::move(text);
  return page().result.c_str();
}

const char* failure(const std::string& message) {
  return answer(nlohmann::json{{"error", message}}.dump());
}

// One picture of `scene` into `target`, as the native viewer draws it.
LogDopplerRange draw_scene(const Scene& scene, const FloatTarget& target,
                           std::unique_ptr<EmissionTable>& emission) {
  const ResolvedScene resolved = resolve_scene(scene);
  if (!emission || !emission->serves(resolved)) {
    emission.reset();
    emission = std::make_unique<EmissionTable>(resolved, kEmissionMargin);
  }
  target.bind();
  page().renderer->prepare(resolved, *emission, {}, false);
  page().renderer->pass();
  return visible_log_doppler(resolved, false);
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
  try {
    p.renderer = std::make_unique<RasterRenderer>();
    p.display = std::make_unique<DisplayPass>();
  } catch (const std::exception& e) {
    return failure(e.what());
  }
  return answer(nlohmann::json{{"gl", gl_description()}}.dump());
}

// Reads the scene file at `path` (in the page's file system) with `overrides` ("key.path=value"
// lines, as --set takes them). On success the page draws it from its camera; on failure the
// previous scene stays. Returns {"warnings", "differences"} or {"error"}.
EMSCRIPTEN_KEEPALIVE const char* lc_load(const char* path, const char* overrides) {
  std::vector<std::string> sets;
  std::istringstream lines(overrides);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) sets.push_back(line);
  try {
    SceneLoadReport report;
    auto scene = std::make_unique<Scene>(load_scene_file(path, sets, report));
    Page& p = page();
    p.scene = std::move(scene);
    p.frame = p.still = *p.scene;
    p.frame_emission.reset();
    p.still_emission.reset();
    p.flight = std::make_unique<Flight>(p.scene->camera);
    p.metered_yet = false;
    p.proper_time = p.scene->camera.motion.proper_time;
    return answer(
        nlohmann::json{{"warnings", report.warnings}, {"differences", raster_differences(*p.scene)}}
            .dump());
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

// Advances the flight by `seconds` of the camera's proper time and draws a frame of
// `width` x `height` pixels into the canvas. Returns the numbers the page shows.
EMSCRIPTEN_KEEPALIVE const char* lc_frame(double seconds, int width, int height) {
  Page& p = page();
  if (!p.scene || !p.renderer) return failure("no scene");
  try {
    const BlackHole* hole = p.scene->black_hole ? &*p.scene->black_hole : nullptr;
    p.flight->advance(seconds, hole);
    p.proper_time += seconds;
    if (!p.relativistic || p.relativistic->width() != width || p.relativistic->height() != height) {
      p.relativistic = std::make_unique<FloatTarget>(width, height);
      p.classical = std::make_unique<FloatTarget>(width, height);
    }
    p.frame.camera = p.flight->camera;
    p.frame.camera.width = width;
    p.frame.camera.height = height;
    const LogDopplerRange seen = draw_scene(p.frame, *p.relativistic, p.frame_emission);
    const bool split = p.split && !p.scene->black_hole;
    if (split) {
      p.still.camera = p.frame.camera;
      p.still.render.relativity = false;
      draw_scene(p.still, *p.classical, p.still_emission);
    }
    const RenderSettings& render = p.scene->render;
    if (render.auto_exposure) {
      const double target = auto_exposure(p.relativistic->sampled(kMeteringStep, p.subject),
                                          render.tonemap, p.subject);
      p.metered = p.metered_yet
                      ? p.metered + (target - p.metered) * (1 - std::exp(-seconds / kMeteringTime))
                      : target;
      p.metered_yet = true;
    }
    const double exposure = render.auto_exposure ? p.metered : render.exposure;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    p.display->draw(*p.relativistic, split ? p.classical.get() : nullptr, exposure, render.tonemap);
    const Camera& camera = p.flight->camera;
    const double beta = length(camera.world_line.velocity);
    return answer(nlohmann::json{
        {"beta", beta},
        {"gamma", 1 / std::sqrt(std::max(0.0, 1 - beta * beta))},
        {"doppler", {std::exp(seen.lo), std::exp(seen.hi)}},
        {"proper_time", p.proper_time},
        {"exposure",
         exposure}}.dump());
  } catch (const std::exception& e) {
    return failure(e.what());
  }
}

}  // extern "C"

// The raster renderer against the limit its geometry sets (issue: "In bench/, the same
// tessellated triangles of a frame drawn by a pass-through shader into the same targets. Report
// lightcone's frame time over it"):
//   RasterFrame/<scene>     one frame as the viewer draws it, after a first one: resolve the
//                           scene, its emission tables (kept from the frame before while they
//                           serve, as the viewer keeps them: EmissionTable::keep), prepare
//                           (tessellation, colour rows, lights), one pass, glFinish; headless
//                           through EGL (llvmpipe here). prepare_ms and pass_ms split it;
//                           tables_ms is the part of prepare_ms that resolves the scene and
//                           finds its emission tables.
//   RasterBaseline/<scene>  the same prepared triangles drawn by BaselinePass (pass-through
//                           vertices, one colour) into the same target, glFinish.
//   RasterFloor/<scene>     the frame with its bodies shaded for nothing: RasterFrame's
//                           preparation, then BaselinePass's bodies and the frame's own sky
//                           behind them (RasterRenderer::sky_pass), glFinish. What no body
//                           program can take the frame below; prepare_ms and pass_ms split it.
// The ratio of the first two times is the figure; `triangles` counts both. Scenes: street.json at
// 640x360 and 1280x720, street-lit.json (with its shadows: the maps are drawn with the first
// frame and kept, as in the viewer) at 640x360, and the 1,000-body swarm (1.28M triangles) at
// 1280x720.
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/raster/baseline_pass.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "meshes.hpp"

using namespace lightcone;

namespace {

Scene raster_scene(const std::string& name, int width, int height) {
  if (name == "swarm") {
    Scene s = bench::swarm_scene(1000, true, width, height);
    s.camera.samples = 1;
    return s;
  }
  SceneLoadReport report;
  return load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/" + name,
                         {"camera.width=" + std::to_string(width),
                          "camera.height=" + std::to_string(height), "camera.samples=1"},
                         report);
}

// What both benchmarks draw with: the scene, a headless context and a renderer drawing into a
// float target of the scene's size (bound).
struct RasterSetup {
  RasterSetup(const std::string& name, int width, int height)
      : scene(raster_scene(name, width, height)), target(width, height) {
    target.bind();
  }
  const Scene scene;
  const HeadlessGlContext context;  // before the GL objects below
  RasterRenderer renderer;
  const FloatTarget target;
};

// Frames as the viewer draws them, after a first one, untimed (what the viewer keeps from frame
// to frame, the tables, the lights' shadow maps, the programs, is made with it): each resolved,
// its emission tables kept while they serve (EmissionTable::keep), prepared, then drawn by
// `draw`; prepare_ms, pass_ms (the drawing) and tables_ms (resolving and finding the tables).
template <class Draw>
void time_frames(benchmark::State& state, RasterSetup& setup, const Draw& draw) {
  std::unique_ptr<EmissionTable> emission;
  const auto tables = [&emission](const ResolvedScene& resolved) -> const EmissionTable& {
    return EmissionTable::keep(emission, resolved);
  };
  {
    const ResolvedScene resolved = resolve_scene(setup.scene);
    setup.renderer.prepare(resolved, tables(resolved));
    setup.renderer.pass();
    glFinish();
  }
  std::size_t triangles = 0;
  double prepare_s = 0, pass_s = 0, tables_s = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const ResolvedScene resolved = resolve_scene(setup.scene);
    const EmissionTable& frame_emission = tables(resolved);
    tables_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    triangles = setup.renderer.prepare(resolved, frame_emission).triangles;
    glFinish();
    const auto t1 = std::chrono::steady_clock::now();
    draw(resolved);
    glFinish();
    prepare_s += std::chrono::duration<double>(t1 - t0).count();
    pass_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["prepare_ms"] = 1e3 * prepare_s / n;
  state.counters["pass_ms"] = 1e3 * pass_s / n;
  state.counters["tables_ms"] = 1e3 * tables_s / n;
}

void RasterFrame(benchmark::State& state, const std::string& name, int width, int height) {
  RasterSetup setup(name, width, height);
  time_frames(state, setup, [&](const ResolvedScene&) { setup.renderer.pass(); });
}

void RasterBaseline(benchmark::State& state, const std::string& name, int width, int height) {
  RasterSetup setup(name, width, height);
  const ResolvedScene resolved = resolve_scene(setup.scene);
  const EmissionTable emission(resolved);
  setup.renderer.prepare(resolved, emission);
  const BaselinePass baseline;
  std::size_t triangles = 0;
  for (auto _ : state) {
    triangles = baseline.draw(resolved, setup.renderer);
    glFinish();
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}

void RasterFloor(benchmark::State& state, const std::string& name, int width, int height) {
  RasterSetup setup(name, width, height);
  const BaselinePass baseline;
  time_frames(state, setup, [&](const ResolvedScene& resolved) {
    baseline.draw(resolved, setup.renderer);
    setup.renderer.sky_pass();
  });
}

void register_pair(const std::string& label, const std::string& scene, int width, int height) {
  benchmark::RegisterBenchmark(("RasterFrame/" + label).c_str(), RasterFrame, scene, width, height)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark(("RasterBaseline/" + label).c_str(), RasterBaseline, scene, width,
                               height)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark(("RasterFloor/" + label).c_str(), RasterFloor, scene, width, height)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
}

const bool registered = [] {
  register_pair("street/640x360", "street.json", 640, 360);
  register_pair("street/1280x720", "street.json", 1280, 720);
  register_pair("street-lit/640x360", "street-lit.json", 640, 360);
  register_pair("swarm/1280x720", "swarm", 1280, 720);
  return true;
}();

}  // namespace

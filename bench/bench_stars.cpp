// The stars (issue: "Loading the catalogue takes at most 20 ms"; "the whole catalogue at
// 1920x1080 adds at most 10 % to the render time of sky.json, in the tracer and in the viewer"):
//   StarCatalogueLoad      read_star_catalogue of the bundled catalogue (8,789 naked-eye stars),
//                          file to memory, checked.
//   SkyTrace/stars:0, :1   scenes/sky.json at 1920x1080 and its own 4 samples, on 2 threads,
//                          render_image whole; without and with sky.stars = true. The ratio of
//                          the two times is the figure; on a shared machine its noise is larger
//                          than the stars' cost, which stars_ms (RenderStats::stars_seconds:
//                          finding and depositing them) and stars_share (of the render) time
//                          directly.
//   SkyRaster/stars:0, :1  one raster frame of the same at 1920x1080 as the viewer draws it
//                          (resolve, prepare, one pass, glFinish), headless through EGL.
//   SkyStarsCpu            the CPU's share of SkyRaster/stars:1: every star's image (star_images).
//   HoleStarsCpu/0, /1, /2 near the hole (black-hole.json at 640x360 with sky.stars): the images
//                          of orders 0 to 2 of every star from a lens table (0: all 26,367 of
//                          them, of which the counter says how many land in the picture), the
//                          lens table itself (1: 3 x 256 exact lens solves, made again when the
//                          camera's radius changes) and the photometry's table (2).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/star_field.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/io/star_catalogue.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/trace/renderer.hpp"

using namespace lightcone;

namespace {

void StarCatalogueLoad(benchmark::State& state) {
  const auto path = bright_star_catalogue_path();
  std::size_t stars = 0;
  for (auto _ : state) {
    const auto catalogue = read_star_catalogue(path);
    stars = catalogue.size();
    benchmark::DoNotOptimize(catalogue.data());
  }
  state.counters["stars"] = static_cast<double>(stars);
}
BENCHMARK(StarCatalogueLoad)->Unit(benchmark::kMillisecond);

Scene sky_1080p(bool stars) {
  std::vector<std::string> overrides = {"camera.width=1920", "camera.height=1080"};
  if (stars) overrides.push_back("sky.stars=true");
  SceneLoadReport report;
  return load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/sky.json", overrides, report);
}

void SkyTrace(benchmark::State& state) {
  const Scene scene = sky_1080p(state.range(0) != 0);
  RenderOptions options;
  options.threads = 2;
  RenderStats stats;
  double stars = 0, total = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(render_image(scene, options, &stats).rgb.data());
    stars += stats.stars_seconds;
    total += stats.seconds;
  }
  state.counters["stars_ms"] = 1e3 * stars / static_cast<double>(state.iterations());
  state.counters["stars_share"] = stars / total;
}
BENCHMARK(SkyTrace)
    ->ArgName("stars")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();

void SkyRaster(benchmark::State& state) {
  const Scene scene = sky_1080p(state.range(0) != 0);
  const HeadlessGlContext context;
  RasterRenderer renderer;
  const FloatTarget target(scene.camera.width, scene.camera.height);
  target.bind();
  for (auto _ : state) {
    const ResolvedScene resolved = resolve_scene(scene);
    const EmissionTable emission(resolved);
    renderer.prepare(resolved, emission);
    renderer.pass();
    glFinish();
  }
}
BENCHMARK(SkyRaster)
    ->ArgName("stars")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void SkyStarsCpu(benchmark::State& state) {
  const Scene scene = sky_1080p(true);
  const ResolvedScene resolved = resolve_scene(scene);
  const StarPhotometry photometry = star_photometry(resolved, 1.0);
  std::size_t n = 0;
  for (auto _ : state) n = star_images(resolved, photometry).size();
  state.counters["images"] = static_cast<double>(n);
}
BENCHMARK(SkyStarsCpu)->Unit(benchmark::kMillisecond);

void HoleStarsCpu(benchmark::State& state) {
  SceneLoadReport report;
  const Scene scene =
      load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/black-hole.json",
                      {"camera.width=640", "camera.height=360", "sky.stars=true"}, report);
  const ResolvedScene resolved = resolve_scene(scene);
  const StarPhotometry photometry = star_photometry(resolved, 1.0);
  const FarImageTable lens = star_lens_table(*resolved.hole);
  std::size_t n = 0;
  for (auto _ : state) {
    if (state.range(0) == 0) n = star_images(resolved, photometry, &lens).size();
    if (state.range(0) == 1) benchmark::DoNotOptimize(star_lens_table(*resolved.hole));
    if (state.range(0) == 2) benchmark::DoNotOptimize(star_photometry(resolved, 1.0));
  }
  state.counters["images"] = static_cast<double>(n);
}
BENCHMARK(HoleStarsCpu)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace

// The black hole (issue: "Tracer: the black-hole.json sky and disk at 1920x1080, 1 sample, in at
// most 0.5 s on 2 threads"):
//   BlackHole              scenes/black-hole.json at 1920x1080, 1 sample, on 2 threads: the
//                          time is render_image's whole (setup, tracing, exposure); cpu_s is the
//                          process's CPU time per render, summed over its threads, which a
//                          shared machine disturbs less than the wall time; setup_s the
//                          time to resolve the scene and build its tables (RenderStats).
//   BlackHoleRays          follow_curved_ray and curved_radiance alone through every pixel
//                          centre of that image, on one thread: ns_per_ray.
#include <benchmark/benchmark.h>

#include <ctime>
#include <string>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/trace/curved_ray.hpp"
#include "lightcone/trace/renderer.hpp"

using namespace lightcone;

namespace {

Scene black_hole_1080p() {
  SceneLoadReport report;
  return load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/black-hole.json",
                         {"camera.width=1920", "camera.height=1080", "camera.samples=1"}, report);
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void BM_BlackHole(benchmark::State& state) {
  const Scene scene = black_hole_1080p();
  RenderOptions options;
  options.threads = 2;
  RenderStats stats;
  double cpu = 0, setup = 0;
  for (auto _ : state) {
    const double before = process_cpu_seconds();
    Image image = render_image(scene, options, &stats);
    cpu += process_cpu_seconds() - before;
    setup += stats.setup_seconds;
    benchmark::DoNotOptimize(image.rgb.data());
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(stats.rays) * n, benchmark::Counter::kIsRate);
  state.counters["cpu_s"] = cpu / n;
  state.counters["setup_s"] = setup / n;
}
BENCHMARK(BM_BlackHole)->Unit(benchmark::kMillisecond)->Iterations(5)->UseRealTime();

void BM_BlackHoleRays(benchmark::State& state) {
  const Scene scene = black_hole_1080p();
  const ResolvedScene resolved = resolve_scene(scene);
  const EmissionTable emission(resolved);
  const int width = scene.camera.width, height = scene.camera.height;
  for (auto _ : state) {
    double sum = 0;
    for (int j = 0; j < height; ++j)
      for (int i = 0; i < width; ++i) {
        const Vec3 u = look_direction(resolved.camera, i + 0.5, j + 0.5);
        const CurvedRay ray = follow_curved_ray(*resolved.hole, u);
        sum += curved_radiance(resolved, emission, ray).g;
      }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["ns_per_ray"] = benchmark::Counter(
      static_cast<double>(width) * height * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_BlackHoleRays)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

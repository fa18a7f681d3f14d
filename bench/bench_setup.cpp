// A render's work outside its rays (issue: "colour tables at a small constant per colour" and
// "PNG encoding at most 10 % of the process"):
//   ColourTables/distinct_colours   the emission tables (EmissionTable) of 1,000 unlit spheres
//                                   of 1,000 distinct RGB colours, each with its own velocity
//                                   (up to 0.5c), seen at 640 x 360. Target: at most 50 ms.
//   ColourTables/tabulated_spectrum the same for 1,920 spheres sharing one tabulated flat
//                                   spectrum. Target: at most 20 ms.
//   PngEncode                       encoding street.json's 1920 x 1080 picture (1 sample,
//                                   tone-mapped as the command does) as PNG, on one thread;
//                                   bench/targets.py divides it by the whole process's time.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <random>
#include <string>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/trace/renderer.hpp"

using namespace lightcone;

namespace {

// `count` unit spheres in a grid before the camera, each with its own velocity up to 0.5c,
// coloured by `pattern(i)`.
template <class PatternOf>
Scene sphere_grid(int count, PatternOf pattern) {
  Scene s;
  s.camera.width = 640;
  s.camera.height = 360;
  s.camera.samples = 1;
  s.camera.fov_degrees = 60;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const int side = 48;
  s.objects.reserve(count);
  for (int i = 0; i < count; ++i) {
    Object o;
    o.name = "s" + std::to_string(i);
    o.shape = Sphere{0.3};
    o.world_line.position = {i % side - side / 2.0, (i / side) % side - side / 2.0, -30.0};
    o.world_line.velocity = {0.35 * u(rng), 0.35 * u(rng), 0};
    o.material.pattern = pattern(i);
    s.objects.push_back(std::move(o));
  }
  return s;
}

void ColourTables(benchmark::State& state, const Scene& scene) {
  const ResolvedScene resolved = resolve_scene(scene);
  for (auto _ : state) {
    const EmissionTable table(resolved);
    benchmark::DoNotOptimize(&table);
  }
}

void ColourTablesDistinct(benchmark::State& state) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> channel(0, 1);
  ColourTables(state, sphere_grid(1000, [&](int) -> Pattern {
                 return SolidColor{{channel(rng), channel(rng), channel(rng)}};
               }));
}
BENCHMARK(ColourTablesDistinct)
    ->Name("ColourTables/distinct_colours")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void ColourTablesTabulated(benchmark::State& state) {
  const EmissionSpectrum flat{{300, 900}, {1, 1}};
  ColourTables(state, sphere_grid(1920, [&](int) -> Pattern { return flat; }));
}
BENCHMARK(ColourTablesTabulated)
    ->Name("ColourTables/tabulated_spectrum")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void PngEncode(benchmark::State& state) {
  SceneLoadReport report;
  const Scene scene =
      load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/street.json",
                      {"camera.width=1920", "camera.height=1080", "camera.samples=1"}, report);
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const Image display = tone_map(render_image(scene, RenderOptions{}), scene.render.tonemap);
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::vector<unsigned char> png = encode_png(display);
    bytes = png.size();
    benchmark::DoNotOptimize(png.data());
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(PngEncode)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

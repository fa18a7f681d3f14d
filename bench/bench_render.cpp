// Benchmarks named in the issues. Compare within one run (the machines are shared and noisy):
//   Street/relativistic vs Street/classical           (relativistic cost, target <= 1.25x)
//   Swarm/relativistic vs Swarm/classical             (target <= 2x)
//   Swarm throughput vs StaticStreet throughput       (target >= 1/3)
//   Memory/instances:1000 vs Memory/instances:1       (acceleration + mesh bytes)
//   StreetDefault/variant:0 (the scene's defaults: spectral, physical searchlight) vs
//     variant:1 (doppler off)                         (spectral cost, target <= 1.10x)
//     variant:2 (relativity false)                    (relativistic cost, target <= 1.25x)
//   StreetLitColour/spectral vs StreetLitColour/off   (spectral cost with lights, <= 1.25x)
//   StreetLit/surface vs StreetLit/camera             (exact light delay cost, target <= 1.5x)
// The StreetDefault and StreetLitColour figures run on one thread, the others on all cores.
#include <benchmark/benchmark.h>

#include <array>
#include <map>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/tracer.hpp"
#include "meshes.hpp"

using namespace lightcone;
using lightcone::bench::swarm_scene;

namespace {

Scene street(bool relativity, bool moving) {
  SceneLoadReport report;
  Scene s =
      load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/street.json",
                      {"camera.width=1920", "camera.height=1080", "camera.samples=1"}, report);
  s.render.relativity = relativity;
  // The geometry benchmarks compare tracing costs; colour has its own benchmark.
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kOff;
  if (!moving) s.camera.world_line.velocity = {};
  return s;
}

void render_and_count(benchmark::State& state, const Scene& scene, int threads = 0) {
  RenderStats stats;
  RenderOptions options;
  options.threads = threads;
  for (auto _ : state) {
    Image image = render_image(scene, options, &stats);
    benchmark::DoNotOptimize(image.rgb.data());
  }
  state.counters["rays_per_s"] = benchmark::Counter(
      static_cast<double>(stats.rays) * state.iterations(), benchmark::Counter::kIsRate);
}

void BM_Street(benchmark::State& state) {
  render_and_count(state, street(state.range(0) != 0, true));
}
BENCHMARK(BM_Street)
    ->ArgName("relativistic")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();

Scene scene_at_1080p(const char* name) {
  SceneLoadReport report;
  return load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/" + name,
                         {"camera.width=1920", "camera.height=1080", "camera.samples=1"}, report);
}

// street.json exactly as the scene file says (spectral colour, physical searchlight), against
// the same render with the Doppler colour off and against its classical (relativity false)
// render, on one thread.
void BM_StreetDefault(benchmark::State& state) {
  Scene s = scene_at_1080p("street.json");
  if (state.range(0) == 1) s.render.doppler = DopplerModel::kOff;
  if (state.range(0) == 2) s.render.relativity = false;
  render_and_count(state, s, 1);
}
BENCHMARK(BM_StreetDefault)
    ->ArgName("variant")
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();

// street-lit.json with spectral colour against the Doppler colour off, on one thread.
void BM_StreetLitColour(benchmark::State& state) {
  Scene s = scene_at_1080p("street-lit.json");
  s.render.doppler = state.range(0) != 0 ? DopplerModel::kSpectral : DopplerModel::kOff;
  render_and_count(state, s, 1);
}
BENCHMARK(BM_StreetLitColour)
    ->ArgName("spectral")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

// The street at night at 0.8c, eight point lamps with shadows: the exact (surface) light delay
// against seed 004's camera-centric approximation.
void BM_StreetLit(benchmark::State& state) {
  Scene s = scene_at_1080p("street-lit.json");
  s.render.light_source_delay =
      state.range(0) != 0 ? LightSourceDelay::kSurface : LightSourceDelay::kCamera;
  render_and_count(state, s);
}
BENCHMARK(BM_StreetLit)
    ->ArgName("surface")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2)
    ->UseRealTime();

void BM_StaticStreet(benchmark::State& state) {
  render_and_count(state, street(true, false));
}
BENCHMARK(BM_StaticStreet)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

void BM_Swarm(benchmark::State& state) {
  render_and_count(state, swarm_scene(1000, state.range(0) != 0));
}
BENCHMARK(BM_Swarm)
    ->ArgName("relativistic")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();

// Memory for `instances` uses of one mesh: Embree's acceleration structures plus the mesh.
void BM_Memory(benchmark::State& state) {
  const Scene scene = swarm_scene(static_cast<int>(state.range(0)), true, 64, 64);
  std::size_t bytes = 0;
  for (auto _ : state) {
    const ResolvedScene resolved = resolve_scene(scene);
    const Tracer tracer(resolved);
    const Mesh& mesh = *std::get<MeshShape>(scene.objects[0].shape).mesh;
    bytes = tracer.acceleration_bytes() + mesh.positions.size() * sizeof(Vec3) +
            mesh.triangles.size() * sizeof(mesh.triangles[0]) +
            resolved.bodies.size() * sizeof(ResolvedBody) + scene.objects.size() * sizeof(Object);
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_Memory)
    ->ArgName("instances")
    ->Arg(1)
    ->Arg(1000)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

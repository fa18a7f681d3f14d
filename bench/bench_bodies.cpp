// Per-body cost of a render's setup (issue: 10^6 bodies under 1.5 GB peak and 10 s of setup).
//   Bodies/bodies:N   N unit spheres of N distinct colours, each with its own velocity (up to
//                     0.5c), on a 16 x 16 image with one sample: the time is the setup
//                     (resolving the scene, the emission and lighting tables, the acceleration
//                     structure); peak_rss_bytes is the whole process's peak resident memory
//                     during the benchmark, the scene model included.
// Run one size per process for the peak (it is reset per benchmark through clear_refs, which
// some kernels refuse; then the figure is the process's peak so far):
//   lightcone_bench --benchmark_filter='Bodies/bodies:1000000'
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <fstream>
#include <random>
#include <string>

#include "lightcone/trace/renderer.hpp"

using namespace lightcone;

namespace {

Scene spheres(int count) {
  Scene s;
  s.camera.width = 16;
  s.camera.height = 16;
  s.camera.samples = 1;
  s.camera.fov_degrees = 60;
  s.render.relativity = true;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<float> colour(0, 1);
  s.objects.reserve(count);
  const int side = static_cast<int>(std::cbrt(static_cast<double>(count))) + 1;
  for (int i = 0; i < count; ++i) {
    Object o;
    o.name = fmt::format("s{}", i);
    o.shape = Sphere{0.3};
    o.world_line.position = {i % side - side / 2.0, (i / side) % side - side / 2.0,
                             -5.0 - i / (side * side)};
    o.world_line.velocity = {0.5 * u(rng), 0.5 * u(rng), 0};
    o.material.pattern = SolidColor{{colour(rng), colour(rng), colour(rng)}};
    s.objects.push_back(std::move(o));
  }
  s.sky.pattern = SolidColor{{0.05f, 0.05f, 0.1f}};
  return s;
}

long long status_kilobytes(const char* field) {
  std::ifstream status("/proc/self/status");
  std::string key;
  long long value = 0;
  while (status >> key) {
    if (key == field) {
      status >> value;
      return value;
    }
    status.ignore(1 << 20, '\n');
  }
  return -1;
}

void BM_Bodies(benchmark::State& state) {
  std::ofstream("/proc/self/clear_refs") << "5";  // resets the peak (VmHWM)
  const Scene scene = spheres(static_cast<int>(state.range(0)));
  RenderOptions options;
  for (auto _ : state) {
    Image image = render_image(scene, options);
    benchmark::DoNotOptimize(image.rgb.data());
  }
  state.counters["peak_rss_bytes"] = 1024.0 * status_kilobytes("VmHWM:");
  state.counters["bodies"] = static_cast<double>(state.range(0));
}
BENCHMARK(BM_Bodies)
    ->ArgName("bodies")
    ->Arg(1000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace

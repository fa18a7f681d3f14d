// The cost of motion beyond inertial (issue: 100 bodies on hyperbolic or keyframed world-lines
// at 1920x1080 cost at most 1.5x the same bodies moving inertially).
//   Motion/inertial     100 spheres, each with its own velocity (up to 0.6c), in a grid that
//                       fills the view; one sample per pixel, 1920 x 1080.
//   Motion/hyperbolic   the same spheres, each starting with the same velocity and then
//                       accelerating in two phases of different directions.
//   Motion/keyframed    the same spheres, each on four keyframes.
//   Motion/spinning     the same inertial spheres, each spinning (rim speed up to 0.5).
// The ratio to Motion/inertial in one run is the figure.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <random>
#include <string>

#include "lightcone/trace/renderer.hpp"

using namespace lightcone;

namespace {

enum class Kind { kInertial, kHyperbolic, kKeyframed, kSpinning };

Scene bodies(Kind kind) {
  Scene s;
  s.camera.world_line = {20, {0, 0, 12}, {}};
  s.camera.width = 1920;
  s.camera.height = 1080;
  s.camera.fov_degrees = 60;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 100; ++i) {
    Object o;
    o.name = fmt::format("b{}", i);
    o.shape = Sphere{0.6};
    o.world_line = {0, {2.0 * (i % 10) - 9.0 - 6, 1.4 * (i / 10 % 10) - 6.3, -2.0}, {}};
    o.world_line.velocity = {0.3 + 0.3 * std::abs(u(rng)), 0.1 * u(rng), 0.1 * u(rng)};
    o.material.pattern = Checker{0.2, {{1, 0.8, 0.3}, {0.2, 0.3, 0.9}}};
    if (kind == Kind::kHyperbolic)
      o.motion.phases = {{6, {0.02 * u(rng), 0.02 * u(rng), 0.01 * u(rng)}},
                         {8, {0.02 * u(rng), 0.02 * u(rng), 0}}};
    if (kind == Kind::kKeyframed) {
      const Vec3 v = o.world_line.velocity, p = o.world_line.position;
      for (int k = 0; k < 4; ++k)
        o.motion.keyframes.push_back(
            {6.0 * k, p + v * (6.0 * k) + Vec3{0.3 * u(rng), 0.3 * u(rng), 0.2 * u(rng)}});
    }
    if (kind == Kind::kSpinning) o.spin = Spin{normalize(Vec3{u(rng), u(rng), u(rng)}), 0.8};
    s.objects.push_back(std::move(o));
  }
  s.sky.pattern = SkyGrid{};
  return s;
}

void Motion(benchmark::State& state, Kind kind) {
  const Scene scene = bodies(kind);
  for (auto _ : state) benchmark::DoNotOptimize(render_image(scene, {}));
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(scene.camera.width) * scene.camera.height,
                         benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK_CAPTURE(Motion, inertial, Kind::kInertial)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Motion, hyperbolic, Kind::kHyperbolic)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Motion, keyframed, Kind::kKeyframed)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Motion, spinning, Kind::kSpinning)->Unit(benchmark::kMillisecond);

}  // namespace

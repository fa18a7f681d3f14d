// A probe (issue 57: "A probe takes no longer than one pixel's ray plus the JSON: under 5 ms in
// the CLI, not counting the load"): probe_pixel and its JSON for one pixel of a loaded scene,
// the work `lightcone locate --pixel` does after reading the file (resolving the scene, each
// body met directly, near a hole the curved ray and its chords).
//   ProbePixel/0   terrell.json, a point on the crate (flat spacetime, two moving bodies)
//   ProbePixel/1   street.json, a point on a building (flat, meshes of 1,920 bodies)
//   ProbePixel/2   lensed-clock.json, the clock's secondary image (a curved ray round the hole)
//   ProbePixel/3   infall.json, a point near the falling clocks (a curved ray, falling bodies)
#include <benchmark/benchmark.h>

#include <array>
#include <string>

#include "lightcone/frame/pixel_probe.hpp"
#include "lightcone/io/locate_json.hpp"
#include "lightcone/io/scene_file.hpp"

using namespace lightcone;

namespace {

struct ProbeCase {
  const char* scene;
  double x, y;
};
constexpr std::array<ProbeCase, 4> kCases{{{"terrell.json", 699.25, 256.5},
                                           {"street.json", 700.5, 300.5},
                                           {"lensed-clock.json", 284, 304},
                                           {"infall.json", 600.5, 200.5}}};

void ProbePixel(benchmark::State& state) {
  const ProbeCase& c = kCases[static_cast<std::size_t>(state.range(0))];
  SceneLoadReport report;
  const Scene scene =
      load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/" + c.scene, {}, report);
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::string json = probe_json(probe_pixel(scene, c.x, c.y), scene);
    bytes += json.size();
    benchmark::DoNotOptimize(json.data());
  }
  state.SetLabel(c.scene);
  benchmark::DoNotOptimize(bytes);
}
BENCHMARK(ProbePixel)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

}  // namespace

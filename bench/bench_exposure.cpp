// The automatic exposure on a 1920x1080 picture with a subject (issue 54: at most 2 % of a
// render). AutoExposure/threads:1 and threads:0 (all cores) time auto_exposure alone; set them
// against a default render's time (bench_render.cpp, or a whole-process render at the scene's
// defaults against --set render.exposure=0).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "lightcone/frame/tone_map.hpp"

using namespace lightcone;

namespace {

// A picture like a render's: a sky of slowly varying blue, 30 % of it bodies whose luminance
// spans 10 octaves, their edges covered in part, and black where the bodies are unlit.
struct Picture {
  Image image;
  std::vector<float> subject;
};

const Picture& picture() {
  static const Picture p = [] {
    Picture out;
    const int width = 1920, height = 1080;
    out.image.width = width, out.image.height = height;
    out.image.rgb.resize(3 * static_cast<std::size_t>(width) * height);
    out.subject.assign(static_cast<std::size_t>(width) * height, 0.0f);
    std::mt19937 random(1080);
    std::uniform_real_distribution<float> unit(0, 1);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t p = static_cast<std::size_t>(y) * width + x;
        float* c = &out.image.rgb[3 * p];
        const double cell = std::hypot(x % 240 - 120, y % 216 - 108);  // a body in each cell
        if (cell < 70) {
          const float v = unit(random) < 0.1f ? 0.0f : std::exp2(10 * unit(random) - 8);
          c[0] = v, c[1] = 0.8f * v, c[2] = 0.6f * v;
          out.subject[p] = cell > 69 ? unit(random) : 1.0f;
        } else {
          c[0] = 0.2f, c[1] = 0.3f + 0.1f * y / height, c[2] = 0.5f + 0.01f * unit(random);
        }
      }
    return out;
  }();
  return p;
}

void BM_AutoExposure(benchmark::State& state) {
  const Picture& p = picture();
  const auto threads = static_cast<std::size_t>(state.range(0));
  const auto limit = threads ? std::make_unique<tbb::global_control>(
                                   tbb::global_control::max_allowed_parallelism, threads)
                             : nullptr;
  for (auto _ : state)
    benchmark::DoNotOptimize(auto_exposure(p.image, ToneMap::kFilmic, p.subject));
}
BENCHMARK(BM_AutoExposure)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Scaling the picture by 2^EV (expose), which a fixed exposure of 0 skips.
void BM_Expose(benchmark::State& state) {
  Image image = picture().image;
  const auto threads = static_cast<std::size_t>(state.range(0));
  const auto limit = threads ? std::make_unique<tbb::global_control>(
                                   tbb::global_control::max_allowed_parallelism, threads)
                             : nullptr;
  for (auto _ : state) {
    expose(image, 0.25);
    benchmark::DoNotOptimize(image.rgb.data());
  }
}
BENCHMARK(BM_Expose)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

#include "viewer/frame_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/raster/gl.hpp"
#include "viewer/flight.hpp"

namespace lightcone {
namespace {

constexpr double kMeteringTime = 0.5;  // s

}  // namespace

FrameDraw draw_scene(RasterRenderer& renderer, const Scene& scene, const FloatTarget& target,
                     bool on_gpu, std::unique_ptr<EmissionTable>& emission) {
  const ResolvedScene resolved = resolve_scene(scene);
  const EmissionTable& tables = EmissionTable::keep(emission, resolved);
  target.bind();
  FrameDraw draw;
  draw.triangles = renderer.prepare(resolved, tables, {}, on_gpu).triangles;
  renderer.pass();
  const LogDopplerRange seen = visible_log_doppler(resolved, false);
  draw.doppler_min = std::exp(seen.lo);
  draw.doppler_max = std::exp(seen.hi);
  return draw;
}

FlightBenchmark benchmark_flight(RasterRenderer& renderer, const Scene& scene,
                                 const FloatTarget& target, int frames, bool on_gpu) {
  Flight flight(scene.camera);
  std::size_t triangles = 0;
  Scene frame = scene;
  std::unique_ptr<EmissionTable> emission;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) {
    flight.set_speed(0.9 * std::min(1.0, 3.0 * i / std::max(frames, 1)));
    flight.turn(0.002, 0);
    flight.advance(1.0 / 30, scene.black_hole ? &*scene.black_hole : nullptr);
    frame.camera = flight.camera;
    frame.camera.width = target.width();
    frame.camera.height = target.height();
    triangles += draw_scene(renderer, frame, target, on_gpu, emission).triangles;
    glFinish();
  }
  FlightBenchmark result;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.triangles = frames > 0 ? triangles / static_cast<std::size_t>(frames) : 0;
  return result;
}

double ExposureFollower::follow(const FloatTarget& frame, ToneMap tonemap, double seconds) {
  const double target = frame.metered_exposure(tonemap);
  metered_ = metered_yet_
                 ? metered_ + (target - metered_) * (1 - std::exp(-seconds / kMeteringTime))
                 : target;
  metered_yet_ = true;
  return metered_;
}

}  // namespace lightcone

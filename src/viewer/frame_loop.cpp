#include "viewer/frame_loop.hpp"

#include <cmath>

#include "lightcone/frame/resolved_scene.hpp"

namespace lightcone {
namespace {

constexpr double kEmissionMargin = 0.25;
constexpr int kMeteringStep = 4;
constexpr double kMeteringTime = 0.5;  // s

}  // namespace

FrameDraw draw_scene(RasterRenderer& renderer, const Scene& scene, const FloatTarget& target,
                     bool on_gpu, std::unique_ptr<EmissionTable>& emission) {
  const ResolvedScene resolved = resolve_scene(scene);
  if (!emission || !emission->serves(resolved)) {
    emission.reset();  // (the old tables go before the new are built)
    emission = std::make_unique<EmissionTable>(resolved, kEmissionMargin);
  }
  target.bind();
  FrameDraw draw;
  draw.triangles = renderer.prepare(resolved, *emission, {}, on_gpu).triangles;
  renderer.pass();
  const LogDopplerRange seen = visible_log_doppler(resolved, false);
  draw.doppler_min = std::exp(seen.lo);
  draw.doppler_max = std::exp(seen.hi);
  return draw;
}

double ExposureMeter::follow(const FloatTarget& frame, ToneMap tonemap, double seconds) {
  const double target = auto_exposure(frame.sampled(kMeteringStep, subject_), tonemap, subject_);
  metered_ = metered_yet_
                 ? metered_ + (target - metered_) * (1 - std::exp(-seconds / kMeteringTime))
                 : target;
  metered_yet_ = true;
  return metered_;
}

}  // namespace lightcone

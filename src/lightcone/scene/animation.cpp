#include "lightcone/scene/animation.hpp"

#include <fmt/format.h>

#include <cmath>

#include "lightcone/physics/keyframe_world_line.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/world_line.hpp"

namespace lightcone {
namespace {

// The camera's proper time (in the model's units) at world time `time` on its world-line.
double proper_time_at_world_time(const Camera& camera, double time) {
  const Camera::Motion& m = camera.motion;
  if (m.geodesic) return geodesic_proper_time_at(*m.geodesic, time);
  if (!m.keyframes.empty()) return KeyframeWorldLine(m.keyframes).at_world_time(time).proper_time;
  return AcceleratedWorldLine(m.start.time, m.start.position, m.start.velocity, m.phases)
      .at_world_time(time)
      .proper_time;
}

bool static_near_hole(const Scene& scene) {
  return scene.black_hole && !scene.camera.motion.geodesic;
}

}  // namespace

std::optional<std::string> animation_part_refused(long long first, long long last,
                                                  long long whole_first, long long whole_last) {
  if (whole_first <= first && last <= whole_last) return std::nullopt;
  return first == last ? fmt::format("the animation must hold the frame {} this run renders", first)
                       : fmt::format("the animation must hold the frames {} to {} this run renders",
                                     first, last);
}

std::optional<std::string> animation_refused(const Scene& scene) {
  if (static_near_hole(scene) && length(scene.camera.world_line.velocity) > 0)
    return "camera.velocity: a camera that moves near a black hole is animated along a geodesic "
           "motion (\"motion\": {\"orbit\": ...} or {\"fall\": ...}); a velocity alone is not "
           "a free path there";
  return std::nullopt;
}

std::optional<std::string> animation_frame(const Scene& scene, long long i, double fps,
                                           AnimationClock clock, Scene& frame) {
  const Camera& camera = scene.camera;
  const double c = scene.speed_of_light;
  const double proper_start = camera.motion.proper_time / c,
               world_start = camera.world_line.time / c;
  const bool world = clock == AnimationClock::kWorld;
  frame = scene;
  Scene& s = frame;
  const double step = static_cast<double>(i) / fps;
  if (static_near_hole(scene)) {
    const double r = length(camera.world_line.position - scene.black_hole->position);
    const double rate = std::sqrt(1 - 2 * scene.black_hole->mass / r);
    s.camera.world_line.time = (world ? world_start + step : world_start + step / rate) * c;
    return std::nullopt;
  }
  s.camera.motion.proper_time = world ? proper_time_at_world_time(camera, (world_start + step) * c)
                                      : (proper_start + step) * c;
  // A falling camera is drawn down to r = kCameraInnermostRadius M; from inside the horizon
  // it sees the sky and the disk only. Every reason names its frame, so callers print it as it is.
  if (const auto why = geodesic_camera_refused(s.camera.motion, c))
    return fmt::format("frame {}: {}", i, *why);
  s.camera.world_line = camera_observation(s.camera.motion);
  if (camera_inside_horizon(s.camera.motion) && !s.objects.empty()) {
    const RadialObserver falling = *falling_camera(s.camera.motion);
    return fmt::format(
        "frame {}: by then the falling camera has reached the black hole's horizon (it is at "
        "r = {:.12g}, not outside 2M (1 + {:g}) = {:.12g}), where objects are not drawn yet "
        "(this version draws the sky and the disk from there)",
        i, falling.radius, kCameraHorizonMargin, 2 * falling.mass * (1 + kCameraHorizonMargin));
  }
  const double speed = length(s.camera.world_line.velocity);
  if (!(speed < 1) || !std::isfinite(lorentz_gamma(s.camera.world_line.velocity)))
    return fmt::format("frame {}: the camera is at the speed of light by then", i);
  // The scene file's limits hold at its own moment; the camera's clock moves them. Checked
  // at the frame's observation and, with a shutter, at its close. Not near a black hole,
  // where the flat speed of a body relative to the camera means nothing (the loader held each
  // body's speed, measured by the local static observers, to the limit instead).
  for (const double later : {0.0, s.camera.shutter}) {
    if (s.black_hole) break;
    const Vec3 v =
        later > 0 ? observation_after(s.camera, later).velocity : s.camera.world_line.velocity;
    const Fastest fastest = fastest_relative_to(s, four_velocity(v));
    if (!(fastest.gamma <= kMaxLorentzFactor))
      return fmt::format(
          "frame {}: by then {} moves too close to the speed of light relative to the camera "
          "(gamma {:.3g}; at most {:g})",
          i, fastest.name, fastest.gamma, kMaxLorentzFactor);
  }
  return std::nullopt;
}

}  // namespace lightcone

#include "lightcone/physics/lorentz.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

WorldLine camera_observation(const Camera::Motion& motion) {
  const AcceleratedWorldLine line(motion.start.time, motion.start.position, motion.start.velocity,
                                  motion.phases);
  return tangent_line(line.at_proper_time(motion.proper_time));
}

WorldLine tangent_line(const WorldLinePoint& point) {
  return {point.event.t, point.event.x, velocity_of(point.four_velocity), point.proper_time};
}

std::unique_ptr<TimelikeWorldLine> body_world_line(const WorldLine& start,
                                                   const BodyMotion& motion) {
  if (!motion.keyframes.empty()) return std::make_unique<KeyframeWorldLine>(motion.keyframes);
  if (!motion.phases.empty())
    return std::make_unique<AcceleratedWorldLine>(start.time, start.position, start.velocity,
                                                  motion.phases);
  return nullptr;
}

}  // namespace lightcone

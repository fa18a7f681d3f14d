#include "lightcone/physics/lorentz.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

WorldLine camera_observation(const Camera::Motion& motion) {
  const AcceleratedWorldLine line(motion.start.time, motion.start.position, motion.start.velocity,
                                  motion.phases);
  const WorldLinePoint p = line.at_proper_time(motion.proper_time);
  return {p.event.t, p.event.x, velocity_of(p.four_velocity)};
}

}  // namespace lightcone

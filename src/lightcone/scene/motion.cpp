#include <algorithm>
#include <cmath>

#include "lightcone/physics/lorentz.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

WorldLine camera_observation(const Camera::Motion& motion) {
  if (!motion.keyframes.empty())
    return tangent_line(
        point_at_proper_time(KeyframeWorldLine(motion.keyframes), motion.proper_time));
  const AcceleratedWorldLine line(motion.start.time, motion.start.position, motion.start.velocity,
                                  motion.phases);
  return tangent_line(line.at_proper_time(motion.proper_time));
}

double origin_radius(const Shape& shape, const Vec3& scale) {
  struct Visitor {
    const Vec3& k;
    double operator()(const Sphere& s) const {
      return s.radius * std::max({std::abs(k.x), std::abs(k.y), std::abs(k.z)});
    }
    double operator()(const Box& b) const { return length(component_mul(k, b.size * 0.5)); }
    double operator()(const Plane& p) const {
      return length(component_mul(k, Vec3{p.size_x / 2, 0, p.size_z / 2}));
    }
    double operator()(const MeshShape& m) const {
      double r = 0;
      if (m.mesh)
        for (const Vec3& p : m.mesh->positions) r = std::max(r, length(component_mul(k, p)));
      return r;
    }
  };
  return std::visit(Visitor{scale}, shape);
}

WorldLine observation_after(const Camera& camera, double later) {
  if (later == 0) return camera.world_line;
  if (!camera.motion.phases.empty() || !camera.motion.keyframes.empty()) {
    Camera::Motion motion = camera.motion;
    motion.proper_time += later;
    return camera_observation(motion);
  }
  const WorldLine& w = camera.world_line;
  const double gamma = lorentz_gamma(w.velocity);
  return {w.time + gamma * later, w.position + w.velocity * (gamma * later), w.velocity,
          w.proper_time + later};
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

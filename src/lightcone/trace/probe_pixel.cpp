#include "lightcone/trace/probe_pixel.hpp"

#include <memory>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/trace/tracer.hpp"

namespace lightcone {

PixelProbe probe_pixel(const Scene& scene, double x, double y) {
  const ResolvedScene resolved = resolve_scene(scene);
  // The scene's bodies as a render meets them: through Embree, and near a hole along the chords
  // of the curved ray.
  const Tracer tracer(resolved);
  const Vec3 u = look_direction(resolved.camera, x, y);
  if (!resolved.hole) return probe_on_straight_ray(resolved, x, y, u, tracer.trace(u));
  const std::unique_ptr<CurvedBodies> bodies =
      resolved.bodies.empty() ? nullptr : std::make_unique<CurvedBodies>(resolved, tracer);
  return probe_on_curved_ray(resolved, x, y, u, follow_curved_ray(*resolved.hole, u, bodies.get()));
}

}  // namespace lightcone

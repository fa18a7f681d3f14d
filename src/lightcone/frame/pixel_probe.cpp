#include "lightcone/frame/pixel_probe.hpp"

#include <memory>

#include "lightcone/frame/body_segments.hpp"
#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/frame/ray_seen.hpp"
#include "lightcone/frame/straight_hit.hpp"

namespace lightcone {
namespace {

// The fields every probe has, and a surface's emission event from what the ray saw.
PixelProbe probe_seen(double x, double y, const Vec3& u, const RaySeen& seen) {
  PixelProbe probe;
  probe.pixel_x = x;
  probe.pixel_y = y;
  probe.direction = u;
  probe.doppler = seen.doppler;
  probe.order = seen.order;
  if (seen.surface) {
    probe.emission_time = seen.event.t;
    probe.emission_position = seen.event.x;
    probe.distance = seen.distance;
  }
  return probe;
}

// The sky's direction in locate's terms: its pattern coordinates turned by sky.rotation (locate
// turns a --direction back by its transpose).
Vec3 sky_direction_asked(const ResolvedScene& scene, const Vec3& pattern_direction) {
  return scene.scene->sky.rotation * pattern_direction;
}

}  // namespace

PixelProbe probe_on_straight_ray(const ResolvedScene& scene, double x, double y, const Vec3& u,
                                 const std::optional<Hit>& hit) {
  PixelProbe probe = probe_seen(x, y, u, seen_on_straight_ray(scene, u, hit));
  if (!hit) {
    probe.meets = ProbeMeets::kSky;
    probe.sky_direction = sky_direction_asked(scene, scene.sky_direction(u));
    return probe;
  }
  probe.meets = ProbeMeets::kObject;
  probe.object = hit->body;
  probe.point = hit->shape_point;
  probe.emission_proper_time = hit->proper_time;
  return probe;
}

PixelProbe probe_on_curved_ray(const ResolvedScene& scene, double x, double y, const Vec3& u,
                               const CurvedRay& ray) {
  PixelProbe probe = probe_seen(x, y, u, seen_on_curved_ray(scene, u, ray));
  switch (ray.end) {
    case CurvedRayEnd::kSky:
      probe.meets = ProbeMeets::kSky;
      probe.sky_direction = sky_direction_asked(scene, ray.sky_direction);
      break;
    case CurvedRayEnd::kDisk:
      probe.meets = ProbeMeets::kDisk;
      probe.disk_radius = ray.disk_radius * scene.hole->scale;
      break;
    case CurvedRayEnd::kBody:
      probe.meets = ProbeMeets::kObject;
      probe.object = ray.hit.body;
      probe.point = ray.hit.shape_point;
      probe.emission_proper_time = ray.hit.proper_time;
      break;
    case CurvedRayEnd::kHorizon:
      probe.meets = ProbeMeets::kShadow;
      break;
  }
  return probe;
}

PixelProbe probe_pixel(const Scene& scene, double x, double y) {
  const ResolvedScene resolved = resolve_scene(scene);
  const DirectBodySegments segments(resolved);
  const Vec3 u = look_direction(resolved.camera, x, y);
  if (!resolved.hole)
    return probe_on_straight_ray(resolved, x, y, u, first_straight_hit(resolved, segments, u));
  const std::unique_ptr<CurvedBodies> bodies =
      resolved.bodies.empty() ? nullptr : std::make_unique<CurvedBodies>(resolved, segments);
  return probe_on_curved_ray(resolved, x, y, u, follow_curved_ray(*resolved.hole, u, bodies.get()));
}

}  // namespace lightcone

#include "lightcone/trace/aov.hpp"

#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/ray_seen.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

// A body's surface normal with W's axes (its rest frame's), from the shape's own.
Vec3 body_normal(const ResolvedBody& body, const Vec3& shape_normal) {
  const Object& o = *body.object;
  return normalize(o.rotation * component_div(shape_normal, o.scale));
}

// A straight ray's hit's normal: a spinning body's turned with its spin at the event met, as
// its lighting takes it (frame/lighting.cpp).
Vec3 hit_normal(const ResolvedScene& scene, const Hit& hit) {
  const ResolvedBody& body = scene.bodies[hit.body];
  const Vec3 normal = body_normal(body, hit.shape_normal);
  if (body.spin < 0) return normal;
  return Mat3::rotation(scene.spins[body.spin].axis, hit.spin_angle) * normal;
}

// The event where a camera ray on `path` meets the disk (ray.end kDisk), in W: after sweeping
// ray.phi at radius ray.disk_radius, as long before the observation as the light's coordinate
// time on the stretches of the path between (on each, r is monotonic).
Vec4 disk_event(const ResolvedScene& scene, const CurvedPath& path, const CurvedRay& ray) {
  const HoleView& hole = *scene.hole;
  const double r0 = hole.camera_radius, r = ray.disk_radius, turn = path.sweep.turning_radius;
  const double delay =
      turn > 0 && ray.phi > path.sweep.angle_to_turn
          ? coordinate_time(path.orbit, r0, turn) + coordinate_time(path.orbit, turn, r)
          : coordinate_time(path.orbit, r0, r);
  return {scene.observation_event.t - delay * hole.scale,
          hole.centre + path.offset(ray.phi, r) * hole.scale};
}

// The disk's normal on the side a backward ray on `path` that crosses its plane at phi comes
// from: against the path's direction there (its radial part lies in the plane).
Vec3 disk_normal_met(const HoleView& hole, const CurvedPath& path, double phi) {
  const Vec3 along = path.e2 * std::cos(phi) - path.e1 * std::sin(phi);
  const Vec3& n = hole.disk->normal;
  return dot(n, along) > 0 ? n * -1.0 : n;
}

RaySeen seen_along_curved_ray(const ResolvedScene& scene, const Vec3& u,
                              const CurvedBodies* bodies) {
  const HoleView& hole = *scene.hole;
  const CurvedRay ray = follow_curved_ray(hole, u, bodies);
  RaySeen seen;
  seen.doppler = ray.shift;
  seen.order = ray.order;
  if (ray.end == CurvedRayEnd::kSky || ray.end == CurvedRayEnd::kHorizon) {
    seen.object = ray.end == CurvedRayEnd::kSky ? kObjectSky : kObjectShadow;
    return seen;
  }
  seen.surface = true;
  if (ray.end == CurvedRayEnd::kDisk) {
    const CurvedPath path = curved_path(hole, u);
    seen.event = disk_event(scene, path, ray);
    seen.normal = disk_normal_met(hole, path, ray.phi);
    seen.object = kObjectDisk;
  } else {
    seen.event = ray.event;
    seen.normal = body_normal(scene.bodies[ray.hit.body], ray.hit.shape_normal);
    seen.object = static_cast<float>(ray.hit.body);
  }
  seen.distance = camera_frame_distance(hole, u, scene.observation_event.t - seen.event.t);
  return seen;
}

RaySeen seen_along_straight_ray(const ResolvedScene& scene, const Tracer& tracer, const Vec3& u) {
  RaySeen seen;
  const auto hit = tracer.trace(u);
  if (!hit) {
    seen.doppler = scene.doppler(u, scene.sky_velocity);
    return seen;
  }
  seen.doppler = scene.doppler(u, hit->velocity);
  seen.surface = true;
  seen.object = static_cast<float>(hit->body);
  seen.event = scene.trace_to_world(Vec4{scene.ray_time * hit->s, u * hit->s});
  seen.distance = hit->s;
  seen.normal = hit_normal(scene, *hit);
  return seen;
}

}  // namespace

void aov_values(const ResolvedScene& scene, const Tracer& tracer, const Vec3& u,
                std::span<const Aov> aovs, float* out, const CurvedBodies* bodies) {
  const RaySeen seen = scene.hole ? seen_along_curved_ray(scene, u, bodies)
                                  : seen_along_straight_ray(scene, tracer, u);
  write_aov_values(scene, u, seen, aovs, out);
}

}  // namespace lightcone

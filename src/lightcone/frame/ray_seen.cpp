#include "lightcone/frame/ray_seen.hpp"

#include <cmath>
#include <limits>

#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

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

}  // namespace

Vec3 body_normal(const ResolvedBody& body, const Vec3& shape_normal) {
  const Object& o = *body.object;
  return normalize(o.rotation * component_div(shape_normal, o.scale));
}

RaySeen seen_on_straight_ray(const ResolvedScene& scene, const Vec3& u,
                             const std::optional<Hit>& hit) {
  RaySeen seen;
  if (!hit) {
    seen.doppler = scene.doppler(u, scene.sky_velocity);
    return seen;
  }
  const ResolvedBody& body = scene.bodies[hit->body];
  seen.doppler = scene.doppler(u, hit->velocity);
  seen.surface = true;
  seen.object = static_cast<float>(hit->body);
  seen.event = scene.trace_to_world(Vec4{scene.ray_time * hit->s, u * hit->s});
  seen.distance = hit->s;
  // A spinning body's normal turned with its spin at the event met, as its lighting takes it
  // (lighting.cpp).
  seen.normal = body_normal(body, hit->shape_normal);
  if (body.spin >= 0)
    seen.normal = Mat3::rotation(scene.spins[body.spin].axis, hit->spin_angle) * seen.normal;
  return seen;
}

RaySeen seen_on_curved_ray(const ResolvedScene& scene, const Vec3& u, const CurvedRay& ray) {
  const HoleView& hole = *scene.hole;
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

RaySeen seen_along_curved_ray(const ResolvedScene& scene, const Vec3& u,
                              const CurvedBodies* bodies) {
  return seen_on_curved_ray(scene, u, follow_curved_ray(*scene.hole, u, bodies));
}

void write_aov_values(const ResolvedScene& scene, const Vec3& u, const RaySeen& seen,
                      std::span<const Aov> aovs, float* out) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (const Aov aov : aovs) {
    switch (aov) {
      case Aov::kDoppler:
        *out++ = static_cast<float>(seen.doppler);
        break;
      case Aov::kImageOrder:
        *out++ = static_cast<float>(seen.order);
        break;
      case Aov::kObject:
        *out++ = seen.object;
        break;
      case Aov::kEmissionTime:
        *out++ =
            seen.surface ? static_cast<float>(seen.event.t / scene.scene->speed_of_light) : -kInf;
        break;
      case Aov::kDistance:
        *out++ = seen.surface ? static_cast<float>(seen.distance) : kInf;
        break;
      case Aov::kDepth:
        *out++ =
            seen.surface ? static_cast<float>(seen.distance * dot(u, scene.camera.forward)) : kInf;
        break;
      case Aov::kNormal:
        *out++ = static_cast<float>(seen.normal.x);
        *out++ = static_cast<float>(seen.normal.y);
        *out++ = static_cast<float>(seen.normal.z);
        break;
    }
  }
}

}  // namespace lightcone

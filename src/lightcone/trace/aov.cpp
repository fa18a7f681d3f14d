#include "lightcone/trace/aov.hpp"

#include <limits>

#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// What a ray that met no surface gives (the sky, the hole's shadow): `object` its code.
void no_surface_values(Aov aov, float object, float* out) {
  switch (aov) {
    case Aov::kEmissionTime:
      out[0] = -kInf;
      return;
    case Aov::kDistance:
    case Aov::kDepth:
      out[0] = kInf;
      return;
    case Aov::kObject:
      out[0] = object;
      return;
    case Aov::kNormal:
      out[0] = out[1] = out[2] = 0;
      return;
    case Aov::kDoppler:
    case Aov::kImageOrder:  // the callers give these
      return;
  }
}

// A body's surface normal with W's axes (its rest frame's), from the shape's own.
Vec3 body_normal(const ResolvedBody& body, const Vec3& shape_normal) {
  const Object& o = *body.object;
  return normalize(o.rotation * component_div(shape_normal, o.scale));
}

// What a ray met on a surface gives: the event met (W), its distance in the camera's frame,
// the surface's normal (W's axes, facing the incoming ray) and the object code.
struct SurfaceMet {
  Vec4 event;
  double distance = 0;
  Vec3 normal;
  float object = 0;
};

void surface_values(const ResolvedScene& scene, const Vec3& u, Aov aov, const SurfaceMet& met,
                    float* out) {
  switch (aov) {
    case Aov::kEmissionTime:
      out[0] = static_cast<float>(met.event.t / scene.scene->speed_of_light);
      return;
    case Aov::kDistance:
      out[0] = static_cast<float>(met.distance);
      return;
    case Aov::kDepth:
      out[0] = static_cast<float>(met.distance * dot(u, scene.camera.forward));
      return;
    case Aov::kObject:
      out[0] = met.object;
      return;
    case Aov::kNormal:
      out[0] = static_cast<float>(met.normal.x);
      out[1] = static_cast<float>(met.normal.y);
      out[2] = static_cast<float>(met.normal.z);
      return;
    case Aov::kDoppler:
    case Aov::kImageOrder:  // the callers give these
      return;
  }
}

// The event where a camera ray meets the disk (ray.end kDisk), in W: after sweeping ray.phi at
// radius ray.disk_radius, as long before the observation as the light's coordinate time on the
// stretches of the path between (on each, r is monotonic).
Vec4 disk_event(const ResolvedScene& scene, const Vec3& u, const CurvedRay& ray) {
  const HoleView& hole = *scene.hole;
  const CurvedPath path = curved_path(hole, u);
  const double r0 = hole.camera_radius, r = ray.disk_radius, turn = path.sweep.turning_radius;
  const double delay =
      turn > 0 && ray.phi > path.sweep.angle_to_turn
          ? coordinate_time(path.orbit, r0, turn) + coordinate_time(path.orbit, turn, r)
          : coordinate_time(path.orbit, r0, r);
  return {scene.observation_event.t - delay * hole.scale,
          hole.centre + path.offset(ray.phi, r) * hole.scale};
}

// The disk's normal on the side a backward ray that crosses its plane at phi comes from: against
// the path's direction there (its radial part lies in the plane).
Vec3 disk_normal_met(const HoleView& hole, const Vec3& u, double phi) {
  const CurvedPath path = curved_path(hole, u);
  const Vec3 along = path.e2 * std::cos(phi) - path.e1 * std::sin(phi);
  const Vec3& n = hole.disk->normal;
  return dot(n, along) > 0 ? n * -1.0 : n;
}

void curved_aov_values(const ResolvedScene& scene, const Vec3& u, Aov aov, float* out,
                       const CurvedBodies* bodies) {
  const HoleView& hole = *scene.hole;
  const CurvedRay ray = follow_curved_ray(hole, u, bodies);
  if (aov == Aov::kDoppler || aov == Aov::kImageOrder) {
    out[0] = static_cast<float>(aov == Aov::kDoppler ? ray.shift : ray.order);
    return;
  }
  if (ray.end == CurvedRayEnd::kSky) return no_surface_values(aov, kObjectSky, out);
  if (ray.end == CurvedRayEnd::kHorizon) return no_surface_values(aov, kObjectShadow, out);
  SurfaceMet met;
  if (ray.end == CurvedRayEnd::kDisk) {
    met.event = disk_event(scene, u, ray);
    met.normal = disk_normal_met(hole, u, ray.phi);
    met.object = kObjectDisk;
  } else {
    met.event = ray.event;
    met.normal = body_normal(scene.bodies[ray.hit.body], ray.hit.shape_normal);
    met.object = static_cast<float>(ray.hit.body);
  }
  // The light's coordinate travel time in the camera's frame: times the photon's energy there
  // over the static observer's (camera_photon_energy is in units of the energy far away, the
  // static observer's 1 / lapse), as flat space takes a ray's length from W into F.
  met.distance =
      (scene.observation_event.t - met.event.t) * camera_photon_energy(hole, u) * hole.camera_lapse;
  surface_values(scene, u, aov, met, out);
}

}  // namespace

void aov_values(const ResolvedScene& scene, const Tracer& tracer, const Vec3& u, Aov aov,
                float* out, const CurvedBodies* bodies) {
  if (scene.hole) return curved_aov_values(scene, u, aov, out, bodies);
  const auto hit = tracer.trace(u);
  if (!hit) {
    if (aov == Aov::kDoppler)
      out[0] = static_cast<float>(scene.doppler(u, scene.sky_velocity));
    else if (aov == Aov::kImageOrder)  // flat space: every image is the primary
      out[0] = 0;
    else
      no_surface_values(aov, kObjectSky, out);
    return;
  }
  if (aov == Aov::kDoppler) {
    out[0] = static_cast<float>(scene.doppler(u, hit->velocity));
    return;
  }
  if (aov == Aov::kImageOrder) {
    out[0] = 0;
    return;
  }
  SurfaceMet met;
  met.event = scene.trace_to_world(Vec4{scene.ray_time * hit->s, u * hit->s});
  met.distance = hit->s;
  met.normal = body_normal(scene.bodies[hit->body], hit->shape_normal);
  met.object = static_cast<float>(hit->body);
  surface_values(scene, u, aov, met, out);
}

}  // namespace lightcone

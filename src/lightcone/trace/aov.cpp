#include "lightcone/trace/aov.hpp"

#include "lightcone/frame/ray_seen.hpp"

namespace lightcone {
namespace {

// A straight ray's hit's normal: a spinning body's turned with its spin at the event met, as
// its lighting takes it (frame/lighting.cpp).
Vec3 hit_normal(const ResolvedScene& scene, const Hit& hit) {
  const ResolvedBody& body = scene.bodies[hit.body];
  const Vec3 normal = body_normal(body, hit.shape_normal);
  if (body.spin < 0) return normal;
  return Mat3::rotation(scene.spins[body.spin].axis, hit.spin_angle) * normal;
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

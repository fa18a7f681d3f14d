#include "lightcone/frame/straight_rays.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(length(cross(a, b)), dot(a, b));
}

}  // namespace

std::optional<StraightRays> StraightRays::of(const ResolvedScene& scene) {
  if (!scene.hole || scene.hole->falling || scene.ray_time != -1) return std::nullopt;
  const Scene& s = *scene.scene;
  for (const Object& object : s.objects) {
    if (object.motion.geodesic) return std::nullopt;
    if (!object.material.unlit && !s.lights.empty()) return std::nullopt;
  }
  StraightRays rays(scene);
  // Every path comes within the camera's radius of the hole, so its delay term alone is at least
  // 2M / (r - 2M) there: where that is too much, no ray is straight.
  const double r = scene.hole->camera_radius, m = HoleView::mass;
  if (!(2 * m / (r - 2 * m) <= kTolerance * rays.pixel_angle_)) return std::nullopt;
  return rays;
}

StraightRays::StraightRays(const ResolvedScene& scene) : scene_(&scene) {
  // A pinhole's pixels span the least angle at the image's corners.
  const CameraBasis& camera = scene.camera;
  const Vec3 corner = look_direction(camera, 0.5, 0.5);
  pixel_angle_ = std::min(angle_between(corner, look_direction(camera, 1.5, 0.5)),
                          angle_between(corner, look_direction(camera, 0.5, 1.5)));
}

bool StraightRays::straight(const Vec3& u) const {
  const HoleView& hole = *scene_->hole;
  // The true path's direction at the camera in W's coordinates: the static observer's direction
  // d with its radial part shortened by the lapse (dr/dt = f d_r, r dphi/dt = sqrt(f) d_t).
  const Vec4 back = hole.trace_to_static * Vec4{-1, u};
  const Vec3 d = back.x / -back.t;
  const double radial = dot(d, hole.outward);
  const Vec3 curved = d + hole.outward * ((hole.camera_lapse - 1) * radial);
  // The flat tracer's: the backward ray (-1, u) carried to W.
  const Vec3 flat = (scene_->trace_to_world.linear * Vec4{-1, u}).x;
  const double m = HoleView::mass, r = hole.camera_radius;
  double r_min = r;
  if (radial < 0) {
    // Inward: the periapsis r_p = b sqrt(f(r_p)) > 3M, so f(r_p) > 1/3, r_p > b / sqrt(3) and
    // r_p >= b sqrt(1 - 2 sqrt(3) M / b). Far from the photon sphere only.
    const double b = static_impact_parameter(m, r, length(d - hole.outward * radial));
    if (!(b > 100 * m)) return false;
    r_min = std::min(r, b * std::sqrt(1 - 2 * std::numbers::sqrt3 * m / b));
  }
  if (!(r_min > 100 * m)) return false;
  // pi (1 / sqrt(1 - 3M / r_min) - 1), without cancelling.
  const double turning = std::numbers::pi * std::expm1(-0.5 * std::log1p(-3 * m / r_min));
  const double delay = 2 * m / (r_min - 2 * m);
  return angle_between(curved, flat) + turning + delay <= kTolerance * pixel_angle_;
}

}  // namespace lightcone

#include "lightcone/frame/camera_model.hpp"

#include <cmath>
#include <numbers>

namespace lightcone {

CameraBasis camera_basis(const Camera& camera) {
  CameraBasis b;
  b.forward = normalize(camera.forward);
  b.right = normalize(cross(b.forward, camera.up));
  b.up = cross(b.right, b.forward);
  b.tan_half_fov = std::tan(camera.fov_degrees * std::numbers::pi / 360.0);
  b.width = camera.width;
  b.height = camera.height;
  b.aspect = static_cast<double>(camera.width) / camera.height;
  return b;
}

Vec3 look_direction(const CameraBasis& b, double x, double y) {
  const double a = (2.0 * x / b.width - 1.0) * b.tan_half_fov * b.aspect;
  const double c = (1.0 - 2.0 * y / b.height) * b.tan_half_fov;
  return normalize(b.forward + b.right * a + b.up * c);
}

ImagePoint project_direction(const CameraBasis& b, const Vec3& d) {
  const double f = dot(d, b.forward);
  ImagePoint p;
  p.in_front = f > 0;
  const double a = dot(d, b.right) / f;
  const double c = dot(d, b.up) / f;
  p.x = (a / (b.tan_half_fov * b.aspect) + 1.0) * 0.5 * b.width;
  p.y = (1.0 - c / b.tan_half_fov) * 0.5 * b.height;
  return p;
}

ViewExtremes view_extremes_along(const CameraBasis& basis, const Vec3& b) {
  ViewExtremes e{basis.forward, basis.forward};
  if (b.x == 0 && b.y == 0 && b.z == 0) return e;
  double lo = dot(b, e.smallest), hi = lo;
  const auto consider = [&](const Vec3& u) {
    const double d = dot(b, u);
    if (d < lo) lo = d, e.smallest = u;
    if (d > hi) hi = d, e.largest = u;
  };
  const auto in_view = [&](const Vec3& u) {
    const ImagePoint p = project_direction(basis, u);
    return p.in_front && p.x >= 0 && p.x <= basis.width && p.y >= 0 && p.y <= basis.height;
  };
  const Vec3 along = normalize(b);
  if (in_view(along)) consider(along);
  if (in_view(-along)) consider(-along);
  const double w = basis.width, h = basis.height;
  const Vec3 corners[4] = {look_direction(basis, 0, 0), look_direction(basis, w, 0),
                           look_direction(basis, w, h), look_direction(basis, 0, h)};
  for (int k = 0; k < 4; ++k) {
    const Vec3& c1 = corners[k];
    const Vec3& c2 = corners[(k + 1) % 4];
    consider(c1);
    // The edge's great circle (normal m) comes nearest to +-b at +-(b - (b.m) m), normalised;
    // that point counts where it lies on the arc from c1 to c2 (shorter than half a circle).
    const Vec3 m = normalize(cross(c1, c2));
    const Vec3 in_plane = b - m * dot(b, m);
    if (length(in_plane) <= 1e-300) continue;
    const Vec3 q = normalize(in_plane);
    for (const Vec3& candidate : {q, -q})
      if (dot(cross(c1, candidate), m) >= 0 && dot(cross(candidate, c2), m) >= 0)
        consider(candidate);
  }
  return e;
}

}  // namespace lightcone

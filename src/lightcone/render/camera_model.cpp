#include "lightcone/render/camera_model.hpp"

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

}  // namespace lightcone

#include "lightcone/physics/schwarzschild_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace lightcone {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The length of `a` and its direction, scaled by its largest component first, so that neither
// huge nor tiny (but finite) vectors overflow or underflow. Zero: length 0, direction zero.
struct Polar {
  double length = 0;
  Vec3 direction;
};
Polar polar(const Vec3& a) {
  const double largest = std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)});
  if (largest == 0) return {};
  const Vec3 scaled = a / largest;
  const double norm = length(scaled);
  return {largest * norm, scaled / norm};
}

bool finite(const Vec3& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

}  // namespace

double static_observer_speed(double mass, const Vec3& from_hole, const Vec3& coordinate_velocity) {
  const Polar position = polar(from_hole), velocity = polar(coordinate_velocity);
  if (mass == 0 || !finite(from_hole)) return velocity.length;  // flat, or infinitely far away
  // f = 1 - 2M/r, as 1 - 2 (M/r) so that 2M cannot overflow.
  const double f = 1 - 2 * (mass / position.length);
  if (!(f > 0)) return kInf;
  const double radial = velocity.length * dot(velocity.direction, position.direction);
  const Vec3 across = coordinate_velocity - position.direction * radial;
  const double radial_part = radial / f;
  return std::sqrt(radial_part * radial_part + dot(across, across) / f);
}

LineSpeedPeak peak_static_observer_speed(double mass, const Vec3& from_hole,
                                         const Vec3& coordinate_velocity) {
  const Polar velocity = polar(coordinate_velocity);
  if (!finite(from_hole)) return {velocity.length, kInf, false};
  const Polar position = polar(from_hole);
  if (mass == 0) return {velocity.length, position.length, false};
  if (velocity.length == 0) {
    // At rest: one point.
    const bool inside = !(2 * (mass / position.length) < 1);
    return {inside ? kInf : 0, position.length, inside};
  }
  // The closest approach b = |d x v^|, d scaled by its largest component.
  const double largest =
      std::max({std::abs(from_hole.x), std::abs(from_hole.y), std::abs(from_hole.z)});
  const double b =
      largest == 0 ? 0 : largest * length(cross(from_hole / largest, velocity.direction));
  const double a = 2 * (mass / b);
  if (!(a < 1)) return {kInf, b, true};
  const double rho =
      std::numbers::sqrt2 * std::cos(std::acos(-a / std::numbers::sqrt2) / 3);  // in [1, 1.23)
  const double gap = rho - a;
  const double g = (rho - 1) * (rho + 1) / (gap * gap) + 1 / (rho * gap);
  return {velocity.length * std::sqrt(g), b * rho, false};
}

}  // namespace lightcone

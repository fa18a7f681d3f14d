#include "lightcone/physics/hole_world_line.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <limits>

#include "lightcone/physics/accretion_disk.hpp"
#include "lightcone/physics/math_policy.hpp"
#include "lightcone/physics/schwarzschild_motion.hpp"

namespace lightcone {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The clock rate dtau/dt of a body with coordinate velocity v at x: from
// dtau^2 = f dt^2 - dr^2 / f - r^2 dOmega^2.
double clock_rate(double mass, const Vec3& x, const Vec3& v) {
  const double r = length(x), f = 1 - 2 * mass / r;
  const double v_r = dot(v, x) / r;
  const double v_t2 = std::max(0.0, dot(v, v) - v_r * v_r);
  return std::sqrt(std::max(0.0, f - v_r * v_r / f - v_t2));
}

}  // namespace

HoleWorldLine HoleWorldLine::straight(double mass, double time, const Vec3& position,
                                      const Vec3& velocity, double proper_time) {
  return {mass, Straight{time, proper_time, position, velocity}};
}

HoleWorldLine HoleWorldLine::orbit(double mass, double radius, const Vec3& axis_x,
                                   const Vec3& axis_y, double phase) {
  return {mass, Orbit{radius, phase, axis_x, axis_y}};
}

HoleWorldLine HoleWorldLine::fall(const RadialFall& fall, const Vec3& direction, double time) {
  return {fall.mass(), Fall{fall, direction, time}};
}

bool HoleWorldLine::still() const {
  const auto* s = std::get_if<Straight>(&path_);
  return s && s->velocity == Vec3{};
}

HoleWorldLineState HoleWorldLine::at(double t) const {
  const double m = mass_;
  if (const auto* s = std::get_if<Straight>(&path_)) {
    const Vec3 x = s->position + s->velocity * (t - s->time);
    if (still()) return {x, {}, {}, s->proper_time + clock_rate(m, x, {}) * (t - s->time)};
    const auto rate = [&](double u) {
      return clock_rate(m, s->position + s->velocity * (u - s->time), s->velocity);
    };
    const auto integral = [&](double from, double to) {
      return boost::math::quadrature::gauss_kronrod<double, 21, MathPolicy>::integrate(
          rate, from, to, 12, 1e-13);
    };
    const double elapsed = t >= s->time ? integral(s->time, t) : -integral(t, s->time);
    const double r = length(x), f = 1 - 2 * m / r, v_r = dot(s->velocity, x) / r;
    const Vec3 local = x * (v_r / (f * r)) + (s->velocity - x * (v_r / r)) / std::sqrt(f);
    return {x, s->velocity, local, s->proper_time + elapsed};
  }
  if (const auto* o = std::get_if<Orbit>(&path_)) {
    const double omega = circular_orbit_angular_velocity(m, o->radius);
    const double phi = o->phase + omega * t, c = std::cos(phi), sn = std::sin(phi);
    const Vec3 along = o->axis_y * c - o->axis_x * sn;
    return {(o->axis_x * c + o->axis_y * sn) * o->radius, along * (o->radius * omega),
            along * circular_orbit_local_speed(m, o->radius),
            circular_orbit_proper_time(m, o->radius, t)};
  }
  const Fall& fall = std::get<Fall>(path_);
  // From rest at r0: held there until it is let go.
  if (!fall.fall.is_from_infinity() && t < fall.time) {
    const Vec3 x = fall.direction * fall.fall.at_proper_time(0).radius;
    return {x, {}, {}, clock_rate(m, x, {}) * (t - fall.time)};
  }
  const double tau = fall.fall.proper_time_at_coordinate_time(t - fall.time);
  const RadialFallPoint p = fall.fall.at_proper_time(tau);
  // dr/dt = f v, v the static observer's radial velocity (none at the horizon, which the body
  // reaches at t = infinity, at rest in t).
  const double f = 1 - 2 * m / p.radius;
  const double dr_dt =
      p.radius > 2 * m && std::isfinite(p.local_velocity) ? f * p.local_velocity : 0.0;
  const double local =
      p.radius > 2 * m && std::isfinite(p.local_velocity) ? p.local_velocity : -1.0;
  return {fall.direction * p.radius, fall.direction * dr_dt, fall.direction * local, tau};
}

double HoleWorldLine::nearest() const {
  if (const auto* s = std::get_if<Straight>(&path_)) {
    const double vv = dot(s->velocity, s->velocity);
    return vv > 0 ? length(s->position - s->velocity * (dot(s->position, s->velocity) / vv))
                  : length(s->position);
  }
  if (const auto* o = std::get_if<Orbit>(&path_)) return o->radius;
  return 2 * mass_;
}

double HoleWorldLine::farthest() const {
  if (const auto* s = std::get_if<Straight>(&path_)) return still() ? length(s->position) : kInf;
  if (const auto* o = std::get_if<Orbit>(&path_)) return o->radius;
  return std::get<Fall>(path_).fall.start_radius();
}

double HoleWorldLine::max_coordinate_speed() const {
  if (const auto* s = std::get_if<Straight>(&path_)) return length(s->velocity);
  if (const auto* o = std::get_if<Orbit>(&path_))
    return o->radius * circular_orbit_angular_velocity(mass_, o->radius);
  // |dr/dt| = f sqrt(E^2 - f) / E over f in (0, E^2]: largest at f = 2E^2/3.
  const double e = std::get<Fall>(path_).fall.energy();
  return 2 * e * e / (3 * std::sqrt(3.0));
}

double HoleWorldLine::max_local_speed() const {
  if (const auto* s = std::get_if<Straight>(&path_))
    return still() ? 0.0 : peak_static_observer_speed(mass_, s->position, s->velocity).speed;
  if (const auto* o = std::get_if<Orbit>(&path_))
    return circular_orbit_local_speed(mass_, o->radius);
  return 1;
}

}  // namespace lightcone

// The world-line of a body near one Schwarzschild black hole, as the curved-ray walker reads it
// (PHYSICS.md, "Curved spacetime"; docs/design/black-hole.md, "Bodies"): its position relative
// to the hole, coordinate velocity dx/dt and proper time at any Schwarzschild coordinate time t.
// G = c = 1, M the gravitational radius, f = 1 - 2M/r.
//
// Three kinds, each exact:
// - a straight coordinate line x(t) = position + velocity (t - time), its clock the integral of
//   sqrt(f - v_r^2 / f - |v_t|^2) dt (Gauss-Kronrod, to 1e-13);
// - a circular geodesic (schwarzschild_geodesics.hpp): x = r (cos phi a + sin phi b),
//   phi = phase + Omega t, tau = t sqrt(1 - 3M/r);
// - a radial free fall (RadialFall) along a unit direction, its proper time found from t; one
//   from rest at r0 is held at rest there (proper time sqrt(1 - 2M/r0) (t - time)) until it is
//   let go at `time`, so its radius never grows with t.
#pragma once

#include <variant>

#include "lightcone/physics/schwarzschild_geodesics.hpp"
#include "lightcone/physics/vec.hpp"

namespace lightcone {

struct HoleWorldLineState {
  Vec3 position;  // relative to the hole
  Vec3 velocity;  // coordinate velocity dx/dt
  // The velocity the static observer where it is measures (radial v_r / f, across v_t /
  // sqrt(f)), below 1: in closed form on a geodesic, where the coordinate velocity loses it to
  // rounding near the horizon.
  Vec3 local_velocity;
  double proper_time = 0;
};

class HoleWorldLine {
 public:
  // Requires a line that stays outside r = 2M (its static-observer speed below 1 along it).
  static HoleWorldLine straight(double mass, double time, const Vec3& position,
                                const Vec3& velocity, double proper_time);
  // radius > 3M; axis_x, axis_y orthonormal; counter-clockwise about axis_x x axis_y; proper
  // time 0 at t = 0.
  static HoleWorldLine orbit(double mass, double radius, const Vec3& axis_x, const Vec3& axis_y,
                             double phase);
  // Along the unit `direction`, the fall's coordinate time offset by `time`.
  static HoleWorldLine fall(const RadialFall& fall, const Vec3& direction, double time);

  double mass() const { return mass_; }
  bool still() const;
  HoleWorldLineState at(double t) const;

  // The nearest and farthest radius over every t (2M and r0 for a fall, r0 infinite from
  // infinity; for a straight line, its closest approach and infinity unless it is at rest).
  double nearest() const;
  double farthest() const;
  // A bound over every t on |dx/dt|.
  double max_coordinate_speed() const;
  // The largest speed a static observer measures for the body where it is, over every t (1 for
  // a fall, which reaches it at the horizon).
  double max_local_speed() const;

  struct Straight {
    double time = 0, proper_time = 0;
    Vec3 position, velocity;
  };
  struct Orbit {
    double radius = 0, phase = 0;
    Vec3 axis_x, axis_y;
  };
  struct Fall {
    RadialFall fall;
    Vec3 direction;
    double time = 0;
  };
  const std::variant<Straight, Orbit, Fall>& path() const { return path_; }

 private:
  HoleWorldLine(double mass, std::variant<Straight, Orbit, Fall> path)
      : mass_(mass), path_(std::move(path)) {}
  double mass_ = 0;
  std::variant<Straight, Orbit, Fall> path_;
};

}  // namespace lightcone

// Bodies on straight coordinate lines near one Schwarzschild black hole (PHYSICS.md, "Curved
// spacetime"): G = c = 1, M the gravitational radius, f = 1 - 2M/r, Schwarzschild coordinate
// time t, and Cartesian coordinates x = hole + r n(theta, phi). A body's position, time and
// velocity in a scene describe the coordinate line x(t) = position + velocity (t - time); what
// limits it is the speed the static observers along it measure, which must stay below 1.
#pragma once

#include "lightcone/physics/vec.hpp"

namespace lightcone {

// The speed measured by the static observer at `from_hole` (the position relative to the hole,
// r = |from_hole|) of a body passing there with coordinate velocity v = dx/dt. From
// ds^2 = -f dt^2 + dr^2 / f + r^2 dOmega^2, the static observer's proper time is sqrt(f) dt and
// its proper lengths are dr / sqrt(f) along n and r dOmega across, so with v_r = v.n and
// v_t = v - v_r n:
//   speed^2 = v_r^2 / f^2 + |v_t|^2 / f.
// Infinity for r <= 2M, where there are no static observers; |v| when M = 0. Requires M >= 0.
double static_observer_speed(double mass, const Vec3& from_hole, const Vec3& coordinate_velocity);

// The largest static_observer_speed along a whole coordinate line, over every t.
struct LineSpeedPeak {
  double speed = 0;  // infinity when the line reaches r <= 2M
  // Where the largest speed is reached: r at the peak, or the line's closest approach to the
  // hole when it reaches r <= 2M (r itself for a line at rest). Infinity for a line infinitely
  // far away.
  double radius = 0;
  bool reaches_horizon = false;  // the line comes to r <= 2M at some t
};

// The line through `from_hole` (relative to the hole) with coordinate velocity v. In closed form:
// with b the line's closest approach to the hole (b > 2M), a = 2M/b and rho = r/b >= 1, the
// radial part is |v| sqrt(rho^2 - 1) / rho and the tangential part |v| / rho, so
//   speed^2 / |v|^2 = G(rho) = (rho^2 - 1) / (rho - a)^2 + 1 / (rho (rho - a)),
//   dG/drho = -a (2 rho^3 - 3 rho + a) / (rho^2 (rho - a)^3).
// The cubic is negative at rho = 1 (a < 1) and increasing beyond, so G rises from 1 / f(b) at the
// closest approach to one maximum, at the root rho* = sqrt(2) cos(arccos(-a / sqrt(2)) / 3) in
// [1, sqrt(3/2)), and falls to 1 far away (G > 1 everywhere: the peak is always reached, twice,
// at r = b rho* on either side of the closest approach). M = 0: |v| everywhere (radius: r at
// `from_hole`).
LineSpeedPeak peak_static_observer_speed(double mass, const Vec3& from_hole,
                                         const Vec3& coordinate_velocity);

}  // namespace lightcone

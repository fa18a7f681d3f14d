// Timelike geodesics of one Schwarzschild black hole in closed form, for a camera that moves
// freely near it (PHYSICS.md, "Curved spacetime"): G = c = 1, M the gravitational radius (a
// length, > 0), r the Schwarzschild radius, f = 1 - 2M/r, t Schwarzschild coordinate time, tau
// the body's proper time. Speeds are those the static observer where the body is measures.
//
// Radial geodesics (Misner, Thorne & Wheeler 1973, section 31.4; Chandrasekhar 1983, section
// 19): with the conserved energy per unit rest mass E = f dt/dtau,
//   (dr/dtau)^2 = E^2 - f,   dt/dtau = E / f,
// and the static observer, whose proper time is sqrt(f) dt and proper radial length dr/sqrt(f),
// measures the radial velocity v = (dr/dt) / f = (dr/dtau) / E (so that 1 - v^2 = f / E^2,
// gamma = E / sqrt(f)). From rest at r0: E = sqrt(1 - 2M/r0); from rest at infinity: E = 1.
#pragma once

#include <limits>

namespace lightcone {

// A point of a radial fall.
struct RadialFallPoint {
  double radius = 0;           // Schwarzschild r
  double coordinate_time = 0;  // t, from the fall's reference event; NaN at or inside r = 2M
  // The radial velocity the static observer there measures, outward positive (negative while
  // falling); NaN at or inside r = 2M.
  double local_velocity = 0;
};

// Free radial fall, from rest at r0 or from rest at infinity.
//
// From rest at r0 (> 2M), the cycloid, with a = sqrt(r0 / 2M - 1) and eta in (-pi, pi):
//   r = r0 / 2 (1 + cos eta) = r0 cos^2(eta / 2),
//   tau = sqrt(r0^3 / 8M) (eta + sin eta),
//   t = 2M [ln((a + tan(eta/2)) / (a - tan(eta/2))) + a (eta + r0 / 4M (eta + sin eta))]
//     (MTW eq. 31.10),
//   v = -sqrt(2M / r0) tan(eta / 2) / E.
// tau = t = 0 at r0 (eta = 0); negative eta is the same geodesic before it, rising to rest at r0
// (t and tau odd in eta, r even). The horizon is reached at tan(eta_h / 2) = a, the singularity
// at eta = pi, tau = pi sqrt(r0^3 / 8M) = (pi / 2) sqrt(r0^3 / 2M).
//
// From rest at infinity, with x = sqrt(r / 2M), proper time 0 at r = reference (x_ref):
//   x^3 = x_ref^3 - 3 tau / 4M,   i.e. r = (9M / 2)^(1/3) (tau_0 - tau)^(2/3),
//   t = -2M [F(x) - F(x_ref)],   F(x) = 2/3 x^3 + 2 x + ln((x - 1) / (x + 1)),
//   v = -sqrt(2M / r) = -1 / x.
// (From dt/dr = -sqrt(r / 2M) / f: with r = 2M x^2, dt = -4M x^4 / (x^2 - 1) dx and
// x^4 / (x^2 - 1) = x^2 + 1 + 1 / (x^2 - 1).)
class RadialFall {
 public:
  // From rest at r0 > 2M (r0 finite): proper time and coordinate time 0 there.
  static RadialFall from_rest(double mass, double r0);
  // From rest at infinity: proper time and coordinate time 0 where it passes r = reference
  // (> 2M, finite).
  static RadialFall from_infinity(double mass, double reference);

  double mass() const { return mass_; }
  bool is_from_infinity() const { return !(r0_ < std::numeric_limits<double>::infinity()); }
  // Energy per unit rest mass, E = sqrt(1 - 2M/r0) (1 from infinity).
  double energy() const { return energy_; }

  // The point at proper time tau: outside the horizon for |tau| < horizon_proper_time() from
  // rest at r0, and for every tau < horizon_proper_time() from infinity (r grows without bound
  // as tau -> -infinity). At or inside the horizon only the radius is given (0 at and beyond
  // the singularity).
  RadialFallPoint at_proper_time(double tau) const;

  // The proper time at which the falling body is at r, 0 <= r (<= r0 from rest at r0), on its
  // way in (>= 0 from rest at r0).
  double proper_time_at_radius(double r) const;
  // The point at r > 2M (<= r0 from rest at r0) on its way in, in closed form: eta (or tau, from
  // infinity) from r, then t and v as at_proper_time gives them (which finds eta from tau).
  RadialFallPoint at_radius(double r) const;
  // The point at coordinate time t on its way in, given radii lo < hi (> 2M, <= r0 from rest at
  // r0) at which its times t_lo >= t >= t_hi bracket t: Newton's method on the closed-form t(r)
  // with its derivative dt/dr = -E / (f sqrt(E^2 - f)), from the bracket's linear interpolation,
  // a step that leaves the bracket (which each point's side of t narrows) replaced by its
  // midpoint, to where the step is within a few units in the last place of r.
  RadialFallPoint at_coordinate_time_between(double t, double lo, double t_lo, double hi,
                                             double t_hi) const;
  // The proper time at which it reaches the horizon, r = 2M.
  double horizon_proper_time() const { return proper_time_at_radius(2 * mass_); }
  // Where it is at rest: r0, infinity for a fall from infinity.
  double start_radius() const { return r0_; }

  // The proper time at which the body's coordinate time is t (finite). t(tau) is increasing
  // and goes to +infinity at the horizon (and, from rest at r0, to -infinity at the past
  // horizon, as tau -> -horizon_proper_time()); a t so late that the body is closer to the
  // horizon than double precision resolves gives +-horizon_proper_time(). Found with TOMS 748
  // on the monotonic t(eta) or t(tau), in a bracket from bounds on dt/dtau (or halved toward
  // the horizon).
  double proper_time_at_coordinate_time(double t) const;

 private:
  RadialFall(double mass, double r0, double reference);

  // From rest at r0: t at eta in [0, eta_h) (>= 0) and its proper time tau, and eta at tau in
  // [0, the singularity].
  double cycloid_time(double eta, double tau) const;
  double cycloid_eta(double tau) const;
  // From infinity: t at tau < tau_h.
  double infinity_time(double tau) const;

  double mass_ = 0;
  double r0_ = 0;         // infinity for a fall from infinity
  double reference_ = 0;  // from infinity: r at proper time 0
  double energy_ = 1;
  // e = sqrt(2M / r0), or sqrt(2M / reference) from infinity (and then 1 - e, without
  // cancellation); from rest at r0, eta at the horizon.
  double e_ = 0, one_minus_e_ = 0, eta_horizon_ = 0;
};

// A circular geodesic at radius r > 3M (stable for r >= 6M, the ISCO): Omega = dphi/dt =
// sqrt(M / r^3), dt/dtau = 1 / sqrt(1 - 3M/r) (from the normalisation
// -1 = (-f + r^2 Omega^2) (dt/dtau)^2), speed relative to the static observer there
// sqrt(M / (r - 2M)) (see accretion_disk.hpp). Angle and times from the event where both
// proper time and coordinate time are 0.
struct CircularOrbitPoint {
  double coordinate_time = 0;  // t = tau / sqrt(1 - 3M/r)
  double angle = 0;            // phi swept since t = 0: Omega t (radians)
  double local_speed = 0;      // sqrt(M / (r - 2M)), along the direction of motion
};
CircularOrbitPoint circular_orbit_at_proper_time(double mass, double r, double tau);
// tau = t sqrt(1 - 3M/r).
double circular_orbit_proper_time(double mass, double r, double t);

}  // namespace lightcone

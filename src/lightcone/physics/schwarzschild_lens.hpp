// The images of a point seen past a Schwarzschild black hole (PHYSICS.md, "Curved spacetime"):
// which rays from an observer reach it, solved exactly on the closed-form geodesics of
// schwarzschild.hpp. G = c = 1, M the gravitational radius.
#pragma once

#include <optional>
#include <vector>

namespace lightcone {

// An observer at radius r0 and a point at radius r_e (both > 2M; r_e may be infinity, a
// direction far away), at angle psi in [0, pi] apart about the hole. The ray of image order k
// sweeps phi_k = psi + k pi about the hole for even k (on the side toward the point) and
// (k + 1) pi - psi for odd k (round the other side): 0 the primary image, 1 the secondary.
double image_sweep(double psi, int order);

// Where a solve of ray_between for ends near those of an earlier one starts: that one's look
// angle at its inner end, on its stretch (turned at r_3 inside the photon sphere or not), with
// |dsweep / dalpha| there. A rate of 0 starts nothing.
struct RayBetweenStart {
  double alpha = 0, rate = 0;
  bool inner_is_a = true, turned_inside = false;
};

// The side that a static surface at end a faces, for a caller that wants no light on its back:
// its normal's components along the outward radial direction there and across it, toward the
// way the ray goes round (the plane's e2 of hole_light_leg.hpp).
struct FacingSide {
  double outward = 0, round = 0;
};

// The ray of image order k between two points at radii r_a and r_b (> 2M; r_b may be
// infinity, a direction far away), psi in [0, pi] apart about the hole: the image of order k of
// the point at b seen from a (locate), or the light that lights a surface from a lamp, directly
// (k = 0) or round the far side (k = 1). Every order exists for M > 0 (none for k >= 1 when
// M = 0, nor the ray through the centre). Solved in the look angle
// alpha at the inner point, on which the angle swept to the outer radius grows continuously and
// monotonically from 0 (radially outward) to infinity (the critical angle, b -> b_c: inward for
// an inner point outside the photon sphere, outward inside it), so one bracket holds the one
// root of sweep = image_sweep(psi, k); TOMS 748 on the exact swept_angle.
//
// Neighbouring lit points have rays a little apart. With `warm_start` (an earlier solve's, for
// ends nearby; set to this one's), the bracket is found from its look angle by a Newton step on
// its rate, a twentieth too long, then steps doubling toward the root: some six evaluations of
// the sweep fewer. The root is the same whatever the start (to the sweep's own rounding, some
// 1e-14 of the impact parameter at worst), solved in a bracket whose ends are evaluated (a
// start that brackets nothing in six steps gives way to the bracket found from the stretch's
// start). With `facing`, the solve stops and gives none once its bracket holds only rays that
// leave end a on the surface's back, where the light would bring nothing; `warm_start` then
// moves to the secant's root in that bracket. Without `timed`, the coordinate time between the
// ends (elliptic integrals of all three kinds) is not taken: a lamp at rest needs none.
struct RayBetween {
  double impact = 0;
  double sweep = 0;  // image_sweep(psi, order)
  // At each end, the direction in which the ray leaves toward the other end, in the static
  // observer's frame there: at angle alpha from the outward radial direction, tipped toward the
  // way the ray goes round (toward the other end for even orders, away from it for odd ones;
  // sin >= 0).
  double cos_a = 0, sin_a = 0, cos_b = 0, sin_b = 0;
  // The coordinate time between the ends (infinity for r_b = infinity; NaN where not `timed`).
  double time = 0;
  // The bundle's cross-section at one end per unit solid angle at the other, both in the
  // static observers' frames: dA_b / dOmega_a (light sent from a) and dA_a / dOmega_b (from b;
  // Etherington's reciprocity: f_a / f_b times the first). With the outer end at R, the inner
  // at rho with look angle alpha there, dA_outer / dOmega_inner =
  //   R^2 sin(psi) |cos(beta_outer)| |dsweep / dalpha| / sin(alpha),
  // the sphere's area element over the emitted one (dsweep / dalpha by a central difference of
  // the exact sweep; sin(psi) / sin(alpha) -> dsweep / dalpha toward the radial ray). 0 on the
  // caustic psi = pi, where a point's light is focused onto a ring. Unset for r_b = infinity.
  double spread_a_to_b = 0, spread_b_to_a = 0;
  // r_b = infinity: a plane wave from there is focused at a by dA_far / dA_a =
  // sin(alpha) / (f_a sin(psi) |dsweep / dalpha|) (the areas across the ray).
  double focusing = 0;
  // |dsweep / dalpha| at the inner end.
  double sweep_rate = 0;
};
std::optional<RayBetween> ray_between(double mass, double r_a, double r_b, double psi, int order,
                                      RayBetweenStart* warm_start = nullptr,
                                      const FacingSide* facing = nullptr, bool timed = true);

// The images of directions far away seen by the static observer at radius r0 (> 2M), orders 0
// to orders - 1, for many directions: ray_between's look angle alpha_k(psi) tabulated at `nodes`
// equal steps of psi over [0, pi] and interpolated by cubic Hermite, with the exact slopes
// d alpha / d psi = +-1 / |dsweep / dalpha| at the nodes (+ for even orders, whose sweep grows
// with psi; the sweep to infinity grows with alpha over every escaping ray). Between nodes
// h = pi / (nodes - 1) apart its error is of order h^4 in alpha and h^3 in the slope.
class FarImageTable {
 public:
  FarImageTable(double mass, double r0, int orders, int nodes = 256);
  double mass() const { return mass_; }
  double radius() const { return r0_; }
  struct Image {
    double alpha = 0;
    // The solid angle a small bundle subtends at r0, in the static observer's frame, over what
    // it subtends far away: sin(alpha) |d alpha / d psi| / sin(psi) (its limit (d alpha /
    // d psi)^2 on the axis where alpha -> 0 too).
    double solid_angle_ratio = 1;
  };
  // None where the order has no image (M = 0 beyond the primary), and on the caustic (psi = 0 or
  // pi with alpha off the axis: a point there is seen as a ring).
  std::optional<Image> at(double psi, int order) const;

 private:
  double mass_, r0_, step_;
  int nodes_;
  std::vector<bool> present_;  // per order
  std::vector<double> alpha_;  // order-major
  std::vector<double> slope_;  // d alpha / d psi
};

}  // namespace lightcone

// The images of a point seen past a Schwarzschild black hole (PHYSICS.md, "Curved spacetime"):
// which rays from an observer reach it, solved exactly on the closed-form geodesics of
// schwarzschild.hpp. G = c = 1, M the gravitational radius.
#pragma once

#include <optional>

namespace lightcone {

// An observer at radius r0 and a point at radius r_e (both > 2M; r_e may be infinity, a
// direction far away), at angle psi in [0, pi] apart about the hole. The ray of image order k
// sweeps phi_k = psi + k pi about the hole for even k (on the side toward the point) and
// (k + 1) pi - psi for odd k (round the other side): 0 the primary image, 1 the secondary.
double image_sweep(double psi, int order);

struct LensImage {
  // The direction in which the observer's static frame receives the ray (its look direction):
  // at angle alpha from the outward radial direction, tipped toward the point for even orders
  // and away from it for odd ones.
  double cos_alpha = 0, sin_alpha = 0;
  double impact = 0;  // b = r0 sin(alpha) / sqrt(1 - 2M / r0)
  double sweep = 0;   // the angle it sweeps, image_sweep(psi, order)
  // The coordinate time the light takes from the point to the observer (infinity for r_e =
  // infinity).
  double time = 0;
};

// The ray of image order `order` from the point to the observer, if there is one (none for a
// point on the far side of the photon sphere's shadow region that no ray of that order
// reaches). Found by bracketing the sweep at r_e as a function of alpha on a grid that crowds
// toward the critical angle (where the sweep diverges) and solving each bracket with Boost's
// TOMS 748 on the exact swept_angle: a root of a continuous, monotonic function, to double
// precision.
std::optional<LensImage> lens_image(double mass, double r0, double r_e, double psi, int order);

}  // namespace lightcone

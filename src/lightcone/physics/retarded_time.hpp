// Light delay of an inertial world-line, in closed form.
#pragma once

#include "lightcone/physics/vec.hpp"

namespace lightcone {

// Receiver at (t_R, x_R); body at X(t) = X0 + beta (t - t0) with |beta| < 1. With
// delta = X(t_R) - x_R, returns tau = t_R - t_emit >= 0, the root of |delta - beta tau| = tau.
// Numerically stable in both signs of beta.delta.
double retarded_delay(const Vec3& delta, const Vec3& beta);

}  // namespace lightcone

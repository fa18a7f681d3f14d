// Aberration of look directions and the scaling of the backward-ray parameter between frames.
#pragma once

#include "lightcone/physics/vec.hpp"

namespace lightcone {

// Look direction (unit, from observer toward the source) seen in a frame moving with beta
// relative to frame F, given the look direction d_f in F. Exact (PHYSICS.md).
Vec3 aberrate_into_moving_frame(const Vec3& d_f, const Vec3& beta);

// The same with gamma = lorentz_gamma(beta) given: the law itself, which the form above calls;
// for many directions seen from one moving frame.
inline Vec3 aberrate_into_moving_frame_with_gamma(const Vec3& d_f, const Vec3& beta, double g) {
  // d' = (d + (g - 1)(bh.d) bh + g beta) / (g (1 + beta.d)), written with
  // (g - 1)/b^2 = g^2/(g + 1) so that beta -> 0 is exact.
  const double bd = dot(beta, d_f);
  const Vec3 num = d_f + beta * (g * g / (g + 1.0) * bd + g);
  return num / (g * (1.0 + bd));
}

// Inverse of the above: look direction in F given the one in the moving frame.
Vec3 aberrate_out_of_moving_frame(const Vec3& d_moving, const Vec3& beta);

// Ratio s_moving / s_F of the backward null-ray parameter (light travel time) along a look
// direction d_f of F: gamma (1 + beta.d_f).
double ray_parameter_scale(const Vec3& d_f, const Vec3& beta);

}  // namespace lightcone

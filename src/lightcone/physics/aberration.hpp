// Aberration of look directions and the scaling of the backward-ray parameter between frames.
#pragma once

#include "lightcone/physics/vec.hpp"

namespace lightcone {

// Look direction (unit, from observer toward the source) seen in a frame moving with beta
// relative to frame F, given the look direction d_f in F. Exact (PHYSICS.md).
Vec3 aberrate_into_moving_frame(const Vec3& d_f, const Vec3& beta);

// Inverse of the above: look direction in F given the one in the moving frame.
Vec3 aberrate_out_of_moving_frame(const Vec3& d_moving, const Vec3& beta);

// Ratio s_moving / s_F of the backward null-ray parameter (light travel time) along a look
// direction d_f of F: gamma (1 + beta.d_f).
double ray_parameter_scale(const Vec3& d_f, const Vec3& beta);

}  // namespace lightcone

#include "lightcone/physics/aberration.hpp"

#include "lightcone/physics/lorentz.hpp"

namespace lightcone {

Vec3 aberrate_into_moving_frame(const Vec3& d_f, const Vec3& beta) {
  return aberrate_into_moving_frame_with_gamma(d_f, beta, lorentz_gamma(beta));
}

// The frame F moves with -beta relative to the moving one.
Vec3 aberrate_out_of_moving_frame(const Vec3& d_moving, const Vec3& beta) {
  return aberrate_into_moving_frame_with_gamma(d_moving, -beta, lorentz_gamma(beta));
}

double ray_parameter_scale(const Vec3& d_f, const Vec3& beta) {
  return lorentz_gamma(beta) * (1.0 + dot(beta, d_f));
}

}  // namespace lightcone

#include "lightcone/physics/aberration.hpp"

#include "lightcone/physics/lorentz.hpp"

namespace lightcone {
namespace {

// d' = (d + (g - 1)(bh.d) bh + sign g beta) / (g (1 + sign beta.d)), written with
// (g - 1)/b^2 = g^2/(g + 1) so that beta -> 0 is exact.
Vec3 aberrate(const Vec3& d, const Vec3& beta, double sign) {
  const double g = lorentz_gamma(beta);
  const double bd = dot(beta, d);
  const Vec3 num = d + beta * (g * g / (g + 1.0) * bd + sign * g);
  return num / (g * (1.0 + sign * bd));
}

}  // namespace

Vec3 aberrate_into_moving_frame(const Vec3& d_f, const Vec3& beta) {
  return aberrate(d_f, beta, +1.0);
}

Vec3 aberrate_out_of_moving_frame(const Vec3& d_moving, const Vec3& beta) {
  return aberrate(d_moving, beta, -1.0);
}

double ray_parameter_scale(const Vec3& d_f, const Vec3& beta) {
  return lorentz_gamma(beta) * (1.0 + dot(beta, d_f));
}

}  // namespace lightcone

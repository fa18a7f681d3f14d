#include "lightcone/physics/doppler.hpp"

#include "lightcone/physics/lorentz.hpp"

namespace lightcone {

double doppler_factor(const Vec3& n, const Vec3& beta_e, const Vec3& beta_r) {
  const Vec4 k{1.0, n};
  const double g_e = lorentz_gamma(beta_e), g_r = lorentz_gamma(beta_r);
  const Vec4 u_e{g_e, beta_e * g_e}, u_r{g_r, beta_r * g_r};
  return minkowski_dot(k, u_r) / minkowski_dot(k, u_e);
}

}  // namespace lightcone

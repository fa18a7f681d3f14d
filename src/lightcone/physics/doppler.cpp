#include "lightcone/physics/doppler.hpp"

#include "lightcone/physics/lorentz.hpp"

namespace lightcone {

double doppler_factor(const Vec3& n, const Vec3& beta_e, const Vec3& beta_r) {
  return doppler_factor_of_four_velocities(n, four_velocity(beta_e), four_velocity(beta_r));
}

}  // namespace lightcone

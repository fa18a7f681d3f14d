// The Doppler factor between an emitter and a receiver of the same photon.
#pragma once

#include "lightcone/physics/vec.hpp"

namespace lightcone {

// D = nu_R / nu_E for light travelling along the unit direction n (from emitter toward
// receiver), with emitter and receiver velocities beta_e, beta_r in the same frame. Computed
// as the ratio (k.U_R)/(k.U_E) of the photon's 4-momentum k = (1, n) with the 4-velocities,
// which is frame-independent. D > 1 is a blueshift; lambda_R = lambda_E / D.
double doppler_factor(const Vec3& n, const Vec3& beta_e, const Vec3& beta_r);

// The same with the 4-velocities u_e, u_r given (u = gamma (1, beta)): the law itself, which
// the form above calls; for many directions seen by the same emitter and receiver.
inline double doppler_factor_of_four_velocities(const Vec3& n, const Vec4& u_e, const Vec4& u_r) {
  const Vec4 k{1.0, n};
  return minkowski_dot(k, u_r) / minkowski_dot(k, u_e);
}

}  // namespace lightcone

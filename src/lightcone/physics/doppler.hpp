// The Doppler factor between an emitter and a receiver of the same photon.
#pragma once

#include "lightcone/physics/vec.hpp"

namespace lightcone {

// D = nu_R / nu_E for light travelling along the unit direction n (from emitter toward
// receiver), with emitter and receiver velocities beta_e, beta_r in the same frame. Computed
// as the ratio (k.U_R)/(k.U_E) of the photon's 4-momentum k = (1, n) with the 4-velocities,
// which is frame-independent. D > 1 is a blueshift; lambda_R = lambda_E / D.
double doppler_factor(const Vec3& n, const Vec3& beta_e, const Vec3& beta_r);

}  // namespace lightcone

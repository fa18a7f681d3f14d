// One leg of light from an emission event to a reception event, seen by the receiver: the
// quantities the irradiance of a moving light needs (seed 002, eqs. 18-19; PHYSICS.md).
#pragma once

#include "lightcone/physics/vec.hpp"

namespace lightcone {

struct ReceivedLeg {
  double doppler = 1;      // D = nu_receiver / nu_emitter
  double distance = 0;     // emission-to-reception distance in the receiver's rest frame
  Vec3 direction;          // propagation direction (emitter -> receiver), receiver's rest frame
  Vec3 emitted_direction;  // propagation direction in the emitter's rest frame
};

// Events and velocities in one common frame; rest frames are pure boosts of it. For a null
// separation (the exact, "surface" light delay) this is exact. For a separation that is not
// null (the approximate light-delay modes) the leg is taken as the light travelling along the
// receiver-frame spatial separation: direction and distance from it, D and the emitted
// direction from the null vector (1, direction) in the receiver's frame.
ReceivedLeg receive_leg(const Vec4& emission, const Vec3& beta_emitter, const Vec4& reception,
                        const Vec3& beta_receiver);

// Irradiance at the receiver from a point source of rest-frame intensity I (in the emitted
// direction), integrated over wavelength: D^4 I cos(alpha) / r^2 with r and alpha in the
// receiver's rest frame (seed 002, eq. 18). cos_incidence <= 0 gives 0.
double point_source_irradiance(const ReceivedLeg& leg, double intensity, double cos_incidence);

// The same per unit wavelength at the receiver's wavelength: D^5 I_lambda(D lambda) cos / r^2;
// this returns the factor D^5 cos / r^2 that multiplies I_lambda read at D lambda.
double point_source_spectral_factor(const ReceivedLeg& leg, double cos_incidence);

// Irradiance from a plane wave (a directional light) of rest-frame irradiance E on a surface
// facing it: D^2 E cos(alpha), the energy density of a plane wave scaling as D^2 (PHYSICS.md).
double plane_wave_irradiance(double doppler, double irradiance, double cos_incidence);

// The same per unit wavelength: the factor D^3 cos(alpha) that multiplies E_lambda read at
// D lambda.
double plane_wave_spectral_factor(double doppler, double cos_incidence);

}  // namespace lightcone

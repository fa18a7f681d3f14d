#include "lightcone/physics/light_path.hpp"

#include <cmath>

#include "lightcone/physics/doppler.hpp"
#include "lightcone/physics/lorentz.hpp"

namespace lightcone {

ReceivedLeg receive_leg(const Vec4& emission, const Vec3& beta_emitter, const Vec4& reception,
                        const Vec3& beta_receiver) {
  // The separation in the receiver's rest frame.
  const Vec4 in_receiver = boost(beta_receiver) * (reception - emission);
  ReceivedLeg leg;
  leg.distance = length(in_receiver.x);
  leg.direction = in_receiver.x / leg.distance;
  // The photon's 4-momentum direction (1, n) in the receiver's frame, carried to the common
  // frame and to the emitter's frame.
  const Vec4 k_receiver{1.0, leg.direction};
  const Vec4 k_common = boost(-beta_receiver) * k_receiver;
  const Vec4 k_emitter = boost(beta_emitter) * k_common;
  leg.emitted_direction = k_emitter.x / length(k_emitter.x);
  leg.doppler = doppler_factor(k_common.x / k_common.t, beta_emitter, beta_receiver);
  return leg;
}

double point_source_irradiance(const ReceivedLeg& leg, double intensity, double cos_incidence) {
  if (!(cos_incidence > 0)) return 0;
  const double d2 = leg.doppler * leg.doppler;
  return d2 * d2 * intensity * cos_incidence / (leg.distance * leg.distance);
}

double point_source_spectral_factor(const ReceivedLeg& leg, double cos_incidence) {
  if (!(cos_incidence > 0)) return 0;
  const double d2 = leg.doppler * leg.doppler;
  return d2 * d2 * leg.doppler * cos_incidence / (leg.distance * leg.distance);
}

double plane_wave_irradiance(double doppler, double irradiance, double cos_incidence) {
  if (!(cos_incidence > 0)) return 0;
  return doppler * doppler * irradiance * cos_incidence;
}

double plane_wave_spectral_factor(double doppler, double cos_incidence) {
  if (!(cos_incidence > 0)) return 0;
  return doppler * doppler * doppler * cos_incidence;
}

}  // namespace lightcone

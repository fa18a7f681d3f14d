#include "lightcone/physics/kerr.hpp"

#include <algorithm>
#include <cmath>

namespace lightcone::kerr {

double outer_horizon(double a) {
  return 1 + std::sqrt((1 - a) * (1 + a));
}

double inner_horizon(double a) {
  return a * a / outer_horizon(a);
}

double ergosphere_radius(double a, double cos_theta) {
  const double ac = a * cos_theta;
  return 1 + std::sqrt((1 - ac) * (1 + ac));
}

double isco_radius(double a, bool prograde) {
  const double z1 = 1 + std::cbrt((1 - a) * (1 + a)) * (std::cbrt(1 + a) + std::cbrt(1 - a));
  const double z2 = std::sqrt(3 * a * a + z1 * z1);
  const double root = std::sqrt((3 - z1) * (3 + z1 + 2 * z2));
  return prograde ? 3 + z2 - root : 3 + z2 + root;
}

double circular_photon_orbit_radius(double a, bool prograde) {
  return 2 * (1 + std::cos(2.0 / 3.0 * std::acos(prograde ? -a : a)));
}

double circular_orbit_angular_velocity(double a, double r, bool prograde) {
  const double r15 = r * std::sqrt(r);
  return prograde ? 1 / (r15 + a) : -1 / (r15 - a);
}

PhotonConstants spherical_photon_orbit(double a, double r) {
  const double a2 = a * a, rm1 = r - 1, r3 = r - 3;
  return {(r * r * (3 - r) - a2 * (1 + r)) / (a * rm1),
          r * r * r * (4 * a2 - r * r3 * r3) / (a2 * rm1 * rm1)};
}

ScreenPoint critical_curve_point(double a, double r, double inclination) {
  const PhotonConstants c = spherical_photon_orbit(a, r);
  const double s = std::sin(inclination), co = std::cos(inclination), cot = co / s;
  return {-c.lambda / s, c.eta + a * a * co * co - c.lambda * c.lambda * cot * cot};
}

PhotonConstants screen_constants(double a, double alpha, double beta, double inclination) {
  const double co = std::cos(inclination);
  return {-alpha * std::sin(inclination), (alpha - a) * (alpha + a) * co * co + beta * beta};
}

Zamo zamo(double a, double r, double cos_theta, double sin_theta) {
  const double a2 = a * a, r2a2 = r * r + a2;
  const double sigma = r * r + a2 * cos_theta * cos_theta;
  const double delta = (r - outer_horizon(a)) * (r - inner_horizon(a));
  const double big_a = r2a2 * r2a2 - a2 * delta * sin_theta * sin_theta;
  Zamo z;
  z.omega = 2 * a * r / big_a;
  z.lapse = std::sqrt(sigma * delta / big_a);
  z.sqrt_sigma = std::sqrt(sigma);
  z.sqrt_delta = std::sqrt(delta);
  z.phi_scale = std::sqrt(big_a / sigma) * sin_theta;
  return z;
}

namespace {
int sign_of(double x) {
  return (x > 0) - (x < 0);
}
}  // namespace

RayConstants ray_constants(double a, double r, double cos_theta, double sin_theta,
                           const ZamoDirection& n) {
  const Zamo z = zamo(a, r, cos_theta, sin_theta);
  const double l = z.phi_scale * n.n_phi;
  const double e = z.lapse + z.omega * l;
  const double p_theta = z.sqrt_sigma * n.n_theta;
  const double lambda = l / e;
  // Q / E^2 = (p_theta / E)^2 + cos^2 theta (lambda^2 / sin^2 theta - a^2).
  const double pt = p_theta / e, cot = cos_theta / sin_theta;
  const double eta = pt * pt + lambda * lambda * cot * cot - a * a * cos_theta * cos_theta;
  // Mino time per unit E runs against the photon where E < 0 (inside the ergosphere).
  const int sense = e > 0 ? 1 : -1;
  return {{lambda, eta}, sense * sign_of(n.n_r), sense * sign_of(n.n_theta)};
}

ZamoDirection zamo_direction(double a, double r, double cos_theta, double sin_theta,
                             const RayConstants& ray) {
  const Zamo z = zamo(a, r, cos_theta, sin_theta);
  const PhotonConstants& c = ray.constants;
  // Per unit E: E_loc = (1 - omega lambda) / alpha (negative where E is); p_r = +-sqrt(R) / Delta,
  // p_theta =
  // +-sqrt(Theta), and the frame's components p_r sqrt(Delta / Sigma), p_theta / sqrt(Sigma),
  // lambda / (sqrt(A / Sigma) sin theta), each over E_loc.
  const double e_loc = (1 - z.omega * c.lambda) / z.lapse;
  const double big_r = std::max(radial_potential(a, c, r), 0.0);
  const double big_theta = std::max(polar_potential(a, c, cos_theta, sin_theta), 0.0);
  return {ray.sign_r * std::sqrt(big_r) / (z.sqrt_delta * z.sqrt_sigma * e_loc),
          ray.sign_theta * std::sqrt(big_theta) / (z.sqrt_sigma * e_loc),
          c.lambda / (z.phi_scale * e_loc)};
}

double radial_potential(double a, const PhotonConstants& c, double r) {
  const double a2 = a * a, p = r * r + a2 - a * c.lambda, la = c.lambda - a;
  const double delta = r * r - 2 * r + a2;
  return p * p - delta * (c.eta + la * la);
}

double polar_potential(double a, const PhotonConstants& c, double cos_theta, double sin_theta) {
  const double cot = cos_theta / sin_theta;
  return c.eta + a * a * cos_theta * cos_theta - c.lambda * c.lambda * cot * cot;
}

}  // namespace lightcone::kerr

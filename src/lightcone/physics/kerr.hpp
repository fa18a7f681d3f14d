// A spinning (Kerr) black hole in closed form (../shared/PHYSICS.md, "Curved spacetime: a spinning
// (Kerr) black hole"): G = c = 1 and lengths in units of the hole's mass M, so that a is the spin
// a/M in [0, 1). Boyer-Lindquist coordinates (t, r, theta, phi), theta from the spin axis, the
// hole turning toward +phi. Sigma = r^2 + a^2 cos^2 theta, Delta = r^2 - 2r + a^2,
// A = (r^2 + a^2)^2 - a^2 Delta sin^2 theta.
#pragma once

namespace lightcone::kerr {

// The outer and inner horizons r_+- = 1 +- sqrt(1 - a^2) (r_- from r_+ r_- = a^2, without
// cancellation as a -> 0).
double outer_horizon(double a);
double inner_horizon(double a);
// The ergosphere's outer surface at polar angle theta: r_E = 1 + sqrt(1 - a^2 cos^2 theta).
double ergosphere_radius(double a, double cos_theta);

// The innermost stable circular orbit in the equatorial plane, prograde (co-rotating with the
// hole) or retrograde (Bardeen, Press & Teukolsky 1972): Z1 = 1 + (1 - a^2)^(1/3) ((1 + a)^(1/3) +
// (1 - a)^(1/3)), Z2 = sqrt(3 a^2 + Z1^2), r = 3 + Z2 -+ sqrt((3 - Z1)(3 + Z1 + 2 Z2)).
double isco_radius(double a, bool prograde);
// The circular photon orbit in the equatorial plane: r = 2 (1 + cos(2/3 arccos(-+a))).
double circular_photon_orbit_radius(double a, bool prograde);
// The angular velocity dphi/dt of a circular equatorial geodesic at r (Bardeen, Press & Teukolsky
// 1972): +-1 / (r^1.5 +- a), upper sign prograde.
double circular_orbit_angular_velocity(double a, double r, bool prograde);

// A photon's constants of motion per unit energy: lambda = L / E (angular momentum about the
// axis) and eta = Q / E^2 (Carter's constant).
struct PhotonConstants {
  double lambda = 0, eta = 0;
};
// The spherical photon orbit at radius r in [r_ph+, r_ph-] (Bardeen 1973; Teo 2003):
// lambda = (r^2 - a^2 - r Delta) / (a (r - 1)) = (r^2 (3 - r) - a^2 (1 + r)) / (a (r - 1)),
// eta = r^3 (4 Delta - r (r - 1)^2) / (a^2 (r - 1)^2) = r^3 (4 a^2 - r (r - 3)^2) / (a^2 (r -
// 1)^2), the second forms without cancellation as a -> 0 (where r - 3 is of order a).
PhotonConstants spherical_photon_orbit(double a, double r);

// The critical curve (the shadow's edge) seen by an observer at infinity at inclination theta_o
// from the axis: the spherical photon orbit of radius r seen at screen coordinates
// alpha = -lambda / sin theta_o, beta = +-sqrt(eta + a^2 cos^2 theta_o - lambda^2 cot^2 theta_o)
// (Bardeen 1973). beta2 < 0 where that orbit's photons never reach theta_o: no point there.
struct ScreenPoint {
  double alpha = 0, beta2 = 0;  // beta = +-sqrt(beta2)
};
ScreenPoint critical_curve_point(double a, double r, double inclination);
// The constants of the ray that reaches the distant observer at screen point (alpha, beta):
// lambda = -alpha sin theta_o, eta = (alpha^2 - a^2) cos^2 theta_o + beta^2.
PhotonConstants screen_constants(double a, double alpha, double beta, double inclination);

// The zero-angular-momentum observer (ZAMO, Bardeen 1972) at (r, theta): frame dragging
// omega = 2ar / A and lapse alpha = sqrt(Sigma Delta / A), outside the outer horizon.
struct Zamo {
  double omega = 0, lapse = 0;
  double sqrt_sigma = 0, sqrt_delta = 0;  // sqrt(Sigma), sqrt(Delta)
  double phi_scale = 0;                   // sqrt(A / Sigma) sin theta: g_phiphi^(1/2)
};
Zamo zamo(double a, double r, double cos_theta, double sin_theta);

// A photon's direction in the ZAMO's frame, a unit vector on (e_r, e_theta, e_phi), and the
// constants and senses of its motion: lambda, eta and the signs of dr/dtau and dtheta/dtau in
// Mino time per unit energy, those of n_r and n_theta unless E < 0 (a photon that only the
// ergosphere holds), where they are the opposite.
struct ZamoDirection {
  double n_r = 0, n_theta = 0, n_phi = 0;
};
struct RayConstants {
  PhotonConstants constants;
  int sign_r = 1, sign_theta = 1;  // +1, -1 (0 at a turning point)
};
// E_loc = 1: L = sqrt(A / Sigma) sin theta n_phi, E = alpha + omega L, p_theta = sqrt(Sigma)
// n_theta, Q = p_theta^2 + cos^2 theta (L^2 / sin^2 theta - a^2 E^2), divided by E and E^2.
RayConstants ray_constants(double a, double r, double cos_theta, double sin_theta,
                           const ZamoDirection& n);
// The inverse: the direction at (r, theta) of the ray with these constants and senses, from the
// radial and polar potentials R(r) and Theta(theta) (kerr_geodesic.hpp) and E_loc = (1 - omega
// lambda) / alpha. The ray must pass there (R, Theta >= 0).
ZamoDirection zamo_direction(double a, double r, double cos_theta, double sin_theta,
                             const RayConstants& ray);

// The radial and polar potentials per unit energy: (dr/dtau)^2 = R(r) and (dtheta/dtau)^2 =
// Theta(theta) in Mino time tau (Sigma dtau = d(affine parameter)).
double radial_potential(double a, const PhotonConstants& c, double r);
double polar_potential(double a, const PhotonConstants& c, double cos_theta, double sin_theta);

}  // namespace lightcone::kerr

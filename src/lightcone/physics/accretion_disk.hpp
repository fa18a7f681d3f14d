// Circular geodesics of one Schwarzschild black hole and the thin accretion disk made of them
// (PHYSICS.md, "Curved spacetime"): G = c = 1, M the gravitational radius (a length, > 0), r the
// Schwarzschild radius, f = 1 - 2M/r. Gas on circular geodesics in the equatorial plane;
// Novikov & Thorne (1973) / Page & Thorne (1974) give the flux the disk radiates from each face,
// with zero torque at the innermost stable circular orbit.
#pragma once

namespace lightcone {

// The innermost stable circular orbit, r = 6M, where the disk's inner edge lies.
double isco_radius(double mass);
// The photon sphere, r = 3M: circular orbits exist only outside it (they are null on it).
double photon_sphere_radius(double mass);

// A circular geodesic at radius r > 3M (stable for r >= 6M); NaN for r <= 3M.
// Its angular velocity seen from afar, Omega = dphi/dt = sqrt(M / r^3) (Kepler's law, exactly).
double circular_orbit_angular_velocity(double mass, double r);
// u^t = dt/dtau = 1 / sqrt(1 - 3M/r): gravitational and orbital time dilation together.
double circular_orbit_time_dilation(double mass, double r);
// Its speed measured by the static observer there, v = r Omega / sqrt(f) = sqrt(M / (r - 2M))
// (1/2 at the ISCO, 1 at the photon sphere).
double circular_orbit_local_speed(double mass, double r);
// g = nu_received / nu_emitted for light from gas on this orbit to a camera at rest at infinity,
// the photon's angular momentum about the orbit's axis per unit energy being lambda = L_z / E
// (signed: positive along the gas's motion): g = sqrt(1 - 3M/r) / (1 - Omega lambda)
// (Cunningham 1975).
double circular_orbit_frequency_shift(double mass, double r, double lambda);

// The flux F(r) emitted from each face of the disk (energy per unit time per unit proper area,
// in the frame of the gas) per unit rest-mass accretion rate Mdot (G = c = 1: Mdot a number,
// F in units of 1 / length^2), zero torque at the ISCO: 0 for r <= 6M. With x = r/M,
// y = sqrt(x) (Page & Thorne 1974, eq. 15n, for a = 0; derived again in accretion_disk.cpp):
//   F = 3 Mdot / (8 pi M^2) I(y) / ((x - 3) x^(5/2)),
//   I(y) = y - sqrt 6 + (sqrt 3 / 2) ln[(y + sqrt 3)(sqrt 6 - sqrt 3)
//                                       / ((y - sqrt 3)(sqrt 6 + sqrt 3))].
// Far out F = 3 M Mdot / (8 pi r^3) (1 - C sqrt(M / r) + O(M / r)), Newtonian in its leading
// term, but with C = sqrt 6 + (sqrt 3 / 2) ln((sqrt 6 + sqrt 3) / (sqrt 6 - sqrt 3)) = 3.976, not
// the sqrt 6 of a Newtonian disk with its inner edge at 6M: the relativistic orbits near the
// ISCO carry the difference. mass > 0.
double novikov_thorne_flux(double mass, double r);

// The maximum of novikov_thorne_flux over r: at r = 9.55M, the root of (x - 6) y = (7x - 15) I(y)
// (dF/dr = 0).
struct FluxPeak {
  double radius = 0;
  double flux = 0;  // per unit accretion rate
};
FluxPeak novikov_thorne_peak(double mass);

// (F(r) / F_peak)^(1/4): the disk's local blackbody temperature is T(r) = T_peak * this ratio
// (T = (F / sigma)^(1/4)). 0 for r <= 6M, 1 at the peak; independent of the mass for a given
// r / M.
double disk_temperature_ratio(double mass, double r);

}  // namespace lightcone

// Null geodesics of a Kerr hole in closed form (../shared/PHYSICS.md, "Curved spacetime: a
// spinning (Kerr) black hole"; units of the hole's mass, Boyer-Lindquist coordinates). No step
// size: a ray of constants lambda, eta is parametrised by its Mino time tau, in which the radial
// and polar motions separate,
//   (dr/dtau)^2 = R(r),  (dcos(theta)/dtau)^2 = a^2 (u_+ - cos^2 theta)(cos^2 theta - u_-),
// r(tau) and theta(tau) are Jacobi elliptic functions of tau, and phi and t are sums of Legendre's
// (Carlson's) elliptic integrals of the first, second and third kind (Gralla & Lupsasca 2020, "Null
// geodesics of the Kerr exterior"; Dexter & Agol 2009, "A fast new public code for computing
// photon orbits in a Kerr spacetime"). Everything is taken through Carlson's R_F, R_D and R_J
// (physics/carlson_integrals.hpp) and the Jacobi functions of physics/schwarzschild.hpp.
//
// The radial motion has three cases, by the roots r1..r4 of R (Gralla & Lupsasca's order):
//   four real roots: the ray lives on r >= r4, turning there if r4 > r_+ (it scatters), else
//                    falling through the horizon; or, from a source between the horizon and
//                    r3 > r_+, it turns at r3 and falls;
//   two real roots r1 < r2 (inside the horizon) and a complex pair: no turning point outside it;
//   no real root: the same.
// Every coordinate is exact in all three. The polar motion is ordinary (eta > 0: the ray
// oscillates about the equator between theta_+- = arccos(+-sqrt(u_+))) or vortical (eta < 0:
// it stays in one hemisphere, between arccos(sqrt(u_+)) and arccos(sqrt(u_-))).
#pragma once

#include "lightcone/physics/kerr.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone::kerr {

enum class RadialCase { FourReal, TwoReal, NoneReal };

// The roots of R(r) = r^4 + (a^2 - eta - lambda^2) r^2 + 2 (eta + (lambda - a)^2) r - a^2 eta in
// the closed form of Gralla & Lupsasca 2020 (their eq. 95): real roots in r[] in increasing
// order; a complex pair as re +- i im.
struct RadialRoots {
  RadialCase kind = RadialCase::FourReal;
  double r[4] = {};                   // FourReal: r1 <= r2 <= r3 <= r4; TwoReal: r1 <= r2
  double pair_re = 0, pair_im = 0;    // TwoReal: r3, r4 = pair_re -+ i pair_im
  double pair2_re = 0, pair2_im = 0;  // NoneReal: the pairs (pair_re, pair_im) and these
};
RadialRoots radial_roots(double a, const PhotonConstants& c);

// The polar motion of a ray from cos(theta_s) in the sense sign_theta of dtheta/dtau.
struct PolarMotion {
  bool vortical = false;
  double u_plus = 0;              // cos^2 of the turning points nearest the equator (ordinary) or
  double hemisphere = 1;          // vortical: the sign of cos(theta) throughout
  double rate = 0;                // the Jacobi argument w advances by rate per unit Mino time
  JacobiModulus jacobi;           // parameter m (see kerr_geodesic.cpp)
  double m = 0, quarter = 0;      // m and K(m)
  double pi_n = 0, pi_scale = 0;  // Pi's characteristic and 1 / ((1 - u_+) rate)
  double complete_pi = 0, complete_d = 0;   // Pi(n | m) and (K - E) / m
  double w_source = 0;                      // w at the source
  double g_phi_source = 0, g_t_source = 0;  // the antiderivatives below at w_source
  double lambda = 0, a2 = 0;
};

// The radial motion of a ray from r_s in the sense sign_r of dr/dtau.
struct RadialMotion {
  RadialRoots roots;
  double rate = 0;  // the Jacobi argument per unit Mino time
  JacobiModulus jacobi;
  double m = 0;
  double x_source = 0;  // the Jacobi argument at the source
  double x_end = 0;     // where the ray leaves the exterior (infinity or the horizon)
  int sense = 1;        // +1: the argument grows with tau (four real roots beyond r4: always)
  // FourReal: r = base + gap / (1 - n sn^2), and the characteristics of I_+-: base r3 and gap
  // r4 - r3 beyond r4; base r1 and gap r2 - r1 for a ray between the horizon and r3 (bound).
  bool bound = false;
  double base = 0, gap = 0, n = 0, n_plus = 0, n_minus = 0;
  // TwoReal: z = (r - r2) / (r - r1) = big_a (1 - cn) / (1 + cn); z's quadratic
  // h ((z - c)^2 + n^2) (Byrd & Friedman 1971, 239.00).
  double big_a = 0, quad_c = 0, quad_n = 0, quad_h = 0;
  // NoneReal: r = u + v (s + h) / (1 - h s), s = g_small sc(g_big w) (see kerr_geodesic.cpp).
  double rot_h = 0, g_small = 0, g_big = 0;
  // NoneReal: r = c0 + c1 t / (1 + gamma t), t = sc(w), and 1 / (r - r_+-) by kappa_+- (see
  // kerr_geodesic.cpp), and the integrals T1(gamma), T2(gamma), T1(kappa_+), T1(kappa_-) at the
  // source. NoneReal and bound FourReal: K, the complete (K - E) / m and the complete Pi of the
  // three characteristics (1 + kappa^2, or n and n_+-).
  double c0 = 0, c1 = 0, kappa[3] = {}, quarter = 0, complete_d = 0, complete_pi[3] = {};
  double none_real_source[4] = {};
  double r_source = 0;
  // The antiderivatives of the phi and t integrals at the source (FourReal: of the Jacobi
  // argument; TwoReal: the source's z, from which they are taken between limits).
  double pi_source = 0, pi_plus_source = 0, pi_minus_source = 0, v2_source = 0;
  double z_source = 0;
};

struct KerrRay {
  double a = 0;
  PhotonConstants constants;
  PolarMotion polar;
  RadialMotion radial;
  // The Mino time at which the ray leaves the exterior: reaches infinity or the outer horizon.
  double mino_time_limit = 0;
};
KerrRay kerr_ray(double a, const PhotonConstants& c, double r_source, double cos_theta_source,
                 int sign_r, int sign_theta);

// A point of the ray, Mino time tau (0 <= tau < mino_time_limit) after its source, and the phi
// and t that the ray has advanced since.
struct KerrPoint {
  double r = 0, cos_theta = 0, phi = 0, t = 0;
};
KerrPoint point_after(const KerrRay& ray, double tau);
// Only r and cos(theta) (no phi, t): the cheaper part of point_after.
double radius_after(const KerrRay& ray, double tau);
double cos_theta_after(const KerrRay& ray, double tau);

// The Mino time of the ray's n-th crossing (n >= 1) of the equatorial plane after its source;
// infinity for a vortical ray (which never crosses) or one in the plane (eta = 0 there).
double mino_time_to_equator(const KerrRay& ray, int crossing);
// The point of that crossing (cos(theta) = 0 exactly), its polar integrals complete ones: less
// work than point_after at that Mino time. NaN where there is no crossing.
KerrPoint point_at_equator(const KerrRay& ray, int crossing);

}  // namespace lightcone::kerr

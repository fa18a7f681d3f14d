// The Kerr hole's closed forms (physics/kerr.hpp) against their limits, published values and the
// metric itself, written out here: the circular orbits' energy and the ZAMO's tetrad are built
// from g_munu in this file, not from the library's formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "lightcone/physics/kerr.hpp"

namespace lightcone::kerr {
namespace {

constexpr double kPi = std::numbers::pi;

// Boyer-Lindquist metric components (M = 1) at (r, theta).
struct Metric {
  double tt, tphi, phiphi, rr, thth;
};
Metric metric(double a, double r, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  const double sigma = r * r + a * a * c * c, delta = r * r - 2 * r + a * a;
  const double big_a = (r * r + a * a) * (r * r + a * a) - a * a * delta * s * s;
  return {-(1 - 2 * r / sigma), -2 * a * r * s * s / sigma, big_a * s * s / sigma, sigma / delta,
          sigma};
}

// The specific energy -u_t of the circular equatorial geodesic at r of angular velocity omega.
double circular_energy(double a, double r, bool prograde) {
  const double w = circular_orbit_angular_velocity(a, r, prograde);
  const Metric g = metric(a, r, kPi / 2);
  const double ut = 1 / std::sqrt(-(g.tt + 2 * g.tphi * w + g.phiphi * w * w));
  return -(g.tt + g.tphi * w) * ut;
}

TEST(KerrClosedForms, HorizonsAndErgosphere) {
  EXPECT_DOUBLE_EQ(outer_horizon(0), 2);
  EXPECT_DOUBLE_EQ(inner_horizon(0), 0);
  EXPECT_DOUBLE_EQ(outer_horizon(1), 1);
  EXPECT_DOUBLE_EQ(inner_horizon(1), 1);
  EXPECT_NEAR(outer_horizon(0.94), 1.34117, 5e-6);
  for (double a : {1e-9, 0.3, 0.7, 0.94, 0.999}) {
    for (double r : {outer_horizon(a), inner_horizon(a)}) {
      EXPECT_NEAR(r * r - 2 * r + a * a, 0, 1e-15) << a;  // Delta = 0
    }
    EXPECT_DOUBLE_EQ(ergosphere_radius(a, 0), 2);
    EXPECT_DOUBLE_EQ(ergosphere_radius(a, 1), outer_horizon(a));
    // g_tt = 0 on the ergosphere: a static observer would need to move at c.
    for (double theta : {0.3, 1.0, 2.0}) {
      EXPECT_NEAR(metric(a, ergosphere_radius(a, std::cos(theta)), theta).tt, 0, 1e-15);
    }
  }
  EXPECT_NEAR(inner_horizon(1e-9), 0.5e-18, 1e-30);  // a^2 / 2, no cancellation
}

TEST(KerrClosedForms, IscoLimitsAndPublishedValues) {
  EXPECT_DOUBLE_EQ(isco_radius(0, true), 6);
  EXPECT_DOUBLE_EQ(isco_radius(0, false), 6);
  EXPECT_NEAR(isco_radius(1, true), 1, 1e-12);
  EXPECT_NEAR(isco_radius(1, false), 9, 1e-12);
  EXPECT_NEAR(isco_radius(0.94, true), 2.02359, 5e-6);
  EXPECT_NEAR(isco_radius(0.94, false), 8.83075, 5e-6);
}

TEST(KerrClosedForms, IscoIsTheLeastEnergyOfCircularOrbits) {
  for (double a : {0.0, 0.2, 0.5, 0.94, 0.99}) {
    for (bool prograde : {true, false}) {
      const double r = isco_radius(a, prograde), h = 1e-4 * r;
      const double slope =
          (circular_energy(a, r + h, prograde) - circular_energy(a, r - h, prograde)) / (2 * h);
      EXPECT_NEAR(slope, 0, 1e-7) << a << " " << prograde;
      // Stable outside (energy rising), so the orbit just inside costs more than the ISCO's.
      EXPECT_GT(circular_energy(a, r * 1.01, prograde), circular_energy(a, r, prograde));
      EXPECT_GT(circular_energy(a, r * 0.99, prograde), circular_energy(a, r, prograde));
    }
  }
}

TEST(KerrClosedForms, CircularPhotonOrbits) {
  EXPECT_DOUBLE_EQ(circular_photon_orbit_radius(0, true), 3);
  EXPECT_DOUBLE_EQ(circular_photon_orbit_radius(0, false), 3);
  EXPECT_NEAR(circular_photon_orbit_radius(1, true), 1, 1e-15);
  EXPECT_NEAR(circular_photon_orbit_radius(1, false), 4, 1e-15);
  EXPECT_NEAR(circular_photon_orbit_radius(0.94, true), 1.42524, 5e-6);
  EXPECT_NEAR(circular_photon_orbit_radius(0.94, false), 3.94637, 5e-6);
  for (double a : {0.1, 0.5, 0.94}) {
    for (bool prograde : {true, false}) {
      // An equatorial circular null orbit: the spherical orbit there has eta = 0.
      const double r = circular_photon_orbit_radius(a, prograde);
      const PhotonConstants c = spherical_photon_orbit(a, r);
      EXPECT_NEAR(c.eta, 0, 1e-11) << a;
      EXPECT_EQ(c.lambda > 0, prograde);
      // The orbit's photons have d(theta) = 0 and R = R' = 0 at r (a double root).
      const auto big_r = [&](double x) { return radial_potential(a, c, x); };
      EXPECT_NEAR(big_r(r), 0, 1e-10);
      EXPECT_NEAR((big_r(r + 1e-5) - big_r(r - 1e-5)) / 2e-5, 0, 1e-7);
    }
  }
}

TEST(KerrClosedForms, SphericalPhotonOrbitsAreDoubleRootsOfTheRadialPotential) {
  for (double a : {0.01, 0.5, 0.94, 0.999}) {
    const double lo = circular_photon_orbit_radius(a, true);
    const double hi = circular_photon_orbit_radius(a, false);
    for (int i = 0; i <= 10; ++i) {
      const double r = lo + (hi - lo) * i / 10.0;
      const PhotonConstants c = spherical_photon_orbit(a, r);
      const auto big_r = [&](double x) { return radial_potential(a, c, x); };
      const double scale = std::pow(r, 4);
      EXPECT_NEAR(big_r(r) / scale, 0, 1e-13) << a << " " << r;
      EXPECT_NEAR((big_r(r + 1e-5) - big_r(r - 1e-5)) / 2e-5 / std::pow(r, 3), 0, 1e-8);
      EXPECT_GE(c.eta, -1e-10);  // reaches the equator
    }
  }
}

TEST(KerrClosedForms, ShadowOfASlowHoleIsACircleOfRadiusThreeRootThree) {
  const double a = 1e-6;
  const double lo = circular_photon_orbit_radius(a, true);
  const double hi = circular_photon_orbit_radius(a, false);
  for (double inclination : {0.3, kPi / 3, kPi / 2}) {
    int points = 0;
    for (int i = 0; i <= 20; ++i) {
      const ScreenPoint p = critical_curve_point(a, lo + (hi - lo) * i / 20.0, inclination);
      if (p.beta2 < 0) continue;
      ++points;
      EXPECT_NEAR(std::sqrt(p.alpha * p.alpha + p.beta2), 3 * std::sqrt(3.0), 1e-5);
    }
    EXPECT_GT(points, 2);
  }
}

TEST(KerrClosedForms, ShadowOfAFastHoleIsShiftedTowardTheProgradeSide) {
  // Seen edge-on, the shadow's edges are the equatorial photon orbits at alpha = -lambda: the
  // prograde one (lambda > 0) at alpha < 0 hugs the hole, the retrograde one lies farther out.
  const double a = 0.94;
  const ScreenPoint pro = critical_curve_point(a, circular_photon_orbit_radius(a, true), kPi / 2);
  const ScreenPoint retro =
      critical_curve_point(a, circular_photon_orbit_radius(a, false), kPi / 2);
  EXPECT_NEAR(pro.beta2, 0, 1e-10);
  EXPECT_NEAR(retro.beta2, 0, 1e-10);
  EXPECT_LT(pro.alpha, 0);
  EXPECT_GT(retro.alpha, 0);
  EXPECT_GT(retro.alpha, -pro.alpha + 2);  // the shadow's centre shifted by more than 1 M
}

TEST(KerrClosedForms, ScreenConstantsRoundTripTheCriticalCurve) {
  const double a = 0.94, inclination = 17 * kPi / 180;
  const double lo = circular_photon_orbit_radius(a, true);
  const double hi = circular_photon_orbit_radius(a, false);
  for (int i = 0; i <= 20; ++i) {
    const double r = lo + (hi - lo) * i / 20.0;
    const ScreenPoint p = critical_curve_point(a, r, inclination);
    if (p.beta2 < 0) continue;
    const PhotonConstants c = screen_constants(a, p.alpha, std::sqrt(p.beta2), inclination);
    const PhotonConstants want = spherical_photon_orbit(a, r);
    EXPECT_NEAR(c.lambda, want.lambda, 1e-12);
    EXPECT_NEAR(c.eta, want.eta, 1e-11);
  }
}

// The photon of unit local energy along n in the ZAMO's frame, built from the tetrad of
// PHYSICS.md on this file's metric: p = e_t + n_r e_r + n_theta e_theta + n_phi e_phi.
struct Momentum {
  double t, r, theta, phi;  // contravariant components
};
Momentum tetrad_momentum(double a, double r, double theta, const ZamoDirection& n) {
  const Metric g = metric(a, r, theta);
  const double omega = -g.tphi / g.phiphi;
  const double lapse = std::sqrt(g.tphi * g.tphi / g.phiphi - g.tt);
  return {1 / lapse, n.n_r / std::sqrt(g.rr), n.n_theta / std::sqrt(g.thth),
          omega / lapse + n.n_phi / std::sqrt(g.phiphi)};
}

ZamoDirection random_direction(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  double x = normal(rng), y = normal(rng), z = normal(rng);
  const double len = std::sqrt(x * x + y * y + z * z);
  return {x / len, y / len, z / len};
}

TEST(KerrZamo, ConstantsAreTheMomentumsOwnAndTheDirectionRoundTrips) {
  std::mt19937 rng(56);
  std::uniform_real_distribution<double> unit(0, 1);
  for (double a : {0.0, 1e-12, 0.5, 0.94, 0.999}) {
    for (int i = 0; i < 200; ++i) {
      const double r = outer_horizon(a) * (1.01 + 30 * unit(rng));
      const double theta = 0.05 + (kPi - 0.1) * unit(rng);
      const double c = std::cos(theta), s = std::sin(theta);
      const ZamoDirection n = random_direction(rng);
      const RayConstants ray = ray_constants(a, r, c, s, n);

      const Metric g = metric(a, r, theta);
      const Momentum p = tetrad_momentum(a, r, theta, n);
      EXPECT_NEAR(g.tt * p.t * p.t + 2 * g.tphi * p.t * p.phi + g.phiphi * p.phi * p.phi +
                      g.rr * p.r * p.r + g.thth * p.theta * p.theta,
                  0, 1e-12 * (1 + p.t * p.t));  // the tetrad is orthonormal
      const double e = -(g.tt * p.t + g.tphi * p.phi), l = g.tphi * p.t + g.phiphi * p.phi;
      const double p_theta = g.thth * p.theta;
      EXPECT_NEAR(ray.constants.lambda, l / e, 1e-12 * (1 + std::abs(l / e)));
      const double q = p_theta * p_theta + c * c * (l * l / (s * s) - a * a * e * e);
      EXPECT_NEAR(ray.constants.eta, q / (e * e), 1e-11 * (1 + std::abs(q / (e * e))));
      // Mino time: dr/dtau = Sigma p^r / E and dtheta/dtau = Sigma p^theta / E obey the
      // potentials.
      const double sigma = g.thth;
      const double dr = sigma * p.r / e, dtheta = sigma * p.theta / e;
      const double rr = radial_potential(a, ray.constants, r);
      EXPECT_NEAR(dr * dr, rr, 1e-9 * (1 + std::abs(rr)));
      const double th = polar_potential(a, ray.constants, c, s);
      EXPECT_NEAR(dtheta * dtheta, th, 1e-9 * (1 + std::abs(th)));

      const ZamoDirection back = zamo_direction(a, r, c, s, ray);
      EXPECT_NEAR(back.n_r, n.n_r, 1e-9);
      EXPECT_NEAR(back.n_theta, n.n_theta, 1e-9);
      EXPECT_NEAR(back.n_phi, n.n_phi, 1e-12);
    }
  }
}

}  // namespace
}  // namespace lightcone::kerr

// Circular orbits and the thin disk (accretion_disk.hpp) against derivations made here: the
// circular geodesic from the Christoffel symbols of the metric (differentiated by the complex
// step), the effective potential, the Page-Thorne flux integral by quadrature with its ingredients
// differentiated by the complex step, the frequency shift as a contraction of 4-vectors, and the
// flux's peak by a dense scan. Units: G = c = 1, M = 1 unless a test says otherwise.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <initializer_list>
#include <numbers>

#include "lightcone/physics/accretion_disk.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;

// The derivative of g at x by the complex step, Im g(x + ih) / h (Squire & Trapp 1998): no
// difference of nearby values, so exact to rounding in long double for an analytic g written
// generically (it is called with std::complex<long double>).
template <class G>
long double derivative(G g, long double x) {
  const long double h = 1e-40L * x;
  return std::imag(g(std::complex<long double>(x, h))) / h;
}

template <class T>
T metric_f(long double m, T r) {
  return 1.0L - 2 * m / r;
}

TEST(CircularOrbit, RadiiOfTheIscoAndThePhotonSphere) {
  EXPECT_EQ(isco_radius(1), 6);
  EXPECT_EQ(isco_radius(2.5), 15);
  EXPECT_EQ(photon_sphere_radius(2.5), 7.5);
  // The ISCO is where the circular orbits' angular momentum L^2 = M r^2 / (r - 3M) (from the
  // effective potential below) is least: dL^2/dr changes sign there.
  const auto l2 = [](auto r) { return r * r / (r - 3.0L); };
  EXPECT_LT(derivative(l2, 5.99L), 0);
  EXPECT_GT(derivative(l2, 6.01L), 0);
  EXPECT_NEAR(static_cast<double>(derivative(l2, 6.0L)), 0, 1e-15);
  // The photon sphere is the circular null orbit: its impact parameter r / sqrt(f) is the
  // critical one.
  EXPECT_NEAR(3 / std::sqrt(1 - 2.0 / 3), critical_impact_parameter(1), 1e-15);
}

TEST(CircularOrbit, AngularVelocityAndTimeDilationFromTheGeodesicEquation) {
  for (double m : {1.0, 0.3}) {
    for (double r : {3.2, 4.0, 6.0, 9.5, 30.0, 1e4}) {
      const double rr = r * m;  // the same r / M for each mass
      // A circular orbit has u^r = 0 and du^r/dtau = 0: Gamma^r_tt (u^t)^2 + Gamma^r_phiphi
      // (u^phi)^2 = 0, with Gamma^r_tt = f f' / 2 and Gamma^r_phiphi = -f r (equatorial), so
      // Omega^2 = f' / (2r); and the normalisation -f (u^t)^2 + r^2 (u^phi)^2 = -1 gives u^t.
      const auto f = [m](auto x) { return metric_f(m, x); };
      const long double df = derivative(f, rr);
      const long double omega = std::sqrt(df / (2 * rr));
      const long double ut = 1 / std::sqrt(f(rr) - rr * rr * omega * omega);
      EXPECT_NEAR(circular_orbit_angular_velocity(m, rr), static_cast<double>(omega), 1e-14 * omega)
          << m << " " << r;
      EXPECT_NEAR(circular_orbit_time_dilation(m, rr), static_cast<double>(ut), 1e-14 * ut)
          << m << " " << r;
      // The effective potential V = f (1 + L^2 / r^2): V' = 0 gives L^2 = M r^2 / (r - 3M),
      // E^2 = V; then u^t = E / f, u^phi = L / r^2.
      const long double l2 = m * rr * rr / (rr - 3 * m);
      const long double e = std::sqrt(f(rr) * (1 + l2 / (rr * rr)));
      const auto v = [&](auto x) { return metric_f(m, x) * (1.0L + l2 / (x * x)); };
      EXPECT_NEAR(static_cast<double>(derivative(v, rr)), 0, 1e-15 / m) << r;
      EXPECT_NEAR(circular_orbit_time_dilation(m, rr), static_cast<double>(e / f(rr)), 1e-14 * ut);
      EXPECT_NEAR(circular_orbit_angular_velocity(m, rr),
                  static_cast<double>(std::sqrt(l2) / (rr * rr) / (e / f(rr))), 1e-14 * omega);
      // The static observer there: v = r Omega / sqrt(f), and gamma = u^t sqrt(f).
      const double speed = circular_orbit_local_speed(m, rr);
      EXPECT_NEAR(speed, static_cast<double>(rr * omega / std::sqrt(f(rr))), 1e-14 * speed);
      EXPECT_NEAR(1 / std::sqrt(1 - speed * speed), static_cast<double>(ut * std::sqrt(f(rr))),
                  1e-14 * ut);
    }
  }
  EXPECT_NEAR(circular_orbit_local_speed(1, 6), 0.5, 1e-16);  // at the ISCO
  EXPECT_TRUE(std::isnan(circular_orbit_angular_velocity(1, 3)));
  EXPECT_TRUE(std::isnan(circular_orbit_time_dilation(1, 2.5)));
  EXPECT_TRUE(std::isnan(circular_orbit_frequency_shift(1, 3, 0)));
}

TEST(CircularOrbit, FrequencyShiftIsTheContractionOfMomentumAndVelocities) {
  // The photon's covariant 4-momentum at the emitter (equatorial, theta = pi/2) p_mu = (-E, p_r,
  // p_theta, L_z), E = 1, L_z = lambda, p_r from g^{mu nu} p_mu p_nu = 0; the gas's u^mu =
  // u^t (1, 0, 0, Omega) with u^t and Omega from the geodesic (as above); a static camera at
  // radius R has u^mu = (1 / sqrt f(R), 0, 0, 0), and E is conserved along the ray. g =
  // (p . u_camera) / (p . u_gas), and R -> infinity is the camera at rest at infinity.
  for (double r : {4.0, 6.0, 10.0, 100.0}) {
    const long double f = metric_f(1, r);
    const long double omega = std::sqrt(1 / (r * r * r * 1.0L));
    const long double ut = 1 / std::sqrt(f - r * r * omega * omega);
    const long double b_max = r / std::sqrt(f);  // |lambda| up to the tangential ray
    for (double s : {-0.99, -0.5, 0.0, 0.3, 0.7, 0.99}) {
      const long double lambda = s * b_max;
      for (long double p_theta : {0.0L, 0.2L * std::sqrt(1 - s * s) * r / std::sqrt(f)}) {
        const long double pr2 = (1 / f - (p_theta * p_theta + lambda * lambda) / (r * r)) / f;
        ASSERT_GE(pr2, 0) << r << " " << s;
        const long double p_dot_gas = -1 * ut + lambda * ut * omega;  // p_t u^t + p_phi u^phi
        for (long double big_r : {1e3L, 1e9L}) {
          const long double p_dot_camera = -1 / std::sqrt(metric_f(1, big_r));
          const double g = static_cast<double>(p_dot_camera / p_dot_gas);
          const double far = circular_orbit_frequency_shift(1, r, static_cast<double>(lambda));
          // The camera at R sees g / sqrt(f(R)): the static blueshift from infinity to R.
          EXPECT_NEAR(g, far / std::sqrt(static_cast<double>(metric_f(1, big_r))), 1e-13 * g)
              << r << " " << s;
        }
      }
    }
    // Light sent with lambda = 0 shows the time dilation alone.
    EXPECT_NEAR(circular_orbit_frequency_shift(1, r, 0), 1 / static_cast<double>(ut), 1e-15);
  }
}

// --- The Novikov-Thorne / Page-Thorne flux ---

// F(r) = -(Mdot / (4 pi sqrt(-g))) Omega_{,r} / (E - Omega L)^2 int_{r_isco}^r (E - Omega L)
// L_{,r} dr (Page & Thorne 1974, eq. 15; Mdot = 1), sqrt(-g) = r, with E, L, Omega of the
// circular orbits written here and their derivatives by the complex step; Simpson's rule on n
// intervals.
double page_thorne_quadrature(long double m, long double r, int n = 20000) {
  const auto e = [m](auto x) { return (1.0L - 2 * m / x) / std::sqrt(1.0L - 3 * m / x); };
  const auto l = [m](auto x) { return std::sqrt(m * x) / std::sqrt(1.0L - 3 * m / x); };
  const auto omega = [m](auto x) { return std::sqrt(m / (x * x * x)); };
  const auto integrand = [&](long double x) { return (e(x) - omega(x) * l(x)) * derivative(l, x); };
  const long double a = 6 * m, h = (r - a) / n;
  long double sum = integrand(a) + integrand(r);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * integrand(a + i * h);
  const long double integral = sum * h / 3;
  const long double de = e(r) - omega(r) * l(r);
  return static_cast<double>(-1 / (4 * std::numbers::pi_v<long double> * r) * derivative(omega, r) /
                             (de * de) * integral);
}

TEST(NovikovThorne, FluxIsThePageThorneIntegral) {
  for (double m : {1.0, 3.0}) {
    for (double x : {6.1, 7.0, 9.55, 12.0, 30.0, 200.0}) {
      const double expected = page_thorne_quadrature(m, x * m);
      EXPECT_NEAR(novikov_thorne_flux(m, x * m), expected, 1e-12 * expected) << m << " " << x;
    }
  }
  // Close to the ISCO the flux vanishes like (r - 6M)^2, computed without cancellation.
  for (double d : {1e-3, 1e-5, 1e-7}) {
    const double expected = page_thorne_quadrature(1, 6 + d, 200);
    EXPECT_NEAR(novikov_thorne_flux(1, 6 + d), expected, 1e-11 * expected) << d;
  }
  EXPECT_EQ(novikov_thorne_flux(1, 6), 0);
  EXPECT_EQ(novikov_thorne_flux(1, 4), 0);
  EXPECT_EQ(novikov_thorne_flux(1, INFINITY), 0);
}

TEST(NovikovThorne, FarOutTheFluxIsNewtonianToLeadingOrder) {
  // 3 M Mdot / (8 pi r^3) (1 - C sqrt(M / r) + O(M / r)), C = sqrt 6 + (sqrt 3 / 2)
  // ln((sqrt 6 + sqrt 3) / (sqrt 6 - sqrt 3)): int_6^x (1 - 3 / (r - 3)) dr / (2 sqrt r) is
  // sqrt x - C + O(1 / sqrt x).
  const double c = std::sqrt(6.0) + std::sqrt(3.0) / 2 *
                                        std::log((std::sqrt(6.0) + std::sqrt(3.0)) /
                                                 (std::sqrt(6.0) - std::sqrt(3.0)));
  for (double r : {1e4, 1e6, 1e8}) {
    const double newton = 3 / (8 * kPi * r * r * r) * (1 - c / std::sqrt(r));
    EXPECT_NEAR(novikov_thorne_flux(1, r), newton, 10 / r * newton) << r;
  }
}

TEST(NovikovThorne, PeakByADenseScan) {
  double best_x = 0, best = 0;
  for (double x = 6; x <= 30; x += 1e-4) {
    const double f = novikov_thorne_flux(1, x);
    if (f > best) best = f, best_x = x;
  }
  const FluxPeak peak = novikov_thorne_peak(1);
  EXPECT_NEAR(peak.radius, best_x, 1e-4);
  EXPECT_NEAR(peak.radius, 9.55, 0.01);  // Page & Thorne (1974): about 9.55M
  EXPECT_GE(peak.flux, best);
  EXPECT_NEAR(peak.flux, best, 1e-8 * best);
  EXPECT_EQ(peak.flux, novikov_thorne_flux(1, peak.radius));
  // A stationary point: the flux either side is lower, and symmetric to second order.
  for (double d : {1e-3, 1e-2}) {
    const double lo = novikov_thorne_flux(1, peak.radius - d);
    const double hi = novikov_thorne_flux(1, peak.radius + d);
    EXPECT_LT(lo, peak.flux);
    EXPECT_LT(hi, peak.flux);
    EXPECT_NEAR((hi - lo) / (peak.flux - lo), 0, 20 * d);
  }
  // Lengths scale with M, the flux per unit accretion rate as 1 / M^2.
  const FluxPeak heavy = novikov_thorne_peak(4);
  EXPECT_NEAR(heavy.radius, 4 * peak.radius, 1e-14 * heavy.radius);
  EXPECT_NEAR(heavy.flux, peak.flux / 16, 1e-15 * peak.flux);
}

TEST(NovikovThorne, TemperatureRatio) {
  const FluxPeak peak = novikov_thorne_peak(2);
  EXPECT_NEAR(disk_temperature_ratio(2, peak.radius), 1, 1e-15);
  EXPECT_EQ(disk_temperature_ratio(2, 12), 0);  // the ISCO
  EXPECT_EQ(disk_temperature_ratio(2, 5), 0);
  for (double r : {13.0, 19.1, 40.0, 1e3}) {
    const double ratio = disk_temperature_ratio(2, r);
    EXPECT_NEAR(ratio, std::pow(novikov_thorne_flux(2, r) / peak.flux, 0.25), 1e-15) << r;
    EXPECT_LE(ratio, 1) << r;
    EXPECT_EQ(ratio, disk_temperature_ratio(1, r / 2)) << r;  // depends on r / M alone
  }
  // Far out T ~ r^(-3/4).
  EXPECT_NEAR(disk_temperature_ratio(1, 2e6) / disk_temperature_ratio(1, 1e6), std::pow(2, -0.75),
              1e-3);
}

}  // namespace
}  // namespace lightcone

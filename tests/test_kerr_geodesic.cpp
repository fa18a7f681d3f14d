// The Kerr hole's exact null geodesics (physics/kerr_geodesic.hpp) against the geodesic equations
// integrated numerically here (Boost.Odeint's Runge-Kutta-Fehlberg 7(8) in Mino time, in long
// double to 1e-19 a step, the radial and polar motions in their second-order form so that turning
// points need no care), the
// Schwarzschild kernel in the limit of small spin, and the constants of motion along rays.
#include <gtest/gtest.h>

#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "lightcone/physics/kerr.hpp"
#include "lightcone/physics/kerr_geodesic.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone::kerr {
namespace {

constexpr double kPi = std::numbers::pi;

// (r, theta, phi, t, dr/dtau, dtheta/dtau) in Mino time, per unit energy (PHYSICS.md's
// equations, differentiated once for r and theta: d^2 r/dtau^2 = R'(r) / 2, d^2 theta/dtau^2 =
// Theta'(theta) / 2).
using Real = long double;
using State = std::array<Real, 6>;
struct Equations {
  Real a, lambda, eta;
  void operator()(const State& y, State& dy, Real) const {
    const Real r = y[0], c = std::cos(y[1]), s = std::sin(y[1]);
    const Real a2 = a * a, p = r * r + a2 - a * lambda, delta = r * r - 2 * r + a2;
    const Real k = eta + (lambda - a) * (lambda - a);
    dy[0] = y[4];
    dy[1] = y[5];
    dy[2] = a * p / delta + lambda / (s * s) - a;
    dy[3] = (r * r + a2) * p / delta + a * (lambda - a * s * s);
    dy[4] = (4 * r * p - (2 * r - 2) * k) / 2;
    dy[5] = (-2 * a2 * c * s + 2 * lambda * lambda * c / (s * s * s)) / 2;
  }
};

// A ray's source: spin, Boyer-Lindquist r and theta, its constants and senses in Mino time.
struct Source {
  double a, r, theta;
  RayConstants ray;
};

// The numerically integrated ray at the given Mino times.
std::vector<State> integrate(const Source& src, const std::vector<double>& times) {
  using namespace boost::numeric::odeint;
  // The potentials in long double: rounding of the initial speeds would change the ray's
  // constants, to which a ray near the critical curve is sensitive.
  const PhotonConstants& c = src.ray.constants;
  const Real a = src.a, lambda = c.lambda, eta = c.eta, r = src.r;
  const Real cth = std::cos(Real(src.theta)), sth = std::sin(Real(src.theta));
  const Real p = r * r + a * a - a * lambda, delta = r * r - 2 * r + a * a;
  const Real big_r = p * p - delta * (eta + (lambda - a) * (lambda - a));
  const Real big_theta = eta + a * a * cth * cth - lambda * lambda * cth * cth / (sth * sth);
  State y{r,
          Real(src.theta),
          0,
          0,
          src.ray.sign_r * std::sqrt(std::max(big_r, Real(0))),
          src.ray.sign_theta * std::sqrt(std::max(big_theta, Real(0)))};
  std::vector<State> out;
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"  // inside Odeint's stepper's copy
  auto stepper =
      make_controlled<runge_kutta_fehlberg78<State, Real, State, Real>>(Real(1e-19), Real(1e-19));
#pragma GCC diagnostic pop
  Real t = 0;
  for (Real target : times) {
    integrate_adaptive(stepper, Equations{src.a, c.lambda, c.eta}, y, t, target,
                       (target - t) / 100);
    t = target;
    out.push_back(y);
  }
  return out;
}

// A source at r, theta sending a ray along n in the ZAMO's frame.
Source zamo_source(double a, double r, double theta, double nr, double nt, double np) {
  const double len = std::sqrt(nr * nr + nt * nt + np * np);
  return {a, r, theta,
          ray_constants(a, r, std::cos(theta), std::sin(theta), {nr / len, nt / len, np / len})};
}

Source random_source(std::mt19937& rng, double a) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::normal_distribution<double> normal;
  return zamo_source(a, outer_horizon(a) + 2 + 40 * unit(rng) * unit(rng),
                     0.1 + (kPi - 0.2) * unit(rng), normal(rng), normal(rng), normal(rng));
}

struct Counts {
  int bound = 0, turning = 0, outgoing_four_real = 0, plunging_four_real = 0, two_real = 0,
      none_real = 0, vortical = 0, ordinary = 0, many_crossings = 0;
};

// Compares a ray's closed form with its integration at points spread over its Mino time, up to
// where it reaches r = 200 or comes within 1e-2 of the horizon, to the relative tolerance given;
// returns whether it was checked.
bool compare(const Source& src, Counts& counts, double tolerance = 1e-8) {
  const double cth = std::cos(src.theta);
  const RayConstants& rc = src.ray;
  if (rc.sign_r == 0 || rc.sign_theta == 0) return false;
  const KerrRay ray = kerr_ray(src.a, rc.constants, src.r, cth, rc.sign_r, rc.sign_theta);
  const RadialRoots& roots = ray.radial.roots;
  double end = ray.mino_time_limit;
  // Stop short of the horizon or r = 200, where the integrator's steps shrink.
  for (int i = 0; i < 60; ++i) {
    const double r = radius_after(ray, end);
    if (r < 200 && r > outer_horizon(src.a) + 1e-2) break;
    end *= 0.97;
  }
  std::vector<double> times;
  for (int i = 1; i <= 8; ++i) times.push_back(end * i / 8);
  const std::vector<State> want = integrate(src, times);
  for (size_t i = 0; i < times.size(); ++i) {
    const KerrPoint got = point_after(ray, times[i]);
    const std::array<double, 4> w{double(want[i][0]), double(want[i][1]), double(want[i][2]),
                                  double(want[i][3])};
    EXPECT_NEAR(got.r, w[0], tolerance * w[0]) << "tau " << times[i];
    EXPECT_NEAR(got.cos_theta, std::cos(w[1]), tolerance);
    EXPECT_EQ(radius_after(ray, times[i]), got.r);
    EXPECT_EQ(cos_theta_after(ray, times[i]), got.cos_theta);
    EXPECT_NEAR(got.phi, w[2], tolerance * (1 + std::abs(w[2]))) << "tau " << times[i];
    EXPECT_NEAR(got.t, w[3], tolerance * (1 + std::abs(w[3]))) << "tau " << times[i];
  }
  if (::testing::Test::HasFailure()) {
    ADD_FAILURE() << "a " << src.a << " r " << src.r << " theta " << src.theta << " lambda "
                  << rc.constants.lambda << " eta " << rc.constants.eta << " case "
                  << int(roots.kind) << " vortical " << ray.polar.vortical;
    return true;
  }
  if (ray.radial.bound) {
    ++counts.bound;
  } else if (roots.kind == RadialCase::FourReal) {
    (rc.sign_r > 0                       ? counts.outgoing_four_real
     : roots.r[3] > outer_horizon(src.a) ? counts.turning
                                         : counts.plunging_four_real)++;
  }
  if (roots.kind == RadialCase::TwoReal) ++counts.two_real;
  if (roots.kind == RadialCase::NoneReal) ++counts.none_real;
  (ray.polar.vortical ? counts.vortical : counts.ordinary)++;
  if (mino_time_to_equator(ray, 3) < end) ++counts.many_crossings;
  return true;
}

void print(const Counts& c) {
  std::printf(
      "bound %d, turning %d, four real roots outgoing %d, plunging %d, two real %d, none real %d, "
      "vortical %d, ordinary %d, three equator crossings or more %d\n",
      c.bound, c.turning, c.outgoing_four_real, c.plunging_four_real, c.two_real, c.none_real,
      c.vortical, c.ordinary, c.many_crossings);
}

TEST(KerrGeodesic, RandomRaysAgreeWithTheIntegratedGeodesicEquations) {
  std::mt19937 rng(56);
  Counts counts;
  for (double a : {0.3, 0.94, 0.999}) {
    for (int i = 0; i < 120 && !HasFailure(); ++i) compare(random_source(rng, a), counts);
  }
  print(counts);
  EXPECT_GT(counts.turning, 50);
  EXPECT_GT(counts.outgoing_four_real, 50);
  EXPECT_GT(counts.two_real, 30);
}

// Rays of the spherical photon orbits' constants, eta a part in 1e5 or 1e3 off, sent from
// r = 30 on the equator: they wind about the hole, crossing the equator again and again, before
// they escape (four real roots, r3 and r4 a hair apart) or fall (two real roots). After those
// windings the integration's own result moves by some 1e-8 between steps to 1e-17 and 1e-19, and
// an ulp of eta moves the ray by 1e-9: the tolerance is 1e-7.
TEST(KerrGeodesic, RaysNearTheCriticalCurveAgree) {
  Counts counts;
  for (double a : {0.5, 0.94}) {
    const double lo = circular_photon_orbit_radius(a, true);
    const double hi = circular_photon_orbit_radius(a, false);
    for (int i = 1; i < 8; ++i) {
      const PhotonConstants orbit = spherical_photon_orbit(a, lo + (hi - lo) * i / 8);
      for (double off : {-1e-3, -1e-5, 1e-5, 1e-3}) {
        const PhotonConstants c{orbit.lambda, orbit.eta * (1 + off)};
        for (int sign_theta : {-1, 1}) {
          if (!HasFailure()) compare({a, 30, kPi / 2, {c, -1, sign_theta}}, counts, 1e-7);
        }
      }
    }
  }
  print(counts);
  EXPECT_GT(counts.turning, 20);
  EXPECT_GT(counts.two_real, 20);
  EXPECT_GT(counts.many_crossings, 40);
}

// Rays from inside the photon shell, r_+ + 0.02 to 3.5 at spin 0.94, 0.999: those with four
// real roots and r3 above the source turn there (outgoing) and fall.
TEST(KerrGeodesic, RaysFromInsideThePhotonShellAgree) {
  Counts counts;
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> unit(0, 1);
  std::normal_distribution<double> normal;
  for (double a : {0.94, 0.999}) {
    for (int i = 0; i < 150 && !HasFailure(); ++i) {
      const double r = outer_horizon(a) + 0.02 + (3.5 - outer_horizon(a)) * unit(rng);
      compare(zamo_source(a, r, 0.3 + 2.5 * unit(rng), normal(rng), normal(rng), normal(rng)),
              counts);
    }
  }
  print(counts);
  EXPECT_GT(counts.bound, 20);
}

// Rays sent from near the axis nearly along it, in and out: lambda^2 < a^2 and eta < 0, so they
// stay in their hemisphere (vortical motion), and many have no real radial root.
TEST(KerrGeodesic, VorticalRaysAgree) {
  Counts counts;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (double a : {0.5, 0.94, 0.999}) {
    for (int i = 0; i < 40 && !HasFailure(); ++i) {
      const double theta = i % 2 ? 0.2 + 0.1 * unit(rng) : kPi - 0.2 + 0.1 * unit(rng);
      compare(zamo_source(a, 3 + 10 * std::abs(unit(rng)), theta, i % 4 < 2 ? -1 : 1,
                          0.1 * unit(rng), 0.1 * unit(rng)),
              counts);
    }
  }
  print(counts);
  EXPECT_GT(counts.vortical, 40);
  EXPECT_GT(counts.none_real, 40);
}

}  // namespace
}  // namespace lightcone::kerr

namespace lightcone::kerr {
namespace {

// The n-th crossing is on the equator, the motion between crossings stays on one side, and
// point_at_equator (complete polar integrals) is point_after at the crossing's Mino time.
TEST(KerrGeodesic, EquatorCrossings) {
  std::mt19937 rng(9);
  int checked = 0;
  for (int i = 0; i < 300; ++i) {
    const Source src = random_source(rng, 0.94);
    const KerrRay ray = kerr_ray(src.a, src.ray.constants, src.r, std::cos(src.theta),
                                 src.ray.sign_r, src.ray.sign_theta);
    if (ray.polar.vortical) continue;
    double before = 0;
    for (int n = 1; n <= 3; ++n) {
      const double tau = mino_time_to_equator(ray, n);
      if (!(tau < ray.mino_time_limit)) break;
      ++checked;
      EXPECT_GT(tau, before);
      EXPECT_NEAR(cos_theta_after(ray, tau), 0, 1e-12);
      // Halfway from the last crossing (or the source) cos(theta) has the sign it had leaving it.
      const double mid = cos_theta_after(ray, (before + tau) / 2);
      const double after = cos_theta_after(ray, tau * (1 + 1e-9) + 1e-12);
      EXPECT_LT(mid * after, 0) << n;
      const KerrPoint want = point_after(ray, tau), got = point_at_equator(ray, n);
      EXPECT_NEAR(got.r, want.r, 1e-12 * want.r);
      EXPECT_EQ(got.cos_theta, 0);
      EXPECT_NEAR(got.phi, want.phi, 1e-10 * (1 + std::abs(want.phi)));
      EXPECT_NEAR(got.t, want.t, 1e-10 * (1 + std::abs(want.t)));
      before = tau;
    }
  }
  EXPECT_GT(checked, 150);
}

// At spin 1e-12 a ray is the Schwarzschild kernel's of impact parameter b = sqrt(eta + lambda^2)
// in its own plane: the angle it sweeps there is b times its Mino time (dpsi = b dtau, as
// d(affine) = r^2 dtau), its radius radius_after_angle's, its time coordinate_time's.
TEST(KerrGeodesic, SmallSpinIsSchwarzschild) {
  std::mt19937 rng(12);
  int turning = 0, falling = 0;
  for (int i = 0; i < 200; ++i) {
    const Source src = random_source(rng, 1e-12);
    if (src.ray.sign_r > 0) continue;
    const PhotonConstants& c = src.ray.constants;
    const KerrRay ray = kerr_ray(src.a, c, src.r, std::cos(src.theta), -1, src.ray.sign_theta);
    const double b = std::sqrt(c.eta + c.lambda * c.lambda);
    const PhotonOrbit orbit = photon_orbit(1, b);
    (orbit.turning ? turning : falling)++;
    for (int k = 1; k <= 6; ++k) {
      const double tau = ray.mino_time_limit * k / 7;
      const KerrPoint p = point_after(ray, tau);
      EXPECT_NEAR(p.r, radius_after_angle(orbit, src.r, false, b * tau), 1e-9 * p.r);
      // The time along the monotonic stretches: in to the periapsis, then out.
      const bool past = orbit.turning && radius_after(ray, tau * (1 + 1e-6)) > p.r;
      const double t = past ? coordinate_time(orbit, orbit.periapsis, src.r) +
                                  coordinate_time(orbit, orbit.periapsis, p.r)
                            : coordinate_time(orbit, p.r, src.r);
      EXPECT_NEAR(p.t, t, 1e-9 * (1 + t)) << "b " << b << " r_s " << src.r << " r " << p.r;
      if (HasFailure()) return;
    }
  }
  EXPECT_GT(turning, 20);
  EXPECT_GT(falling, 10);
}

// The Mino-time speeds of a ray's closed form (central differences) obey its potentials:
// (dr/dtau)^2 = R(r) and (dcos(theta)/dtau)^2 = sin^2(theta) Theta(theta); and its phi and t grow
// at PHYSICS.md's rates.
TEST(KerrGeodesic, ConstantsOfMotionHoldAlongRays) {
  std::mt19937 rng(21);
  for (int i = 0; i < 100; ++i) {
    const Source src = random_source(rng, 0.94);
    const PhotonConstants& c = src.ray.constants;
    const KerrRay ray =
        kerr_ray(src.a, c, src.r, std::cos(src.theta), src.ray.sign_r, src.ray.sign_theta);
    const double a = src.a;
    for (int k = 1; k <= 5; ++k) {
      const double tau = ray.mino_time_limit * k / 6, h = 1e-5 * ray.mino_time_limit;
      const KerrPoint lo = point_after(ray, tau - h), mid = point_after(ray, tau),
                      hi = point_after(ray, tau + h);
      const double dr = (hi.r - lo.r) / (2 * h), dx = (hi.cos_theta - lo.cos_theta) / (2 * h);
      const double dphi = (hi.phi - lo.phi) / (2 * h), dt = (hi.t - lo.t) / (2 * h);
      const double x = mid.cos_theta, s2 = 1 - x * x, r = mid.r;
      const double big_r = radial_potential(a, c, r);
      EXPECT_NEAR(dr * dr, big_r, 1e-6 * (1 + big_r));
      const double theta_speed2 = s2 * polar_potential(a, c, x, std::sqrt(s2));
      EXPECT_NEAR(dx * dx, theta_speed2, 1e-6 * (1 + theta_speed2));
      const double p = r * r + a * a - a * c.lambda, delta = r * r - 2 * r + a * a;
      const double want_phi = a * p / delta + c.lambda / s2 - a;
      const double want_t = (r * r + a * a) * p / delta + a * (c.lambda - a * s2);
      EXPECT_NEAR(dphi, want_phi, 1e-6 * (1 + std::abs(want_phi)));
      EXPECT_NEAR(dt, want_t, 1e-6 * (1 + std::abs(want_t)));
    }
    if (HasFailure()) return;
  }
}

}  // namespace
}  // namespace lightcone::kerr

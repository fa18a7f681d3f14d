// The images of a point past a Schwarzschild hole (physics/schwarzschild_lens.hpp) against
// derivations made here: each image's ray followed by integrating u'' = 3 M u^2 - u and
// dt/dphi = r^2 / (b f) step by step from the observer (it must arrive at the point's radius
// after sweeping the image's angle, in the time found), the straight line of flat space, and the
// Einstein ring's weak-field radius sqrt(4M D_ls / (D_l D_s)) for a point exactly behind.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "lightcone/physics/schwarzschild_lens.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;

// Follows the ray from the observer at r0 (static frame angle alpha from the outward radial) for
// the angle phi, by classical RK4 in long double: its radius and coordinate time there.
struct Followed {
  double r, t;
};
Followed follow(double m, double r0, double cos_alpha, double sin_alpha, double phi) {
  struct State {
    long double u, du, t;
  };
  const long double f0 = 1 - 2 * m / r0;
  const long double b = r0 * sin_alpha / std::sqrt(f0);
  const auto deriv = [&](const State& s) {
    const long double r = 1 / s.u;
    return State{s.du, 3 * m * s.u * s.u - s.u, r * r / (b * (1 - 2 * m * s.u))};
  };
  // dr/dphi = r sqrt(f) cot(alpha) at the observer, so du/dphi = -sqrt(f0) cot(alpha) / r0.
  State s{1 / static_cast<long double>(r0), -std::sqrt(f0) * cos_alpha / sin_alpha / r0, 0};
  const int steps = 400000;
  const long double h = phi / steps;
  for (int i = 0; i < steps; ++i) {
    const State k1 = deriv(s);
    const State k2 = deriv({s.u + h / 2 * k1.u, s.du + h / 2 * k1.du, 0});
    const State k3 = deriv({s.u + h / 2 * k2.u, s.du + h / 2 * k2.du, 0});
    const State k4 = deriv({s.u + h * k3.u, s.du + h * k3.du, 0});
    s = {s.u + h / 6 * (k1.u + 2 * k2.u + 2 * k3.u + k4.u),
         s.du + h / 6 * (k1.du + 2 * k2.du + 2 * k3.du + k4.du),
         s.t + h / 6 * (k1.t + 2 * k2.t + 2 * k3.t + k4.t)};
  }
  return {static_cast<double>(1 / s.u), static_cast<double>(s.t)};
}

TEST(SchwarzschildLens, EachImagesRayReachesThePointAfterItsSweepInItsTime) {
  const double m = 1;
  struct Case {
    double r0, r_e, psi;
  };
  for (const Case& c : {Case{30, 20, 2.0}, Case{30, 8, 0.7}, Case{50, 100, 2.9}, Case{12, 40, 1.2},
                        Case{30, 20, kPi - 0.01}})
    for (int order = 0; order <= 2; ++order) {
      SCOPED_TRACE(testing::Message() << c.r0 << " " << c.r_e << " " << c.psi << " " << order);
      const auto image = lens_image(m, c.r0, c.r_e, c.psi, order);
      ASSERT_TRUE(image);
      EXPECT_NEAR(image->sweep, image_sweep(c.psi, order), 1e-11);
      const Followed f = follow(m, c.r0, image->cos_alpha, image->sin_alpha, image->sweep);
      EXPECT_NEAR(f.r, c.r_e, 1e-7 * c.r_e);
      EXPECT_NEAR(f.t, image->time, 1e-7 * image->time);
    }
}

TEST(SchwarzschildLens, FlatSpaceSeesTheStraightLineAndNoSecondImage) {
  const double r0 = 10, r_e = 7, psi = 1.1;
  // The point at r_e (cos psi, sin psi) seen from (r0, 0): the direction toward it.
  const double dx = r_e * std::cos(psi) - r0, dy = r_e * std::sin(psi);
  const double len = std::hypot(dx, dy);
  const auto image = lens_image(1e-12, r0, r_e, psi, 0);
  ASSERT_TRUE(image);
  EXPECT_NEAR(image->cos_alpha, dx / len, 1e-9);
  EXPECT_NEAR(image->sin_alpha, dy / len, 1e-9);
  EXPECT_NEAR(image->time, len, 1e-9);
  EXPECT_FALSE(lens_image(0, r0, r_e, psi, 1));
}

TEST(SchwarzschildLens, PointExactlyBehindIsSeenOnTheEinsteinRing) {
  // Weak field: a ring of angular radius sqrt(4M D_ls / (D_l D_s)) about the hole.
  const double m = 1, r0 = 1e6, r_e = 2e6;
  const auto primary = lens_image(m, r0, r_e, kPi, 0), secondary = lens_image(m, r0, r_e, kPi, 1);
  ASSERT_TRUE(primary && secondary);
  EXPECT_NEAR(primary->sin_alpha, secondary->sin_alpha, 1e-12);
  const double ring = std::sqrt(4 * m * r_e / (r0 * (r0 + r_e)));
  EXPECT_NEAR(primary->sin_alpha, ring, 2e-3 * ring);  // to first order in M/b
}

}  // namespace
}  // namespace lightcone

// The images of a point past a Schwarzschild hole (physics/schwarzschild_lens.hpp, ray_between)
// against
// derivations made here: each image's ray followed by integrating u'' = 3 M u^2 - u and
// dt/dphi = r^2 / (b f) step by step from the observer (it must arrive at the point's radius
// after sweeping the image's angle, in the time found), the straight line of flat space, and the
// Einstein ring's weak-field radius sqrt(4M D_ls / (D_l D_s)) for a point exactly behind.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "lightcone/physics/schwarzschild_lens.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;

test::IntegratedOrbit follow(double m, double r0, double cos_alpha, double sin_alpha, double phi) {
  return test::integrate_orbit_from(m, r0, cos_alpha, sin_alpha, phi, 400000);
}

TEST(SchwarzschildLens, EachImagesRayReachesThePointAfterItsSweepInItsTime) {
  const double m = 1;
  struct Case {
    double r0, r_e, psi;
  };
  for (const Case& c : {Case{30, 20, 2.0}, Case{30, 8, 0.7}, Case{50, 100, 2.9}, Case{12, 40, 1.2},
                        Case{30, 20, kPi - 0.01},
                        // Beside the hole, just past the periapsis of its primary's ray: the root
                        // lies between where that ray's stretch begins and the first look angle
                        // of the grid on it.
                        Case{30, 10.0107, 1.49095}})
    for (int order = 0; order <= 2; ++order) {
      SCOPED_TRACE(testing::Message() << c.r0 << " " << c.r_e << " " << c.psi << " " << order);
      const auto image = ray_between(m, c.r0, c.r_e, c.psi, order);
      ASSERT_TRUE(image);
      EXPECT_NEAR(image->sweep, image_sweep(c.psi, order), 1e-11);
      const test::IntegratedOrbit f = follow(m, c.r0, image->cos_a, image->sin_a, image->sweep);
      EXPECT_NEAR(f.r, c.r_e, 1e-7 * c.r_e);
      EXPECT_NEAR(f.t, image->time, 1e-7 * image->time);
    }
}

// A point outside the photon sphere always has a primary image (its light can come round the
// near side on a ray that does not cross r = 3M), wherever it is.
TEST(SchwarzschildLens, EveryPointOutsideThePhotonSphereHasAPrimary) {
  for (const double r_e : {3.5, 10.0, 29.0, 60.0})
    for (int i = 1; i < 200; ++i) {
      const double psi = kPi * i / 200;
      SCOPED_TRACE(testing::Message() << r_e << " " << psi);
      const auto image = ray_between(1, 30, r_e, psi, 0);
      EXPECT_TRUE(image);
      if (image) {
        EXPECT_NEAR(image->sweep, psi, 1e-11);
      }
    }
}

TEST(SchwarzschildLens, FlatSpaceSeesTheStraightLineAndNoSecondImage) {
  const double r0 = 10, r_e = 7, psi = 1.1;
  // The point at r_e (cos psi, sin psi) seen from (r0, 0): the direction toward it.
  const double dx = r_e * std::cos(psi) - r0, dy = r_e * std::sin(psi);
  const double len = std::hypot(dx, dy);
  const auto image = ray_between(1e-12, r0, r_e, psi, 0);
  ASSERT_TRUE(image);
  EXPECT_NEAR(image->cos_a, dx / len, 1e-9);
  EXPECT_NEAR(image->sin_a, dy / len, 1e-9);
  EXPECT_NEAR(image->time, len, 1e-9);
  EXPECT_FALSE(ray_between(0, r0, r_e, psi, 1));
}

TEST(SchwarzschildLens, PointExactlyBehindIsSeenOnTheEinsteinRing) {
  // Weak field: a ring of angular radius sqrt(4M D_ls / (D_l D_s)) about the hole.
  const double m = 1, r0 = 1e6, r_e = 2e6;
  const auto primary = ray_between(m, r0, r_e, kPi, 0), secondary = ray_between(m, r0, r_e, kPi, 1);
  ASSERT_TRUE(primary && secondary);
  EXPECT_NEAR(primary->sin_a, secondary->sin_a, 1e-12);
  const double ring = std::sqrt(4 * m * r_e / (r0 * (r0 + r_e)));
  EXPECT_NEAR(primary->sin_a, ring, 2e-3 * ring);  // to first order in M/b
}

}  // namespace
}  // namespace lightcone

namespace lightcone {
namespace {

// The table of images of directions far away against ray_between's exact solve between its
// nodes: the look angle to 1e-9 rad, the solid-angle ratio (sin(alpha) / (sin(psi) |dsweep /
// dalpha|) from the exact solve: f times its focusing) to 1e-5, for cameras outside and inside
// the photon sphere; and no second image without a hole.
TEST(SchwarzschildLens, TheFarImageTableFollowsTheExactSolve) {
  for (const double r0 : {2.5, 6.0, 60.0}) {
    const FarImageTable table(1, r0, 3);
    const double f = 1 - 2 / r0;
    for (int order = 0; order < 3; ++order)
      for (double psi = 0.0137; psi < kPi; psi += 0.0917) {
        SCOPED_TRACE(testing::Message() << r0 << " " << order << " " << psi);
        const auto exact = ray_between(1, r0, std::numeric_limits<double>::infinity(), psi, order);
        const auto image = table.at(psi, order);
        ASSERT_TRUE(exact && image);
        EXPECT_NEAR(image->alpha, std::atan2(exact->sin_a, exact->cos_a), 1e-9);
        EXPECT_NEAR(image->solid_angle_ratio, f * exact->focusing, 1e-5 * f * exact->focusing);
      }
  }
  const FarImageTable flat(0, 10, 2);
  ASSERT_TRUE(flat.at(1.0, 0));
  EXPECT_NEAR(flat.at(1.0, 0)->alpha, 1.0, 1e-12);
  EXPECT_NEAR(flat.at(1.0, 0)->solid_angle_ratio, 1.0, 1e-9);
  EXPECT_FALSE(flat.at(1.0, 1));
}

}  // namespace
}  // namespace lightcone

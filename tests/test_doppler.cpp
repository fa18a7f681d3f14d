// The Doppler factor against closed forms and an explicit frame change.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "lightcone/physics/doppler.hpp"
#include "lightcone/physics/lorentz.hpp"

namespace lightcone {
namespace {

TEST(Doppler, CameraApproachingAStaticSourceHeadOn) {
  // Source ahead of the camera along -z; light travels along +z to the camera, which moves
  // toward it (-z) at beta: D = sqrt((1 + beta)/(1 - beta)) = 4.3589 at 0.9.
  const double d = doppler_factor({0, 0, 1}, {}, {0, 0, -0.9});
  EXPECT_NEAR(d, std::sqrt(1.9 / 0.1), 1e-12);
  EXPECT_NEAR(d, 4.358898943540674, 1e-12);
}

TEST(Doppler, RecedingAndTransverse) {
  EXPECT_NEAR(doppler_factor({0, 0, 1}, {}, {0, 0, 0.6}), std::sqrt(0.4 / 1.6), 1e-12);
  // Emitter moving perpendicular to the line of sight (in the receiver's frame): the
  // transverse Doppler redshift 1/gamma.
  EXPECT_NEAR(doppler_factor({1, 0, 0}, {0, 0.8, 0}, {}), 0.6, 1e-12);
  // Receiver moving perpendicular to the light it receives (in the emitter's frame): gamma.
  EXPECT_NEAR(doppler_factor({1, 0, 0}, {}, {0, 0.8, 0}), 1.0 / 0.6, 1e-12);
}

TEST(Doppler, EqualsTheFrequencyRatioOfAnExplicitlyBoostedPhoton) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i) {
    const Vec3 n = normalize(Vec3{u(rng), u(rng), u(rng)});
    const Vec3 be = normalize(Vec3{u(rng), u(rng), u(rng)}) * (0.99 * std::abs(u(rng)));
    const Vec3 br = normalize(Vec3{u(rng), u(rng), u(rng)}) * (0.99 * std::abs(u(rng)));
    // The photon's frequency in each body's rest frame is the time component of its
    // 4-momentum boosted into that frame.
    const Vec4 k{1.0, n};
    const double nu_e = (boost(be) * k).t, nu_r = (boost(br) * k).t;
    EXPECT_NEAR(doppler_factor(n, be, br), nu_r / nu_e, 1e-12 * nu_r / nu_e);
  }
}

TEST(Doppler, IsTheSameInEveryFrame) {
  const Vec3 n = normalize(Vec3{0.3, -0.5, 0.8});
  const Vec3 be{0.5, 0.1, -0.2}, br{-0.3, 0.6, 0.1};
  const double here = doppler_factor(n, be, br);
  const Vec3 frame{0.4, 0.4, -0.5};
  const Mat4 l = boost(frame);
  const Vec4 k = l * Vec4{1.0, n};
  auto moved = [&](const Vec3& b) {
    const double g = lorentz_gamma(b);
    return velocity_of(l * Vec4{g, b * g});
  };
  EXPECT_NEAR(doppler_factor(normalize(k.x), moved(be), moved(br)), here, 1e-12);
}

TEST(Doppler, NoMotionNoShift) {
  EXPECT_EQ(doppler_factor({0.6, 0.8, 0}, {}, {}), 1.0);
  EXPECT_NEAR(doppler_factor({0, 0, 1}, {0, 0, 1e-12}, {}), 1.0, 1e-11);
}

}  // namespace
}  // namespace lightcone

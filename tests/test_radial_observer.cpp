// What a radially moving observer sees near a Schwarzschild hole (physics/radial_observer.hpp),
// against derivations made here: outside the horizon, the static observer's view aberrated by
// the radial boost v = u^r / E (the route the renderers take for a camera with a velocity);
// everywhere, the photon's 4-momentum is null in the metric; the shadow of a camera falling
// from rest at infinity is 42.10 degrees in radius at the horizon (PHYSICS.md); and nothing
// jumps as the observer crosses r = 2M. G = c = 1, M = 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "lightcone/physics/radial_observer.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Falling from rest at r0 (infinity for r0 = 0): E = sqrt(1 - 2/r0), u^r = -sqrt(E^2 - f).
RadialObserver falling(double r, double r0 = 0) {
  const double e = r0 > 0 ? std::sqrt(1 - 2 / r0) : 1.0;
  return {1, r, e, -std::sqrt(e * e - (1 - 2 / r))};
}

TEST(RadialObserver, OutsideItIsTheStaticViewAberrated) {
  for (const double r : {2.5, 6.0, 40.0})
    for (const double r0 : {0.0, 60.0})
      for (int i = 0; i <= 12; ++i) {
        const double look = kPi * i / 12;  // from the outward radial
        const RadialObserver o = falling(r, r0);
        const auto ray = observed_ray(o, std::cos(look), std::sin(look));
        ASSERT_TRUE(ray);
        // The backward event (-1, l) in the static frame, boosted by the observer's velocity v.
        const double f = 1 - 2 / r, v = o.radial_velocity / o.energy;
        const double gamma = 1 / std::sqrt(1 - v * v);
        const double t = gamma * (-1 + v * std::cos(look));
        const double x_r = gamma * (std::cos(look) - v), x_t = std::sin(look);
        EXPECT_EQ(ray->outward, x_r > 0);
        EXPECT_NEAR(ray->impact, r * (x_t / -t) / std::sqrt(f), 1e-12 * r);
        EXPECT_NEAR(ray->energy, 1 / (std::sqrt(f) * -t), 1e-12 * ray->energy);
      }
}

TEST(RadialObserver, ThePhotonIsNullInsideAndOut) {
  // (p^r)^2 = E_ph^2 - f L^2 / r^2, with p^r = eps (u^r - E l_r) for eps = 1.
  for (const double r : {0.3, 1.0, 1.99, 2.0, 2.01, 5.0})
    for (int i = 0; i <= 24; ++i) {
      const double look = kPi * i / 24, c = std::cos(look), s = std::sin(look);
      const RadialObserver o = falling(r);
      const auto ray = observed_ray(o, c, s);
      if (!ray) {
        EXPECT_LE(r, 2);  // only at or inside: light of no positive energy
        continue;
      }
      const double e_ph = 1 / ray->energy, l = ray->impact * e_ph, f = 1 - 2 / r;
      const double p_r = o.radial_velocity - o.energy * c;
      EXPECT_NEAR(p_r * p_r, e_ph * e_ph - f * l * l / (r * r), 1e-12 * (1 + p_r * p_r));
      EXPECT_EQ(ray->outward, -p_r > 0);  // backward: against the photon
    }
}

TEST(RadialObserver, InsideTheHorizonEveryBackwardRayMovesOut) {
  for (const double r : {0.1, 1.0, 1.9})
    for (int i = 0; i <= 24; ++i) {
      const double look = kPi * i / 24;
      if (const auto ray = observed_ray(falling(r, 10), std::cos(look), std::sin(look))) {
        EXPECT_TRUE(ray->outward) << r << " " << look;
      }
    }
  // Straight down from r = 1 (u^r = -sqrt(2)): E - u^r l_r = 1 - sqrt(2) < 0, nothing.
  EXPECT_FALSE(observed_ray(falling(1), -1, 0));
  EXPECT_NEAR(observed_ray(falling(1), 1, 0)->energy, 1 / (1 + std::sqrt(2.0)), 1e-15);
}

TEST(RadialObserver, FallingFromInfinityTheShadowIs42DegreesAtTheHorizon) {
  // At r = 2M, E = 1 and u^r = -1: looking beta from straight down, b = 2 cot(beta / 2), so the
  // edge b = 3 sqrt(3) is at beta = 2 atan(2 / 3 sqrt(3)) = 42.10 degrees.
  const double beta = 2 * std::atan(2 / (3 * std::sqrt(3.0)));
  EXPECT_NEAR(beta * 180 / kPi, 42.10, 0.005);
  const auto edge = observed_ray(falling(2), -std::cos(beta), std::sin(beta));
  ASSERT_TRUE(edge);
  EXPECT_NEAR(edge->impact, critical_impact_parameter(1), 1e-12);
  EXPECT_TRUE(edge->outward);
}

TEST(RadialObserver, NothingJumpsAtTheHorizon) {
  for (int i = 1; i < 12; ++i) {
    const double look = kPi * i / 12, c = std::cos(look), s = std::sin(look);
    const auto out = observed_ray(falling(2 * (1 + 1e-10)), c, s);
    const auto in = observed_ray(falling(2 * (1 - 1e-10)), c, s);
    ASSERT_EQ(bool(out), bool(in));
    if (!out) continue;
    EXPECT_NEAR(out->impact, in->impact, 1e-8 * out->impact);
    EXPECT_NEAR(out->energy, in->energy, 1e-8 * out->energy);
  }
}

// The energy range the colour tables are built for holds every ray that can bring light (from
// r >= 3M every one; below it, falling, the outward ones with b <= b_c), found here by sweeping
// look directions, and its ends are reached.
TEST(RadialObserver, SeenEnergyRangeHoldsEveryRayThatBringsLight) {
  for (const double r : {0.5, 1.5, 2.0, 2.5, 4.0, 20.0})
    for (const double r0 : {0.0, 40.0}) {
      const RadialObserver o = falling(r, r0);
      const EnergyRange range = seen_energy_range(o);
      double lo = kInf, hi = 0;
      for (int i = 0; i <= 200000; ++i) {
        const double look = kPi * i / 200000;
        const auto ray = observed_ray(o, std::cos(look), std::sin(look));
        if (!ray) continue;
        if (r < 3 && !(ray->outward && ray->impact <= critical_impact_parameter(1))) continue;
        lo = std::min(lo, ray->energy), hi = std::max(hi, ray->energy);
      }
      SCOPED_TRACE(testing::Message() << r << " " << r0);
      EXPECT_GE(lo, range.lo * (1 - 1e-12));
      EXPECT_LE(hi, range.hi * (1 + 1e-12));
      EXPECT_NEAR(lo, range.lo, 1e-6 * range.lo);
      EXPECT_NEAR(hi, range.hi, 1e-3 * range.hi);
    }
}

}  // namespace
}  // namespace lightcone

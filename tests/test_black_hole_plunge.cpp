// A camera falling into a Schwarzschild black hole, through its horizon (frame/hole_view.hpp's
// falling camera, frame/curved_ray.hpp): the tracer against derivations made independently of
// it. Outside, the falling camera's rays are those of the static camera boosted to its velocity
// (the route every other camera takes); its shadow's edge is where radial_observer's closed form
// puts it, inside the horizon too (42.10 degrees at r = 2M falling from infinity: PHYSICS.md);
// and nothing jumps as it crosses r = 2M. G = c = 1, M = 1.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/radial_observer.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;

// The camera on the +z axis at r, falling from rest at r0 (infinity for r0 = 0), with a disk
// in the xz plane's normal direction y.
HoleView falling_view(double r, double r0 = 0) {
  const double e = r0 > 0 ? std::sqrt(1 - 2 / r0) : 1.0;
  HoleView v;
  v.camera_radius = r;
  v.outward = {0, 0, 1};
  v.falling = RadialObserver{1, r, e, -std::sqrt(e * e - (1 - 2 / r))};
  v.camera_lapse = std::sqrt(std::max(0.0, 1 - 2 / r));
  v.world_to_sky = boost({});
  v.disk = AccretionDisk{};
  v.disk->normal = normalize(Vec3{0, 1, 0.3});
  return v;
}

// The same camera described as every other one: the static observer's frame, boosted.
HoleView static_boosted_view(double r, double r0 = 0) {
  HoleView v = falling_view(r, r0);
  const RadialObserver o = *v.falling;
  v.falling.reset();
  const Vec3 beta = v.outward * (o.radial_velocity / o.energy);
  v.camera_rapidity = rapidity(beta);
  v.trace_to_static = lorentz_inverse(boost(beta));
  return v;
}

Vec3 look(double from_down, double around) {
  return {std::sin(from_down) * std::cos(around), std::sin(from_down) * std::sin(around),
          -std::cos(from_down)};
}

TEST(BlackHolePlunge, OutsideTheFallingFrameIsTheBoostedStaticOne) {
  for (const double r : {2.5, 6.0, 25.0})
    for (int i = 0; i <= 36; ++i) {
      const Vec3 u = look(kPi * i / 36, 0.7);
      const CurvedRay a = follow_curved_ray(falling_view(r, 30), u);
      const CurvedRay b = follow_curved_ray(static_boosted_view(r, 30), u);
      SCOPED_TRACE(testing::Message() << r << " " << i);
      ASSERT_EQ(a.end, b.end);
      EXPECT_EQ(a.order, b.order);
      EXPECT_NEAR(a.phi, b.phi, 1e-9 * (1 + b.phi));
      EXPECT_NEAR(a.shift, b.shift, 1e-9 * b.shift);
    }
}

TEST(BlackHolePlunge, TheShadowsEdgeIsRadialObserversInsideAndOut) {
  for (const double r : {8.0, 2.5, 2.0, 1.5, 0.5}) {
    const HoleView v = falling_view(r);
    const double edge = shadow_angle(*v.falling);
    if (r == 2.0) {
      EXPECT_NEAR(edge * 180 / kPi, 42.10, 0.005);
    }
    HoleView sky_only = v;
    sky_only.disk.reset();
    for (const double around : {0.0, 2.0, 4.0}) {
      SCOPED_TRACE(testing::Message() << r << " " << around);
      EXPECT_EQ(follow_curved_ray(sky_only, look(edge * (1 - 1e-6), around)).end,
                CurvedRayEnd::kHorizon);
      EXPECT_EQ(follow_curved_ray(sky_only, look(edge * (1 + 1e-6), around)).end,
                CurvedRayEnd::kSky);
    }
  }
}

TEST(BlackHolePlunge, NothingJumpsAtTheHorizon) {
  const HoleView out = falling_view(2 * (1 + 1e-9), 30), in = falling_view(2 * (1 - 1e-9), 30);
  int disk = 0, sky = 0;
  for (int i = 0; i <= 60; ++i)
    for (const double around : {0.3, 1.9}) {
      const Vec3 u = look(kPi * i / 60, around);
      const CurvedRay a = follow_curved_ray(out, u), b = follow_curved_ray(in, u);
      SCOPED_TRACE(testing::Message() << i << " " << around);
      ASSERT_EQ(a.end, b.end);
      EXPECT_NEAR(a.phi, b.phi, 1e-6);
      EXPECT_NEAR(a.shift, b.shift, 1e-6 * a.shift);
      disk += a.end == CurvedRayEnd::kDisk, sky += a.end == CurvedRayEnd::kSky;
    }
  EXPECT_GE(disk, 3);
  EXPECT_GT(sky, 10);
}

TEST(BlackHolePlunge, InsideLightFromStraightDownHasNoPositiveEnergy) {
  // From r = 1 falling from infinity (u^r = -sqrt 2): looking straight down E - u^r l_r < 0.
  const CurvedRay down = follow_curved_ray(falling_view(1), {0, 0, -1});
  EXPECT_EQ(down.end, CurvedRayEnd::kHorizon);
  EXPECT_EQ(down.shift, 0);
  // Straight up: the sky, seen by a camera rushing away from it, redshifted by
  // 1 / (E + |u^r|) = 1 / (1 + sqrt 2).
  const CurvedRay up = follow_curved_ray(falling_view(1), {0, 0, 1});
  EXPECT_EQ(up.end, CurvedRayEnd::kSky);
  EXPECT_NEAR(up.shift, 1 / (1 + std::sqrt(2.0)), 1e-12);
}

}  // namespace
}  // namespace lightcone

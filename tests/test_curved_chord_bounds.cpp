// The light cone's bounds on the times along a light path near the hole (frame/curved_bodies.hpp,
// light_cone_bounds), which spare the chords of a curved ray the exact time of their ends where a
// moving body cannot be near them: against the path's exact coordinate time (Carlson's integrals,
// physics/schwarzschild.hpp), along rays that pass close by the hole, turn, or fall in, over
// chords short and long, and carried along many chords without a new exact time; and a falling
// box, tested against its prism along its line of fall rather than its ball, is met wherever
// `locate`'s independent lens solve sees it, its state solved on its fall's t(r) in closed form.
// G = c = M = 1.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/locate.hpp"
#include "lightcone/physics/schwarzschild.hpp"
#include "lightcone/physics/schwarzschild_geodesics.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

// A backward ray from r0 = 30, inward, of impact parameter b: its time after sweeping phi (0 at
// the start, decreasing), its point, and whether it has passed its turning point.
struct Ray {
  PhotonOrbit orbit;
  AngleSweep sweep;
  double r0 = 30;
  explicit Ray(double b) : orbit(photon_orbit(1, b)), sweep(prepare_sweep(orbit, 30, false)) {}
  bool turned(double phi) const { return sweep.turning_radius > 0 && phi > sweep.angle_to_turn; }
  double radius(double phi) const { return radius_after_angle(sweep, phi); }
  double time(double phi) const {
    const double r = radius(phi);
    if (!turned(phi)) return -coordinate_time(orbit, r0, r);
    return -coordinate_time(orbit, r0, sweep.turning_radius) -
           coordinate_time(orbit, sweep.turning_radius, r);
  }
  Vec3 point(double phi) const { return Vec3{std::cos(phi), std::sin(phi), 0} * radius(phi); }
};

// The bounds from a to b along the ray, as curved_bodies.cpp takes them.
TimeBounds bounds_between(const Ray& ray, const TimeBounds& at_a, double phi_a, double phi_b) {
  const bool turn_between = ray.turned(phi_b) && !ray.turned(phi_a);
  return light_cone_bounds(at_a, ray.point(phi_a), ray.point(phi_b), phi_b - phi_a,
                           turn_between ? ray.sweep.turning_radius : 0.0, ray.orbit.impact);
}

TEST(LightConeBounds, HoldTheExactTimeOverOneChord) {
  // Captured (b < 3 sqrt(3)), grazing the photon sphere, turning near and far.
  for (const double b : {3.0, 5.3, 6.0, 10.0, 25.0}) {
    const Ray ray(b);
    for (const double dphi : {0.01, 0.1, 0.5}) {
      for (double phi = 0; phi + dphi < ray.sweep.angle_total; phi += dphi) {
        if (!(ray.radius(phi + dphi) > 2.05)) break;
        const double t_a = ray.time(phi), t_b = ray.time(phi + dphi);
        const TimeBounds at_b = bounds_between(ray, {t_a, t_a}, phi, phi + dphi);
        SCOPED_TRACE(testing::Message() << "b " << b << ", phi " << phi << ", dphi " << dphi);
        EXPECT_LE(at_b.early, t_b);
        EXPECT_GE(at_b.late, t_b);
        // Not loose beyond use over short chords far out: the path's length at most sqrt(2) times
        // the chord's (its radial and angular parts added), the light's speed at least f > 0.86.
        if (dphi <= 0.1 && ray.radius(phi) > 15 && ray.radius(phi + dphi) > 15) {
          EXPECT_LT(at_b.late - at_b.early, 0.7 * (t_a - t_b));
        }
      }
    }
  }
}

TEST(LightConeBounds, HoldTheExactTimeAlongManyChords) {
  for (const double b : {5.3, 8.0}) {
    const Ray ray(b);
    TimeBounds carried{0, 0};
    const double dphi = 0.02;
    for (double phi = 0; phi + dphi < ray.sweep.angle_total; phi += dphi) {
      if (!(ray.radius(phi + dphi) > 2.05)) break;
      carried = bounds_between(ray, carried, phi, phi + dphi);
      const double t = ray.time(phi + dphi);
      SCOPED_TRACE(testing::Message() << "b " << b << ", phi " << phi);
      EXPECT_LE(carried.early, t);
      EXPECT_GE(carried.late, t);
    }
  }
}

// Along a nearly radial path the time is nearly its tortoise coordinate's variation, which the
// bounds take in closed form: carried along chords from r = 30 down to r = 3, they stay within a
// tenth of the time elapsed (the light's speed bounded between f and 1 alone lets them spread by
// a fifth of it, 2M ln((30 - 2M) / (3 - 2M)) over 27 + that).
TEST(LightConeBounds, TightAlongANearlyRadialPath) {
  const Ray ray(0.5);
  TimeBounds carried{0, 0};
  const double dphi = ray.sweep.angle_total / 400;
  int checked = 0;
  for (double phi = 0; ray.radius(phi + dphi) > 3; phi += dphi, ++checked) {
    carried = bounds_between(ray, carried, phi, phi + dphi);
    const double t = ray.time(phi + dphi);
    SCOPED_TRACE(testing::Message() << "phi " << phi << ", r " << ray.radius(phi + dphi));
    EXPECT_LE(carried.early, t);
    EXPECT_GE(carried.late, t);
    EXPECT_LT(carried.late - carried.early, 0.1 * -t);
  }
  EXPECT_GT(checked, 100);
}

// From far out toward a turning point, most of the angle is swept near the turning point: the
// path's tangential part bounded by the larger radius times the angle would spread the bounds by
// some 30 M from r = 30 to 12 (b = 8, in one piece); the slope of the time in the radius,
// 1 / (f sqrt(1 - b^2 f / r^2)) at most where b^2 f / r^2 is greatest, holds them within a
// fifth of the time elapsed.
TEST(LightConeBounds, TightOnAPieceTowardTheTurningPoint) {
  const Ray ray(8);
  int checked = 0;
  for (double phi = 0.05; phi < ray.sweep.angle_to_turn && ray.radius(phi) > 12; phi += 0.05) {
    const TimeBounds at = bounds_between(ray, {0, 0}, 0, phi);
    const double t = ray.time(phi);
    SCOPED_TRACE(testing::Message() << "phi " << phi << ", r " << ray.radius(phi));
    EXPECT_LE(at.early, t);
    EXPECT_GE(at.late, t);
    EXPECT_LT(at.late - at.early, 0.2 * -t);
    ++checked;
  }
  EXPECT_GT(checked, 5);
}

// A fall's point at a radius in closed form (what a falling body's state near a hole is solved
// on) is the point at its proper time there, which finds its cycloid's parameter by a root.
TEST(RadialFall, AtRadiusIsThePointAtItsProperTime) {
  for (const RadialFall& fall : {RadialFall::from_rest(1, 10), RadialFall::from_infinity(1, 12)})
    for (const double r : {9.5, 6.0, 3.0, 2.1, 2.0001}) {
      const RadialFallPoint p = fall.at_radius(r);
      const RadialFallPoint q = fall.at_proper_time(fall.proper_time_at_radius(r));
      SCOPED_TRACE(r);
      EXPECT_NEAR(p.coordinate_time, q.coordinate_time, 1e-12 * (1 + std::abs(q.coordinate_time)));
      EXPECT_NEAR(p.local_velocity, q.local_velocity, 1e-12);
      EXPECT_NEAR(q.radius, r, 1e-12 * r);
    }
}

// A falling body's state at a time near the hole is solved by Newton's method on t(r) within a
// bracket of two radii (its sampled fall): the point it gives is the one at that time, to the
// last bits, from brackets wide and narrow, one ending where it is at rest (dt/dr infinite)
// and one close to the horizon.
TEST(RadialFall, AtCoordinateTimeBetweenIsThePointAtThatTime) {
  for (const RadialFall& fall : {RadialFall::from_rest(1, 10), RadialFall::from_infinity(1, 12)}) {
    const double top = fall.is_from_infinity() ? 40.0 : 10.0;
    const std::pair<double, double> brackets[] = {
        {9.0, top}, {2.5, top}, {6.0, 6.2}, {2.0 + 1e-6, 2.0 + 2e-6}, {2.0 + 1e-9, 3.0}};
    for (const auto& [lo, hi] : brackets)
      for (const double w : {0.0, 0.1, 0.5, 0.97}) {
        const double r = lo + (hi - lo) * w;
        const double t = fall.at_radius(r).coordinate_time;
        const RadialFallPoint p = fall.at_coordinate_time_between(
            t, lo, fall.at_radius(lo).coordinate_time, hi, fall.at_radius(hi).coordinate_time);
        SCOPED_TRACE(testing::Message() << "bracket " << lo << " to " << hi << ", r " << r);
        EXPECT_NEAR(p.radius, r, 1e-14 * r + 1e-14 * (r - 2));
        EXPECT_NEAR(p.coordinate_time, t, 1e-13 * (1 + std::abs(t)));
      }
  }
}

// infall.json's clocks, turned about an oblique axis so that their outlines across their lines
// of fall are hexagons: every primary image of a point just inside a corner of each, where
// `locate` finds one, is on the clock (a prism too tight, or not holding the contracted box,
// would let the rays at the silhouette's corners through).
TEST(FallingPrism, HoldsTheBoxWhereverItIsSeen) {
  Scene s = test::load_repository_scene("infall.json");
  for (Object& o : s.objects) o.rotation = Mat3::rotation(normalize(Vec3{1, 2, 3}), 0.7);
  const ResolvedScene resolved = resolve_scene(s);
  const Tracer tracer(resolved);
  const CurvedBodies bodies(resolved, tracer);
  int checked = 0;
  for (std::size_t body = 0; body < s.objects.size(); ++body)
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 point =
          Vec3{corner & 1 ? 0.79 : -0.79, corner & 2 ? 0.79 : -0.79, corner & 4 ? 0.79 : -0.79};
      const LocateResult located =
          locate(s, {LocateQuery::Kind::ObjectPoint, s.objects[body].name, point});
      for (const LocateImage& image : located.images) {
        if (image.order != 0) continue;
        SCOPED_TRACE(testing::Message() << s.objects[body].name << ", corner " << corner);
        const CurvedRay ray = follow_curved_ray(*resolved.hole, image.direction, &bodies);
        EXPECT_EQ(ray.end, CurvedRayEnd::kBody);
        EXPECT_EQ(ray.hit.body, static_cast<int>(body));
        ++checked;
      }
    }
  EXPECT_GE(checked, 12);
}

// infall.json's clocks as balls of the clocks' radius: every primary image of a point just inside
// a ball, where `locate` finds one, is on it, the points across its line of fall (which the hole
// sees farthest from the line's direction) and along it. A ray's window of a falling body is
// narrowed to the angles its ball can be seen at from the hole over the window's times, within
// asin(R / r) of its line's direction at its least radius r then: a window too narrow would let
// the rays at the balls' edges through.
TEST(FallWindow, HoldsTheBallWhereverItIsSeen) {
  Scene s = test::load_repository_scene("infall.json");
  const double radius = 0.8 * std::sqrt(3.0);
  for (Object& o : s.objects) o.shape = Sphere{radius};
  const ResolvedScene resolved = resolve_scene(s);
  const Tracer tracer(resolved);
  const CurvedBodies bodies(resolved, tracer);
  int checked = 0;
  for (std::size_t body = 0; body < s.objects.size(); ++body) {
    const Vec3 d = std::get<HoleFall>(s.objects[body].motion.geodesic->path).direction;
    const Vec3 across = normalize(cross(d, Vec3{0, 0, 1})), up = cross(d, across);
    for (int k = 0; k < 10; ++k) {
      const double angle = k * std::numbers::pi / 4;
      const Vec3 direction =
          k < 8 ? across * std::cos(angle) + up * std::sin(angle) : d * (k == 8 ? 1.0 : -1.0);
      const Vec3 point = direction * (0.99 * radius);
      const LocateResult located =
          locate(s, {LocateQuery::Kind::ObjectPoint, s.objects[body].name, point});
      for (const LocateImage& image : located.images) {
        if (image.order != 0) continue;
        SCOPED_TRACE(testing::Message() << s.objects[body].name << ", point " << k);
        const CurvedRay ray = follow_curved_ray(*resolved.hole, image.direction, &bodies);
        EXPECT_EQ(ray.end, CurvedRayEnd::kBody);
        EXPECT_EQ(ray.hit.body, static_cast<int>(body));
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 15);
}

}  // namespace
}  // namespace lightcone

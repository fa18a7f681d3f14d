// Bodies on geodesics near a Schwarzschild black hole (physics/hole_world_line.hpp and
// frame/curved_bodies.hpp), against derivations made independently of the code under test: the
// radial fall's closed forms (MTW 31.10) and the static observer's speed of a body falling from
// rest, sqrt((2M/r - 2M/r0) / (1 - 2M/r0)); the circular orbit's clock sqrt(1 - 3M/r); and the
// photon energy a moving emitter measures written with 4-vectors, -p.u, for the radial fall
// (u^t = E / f, u^r = -sqrt(E^2 - f)) and the circular orbit (u = u^t (1, 0, 0, Omega)).
// G = c = 1, M = 1.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/frame/locate.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/physics/accretion_disk.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(HoleWorldLine, FallFollowsTheCycloidAndIsHeldUntilLetGo) {
  const double r0 = 10, time = -20;
  const HoleWorldLine line = HoleWorldLine::fall(RadialFall::from_rest(1, r0), {0, 1, 0}, time);
  // Before it is let go: at rest at r0, its clock running at sqrt(1 - 2M / r0).
  const HoleWorldLineState held = line.at(time - 5);
  EXPECT_DOUBLE_EQ(held.position.y, r0);
  EXPECT_EQ(held.velocity, Vec3{});
  EXPECT_NEAR(held.proper_time, -5 * std::sqrt(1 - 2 / r0), 1e-12);
  // After: r and t from the cycloid's parameter eta, the static observer's speed from energy.
  for (const double eta : {0.3, 1.0, 1.9}) {
    const double a = std::sqrt(r0 / 2 - 1), h = std::tan(eta / 2);
    const double r = r0 / 2 * (1 + std::cos(eta));
    const double tau = std::sqrt(r0 * r0 * r0 / 8) * (eta + std::sin(eta));
    const double t = 2 * (std::log((a + h) / (a - h)) + a * (eta + r0 / 4 * (eta + std::sin(eta))));
    const HoleWorldLineState s = line.at(time + t);
    SCOPED_TRACE(eta);
    EXPECT_NEAR(length(s.position), r, 1e-9 * r0);
    EXPECT_NEAR(s.proper_time, tau, 1e-9 * tau);
    const double speed = std::sqrt((2 / r - 2 / r0) / (1 - 2 / r0));
    EXPECT_NEAR(s.local_velocity.y, -speed, 1e-9);
    // Its coordinate velocity dr/dt = f v.
    EXPECT_NEAR(s.velocity.y, -(1 - 2 / r) * speed, 1e-9);
  }
}

TEST(HoleWorldLine, OrbitKeepsItsRadiusAndClock) {
  const double r = 8;
  const HoleWorldLine line = HoleWorldLine::orbit(1, r, {1, 0, 0}, {0, 0, -1}, 0.4);
  const double omega = std::sqrt(1 / (r * r * r));  // Kepler's law holds in t
  for (const double t : {-30.0, 0.0, 55.0}) {
    const HoleWorldLineState s = line.at(t);
    EXPECT_NEAR(length(s.position), r, 1e-12);
    EXPECT_NEAR(length(s.velocity), r * omega, 1e-12);
    EXPECT_NEAR(dot(s.position, s.velocity), 0, 1e-12);
    EXPECT_NEAR(s.proper_time, t * std::sqrt(1 - 3 / r), 1e-12);
    // The static observer sees it at r Omega / sqrt(f).
    EXPECT_NEAR(length(s.local_velocity), r * omega / std::sqrt(1 - 2 / r), 1e-12);
  }
}

// The camera at rest on the z axis at r = 30, looking at the hole.
Scene hole_scene() {
  Scene s;
  s.camera.world_line.position = {0, 0, 30};
  s.camera.fov_degrees = 30;
  s.camera.width = 160;
  s.camera.height = 90;
  s.black_hole = BlackHole{{0, 0, 0}, 1, std::nullopt};
  return s;
}

Object geodesic_ball(const Scene& s, double radius, HoleGeodesic g) {
  Object o = test::make_object("ball", Sphere{radius}, {}, {}, test::solid({1, 1, 1}));
  g.hole = s.black_hole->position;
  g.mass = s.black_hole->mass;
  o.motion.geodesic = g;
  const HoleWorldLineState at = hole_world_line(o, *s.black_hole).at(0);
  o.world_line = {0, at.position, at.velocity, at.proper_time};
  return o;
}

struct View {
  explicit View(const Scene& s)
      : resolved(resolve_scene(s)), tracer(resolved), bodies(resolved, tracer) {}
  CurvedRay ray_along(const Vec3& u) const { return follow_curved_ray(*resolved.hole, u, &bodies); }
  CurvedRay ray(int i, int j) const {
    return follow_curved_ray(*resolved.hole, look_direction(resolved.camera, i + 0.5, j + 0.5),
                             &bodies);
  }
  ResolvedScene resolved;
  Tracer tracer;
  CurvedBodies bodies;
};

// A small ball falls from rest at r0 straight at the camera (on the camera's side of the hole):
// the static observer where a ray meets it measures the photon at 1 / sqrt(f) along p^r =
// sqrt(1 - b^2 f / r^2) from the radial, and the ball at the fall's speed v =
// sqrt((2M/r - 2M/r0) / (1 - 2M/r0)) inward, so the ball measures gamma (1 + v p^r) / sqrt(f)
// (-p.u with u the ball's 4-velocity). Its points share its origin's velocity: a hit at the
// angle alpha = radius / r from the line of fall errs by about v alpha (alpha + b / r).
TEST(BlackHoleGeodesicBodies, RadialFallIsSeenWithMinusPDotU) {
  Scene s = hole_scene();
  const double radius = 0.3, f_camera = 1 - 2 / 30.0;
  // From rest at 12M; and from rest at infinity (passing r = 12 at time 0), for which the shift
  // seen straight along the line of fall is (1 - sqrt(2M/r)) / sqrt(f_camera).
  for (const double r0 : {12.0, kInf})
    for (const double time : {-45.0, -60.0}) {
      SCOPED_TRACE(testing::Message() << r0 << " " << time);
      const double from_infinity_time = std::isinf(r0) ? time + 40 : time;
      s.objects = {
          geodesic_ball(s, radius, {{}, 1, HoleFall{r0, 12, {0, 0, 1}, from_infinity_time}})};
      const View view(s);
      int hits = 0, along_the_line = 0;
      double slowest = 1, fastest = 0;
      for (int j = 0; j < 90; ++j)
        for (int i = 0; i < 160; ++i) {
          const CurvedRay ray = view.ray(i, j);
          // The primary image of a ball between the camera and the hole: light leaving it
          // outward.
          if (ray.end != CurvedRayEnd::kBody || ray.order != 0) continue;
          const Vec3 origin = hole_world_line(s.objects[0], *s.black_hole).at(ray.event.t).position;
          if (!(length(origin) < 29)) continue;
          ++hits;
          const double r_origin = length(origin);
          const double v = std::sqrt((2 / r_origin - 2 / r0) / (1 - 2 / r0));
          slowest = std::min(slowest, v), fastest = std::max(fastest, v);
          const double r = length(ray.event.x), f = 1 - 2 / r;
          // b from the camera's direction: r_camera sin(angle to the hole) / sqrt(f_camera).
          const Vec3 u = look_direction(view.resolved.camera, i + 0.5, j + 0.5);
          const double b = 30 * length(cross(u, Vec3{0, 0, -1})) / std::sqrt(f_camera);
          const double p_r = std::sqrt(1 - b * b * f / (r * r));
          const double emitted = (1 + v * p_r) / std::sqrt((1 - v * v) * f);
          const double expected = 1 / std::sqrt(f_camera) / emitted;
          const double alpha = radius / r;
          EXPECT_NEAR(ray.shift, expected, v * alpha * (alpha + b / r) * expected + 1e-9);
          if (std::isinf(r0) && ray.order == 0 && b < 0.5) {
            // Along the line of fall (b -> 0): 1 - sqrt(2M/r) for a point emitter at the ball's
            // centre, over sqrt(f_camera); met on its surface, R nearer the camera, f differs by
            // M R / (r^2 f) < 0.5%.
            const double along = (1 - std::sqrt(2 / r_origin)) / std::sqrt(f_camera);
            EXPECT_NEAR(ray.shift, along, 0.005 * along);
            ++along_the_line;
          }

          // The hit is on the ball at the emission time (contracted along its coordinate
          // velocity, below 0.4: by under 8%).
          EXPECT_NEAR(length(ray.event.x - origin), radius, 0.08 * radius);
        }
      EXPECT_GT(hits, 5);
      EXPECT_GT(slowest, 0.1);  // it is falling fast: the Doppler factor is tested
      if (std::isinf(r0)) {
        EXPECT_GT(along_the_line, 0);
      }
    }
}

// A moon on a circular orbit at 8M, seen edge-on: -p.u = u^t (1 - Omega L_z) for a photon of
// unit energy at infinity and angular momentum L_z about the orbit's axis.
TEST(BlackHoleGeodesicBodies, OrbitingMoonIsSeenWithMinusPDotU) {
  Scene s = hole_scene();
  const double r = 8, radius = 0.6;
  s.objects = {geodesic_ball(s, radius, {{}, 1, HoleOrbit{r, {1, 0, 0}, {0, 0, -1}, 0.5}})};
  const View view(s);
  const double omega = circular_orbit_angular_velocity(1, r);
  const double ut = 1 / std::sqrt(1 - 3 / r);
  const Vec3 axis = cross(Vec3{1, 0, 0}, Vec3{0, 0, -1});
  int hits = 0;
  for (int j = 0; j < 90; ++j)
    for (int i = 0; i < 160; ++i) {
      const CurvedRay ray = view.ray(i, j);
      if (ray.end != CurvedRayEnd::kBody) continue;
      ++hits;
      // The photon's angular momentum: r x p at the camera, p of unit energy at infinity along
      // -u (the backward ray's direction reversed), of length sqrt(f_camera)^-1 ... times f:
      // L = r0 sin(angle) / sqrt(f_camera) about the axis perpendicular to the plane.
      const Vec3 u = look_direction(view.resolved.camera, i + 0.5, j + 0.5);
      const Vec3 l = cross(Vec3{0, 0, 30}, u * -1.0) / std::sqrt(1 - 2 / 30.0);
      const double expected = (1 / std::sqrt(1 - 2 / 30.0)) / (ut * (1 - omega * dot(l, axis)));
      const double off_orbit = radius / r;
      EXPECT_NEAR(ray.shift, expected, off_orbit * expected);
    }
  EXPECT_GT(hits, 5);
}

// locate's images of a point of a body on a geodesic (an independent solve: the lens equation
// for the point's position at t_e, and t_e where its light arrives at the camera's time),
// followed by the tracer, meet the body there, at the same emission time, with the same shift
// and the same reading of its clock.
TEST(BlackHoleGeodesicBodies, EachImageOfABodysPointIsWhereTheTracerMeetsIt) {
  Scene s = hole_scene();
  s.objects = {geodesic_ball(s, 0.8, {{}, 1, HoleFall{12, 0, normalize(Vec3{1, 0.3, 0.2}), -40}}),
               geodesic_ball(s, 0.6, {{}, 1, HoleOrbit{8, {1, 0, 0}, {0, 0, -1}, 2.0}})};
  s.objects[1].name = "moon";
  const View view(s);
  LocateQuery q;
  q.kind = LocateQuery::Kind::ObjectPoint;
  int checked = 0;
  for (const char* name : {"ball", "moon"})
    for (const Vec3& p : {Vec3{0, 0, 1}, Vec3{0.6, 0, 0.8}, Vec3{-0.6, 0.3, 0.74}}) {
      q.object = name;
      q.value = p * (name == std::string("ball") ? 0.8 : 0.6);
      const LocateResult located = locate(s, q);
      EXPECT_FALSE(located.images.empty());
      for (const LocateImage& image : located.images) {
        const CurvedRay ray = view.ray_along(image.direction);
        if (ray.end != CurvedRayEnd::kBody || ray.order != image.order) continue;
        // Another part of the body in front (the point just past its limb as the ray sees it).
        if (length(ray.event.x - *image.emission_position) > 1e-4) continue;
        SCOPED_TRACE(testing::Message() << name << " " << image.order);
        EXPECT_NEAR(length(ray.event.x - *image.emission_position), 0, 1e-6);
        EXPECT_NEAR(ray.event.t, *image.emission_time, 1e-6);
        EXPECT_NEAR(ray.shift, image.shift, 1e-7);
        EXPECT_NEAR(ray.hit.proper_time, *image.emission_proper_time, 1e-6);
        ++checked;
      }
    }
  EXPECT_GE(checked, 4);
}

// A point of a falling clock that is within the horizon by the camera's time (the clock's near
// face, once its centre is at r < 2.8M) is still seen, as it was before it crossed: locate
// finds its images, and the tracer meets the clock there, then.
TEST(BlackHoleGeodesicBodies, PointWithinTheHorizonByNowIsSeenAsItWas) {
  const Scene s = test::load_repository_scene("infall.json");
  const Object& middle = s.objects[1];
  const Vec3 toward_hole =
      normalize(Vec3{1, 0, 0});  // the shape's +x face: the clock falls along -x
  const HoleWorldLine line = hole_world_line(middle, *s.black_hole);
  const Vec3 centre_now = line.at(s.camera.world_line.time).position;
  ASSERT_LT(length(centre_now + toward_hole * 0.8), 2.0);  // that face is within the horizon now
  const View view(s);
  const LocateResult located =
      locate(s, {LocateQuery::Kind::ObjectPoint, "middle", toward_hole * 0.8});
  ASSERT_EQ(located.images.size(), 3u);
  int checked = 0;
  for (const LocateImage& image : located.images) {
    SCOPED_TRACE(image.order);
    EXPECT_LT(*image.emission_time, -30);
    const CurvedRay ray = view.ray_along(image.direction);
    if (ray.end != CurvedRayEnd::kBody || ray.order != image.order) continue;
    if (length(ray.event.x - *image.emission_position) > 1e-4) continue;
    EXPECT_NEAR(ray.event.t, *image.emission_time, 1e-6);
    EXPECT_NEAR(ray.shift, image.shift, 1e-7);
    ++checked;
  }
  EXPECT_GE(checked, 1);
}

TEST(BlackHoleGeodesicBodies, InfallSceneLoadsAndItsClocksRedden) {
  SceneLoadReport report;
  const Scene s =
      load_scene_file(LIGHTCONE_SOURCE_DIR "/scenes/infall.json",
                      {"camera.width=192", "camera.height=108", "camera.samples=1"}, report);
  ASSERT_EQ(s.objects.size(), 3u);
  const View view(s);
  // The mean shift of each clock's hits: the clock let go earlier is seen redder.
  double sum[3] = {0, 0, 0};
  int count[3] = {0, 0, 0};
  for (int j = 0; j < 108; ++j)
    for (int i = 0; i < 192; ++i) {
      const CurvedRay ray = view.ray(i, j);
      if (ray.end != CurvedRayEnd::kBody) continue;
      sum[ray.hit.body] += ray.shift;
      ++count[ray.hit.body];
    }
  for (int k = 0; k < 3; ++k) ASSERT_GT(count[k], 0) << k;
  EXPECT_GT(sum[0] / count[0], sum[1] / count[1]);
  EXPECT_GT(sum[1] / count[1], sum[2] / count[2]);
  EXPECT_LT(sum[2] / count[2], 0.5);
}

// A turned box on an orbit and one on a straight coordinate line are met on their shapes, not
// their balls: every primary image of a point just inside a corner, where `locate` finds one, is
// on the box, and a ray toward a point beside the box but within its ball (a face's centre moved
// out by 0.3 of the half-size: the ball reaches sqrt(3) of it) meets no box there: nothing, or
// the box's own surface (in front of the point or behind it).
TEST(BlackHoleGeodesicBodies, MovingBoxesAreMetOnTheirShapesNotTheirBalls) {
  Scene s = hole_scene();
  const double half = 0.6;
  Object orbiting = geodesic_ball(s, half, {{}, 1, HoleOrbit{8, {1, 0, 0}, {0, 0, -1}, 2.0}});
  orbiting.name = "orbiting";
  Object straight = test::make_object("straight", Sphere{half}, {-5, 1, 4}, {0, 0.05, 0.3},
                                      test::solid({1, 1, 1}));
  for (Object* o : {&orbiting, &straight}) {
    o->shape = Box{{2 * half, 2 * half, 2 * half}};
    o->rotation = Mat3::rotation(normalize(Vec3{1, 2, 3}), 0.7);
  }
  s.objects = {orbiting, straight};
  const View view(s);
  int inside = 0, beside = 0, passed = 0;
  for (int body = 0; body < 2; ++body) {
    SCOPED_TRACE(s.objects[body].name);
    LocateQuery q;
    q.kind = LocateQuery::Kind::ObjectPoint;
    q.object = s.objects[body].name;
    for (int corner = 0; corner < 8; ++corner) {
      q.value = Vec3{corner & 1 ? 1.0 : -1.0, corner & 2 ? 1.0 : -1.0, corner & 4 ? 1.0 : -1.0} *
                (0.98 * half);
      for (const LocateImage& image : locate(s, q).images) {
        if (image.order != 0) continue;
        const CurvedRay ray = view.ray_along(image.direction);
        EXPECT_EQ(ray.end, CurvedRayEnd::kBody) << "corner " << corner;
        EXPECT_EQ(ray.hit.body, body) << "corner " << corner;
        ++inside;
      }
    }
    for (int axis = 0; axis < 3; ++axis)
      for (const double side : {-1.0, 1.0}) {
        Vec3 point;
        point[axis] = side * 1.3 * half;
        q.value = point;
        for (const LocateImage& image : locate(s, q).images) {
          if (image.order != 0) continue;
          const CurvedRay ray = view.ray_along(image.direction);
          ++beside;
          if (ray.end != CurvedRayEnd::kBody || ray.hit.body != body) {
            ++passed;
            continue;
          }
          SCOPED_TRACE(testing::Message() << "axis " << axis << ", side " << side);
          const Vec3& met = ray.hit.shape_point;
          EXPECT_NEAR(std::max({std::abs(met.x), std::abs(met.y), std::abs(met.z)}), half, 1e-6);
        }
      }
  }
  EXPECT_GE(inside, 12);
  EXPECT_GE(passed, 4);
  EXPECT_GE(beside, 10);
}

}  // namespace
}  // namespace lightcone

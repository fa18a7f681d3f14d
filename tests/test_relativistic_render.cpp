// The renderer against physics: limits, the principle of relativity, the sky at infinity,
// the Penrose-Terrell circle, and agreement of `locate` with what is drawn.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/aberration.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/scene/reframe.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;

std::shared_ptr<Mesh> tetrahedron() {
  auto m = std::make_shared<Mesh>();
  m->positions = {{0, 1, 0}, {-1, -0.5, 0.6}, {1, -0.5, 0.6}, {0, -0.5, -1}};
  m->triangles = {{{0, 1, 2}}, {{0, 2, 3}}, {{0, 3, 1}}, {{1, 3, 2}}};
  return m;
}

using test::make_object;

Material checker(double size, Rgb a, Rgb b) {
  return {Checker{size, {a, b}}, true, {}};
}
Material solid(Rgb c) {
  return {SolidColor{c}, true, {}};
}

// A scene with every shape kind, a grid sky and the given velocities.
Scene busy_scene(const Vec3& camera_velocity, double object_speed) {
  Scene s;
  s.camera.world_line.position = {0, 0.5, 6};
  s.camera.world_line.velocity = camera_velocity;
  s.camera.width = 120;
  s.camera.height = 80;
  s.camera.fov_degrees = 70;
  s.objects.push_back(make_object("sphere", Sphere{1.0}, {-1.5, 0.5, -2}, {object_speed, 0, 0},
                                  checker(0.3, {1, 0.2, 0.1}, {0.1, 0.2, 1})));
  Object box = make_object("box", Box{{1, 1.5, 0.8}}, {1.8, 0.3, -1},
                           {0, object_speed * 0.5, 0.4 * object_speed},
                           checker(0.25, {0.9, 0.9, 0.2}, {0.1, 0.5, 0.1}));
  box.rotation = Mat3::rotation({0.3, 1, 0.2}, 0.7);
  box.scale = {1.2, 0.8, 1.0};
  s.objects.push_back(box);
  s.objects.push_back(make_object("ground", Plane{20, 20}, {0, -1, -3}, {},
                                  checker(1.0, {0.8, 0.8, 0.8}, {0.2, 0.2, 0.2})));
  s.objects.push_back(make_object("tetra", MeshShape{tetrahedron()}, {0.2, 1.6, -4},
                                  {-0.6 * object_speed, 0, 0}, solid({0.2, 0.9, 0.9})));
  s.sky.pattern = SkyGrid{};
  return s;
}

Image render_quiet(const Scene& s) {
  return render_image(s, RenderOptions{});
}

TEST(ClassicalLimit, BetaZeroEverywhereEqualsRelativityOffPixelForPixel) {
  Scene relativistic = busy_scene({0, 0, 0}, 0.0);
  relativistic.objects[1].world_line.time = -3.0;  // a static body's reference time is irrelevant
  Scene classical = relativistic;
  classical.render.relativity = false;
  const Image a = render_quiet(relativistic), b = render_quiet(classical);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  EXPECT_EQ(a.rgb, b.rgb);
  // The image is not trivially uniform: several colours are present.
  int changes = 0;
  for (std::size_t i = 3; i < a.rgb.size(); i += 3) changes += a.rgb[i] != a.rgb[i - 3];
  EXPECT_GT(changes, 100);
}

TEST(ClassicalLimit, SmallBetaConvergesToClassical) {
  Scene slow = busy_scene({0.0, 0.0, -1e-9}, 1e-9);
  Scene classical = slow;
  classical.render.relativity = false;
  const Image a = render_quiet(slow), b = render_quiet(classical);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) differing += std::abs(a.rgb[i] - b.rgb[i]) > 1e-6;
  EXPECT_LE(differing, a.rgb.size() / 1000);
}

using test::fraction_differing;

TEST(PrincipleOfRelativity, SameSceneFromAnotherFrameRendersTheSameImage) {
  Scene scene = busy_scene({0.2, -0.1, -0.5}, 0.7);
  scene.sky.velocity = {0.3, 0.1, 0.0};
  for (const Vec3 frame : {Vec3{0.4, -0.3, 0.5}, Vec3{-0.8, 0.1, 0.2}}) {
    const Scene other = describe_in_frame(scene, frame);
    // The description really changed: the camera moves differently in the new frame.
    ASSERT_GT(length(other.camera.world_line.velocity - scene.camera.world_line.velocity), 0.1);
    EXPECT_LT(fraction_differing(render_quiet(scene), render_quiet(other)), 0.003);
  }
}

TEST(PrincipleOfRelativity, HoldsForTheSimultaneousPictureToo) {
  Scene scene = busy_scene({0.0, 0.3, -0.6}, 0.8);
  scene.render.light_delay = false;
  const Scene other = describe_in_frame(scene, {0.5, 0.2, -0.4});
  EXPECT_LT(fraction_differing(render_quiet(scene), render_quiet(other)), 0.003);
}

TEST(PrincipleOfRelativity, IgnoringTheWignerRotationBreaksIt) {
  // The test can fail: re-describing without the Wigner correction changes the image.
  Scene scene = busy_scene({0.6, 0.0, -0.5}, 0.7);
  Scene other = describe_in_frame(scene, {0.0, 0.7, 0.3});
  other.camera.forward = scene.camera.forward;
  other.camera.up = scene.camera.up;
  EXPECT_GT(fraction_differing(render_quiet(scene), render_quiet(other)), 0.05);
}

Scene far_body_scene(const Vec3& direction) {
  Scene s;
  s.camera.world_line.velocity = Vec3{0.3, 0.2, -0.9} * 0.99 / length(Vec3{0.3, 0.2, -0.9});
  s.camera.width = 400;
  s.camera.height = 300;
  s.camera.fov_degrees = 90;
  s.objects.push_back(make_object("far", Sphere{2e3}, direction * 1e8, {}, solid({1, 1, 1})));
  s.sky.pattern = SolidColor{{0, 0, 0}};
  return s;
}

TEST(SkyAtInfinity, FarBodyAndSkyDirectionLandOnTheSamePixel) {
  const Vec3 d = normalize(Vec3{0.9, 0.35, -0.5});
  const Scene s = far_body_scene(d);
  LocateQuery sky{LocateQuery::Kind::SkyDirection, "", d};
  LocateQuery body{LocateQuery::Kind::ObjectPoint, "far", {0, 0, 0}};
  const LocateResult a = locate(s, sky), b = locate(s, body);
  ASSERT_TRUE(a.in_view);
  EXPECT_NEAR(a.pixel_x, b.pixel_x, 1e-3);
  EXPECT_NEAR(a.pixel_y, b.pixel_y, 1e-3);
  // The renderer draws the far body exactly there.
  const ResolvedScene r = resolve_scene(s);
  const Tracer tracer(r);
  const auto hit = tracer.trace(look_direction(r.camera, a.pixel_x, a.pixel_y));
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, 0);

  // The seed's formula (boost at fixed t) puts the sky elsewhere, by many pixels.
  const Vec3 beta = s.camera.world_line.velocity;
  const double g = lorentz_gamma(beta);
  const Vec3 bh = normalize(beta);
  const Vec3 seed = normalize(d + bh * ((g - 1) * dot(bh, d)));
  const ImagePoint wrong = project_direction(r.camera, seed);
  EXPECT_GT(std::hypot(wrong.x - a.pixel_x, wrong.y - a.pixel_y), 5.0);
}

// Directions on the outline of body 0, found by bisection around `centre`.
std::vector<Vec3> outline(const Tracer& tracer, const Vec3& centre, int count) {
  const Vec3 e1 = normalize(cross(centre, Vec3{0, 1, 0}));
  const Vec3 e2 = cross(centre, e1);
  std::vector<Vec3> result;
  for (int k = 0; k < count; ++k) {
    const double phi = 2 * kPi * k / count;
    const Vec3 side = e1 * std::cos(phi) + e2 * std::sin(phi);
    auto dir = [&](double theta) { return centre * std::cos(theta) + side * std::sin(theta); };
    double inside = 0, outside = 1.0;
    EXPECT_TRUE(tracer.trace(dir(inside)).has_value());
    EXPECT_FALSE(tracer.trace(dir(outside)).has_value());
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (inside + outside);
      (tracer.trace(dir(mid)).has_value() ? inside : outside) = mid;
    }
    result.push_back(dir(inside));
  }
  return result;
}

struct Circle {
  Vec3 axis;
  double cos_radius;
};

// Least-squares circle on the unit sphere: w.d = 1 for all d, axis = w/|w|.
Circle fit_circle(const std::vector<Vec3>& ds) {
  Mat3 m;
  m.m = {};
  Vec3 rhs;
  for (const Vec3& d : ds) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m.m[i][j] += d[i] * d[j];
    rhs += d;
  }
  const Vec3 w = m.inverse() * rhs;
  return {normalize(w), 1.0 / length(w)};
}

double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(length(cross(a, b)), dot(a, b));
}

TEST(PenroseTerrell, MovingSphereOutlineIsACircleNotCentredOnItsRetardedCentre) {
  Scene s;
  s.camera.width = 64;
  s.camera.height = 64;
  const Vec3 velocity{0.9, 0, 0};
  s.objects.push_back(make_object("ball", Sphere{1.0}, {2.0, 0.3, -5}, velocity, solid({1, 1, 1})));
  const ResolvedScene r = resolve_scene(s);
  const Tracer tracer(r);
  const LocateResult centre = locate(s, {LocateQuery::Kind::ObjectPoint, "ball", {0, 0, 0}});
  const std::vector<Vec3> boundary = outline(tracer, centre.direction, 48);
  const Circle c = fit_circle(boundary);
  double worst = 0;
  for (const Vec3& d : boundary) worst = std::max(worst, std::abs(dot(d, c.axis) - c.cos_radius));
  EXPECT_LT(worst, 1e-9);
  // The circle's centre is not the apparent direction of the sphere's centre.
  EXPECT_GT(angle_between(c.axis, centre.direction), 0.01);

  // Independent derivation: in the sphere's rest frame the outline is the circle of angular
  // radius asin(R/|x|) around the direction to the centre; aberrating it into the camera's
  // frame (camera velocity -beta relative to the sphere) gives the same circle.
  const AffineMap4 rest = rest_frame_map(Vec4{0, {2.0, 0.3, -5}}, velocity);
  const Vec3 camera_in_rest = rest(Vec4{0, {0, 0, 0}}).x;
  const Vec3 to_centre = normalize(-camera_in_rest);
  const double rho = std::asin(1.0 / length(camera_in_rest));
  const Vec3 e1 = normalize(cross(to_centre, Vec3{0, 0, 1}));
  const Vec3 e2 = cross(to_centre, e1);
  for (int k = 0; k < 12; ++k) {
    const double phi = 2 * kPi * k / 12;
    const Vec3 d_rest =
        to_centre * std::cos(rho) + (e1 * std::cos(phi) + e2 * std::sin(phi)) * std::sin(rho);
    const Vec3 d_cam = aberrate_into_moving_frame(d_rest, -velocity);
    EXPECT_NEAR(dot(d_cam, c.axis), c.cos_radius, 1e-9);
  }
}

TEST(TraceBounds, HoldEveryPointOfAFastBodyWhereTheLightConeMeetsIt) {
  // Points all over a body's surface, each taken where the camera's past light cone meets its
  // world-line (the locate machinery, independent of the bounds), must lie inside the box the
  // BVH culls with; otherwise parts of fast bodies would vanish.
  Scene s;
  s.camera.world_line.velocity = {0.1, -0.3, -0.6};
  const std::vector<Vec3> velocities = {{0.99, 0, 0},    {0, 0, 0.99},     {0, 0, -0.99},
                                        {0.5, 0.5, 0.5}, {-0.7, 0.1, 0.6}, {0, 0, 0}};
  for (std::size_t i = 0; i < velocities.size(); ++i) {
    Object o = make_object("body" + std::to_string(i), Box{{2, 1, 3}},
                           {-4.0 + 2 * i, 0.5, -6.0 - i}, velocities[i], solid({1, 1, 1}));
    o.rotation = Mat3::rotation({1, 2, 3}, 0.5 * i);
    o.scale = {1.5, 0.7, 1.0};
    s.objects.push_back(o);
  }
  for (bool delay : {true, false}) {
    s.render.light_delay = delay;
    const ResolvedScene r = resolve_scene(s);
    for (std::size_t i = 0; i < s.objects.size(); ++i) {
      const Bounds3& b = r.bodies[i].trace_bounds;
      for (double x : {-1.0, -0.3, 1.0})
        for (double y : {-0.5, 0.5})
          for (double z : {-1.5, 0.2, 1.5}) {
            const LocateResult l =
                locate(s, {LocateQuery::Kind::ObjectPoint, s.objects[i].name, {x, y, z}});
            const Vec3 p = l.direction * *l.distance;
            for (int k = 0; k < 3; ++k) {
              EXPECT_GE(p[k], b.lower[k] - 1e-9) << "body " << i;
              EXPECT_LE(p[k], b.upper[k] + 1e-9) << "body " << i;
            }
          }
    }
  }
}

TEST(Locate, AgreesWithTheRendererForAPointOnAMovingRotatedBox) {
  Scene s;
  s.camera.world_line.velocity = {0, 0, -0.6};
  s.camera.width = 320;
  s.camera.height = 200;
  Object box = make_object("crate", Box{{2, 1, 1}}, {3, 0.2, -6}, {-0.8, 0, 0.1},
                           checker(0.2, {1, 1, 1}, {0, 0, 0}));
  box.rotation = Mat3::rotation({0, 1, 0}, 0.4);
  s.objects.push_back(box);
  const ResolvedScene r = resolve_scene(s);
  const Tracer tracer(r);
  for (const Vec3 p : {Vec3{0.3, 0.2, 0.5}, Vec3{-0.7, -0.1, 0.5}, Vec3{0.9, 0.4, 0.5}}) {
    const LocateResult l = locate(s, {LocateQuery::Kind::ObjectPoint, "crate", p});
    ASSERT_TRUE(l.in_view);
    // The pixel reported maps back to the same look direction...
    const Vec3 through_pixel = look_direction(r.camera, l.pixel_x, l.pixel_y);
    EXPECT_LT(angle_between(through_pixel, l.direction), 1e-12);
    // ...and the ray through it meets exactly that point of the box.
    const auto hit = tracer.trace(through_pixel);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(length(hit->shape_point - p), 0.0, 1e-9) << p.x << "," << p.y << "," << p.z;
    EXPECT_NEAR(hit->s, *l.distance, 1e-9);
  }
}

TEST(Locate, EmissionEventLiesOnThePastLightConeOfTheObservation) {
  Scene s;
  s.camera.world_line = {2.0, {1, 2, 3}, {0.3, 0.4, -0.5}};
  s.objects.push_back(make_object("ball", Sphere{1}, {5, 2, -8}, {-0.9, 0.1, 0}, solid({1, 1, 1})));
  const LocateResult l = locate(s, {LocateQuery::Kind::ObjectPoint, "ball", {0, 1, 0}});
  const double dt = 2.0 - *l.emission_time;
  EXPECT_GT(dt, 0);
  EXPECT_NEAR(length(*l.emission_position - Vec3{1, 2, 3}), dt, 1e-9);
  // The camera-frame distance is the light travel time in the camera frame.
  const Vec4 in_camera =
      boost({0.3, 0.4, -0.5}) * Vec4{*l.emission_time - 2.0, *l.emission_position - Vec3{1, 2, 3}};
  EXPECT_NEAR(-in_camera.t, *l.distance, 1e-9);
  EXPECT_NEAR(length(in_camera.x), *l.distance, 1e-9);
}

}  // namespace
}  // namespace lightcone

// The ray along the line through the camera and the hole (b = 0, frame/curved_axis.cpp): a
// radial null geodesic, whose coordinate time is the difference of the tortoise coordinate
// r_* = r + 2M ln(r / 2M - 1) at its ends (written out here, not taken from the library). It
// meets the bodies on the axis in front of the hole and, looking away from it, behind the camera's
// side; behind the hole it falls in. G = c = 1, M = 1.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

double tortoise(double r) {
  return r + 2 * std::log(r / 2 - 1);
}

// A 9 x 9 picture from r = 30 looking along `forward` at one unlit ball of radius R at `centre`,
// moving with `velocity` (where it is at time 0), colours as they are at rest (no Doppler shift
// or searchlight), so that the ball shows its own colour wherever it is seen.
Scene axis_scene(const Vec3& forward, const Vec3& centre, double radius,
                 const Vec3& velocity = {}) {
  Scene s;
  s.camera.world_line.position = {0, 0, 30};
  s.camera.forward = forward;
  s.camera.fov_degrees = 30;
  s.camera.width = 9;
  s.camera.height = 9;
  s.black_hole = BlackHole{{0, 0, 0}, 1, std::nullopt};
  s.objects.push_back(
      test::make_object("ball", Sphere{radius}, centre, velocity, test::solid({1, 0.3f, 0.1f})));
  s.sky.pattern = SolidColor{{0.03f, 0.035f, 0.06f}};
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kOff;
  return s;
}

const float* centre_pixel(const Image& image) {
  return &image.rgb[3 * (4 * 9 + 4)];
}

// The camera's view with the scene's bodies, and its look straight along `forward`; it keeps
// its copy of the scene, to which the resolved scene points.
struct View {
  explicit View(const Scene& s)
      : scene(s), resolved(resolve_scene(scene)), tracer(resolved), bodies(resolved, tracer) {}
  CurvedRay axis_ray() const {
    return follow_curved_ray(*resolved.hole, resolved.scene->camera.forward, &bodies);
  }
  Scene scene;
  ResolvedScene resolved;
  Tracer tracer;
  CurvedBodies bodies;
};

TEST(BlackHoleAxis, CentrePixelShowsABallInFrontOfTheHole) {
  const Image image = render_image(axis_scene({0, 0, -1}, {0, 0, 15}, 2), {});
  const float* c = centre_pixel(image);
  EXPECT_FLOAT_EQ(c[0], 1.0f);
  EXPECT_FLOAT_EQ(c[1], 0.3f);
  EXPECT_FLOAT_EQ(c[2], 0.1f);
}

TEST(BlackHoleAxis, CentrePixelShowsABallOnTheAxisLookingAwayFromTheHole) {
  const Image image = render_image(axis_scene({0, 0, 1}, {0, 0, 45}, 2), {});
  const float* c = centre_pixel(image);
  EXPECT_FLOAT_EQ(c[0], 1.0f);
  EXPECT_FLOAT_EQ(c[1], 0.3f);
  EXPECT_FLOAT_EQ(c[2], 0.1f);
}

TEST(BlackHoleAxis, BehindTheHoleTheAxisRayFallsInAndTheBallIsSeenRoundIt) {
  // A small hole before a large ball: the radial ray ends at the horizon (black), the pixels
  // beside it, outside the shadow (0.06 degrees across), see the ball round the hole.
  Scene s = axis_scene({0, 0, -1}, {0, 0, -15}, 6);
  s.black_hole->mass = 0.01;
  const Image image = render_image(s, {});
  const float* c = centre_pixel(image);
  EXPECT_EQ(c[0], 0.0f);
  EXPECT_FLOAT_EQ(c[3], 1.0f);  // the next pixel's red
  EXPECT_EQ(View(s).axis_ray().end, CurvedRayEnd::kHorizon);
}

TEST(BlackHoleAxis, EmissionTimeIsTheRadialRaysClosedForm) {
  // At rest: the ray meets the ball's near side at r = 17 inward, r = 43 outward, and left it
  // the difference of r_* earlier; a static emitter's shift is sqrt(f_e / f_o).
  struct Case {
    Vec3 forward, centre;
    double r_met;
  };
  for (const Case& k : {Case{{0, 0, -1}, {0, 0, 15}, 17}, Case{{0, 0, 1}, {0, 0, 45}, 43}}) {
    SCOPED_TRACE(k.r_met);
    const View view(axis_scene(k.forward, k.centre, 2));
    const CurvedRay ray = view.axis_ray();
    ASSERT_EQ(ray.end, CurvedRayEnd::kBody);
    EXPECT_NEAR(ray.event.x.z, k.r_met, 1e-12 * k.r_met);
    EXPECT_NEAR(ray.event.t, -std::abs(tortoise(30) - tortoise(k.r_met)), 1e-12);
    EXPECT_NEAR(ray.shift, std::sqrt((1 - 2 / k.r_met) / (1 - 2 / 30.0)), 1e-12);
    EXPECT_EQ(ray.order, 0);
  }
}

TEST(BlackHoleAxis, MeetsABallMovingAlongTheAxisWhereItsLightLeft) {
  // Looking away from the hole at a ball receding up the axis at 0.5c, Lorentz-contracted to
  // R / gamma along it: its near side is at z(t) = 45 + 0.5 t - R / gamma, met where the ray at
  // r left at t(r) = -(r_*(r) - r_*(30)): the root of r - z(t(r)), found here by bisection.
  const double v = 0.5, radius = 2, gamma = 1 / std::sqrt(1 - v * v);
  const auto near_side = [&](double t) { return 45 + v * t - radius / gamma; };
  const auto gap = [&](double r) { return r - near_side(-(tortoise(r) - tortoise(30))); };
  const double r_met = test::bisect_decreasing([&](double r) { return -gap(r); }, 31, 60);
  const View view(axis_scene({0, 0, 1}, {0, 0, 45}, radius, {0, 0, v}));
  const CurvedRay ray = view.axis_ray();
  ASSERT_EQ(ray.end, CurvedRayEnd::kBody);
  EXPECT_NEAR(ray.event.x.z, r_met, 1e-9);
  EXPECT_NEAR(ray.event.t, -(tortoise(r_met) - tortoise(30)), 1e-9);
}

TEST(BlackHoleAxis, MeetsABallFallingAlongTheAxisOnItsSurface) {
  // Let go from rest at r = 16 on the camera's side; the event met is on the contracted ball
  // about where its origin is then, at the radial ray's time.
  Scene s = axis_scene({0, 0, -1}, {0, 0, 16}, 1.5);
  s.objects[0].motion.geodesic = HoleGeodesic{{0, 0, 0}, 1, HoleFall{16, 0, {0, 0, 1}, -60}};
  const View view(s);
  const CurvedRay ray = view.axis_ray();
  ASSERT_EQ(ray.end, CurvedRayEnd::kBody);
  const double r = ray.event.x.z;
  EXPECT_NEAR(ray.event.t, -(tortoise(30) - tortoise(r)), 1e-9);
  const HoleWorldLineState at = hole_world_line(*view.resolved.hole, s.objects[0]).at(ray.event.t);
  EXPECT_GT(length(at.velocity), 0.1);  // falling by then
  EXPECT_NEAR(length(rest_offset_of(ray.event.x - at.position, at.velocity)), 1.5, 1e-9);
}

TEST(BlackHoleAxis, ABodyOnTheAxisShadesTheRadialLegToALight) {
  // A lit point at r = 11 on the axis and a lamp at r = 25 on it: the light's leg is radial, and
  // a ball at r = 18 on the axis blocks it, one beyond the lamp or short of it does not.
  for (const double ball : {18.0, 30.0, 8.0}) {
    SCOPED_TRACE(ball);
    const Scene s = axis_scene({0, 0, -1}, {0, 0, ball}, 1);
    const View view(s);
    CurvedShadowRay leg;
    leg.origin = {0, {0, 0, 11}};
    leg.e1 = {0, 0, 1};
    leg.e2 = {1, 0, 0};
    leg.outward = true;
    leg.radius_near = 11 * (1 + 1e-9);
    leg.radius_far = 25;
    EXPECT_EQ(view.bodies.occluded(leg), ball == 18.0);
  }
}

TEST(BlackHoleAxis, CentrePixelOfALitBallIsShadedAlongTheAxis) {
  // Looking down the axis at a lit ball, lit by a lamp on the axis behind the camera: a pebble
  // between them, behind the camera too, shades the centre pixel's point (its leg to the lamp is
  // radial) and not the next pixel's (whose leg passes the pebble 0.2 away).
  for (const bool pebble : {true, false}) {
    SCOPED_TRACE(pebble);
    std::string json = R"({
      "camera": {"position": [0, 0, 30], "fov": 30, "width": 9, "height": 9},
      "black_hole": {"mass": 1},
      "objects": [
        {"name": "ball", "shape": {"sphere": {"radius": 3}}, "position": [0, 0, 10],
         "material": {"color": [0.8, 0.8, 0.8], "unlit": false}})";
    if (pebble)
      json += R"(,
        {"name": "pebble", "shape": {"sphere": {"radius": 0.1}}, "position": [0, 0, 35],
         "material": {"color": [0.8, 0.8, 0.8]}})";
    json += R"(],
      "lights": [{"name": "lamp", "type": "point", "position": [0, 0, 40], "intensity": 500}],
      "render": {"exposure": 0}
    })";
    const Image image = render_image(test::scene_from_json(json), {});
    const float* c = centre_pixel(image);
    EXPECT_GT(c[3], 0.05f);  // the next pixel: lit
    if (pebble)
      EXPECT_EQ(c[0], 0.0f);
    else
      EXPECT_GT(c[0], c[3]);  // (facing the lamp squarely)
  }
}

}  // namespace
}  // namespace lightcone

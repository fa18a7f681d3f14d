// Spinning bodies: every point has its own (turning) world-line. The tracer meets each where
// that world-line crosses the camera's past light cone, locate agrees with an independent
// solve, and the Doppler factor is that of the point's own 4-velocity (the limb turning toward
// the camera is blueshifted).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/scene/reframe.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

using test::make_object;
using test::minkowski;
using test::solid;

TEST(SpinningSphere, TheLimbTurningTowardTheCameraIsBlueshifted) {
  // A sphere at rest at the origin, turning about +y at rim speed 0.6, seen from +z: its -x
  // limb comes toward the camera, its +x limb goes away.
  Scene s;
  s.camera.world_line = {0, {0, 0, 10}, {}};
  s.camera.width = 96;
  s.camera.height = 96;
  s.camera.fov_degrees = 13;
  Object ball = make_object("ball", Sphere{1}, {}, {}, solid({1, 1, 1}));
  const double rate = 0.6;
  ball.spin = Spin{{0, 1, 0}, rate};
  s.objects.push_back(ball);
  RenderOptions options;
  options.aovs = {Aov::kDoppler};
  const Image image = render_image(s, options);
  const std::vector<float>& doppler = image.channels.at(0).values;
  const CameraBasis camera = camera_basis(s.camera);
  int checked = 0;
  double most = 1, least = 1;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      // Independently: where the pixel's ray meets the sphere, and that point's velocity.
      const Vec3 u = look_direction(camera, x + 0.5, y + 0.5);
      const Vec3 to_centre{0, 0, -10};
      const double b = dot(u, to_centre), c = dot(to_centre, to_centre) - 1;
      if (b * b - c < 1e-6) continue;  // misses, or grazes the limb
      const Vec3 r = u * (b - std::sqrt(b * b - c)) - to_centre;
      const Vec3 v = cross(Vec3{0, rate, 0}, r);
      // D = 1 / (gamma (1 - v.n)), n from the point toward the camera (-u).
      const double expected = 1 / (lorentz_gamma(v) * (1 + dot(v, u)));
      const double d = doppler[static_cast<std::size_t>(y) * image.width + x];
      EXPECT_NEAR(d, expected, 2e-6) << x << " " << y;
      if (r.x < -0.5) {
        EXPECT_GT(d, 1.0) << x << " " << y;
      }
      if (r.x > 0.5) {
        EXPECT_LT(d, 1.0) << x << " " << y;
      }
      most = std::max(most, d);
      least = std::min(least, d);
      ++checked;
    }
  EXPECT_GT(checked, 2000);
  EXPECT_GT(most, 1.2);
  EXPECT_LT(least, 0.85);
}

// A body's point p (shape coordinates) on its own world-line, solved independently: the event
// in W at body time t' (its centre's rest-frame time from its world-line's event) and its
// 4-velocity, for a body moving inertially with velocity v, turned by R(rate t') rotation S.
struct PointEvent {
  Vec4 event, four_velocity;
};
PointEvent point_at(const Object& o, const Vec3& p, double body_time) {
  const double angle = o.spin->rate * body_time;
  const Vec3 rest = Mat3::rotation(o.spin->axis, angle) * (o.rotation * component_mul(o.scale, p));
  const Vec3 rest_velocity = cross(o.spin->axis, rest) * o.spin->rate;
  const Mat4 to_world = boost(-o.world_line.velocity);
  const double g = lorentz_gamma(rest_velocity);
  return {to_world * Vec4{body_time, rest} + Vec4{o.world_line.time, o.world_line.position},
          to_world * Vec4{g, rest_velocity * g}};
}

// The body time at which the point's light reaches `receiver`, by bisection of the light-cone
// condition over a wide bracket.
double bisect_body_time(const Object& o, const Vec3& p, const Vec4& receiver) {
  const auto gap = [&](double t) {
    const Vec4 e = point_at(o, p, t).event;
    return receiver.t - e.t - length(receiver.x - e.x);
  };
  return test::bisect_decreasing(gap, -1e3, 1e3);
}

// A mesh tetrahedron with one face toward +z.
std::shared_ptr<const Mesh> tetrahedron() {
  auto mesh = std::make_shared<Mesh>();
  mesh->positions = {{-1, -1, 0.35}, {1, -1, 0.35}, {0, 1.2, 0.35}, {0, 0, -0.8}};
  mesh->triangles = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  return mesh;
}

TEST(SpinningBody, LocateMatchesAnIndependentSolveAndTheTracerMeetsThePointThere) {
  struct Case {
    const char* name;
    Shape shape;
    Vec3 point;  // on the face toward the camera
  } cases[] = {
      {"box", Box{{2, 1.4, 0.4}}, {0.6, 0.3, 0.2}},
      {"sphere", Sphere{1}, {0.3, -0.2, std::sqrt(1 - 0.09 - 0.04)}},
      {"mesh", MeshShape{tetrahedron()}, {0.2, 0.1, 0.35}},
  };
  for (const Case& c : cases) {
    // Rolling past at 0.6c, turning about z at rim speed up to 0.75: the light from one end
    // of the body left it a good fraction of a turn earlier than from the other.
    Scene s;
    s.camera.world_line = {0, {0.5, 0.2, 6}, {0, 0, 0.1}};
    s.camera.width = 200;
    s.camera.height = 200;
    s.camera.fov_degrees = 40;
    // Its clock reads 8 where it is seen (world time -6, at the origin).
    Object body = make_object(c.name, c.shape, {-6, 0, 0}, {0.6, 0, 0}, solid({1, 1, 1}));
    body.world_line.time = -16;
    body.rotation = Mat3::rotation({1, 0.2, 0}, 0.3);
    body.spin = Spin{{0, 0, 1}, 0.5};
    s.objects.push_back(body);
    const Object& o = s.objects[0];
    const WorldLine& cam = s.camera.world_line;
    const Vec4 receiver{cam.time, cam.position};
    const double body_time = bisect_body_time(o, c.point, receiver);
    const PointEvent expected = point_at(o, c.point, body_time);

    const LocateResult r = locate(s, {LocateQuery::Kind::ObjectPoint, c.name, c.point});
    ASSERT_TRUE(r.emission_time && r.emission_position && r.emission_proper_time) << c.name;
    EXPECT_NEAR(*r.emission_time, expected.event.t, 1e-9) << c.name;
    EXPECT_NEAR(length(*r.emission_position - expected.event.x), 0, 1e-9) << c.name;
    EXPECT_NEAR(*r.emission_proper_time, body_time, 1e-9) << c.name;
    const Vec4 k = receiver - expected.event;
    const double g = lorentz_gamma(cam.velocity);
    const double d = minkowski(k, {g, cam.velocity * g}) / minkowski(k, expected.four_velocity);
    EXPECT_NEAR(r.doppler, d, 1e-9 * d) << c.name;
    // Where a still body's point would be seen is far from there: the spin matters.
    Scene still = s;
    still.objects[0].spin.reset();
    const LocateResult r_still = locate(still, {LocateQuery::Kind::ObjectPoint, c.name, c.point});
    EXPECT_GT(length(*r_still.emission_position - *r.emission_position), 0.05) << c.name;

    // The tracer's ray along the located direction meets the body at that very point, with
    // that point's Doppler factor.
    const ResolvedScene resolved = resolve_scene(s);
    const Tracer tracer(resolved);
    const auto hit = tracer.trace(r.direction);
    ASSERT_TRUE(hit) << c.name;
    EXPECT_NEAR(length(hit->shape_point - c.point), 0, 1e-6) << c.name;
    EXPECT_NEAR(hit->s, *r.distance, 1e-6) << c.name;
    EXPECT_NEAR(resolved.doppler(r.direction, hit->velocity), r.doppler, 1e-6) << c.name;
    EXPECT_NEAR(hit->proper_time, body_time, 1e-6) << c.name;
  }
}

TEST(SpinningBody, AtZeroRateItIsTheStillBody) {
  Scene s;
  s.camera.world_line = {0, {0, 0.5, 5}, {0.2, 0, -0.3}};
  s.camera.width = 120;
  s.camera.height = 90;
  Material checker;
  checker.pattern = Checker{0.3, {{1, 0.7, 0.2}, {0.1, 0.2, 0.8}}};
  s.objects.push_back(make_object("box", Box{{1.5, 1, 0.8}}, {-1, 0, -2}, {0.5, 0, 0}, checker));
  s.objects.push_back(make_object("mesh", MeshShape{tetrahedron()}, {1.2, 0, -2}, {}, checker));
  s.objects.push_back(make_object("ball", Sphere{0.6}, {0, 1.2, -3}, {0, -0.4, 0}, checker));
  Scene spinning = s;
  for (Object& o : spinning.objects) o.spin = Spin{normalize(Vec3{0.2, 1, 0.3}), 0};
  EXPECT_LT(test::fraction_differing(render_image(s, {}), render_image(spinning, {})), 0.002);
}

TEST(PrincipleOfRelativity, HoldsForASpinningBody) {
  Scene s;
  s.camera.world_line = {0, {0, 0.3, 5}, {0.1, 0, -0.2}};
  s.camera.width = 120;
  s.camera.height = 90;
  s.camera.fov_degrees = 50;
  Material checker;
  checker.pattern = Checker{0.25, {{1, 0.7, 0.2}, {0.1, 0.2, 0.8}}};
  Object wheel = make_object("wheel", Box{{2, 2, 0.3}}, {-1, 0, -2}, {0.6, 0, 0}, checker);
  wheel.world_line.time = -4;
  wheel.spin = Spin{normalize(Vec3{0.1, 0.2, 1}), -0.5};
  s.objects.push_back(wheel);
  s.sky.pattern = SkyGrid{};
  const Image image = render_image(s, {});
  for (const Vec3 frame : {Vec3{0.4, -0.3, 0.2}, Vec3{-0.5, 0.2, -0.4}}) {
    const Scene other = describe_in_frame(s, frame);
    EXPECT_LT(test::fraction_differing(image, render_image(other, {})), 0.003);
  }
  // The axis must turn with the Wigner rotation: left as it was, the image changes.
  Scene wrong = describe_in_frame(s, {0.4, -0.3, 0.2});
  wrong.objects[0].spin->axis = s.objects[0].spin->axis;
  EXPECT_GT(test::fraction_differing(image, render_image(wrong, {})), 0.01);
}

}  // namespace
}  // namespace lightcone

// Bodies seen along curved rays near a Schwarzschild black hole (frame/curved_bodies.hpp),
// against derivations made independently of the chords: the flat renderer's picture of the same
// scene as M -> 0 (light delay, aberration, Doppler and Lorentz contraction of moving bodies),
// the static emitter's shift sqrt(f_e / f_o), the lens solve of `locate` (an independent root
// find on the closed-form sweep: each image of a body's point is where the tracer meets that
// body, at the same event time), and a static clock's rate sqrt(f). G = c = 1, M = 1.
#include <gtest/gtest.h>

#include <cmath>

#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/frame/locate.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

Scene moon_scene(double mass, const Vec3& moon_velocity = {}) {
  Scene s;
  s.camera.world_line.position = {0, 0, 40};
  s.camera.fov_degrees = 30;
  s.camera.width = 160;
  s.camera.height = 90;
  s.black_hole = BlackHole{{0, 0, 0}, mass, std::nullopt};
  Material checker;
  checker.pattern = Checker{0.5, {{1, 0.8f, 0.3f}, {0.2f, 0.3f, 1}}};
  s.objects.push_back(test::make_object("moon", Sphere{2}, {3, 0, -20}, moon_velocity, checker));
  Material white;
  white.pattern = SolidColor{{0.8f, 0.8f, 0.8f}};
  s.objects.push_back(test::make_object("box", Box{{2, 1, 1}}, {-4, 1, 20}, {}, white));
  return s;
}

// The camera's view of one look direction, with the scene's bodies.
struct View {
  explicit View(const Scene& s)
      : resolved(resolve_scene(s)), tracer(resolved), bodies(resolved, tracer) {}
  CurvedRay ray(const Vec3& u) const { return follow_curved_ray(*resolved.hole, u, &bodies); }
  ResolvedScene resolved;
  Tracer tracer;
  CurvedBodies bodies;
};

TEST(BlackHoleBodies, FlatLimitIsTheFlatRenderersPicture) {
  for (const Vec3& v : {Vec3{}, Vec3{0.6, 0, 0.3}}) {
    SCOPED_TRACE(v.x);
    Scene curved = moon_scene(1e-12, v);
    curved.objects[0].world_line.time = -55;  // seen about when it is there
    Scene flat = curved;
    flat.black_hole.reset();
    const Image a = render_image(curved, {}), b = render_image(flat, {});
    EXPECT_LT(test::fraction_differing(a, b), 0.003);
  }
}

TEST(BlackHoleBodies, StaticEmitterIsSeenWithSqrtFeOverFo) {
  const Scene s = moon_scene(1);
  const View view(s);
  int hits = 0;
  for (int j = 0; j < 90; j += 3)
    for (int i = 0; i < 160; i += 3) {
      const CurvedRay ray = view.ray(look_direction(view.resolved.camera, i + 0.5, j + 0.5));
      if (ray.end != CurvedRayEnd::kBody) continue;
      ++hits;
      const double r = length(ray.event.x);
      EXPECT_NEAR(ray.shift, std::sqrt((1 - 2 / r) / (1 - 2 / 40.0)), 1e-12);
    }
  EXPECT_GT(hits, 10);
}

TEST(BlackHoleBodies, EachImageOfAPointIsWhereTheTracerMeetsItsBodyAtThatTime) {
  const Scene s = moon_scene(1);
  const View view(s);
  // A point on the moon's surface facing the camera's side: locate's images of it, followed by
  // the tracer, meet the moon there (the point is on its surface), at the same emission time.
  LocateQuery q;
  q.kind = LocateQuery::Kind::WorldPoint;
  int checked = 0;
  for (const Vec3& p : {Vec3{3, 0, -18}, Vec3{3 - 1.2, 0, -20 + 1.6}, Vec3{3, 1.0, -18.27}}) {
    q.value = p;
    const LocateResult located = locate(s, q);
    for (const LocateImage& image : located.images) {
      const CurvedRay ray = view.ray(image.direction);
      if (ray.end != CurvedRayEnd::kBody || ray.order != image.order) continue;
      if (length(ray.event.x - p) > 1e-3) continue;  // another part of the moon is in front
      EXPECT_NEAR(length(ray.event.x - p), 0, 1e-7);
      EXPECT_NEAR(ray.event.t, *image.emission_time, 1e-7);
      EXPECT_NEAR(ray.shift, image.shift, 1e-9);
      ++checked;
    }
  }
  EXPECT_GE(checked, 3);
}

TEST(BlackHoleBodies, StaticClockRunsAtSqrtF) {
  const Scene s = moon_scene(1);
  const View view(s);
  const CurvedRay ray = view.ray(look_direction(view.resolved.camera, 80.5 - 40, 45.5));
  for (int i = 0; i < 160; ++i) {
    const CurvedRay r = view.ray(look_direction(view.resolved.camera, i + 0.5, 45.5));
    if (r.end != CurvedRayEnd::kBody || r.hit.body != 0) continue;
    // The moon's origin is at r = sqrt(409); its clock reads sqrt(f) (t - time) + proper_time.
    EXPECT_NEAR(r.hit.proper_time, std::sqrt(1 - 2 / std::sqrt(409.0)) * r.event.t, 1e-9);
    return;
  }
  (void)ray;
  FAIL() << "no ray met the moon";
}

}  // namespace
}  // namespace lightcone

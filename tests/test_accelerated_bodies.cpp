// Bodies beyond inertial motion in the renderers: accelerated and keyframed world-lines seen
// where an independent solve of the light-cone condition puts them, their clocks (blink
// patterns) seen running at the Doppler factor's rate, the principle of relativity for an
// accelerated body, and a slow speed of light.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>

#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/shading.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/world_line.hpp"
#include "lightcone/scene/reframe.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

using test::make_object;
using test::minkowski;
using test::solid;

// The point of `line` on the past light cone of `receiver`, by plain bisection over proper
// time: independent of the closed forms the renderers use.
WorldLinePoint bisect_retarded(const AcceleratedWorldLine& line, const Vec4& receiver) {
  const auto gap = [&](double tau) {
    const WorldLinePoint p = line.at_proper_time(tau);
    return receiver.t - p.event.t - length(receiver.x - p.event.x);
  };
  EXPECT_GT(gap(-1e3), 0);
  EXPECT_LT(gap(1e3), 0);
  return line.at_proper_time(test::bisect_decreasing(gap, -1e3, 1e3));
}

// A small body accelerating through two phases that turn its path, seen by a moving camera.
Scene accelerating_body_scene() {
  Scene s;
  s.camera.world_line = {30, {0, 1, 8}, {0.2, 0, -0.3}};
  s.camera.width = 200;
  s.camera.height = 200;
  s.camera.fov_degrees = 70;
  Object rocket = make_object("rocket", Sphere{0.05}, {-6, 0, -10}, {0.3, 0, 0}, solid({1, 1, 1}));
  rocket.motion.phases = {{6, {0.08, 0.03, 0}}, {5, {-0.05, 0, 0.06}}};
  s.objects.push_back(rocket);
  s.sky.pattern = SolidColor{{0, 0, 0}};
  return s;
}

TEST(AcceleratedBody, LocateMatchesAnIndependentSolveOfTheLightCone) {
  for (const bool camera_moves : {false, true}) {
    Scene s = accelerating_body_scene();
    if (!camera_moves) s.camera.world_line.velocity = {};
    const Object& o = s.objects[0];
    const AcceleratedWorldLine line(o.world_line.time, o.world_line.position, o.world_line.velocity,
                                    o.motion.phases);
    const WorldLine& cam = s.camera.world_line;
    const Vec4 observation{cam.time, cam.position};
    const WorldLinePoint expected = bisect_retarded(line, observation);
    // The solve really lands inside the accelerated phases.
    ASSERT_GT(expected.proper_time, 0.5);
    ASSERT_LT(expected.proper_time, 10.5);

    const LocateResult r = locate(s, {LocateQuery::Kind::ObjectPoint, "rocket", {}});
    ASSERT_TRUE(r.emission_time && r.emission_position && r.emission_proper_time);
    EXPECT_NEAR(*r.emission_time, expected.event.t, 1e-9);
    EXPECT_NEAR(length(*r.emission_position - expected.event.x), 0, 1e-9);
    EXPECT_NEAR(*r.emission_proper_time, expected.proper_time, 1e-9);
    // D = (k.u_camera) / (k.u_emitter) for the null vector k from emission to reception.
    const Vec4 k = observation - expected.event;
    const double g = lorentz_gamma(cam.velocity);
    const double d = minkowski(k, {g, cam.velocity * g}) / minkowski(k, expected.four_velocity);
    EXPECT_NEAR(r.doppler, d, 1e-9 * d) << camera_moves;
  }
}

// The centroid of the pixels brighter than a threshold, or NaN when there are none.
std::pair<double, double> bright_centroid(const Image& image) {
  double sx = 0, sy = 0, w = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
      const double v = p[0] + p[1] + p[2];
      if (v <= 0.05) continue;
      sx += v * (x + 0.5);
      sy += v * (y + 0.5);
      w += v;
    }
  return {sx / w, sy / w};
}

TEST(AcceleratedBody, RendererDrawsItWhereLocateSaysIt) {
  Scene s = accelerating_body_scene();
  s.camera.samples = 16;
  s.objects[0].shape = Sphere{0.08};
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kOff;
  const LocateResult r = locate(s, {LocateQuery::Kind::ObjectPoint, "rocket", {}});
  ASSERT_TRUE(r.in_view);
  const auto [x, y] = bright_centroid(render_image(s, {}));
  EXPECT_NEAR(x, r.pixel_x, 0.3);
  EXPECT_NEAR(y, r.pixel_y, 0.3);
  // Where the body would be seen on the inertial world-line it started on is far from there.
  Scene inertial = s;
  inertial.objects[0].motion = {};
  const LocateResult away = locate(inertial, {LocateQuery::Kind::ObjectPoint, "rocket", {}});
  EXPECT_GT(std::hypot(away.pixel_x - r.pixel_x, away.pixel_y - r.pixel_y), 10);
}

TEST(KeyframedBody, RendererDrawsItWhereTheRetardedEventIs) {
  Scene s = accelerating_body_scene();
  s.camera.samples = 16;
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kOff;
  Object& o = s.objects[0];
  o.shape = Sphere{0.08};
  o.motion = {};
  o.motion.keyframes = {{0, {-6, 0, -10}}, {10, {-2, 1, -12}}, {20, {1, 3, -11}}, {30, {3, 2, -9}}};
  o.world_line = {0, {-6, 0, -10}, {}};
  const KeyframeWorldLine line(o.motion.keyframes);
  const WorldLine& cam = s.camera.world_line;
  const WorldLinePoint seen = line.retarded({cam.time, cam.position});
  ASSERT_GT(seen.event.t, 1);  // on a curved segment
  const LocateResult r = locate(s, {LocateQuery::Kind::ObjectPoint, "rocket", {}});
  ASSERT_TRUE(r.emission_time && r.emission_position);
  EXPECT_NEAR(*r.emission_time, seen.event.t, 1e-9);
  EXPECT_NEAR(length(*r.emission_position - seen.event.x), 0, 1e-9);
  EXPECT_NEAR(*r.emission_proper_time, seen.proper_time, 1e-9);
  const auto [x, y] = bright_centroid(render_image(s, {}));
  EXPECT_NEAR(x, r.pixel_x, 0.3);
  EXPECT_NEAR(y, r.pixel_y, 0.3);
}

TEST(AcceleratedBody, LightsAndObjectsArePutOnTheirTangentWhereTheCameraSeesThem) {
  // A point light and a keyframed object: the tangent world-lines pass through the events on
  // the camera's past light cone, with the 4-velocities there, and carry the proper time.
  Scene s = accelerating_body_scene();
  Light lamp;
  lamp.name = "lamp";
  lamp.world_line = {0, {3, 2, -8}, {0, 0.2, 0}};
  lamp.motion.phases = {{5, {0.1, 0, 0.05}}};
  s.lights.push_back(lamp);
  const std::shared_ptr<const Scene> tangent = tangent_scene(s);
  ASSERT_TRUE(tangent);
  const WorldLine& cam = s.camera.world_line;
  const Vec4 observation{cam.time, cam.position};
  const auto expect_tangent = [&](const WorldLine& start, const BodyMotion& motion,
                                  const WorldLine& line) {
    const AcceleratedWorldLine exact(start.time, start.position, start.velocity, motion.phases);
    const WorldLinePoint seen = bisect_retarded(exact, observation);
    EXPECT_NEAR(line.time, seen.event.t, 1e-9);
    EXPECT_NEAR(length(line.position - seen.event.x), 0, 1e-9);
    EXPECT_NEAR(length(line.velocity - velocity_of(seen.four_velocity)), 0, 1e-12);
    EXPECT_NEAR(line.proper_time, seen.proper_time, 1e-9);
  };
  expect_tangent(s.objects[0].world_line, s.objects[0].motion, tangent->objects[0].world_line);
  expect_tangent(s.lights[0].world_line, s.lights[0].motion, tangent->lights[0].world_line);
  EXPECT_TRUE(tangent->lights[0].motion.inertial());
  // Nothing to do for a scene that moves inertially.
  Scene still = s;
  still.objects[0].motion = {};
  still.lights[0].motion = {};
  EXPECT_FALSE(tangent_scene(still));
}

TEST(AcceleratedBody, LargeBodiesAreWarnedAbout) {
  Scene s = accelerating_body_scene();
  EXPECT_TRUE(tangent_warnings(s).empty());  // a R = 0.085 * 0.05
  s.objects[0].shape = Sphere{2};
  const auto warnings = tangent_warnings(s);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("object \"rocket\""), std::string::npos) << warnings[0];
}

TEST(PrincipleOfRelativity, HoldsForAnAcceleratedBody) {
  // A box on a turning path (its orientation precesses: Thomas), a checker to show it, and a
  // moving camera; the same physical scene from two other frames.
  Scene s;
  s.camera.world_line = {7, {1.5, 2, 2.5}, {0.1, 0, -0.4}};
  s.camera.width = 160;
  s.camera.height = 120;
  s.camera.fov_degrees = 25;
  Material checker;
  checker.pattern = Checker{0.25, {{1, 0.8, 0.2}, {0.1, 0.2, 0.9}}};
  Object box = make_object("box", Box{{1, 0.6, 0.8}}, {-1.5, -0.5, -1}, {0.3, 0, 0}, checker);
  box.rotation = Mat3::rotation({0.3, 1, 0.2}, 0.7);
  box.motion.phases = {{1.5, {0, 0.9, 0.3}}, {1.5, {0.2, -0.9, 0}}};
  s.objects.push_back(box);
  s.sky.pattern = SkyGrid{};
  // Looking at it, seen in its second phase.
  const LocateResult seen = locate(s, {LocateQuery::Kind::ObjectPoint, "box", {}});
  ASSERT_GT(*seen.emission_proper_time, 2.0);
  s.camera.forward = seen.direction;
  const Image image = render_image(s, {});
  for (const Vec3 frame : {Vec3{0.5, -0.2, 0.3}, Vec3{-0.3, 0.6, -0.2}}) {
    const Scene other = describe_in_frame(s, frame);
    ASSERT_GT(length(other.objects[0].motion.phases[0].acceleration -
                     s.objects[0].motion.phases[0].acceleration),
              1e-3);
    EXPECT_LT(test::fraction_differing(image, render_image(other, {})), 0.003);
  }
}

// --- The body's clock -----------------------------------------------------------------------

// A blinking box moving with `velocity`, at (0, 0, -100) at world time 0, seen by a camera at
// rest at the origin; the camera's view follows the box.
Scene blinking_box(const Vec3& velocity, double period) {
  Scene s;
  s.camera.width = 3;
  s.camera.height = 3;
  s.camera.fov_degrees = 0.004;
  Material m;
  m.pattern = Blink{period, 0.5, {{0, 0, 0}, {1, 1, 1}}};
  // Small, so that the point seen has the Doppler factor of the centre.
  s.objects.push_back(make_object("lamp", Box{{0.02, 0.02, 0.02}}, {0, 0, -100}, velocity, m));
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kOff;
  return s;
}

bool seen_on(Scene s, double camera_time) {
  s.camera.world_line.time = camera_time;
  const LocateResult r = locate(s, {LocateQuery::Kind::ObjectPoint, "lamp", {}});
  s.camera.forward = r.direction;
  s.camera.up = std::abs(r.direction.y) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
  const Image image = render_image(s, {});
  return image.rgb[3 * 4] > 0.5f;  // the centre pixel
}

// The first camera time after `from` at which the lamp is seen switching on.
double next_switch_on(const Scene& s, double from, double step) {
  double lo = from, hi = from;
  bool was = seen_on(s, lo);
  for (;;) {
    hi = lo + step;
    const bool now = seen_on(s, hi);
    if (!was && now) break;
    was = now;
    lo = hi;
  }
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (seen_on(s, mid) ? hi : lo) = mid;
  }
  return hi;
}

TEST(TemporalDoppler, ABlinkingBodyIsSeenBlinkingWithPeriodPOverD) {
  const double period = 0.02, beta = 0.6, gamma = 1.25;
  struct Case {
    const char* name;
    Vec3 velocity;
    double doppler;
  } cases[] = {
      {"approaching", {0, 0, beta}, std::sqrt((1 + beta) / (1 - beta))},
      {"receding", {0, 0, -beta}, std::sqrt((1 - beta) / (1 + beta))},
      // Its light left (0, 0, -100) at world time 0 and reaches the camera at right angles to
      // its velocity: time dilation alone.
      {"transverse", {beta, 0, 0}, 1 / gamma},
  };
  for (const Case& c : cases) {
    const Scene s = blinking_box(c.velocity, period);
    // From the light that left around world time 0.
    const double start = 100 - 0.5 * period / c.doppler;
    const double first = next_switch_on(s, start, 0.1 * period / c.doppler);
    const double second = next_switch_on(s, first + 0.01 * period, 0.1 * period / c.doppler);
    EXPECT_NEAR(second - first, period / c.doppler, 1e-4 * period / c.doppler) << c.name;
    // The renderer and locate agree: what is seen a quarter of a period after the lamp is seen
    // switching on is the blink at the emission proper time of the face toward the camera.
    Scene at = s;
    at.camera.world_line.time = first + 0.25 * period / c.doppler;
    const LocateResult r = locate(at, {LocateQuery::Kind::ObjectPoint, "lamp", {0, 0, 0.01}});
    EXPECT_NEAR(r.doppler, c.doppler, 1e-3 * c.doppler) << c.name;
    EXPECT_EQ(blink_index(std::get<Blink>(s.objects[0].material.pattern), *r.emission_proper_time),
              1)
        << c.name;
  }
}

TEST(TemporalDoppler, TheBodysClockAdvancesAtTheDopplerRate) {
  // d(tau_emission) / d(t_camera) = D, for a body on a turning accelerated path too.
  Scene s = accelerating_body_scene();
  s.camera.world_line.velocity = {};
  const double h = 1e-4;
  for (const double t : {20.0, 30.0, 40.0}) {
    Scene a = s, b = s;
    a.camera.world_line.time = t - h;
    b.camera.world_line.time = t + h;
    Scene at = s;
    at.camera.world_line.time = t;
    const LocateQuery q{LocateQuery::Kind::ObjectPoint, "rocket", {}};
    const double rate =
        (*locate(b, q).emission_proper_time - *locate(a, q).emission_proper_time) / (2 * h);
    const double d = locate(at, q).doppler;
    EXPECT_NEAR(rate, d, 1e-6) << t;
  }
}

// --- A slow speed of light --------------------------------------------------------------------

std::string speed_of_light_scene(double c, double v_scale, double t_scale, double a_scale) {
  const auto n = [](double x) { return fmt::format("{:.17g}", x); };
  return fmt::format(R"({{
    "speed_of_light": {c},
    "camera": {{"position": [0, 1, 6], "time": {t_cam}, "velocity": [{vc}, 0, 0], "width": 96,
                "height": 64, "proper_time": {tau_cam},
                "motion": {{"phases": [{{"duration": {dcam}, "acceleration": [0, 0, {acam}]}}]}}}},
    "objects": [
      {{"name": "ball", "shape": {{"sphere": {{"radius": 1}}}}, "position": [-3, 0, -4],
        "time": {t_ball}, "velocity": [{vb}, 0, 0],
        "material": {{"blink": {{"period": {pb}, "duty": 0.5, "colors": [[0.1, 0.2, 0.9], [1, 0.6, 0.1]]}}}}}},
      {{"name": "rocket", "shape": {{"box": {{"size": [1, 0.5, 0.5]}}}}, "position": [2, 0, -6],
        "velocity": [0, {vr}, 0],
        "motion": {{"phases": [{{"duration": {dr}, "acceleration": [{ar}, 0, 0]}}]}},
        "material": {{"clock": {{"period": {pr}}}}}}},
      {{"name": "drone", "shape": {{"box": {{"size": [0.4, 0.4, 0.4]}}}},
        "motion": {{"keyframes": [{{"time": {k0}, "position": [-2, 2, -8]}},
                                  {{"time": {k1}, "position": [0, 2.5, -8]}},
                                  {{"time": {k2}, "position": [2, 2, -9]}}]}}}}
    ],
    "sky": {{"grid": {{"spacing": 20}}}}
  }})",
                     fmt::arg("c", n(c)), fmt::arg("t_cam", n(9 * t_scale)),
                     fmt::arg("vc", n(0.3 * v_scale)), fmt::arg("tau_cam", n(2 * t_scale)),
                     fmt::arg("dcam", n(3 * t_scale)), fmt::arg("acam", n(-0.1 * a_scale)),
                     fmt::arg("t_ball", n(1 * t_scale)), fmt::arg("vb", n(0.7 * v_scale)),
                     fmt::arg("pb", n(0.75 * t_scale)), fmt::arg("vr", n(0.2 * v_scale)),
                     fmt::arg("dr", n(4 * t_scale)), fmt::arg("ar", n(0.15 * a_scale)),
                     fmt::arg("pr", n(5 * t_scale)), fmt::arg("k0", n(0 * t_scale)),
                     fmt::arg("k1", n(4 * t_scale)), fmt::arg("k2", n(9 * t_scale)));
}

TEST(SpeedOfLight, AScaledSceneRendersPixelForPixelAsTheSameSceneWithCOne) {
  // In units where c = 1 the scene has speeds v, times t and accelerations a; written with
  // speed of light c it has speeds v c, times t / c and accelerations a c^2. With c a power of
  // two every conversion is exact: the images are identical.
  const Image reference = render_image(test::scene_from_json(speed_of_light_scene(1, 1, 1, 1)), {});
  for (const double c : {4.0, 0.25}) {
    const Image scaled =
        render_image(test::scene_from_json(speed_of_light_scene(c, c, 1 / c, c * c)), {});
    EXPECT_EQ(scaled.rgb, reference.rgb) << c;
  }
  // c = 10 m/s: the conversions round, the picture does not change.
  const Image metres =
      render_image(test::scene_from_json(speed_of_light_scene(10, 10, 0.1, 100)), {});
  EXPECT_LT(test::fraction_differing(metres, reference), 0.001);
  // And the scene is not trivial: without the conversion it looks different.
  const Image wrong = render_image(test::scene_from_json(speed_of_light_scene(1, 0.25, 1, 1)), {});
  EXPECT_GT(test::fraction_differing(wrong, reference), 0.05);
}

}  // namespace
}  // namespace lightcone

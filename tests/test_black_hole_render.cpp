// Curved camera rays near a Schwarzschild black hole (frame/curved_ray.hpp) and the pictures
// made from them, against derivations made here: Synge's (1966) shadow and its aberration, the
// published 42.10 degrees of a camera falling through the horizon, the static blueshift
// 1/sqrt(f), Cunningham's (1975) shift of disk gas from the photon's angular momentum taken at
// the camera, the orbit equation u'' = 3 M u^2 - u integrated step by step to the disk, the flat
// limit, and the principle of relativity (a boosted camera sees the static camera's sky,
// aberrated, through the flat aberration and Doppler laws). Units: G = c = 1, M = 1.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/hole_view.hpp"
#include "lightcone/frame/locate.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/physics/aberration.hpp"
#include "lightcone/physics/doppler.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/scene_info.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegrees = 180 / kPi;

// A camera at (0, 0, r) about a hole of mass `mass` at the origin, moving with `velocity`
// relative to its static observer.
Scene hole_scene(double r, const Vec3& velocity = {}, double mass = 1) {
  Scene s;
  s.camera.world_line.position = {0, 0, r};
  s.camera.world_line.velocity = velocity;
  s.black_hole = BlackHole{{0, 0, 0}, mass, std::nullopt};
  return s;
}

HoleView view_of(const Scene& s) {
  return *hole_view(s);
}

// The look direction at angle alpha from the hole's direction (-z), tipped toward +x.
Vec3 toward_hole(double alpha) {
  return {std::sin(alpha), 0, -std::cos(alpha)};
}

// The shadow's edge in the camera's frame: the angle from the hole's direction at which rays
// stop being captured, by bisection.
double shadow_edge(const HoleView& hole) {
  double lo = 0, hi = kPi;
  for (int i = 0; i < 200; ++i) {
    const double mid = (lo + hi) / 2;
    (follow_curved_ray(hole, toward_hole(mid)).end == CurvedRayEnd::kHorizon ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

// Synge (1966): sin(alpha) = 3 sqrt(3) M sqrt(1 - 2M/r) / r, the shadow wider than a hemisphere
// inside the photon sphere.
double synge(double r) {
  const double a = std::asin(std::min(1.0, 3 * std::sqrt(3.0) * std::sqrt(1 - 2 / r) / r));
  return r >= 3 ? a : kPi - a;
}

// A direction at angle alpha from the axis a, seen by an observer moving along a with speed
// beta: cos(alpha') = (cos(alpha) + beta) / (1 + beta cos(alpha)).
double aberrated(double alpha, double beta) {
  const double c = std::cos(alpha);
  return std::acos((c + beta) / (1 + beta * c));
}

TEST(BlackHoleRays, StaticCameraShadowIsSynges) {
  for (const double r : {2.5, 2.9, 3.5, 6.0, 30.0, 1000.0}) {
    SCOPED_TRACE(r);
    EXPECT_NEAR(shadow_edge(view_of(hole_scene(r))), synge(r), 1e-9);
  }
}

TEST(BlackHoleRays, RadiallyBoostedCameraShadowIsSyngesAberrated) {
  for (const double r : {4.0, 30.0})
    for (const double beta : {-0.9, -0.5, 0.3, 0.8}) {
      SCOPED_TRACE(testing::Message() << "r " << r << " beta toward the hole " << beta);
      const HoleView hole = view_of(hole_scene(r, {0, 0, -beta}));
      const double expected = aberrated(synge(r), beta);
      EXPECT_NEAR(shadow_edge(hole), expected, 1e-9);
      EXPECT_NEAR(shadow_angle_for_camera(hole, {0, 0, -beta}), expected, 1e-9);
    }
}

TEST(BlackHoleRays, HoleFallingFromInfinitySeesTheShadowShrinkTo42DegreesAtTheHorizon) {
  // A camera falling from rest at infinity moves inward at sqrt(2M/r) relative to the static
  // observers; at the horizon its shadow is 42.10 degrees in radius.
  for (const double r : {2.000001, 2.5, 3.0, 10.0, 100.0}) {
    SCOPED_TRACE(r);
    const double beta = std::sqrt(2 / r);
    const HoleView hole = view_of(hole_scene(r, {0, 0, -beta}));
    const double edge = shadow_edge(hole);
    EXPECT_NEAR(edge, aberrated(synge(r), beta), 1e-8);
    if (r < 2.001) {
      EXPECT_NEAR(edge * kDegrees, 42.10, 0.005);
    }
  }
}

TEST(BlackHoleRays, StaticCameraSeesTheStaticSkyBlueshiftedByOneOverSqrtF) {
  for (const double r : {2.5, 10.0, 100.0}) {
    const HoleView hole = view_of(hole_scene(r));
    for (const double alpha : {kPi - 0.1, (synge(r) + kPi) / 2, synge(r) + 1e-6}) {
      const CurvedRay ray = follow_curved_ray(hole, toward_hole(alpha));
      ASSERT_EQ(ray.end, CurvedRayEnd::kSky);
      EXPECT_NEAR(ray.shift, 1 / std::sqrt(1 - 2 / r), 1e-12);
    }
  }
}

TEST(BlackHoleRays, ShadowOfAVanishingHoleSeenMovingIsFinite) {
  const Vec3 beta{0.1, 0, 0};
  const double angle = shadow_angle_for_camera(view_of(hole_scene(40, beta, 1e-300)), beta);
  EXPECT_TRUE(std::isfinite(angle));
  EXPECT_LT(angle, 1e-250);
}

TEST(BlackHoleRays, FlatLimitIsTheStraightRayAndNoShift) {
  const HoleView hole = view_of(hole_scene(10, {0.3, 0, -0.2}, 1e-12));
  for (const Vec3& u : {Vec3{0, 0, -1}, normalize(Vec3{1, 2, -3}), normalize(Vec3{-1, 0.5, 0.2})}) {
    const CurvedRay ray = follow_curved_ray(hole, u);
    ASSERT_EQ(ray.end, CurvedRayEnd::kSky);
    const Vec3 expected = aberrate_out_of_moving_frame(u, {0.3, 0, -0.2});
    EXPECT_NEAR(length(ray.sky_direction - expected), 0, 1e-9);
    EXPECT_NEAR(ray.shift, doppler_factor(expected * -1.0, {}, {0.3, 0, -0.2}), 1e-9);
  }
}

TEST(BlackHoleRays, BoostedCameraSeesTheStaticCamerasSkyAberrated) {
  // The principle of relativity: the camera moving at beta relative to its static observer
  // receives along u the photon the static observer receives along the flat aberration of u,
  // and its frequency differs by the flat Doppler factor.
  const Vec3 beta{0.5, 0.2, -0.6};
  const HoleView moving = view_of(hole_scene(8, beta)), still = view_of(hole_scene(8));
  for (int i = 0; i < 40; ++i) {
    const double theta = 0.07 + i * 0.075, az = 2.4 * i;
    const Vec3 u{std::sin(theta) * std::cos(az), std::sin(theta) * std::sin(az), -std::cos(theta)};
    const Vec3 d = aberrate_out_of_moving_frame(u, beta);
    const CurvedRay a = follow_curved_ray(moving, u), b = follow_curved_ray(still, d);
    ASSERT_EQ(a.end, b.end);
    EXPECT_EQ(a.order, b.order);
    if (a.end != CurvedRayEnd::kSky) continue;
    EXPECT_NEAR(length(a.sky_direction - b.sky_direction), 0, 1e-9);
    EXPECT_NEAR(a.shift / b.shift, doppler_factor(d * -1.0, {}, beta), 1e-12);
  }
}

// The disk seen from far away: Cunningham's g = sqrt(1 - 3M/r) / (1 - Omega lambda), with
// Omega = sqrt(M/r^3) and lambda the photon's angular momentum about the disk's normal per unit
// energy, taken where the camera receives it: lambda = (r0 / sqrt(f0)) ((e1 x (-d)) . n) for the
// static camera at r0 (local momentum along -d, energy 1/sqrt(f0) per unit conserved energy).
// The radius where the ray meets the disk is checked by integrating u'' = 3 M u^2 - u from the
// camera to the crossing angle.
double integrated_radius(double r0, double cot_alpha, double phi_end) {
  const double f0 = 1 - 2 / r0;
  // b only enters the time, which is not asked for here.
  return test::integrate_orbit(1, 1, 1 / r0, -std::sqrt(f0) * cot_alpha / r0, phi_end, 200000).r;
}

TEST(BlackHoleRays, DiskRadiusFollowsTheOrbitEquationAndItsShiftIsCunninghams) {
  const double r0 = 60, incline = 12 / kDegrees;
  Scene s = hole_scene(1);
  s.camera.world_line.position = Vec3{0, std::sin(incline), std::cos(incline)} * r0;
  AccretionDisk disk;
  disk.inner = 6;
  disk.outer = 30;
  s.black_hole->disk = disk;
  const HoleView hole = view_of(s);
  const Vec3 e1 = hole.outward, n{0, 1, 0};
  int hits[3] = {};
  for (int j = 0; j < 60; ++j)
    for (int i = 0; i < 60; ++i) {
      const double x = (i - 29.5) / 29.5 * 0.5, y = (j - 29.5) / 29.5 * 0.5;
      const Vec3 d = normalize(e1 * -1.0 + Vec3{x, y, 0});
      const CurvedRay ray = follow_curved_ray(hole, d);
      if (ray.end != CurvedRayEnd::kDisk) continue;
      ++hits[std::min(ray.order, 2)];
      const double f0 = 1 - 2 / r0, r = ray.disk_radius;
      const double lambda = r0 / std::sqrt(f0) * dot(cross(e1, d * -1.0), n);
      const double omega = std::sqrt(1 / (r * r * r));
      const double expected = std::sqrt(1 - 3 / r) / (1 - omega * lambda) / std::sqrt(f0);
      EXPECT_NEAR(ray.shift, expected, 1e-12 * expected);
      if ((i + j) % 7 == 0) {
        const double cos_alpha = dot(d, e1), sin_alpha = length(d - e1 * cos_alpha);
        EXPECT_NEAR(integrated_radius(r0, cos_alpha / sin_alpha, ray.phi), r, 1e-8 * r);
      }
    }
  EXPECT_GT(hits[0], 100);  // the primary image
  EXPECT_GT(hits[1], 0);    // the secondary, round the far side (thin)
}

TEST(BlackHoleRender, BundledSceneRendersTheShadowTheDiskAndItsImages) {
  Scene s = test::load_repository_scene("black-hole.json");
  s.camera.width = 192;
  s.camera.height = 108;
  s.camera.samples = 1;
  RenderOptions options;
  RenderStats stats;
  options.aovs = {Aov::kImageOrder, Aov::kDoppler};
  const Image image = render_image(s, options, &stats);
  int disk_orders[3] = {};
  for (const float v : image.rgb) ASSERT_TRUE(std::isfinite(v)) << v;
  // The hole's centre is dark; the disk's secondary image and sky beyond the shadow ring have
  // image order 1, some of the rays order 2.
  const std::size_t centre = 54 * 192 + 96;
  EXPECT_LT(image.rgb[3 * centre + 1], 1e-3);
  for (const float order : image.channels[0].values)
    ++disk_orders[std::min(2, static_cast<int>(order))];
  EXPECT_GT(disk_orders[0], 0);
  EXPECT_GT(disk_orders[1], 0);
  EXPECT_GT(stats.mean_image_order, 0);
  // The approaching side (left, -x) is blueshifted past the receding one.
  const auto shift_at = [&](int x, int y) { return image.channels[1].values[y * 192 + x]; };
  EXPECT_GT(shift_at(40, 62), shift_at(152, 62));
}

// locate's images against where the tracer's rays go: each image's look direction, followed by
// the walker, reaches the located sky direction, or meets the disk at the located point, with
// the same image order and shift.
TEST(BlackHoleLocate, ImagesAreWhereTheTracersRaysGo) {
  Scene s = test::load_repository_scene("black-hole.json");
  s.camera.world_line.velocity = {0.1, -0.2, -0.3};
  const HoleView hole = *hole_view(s);
  LocateQuery sky;
  sky.kind = LocateQuery::Kind::SkyDirection;
  sky.value = normalize(Vec3{0.3, 0.2, -1});
  const LocateResult far = locate(s, sky);
  ASSERT_EQ(far.images.size(), 3u);
  for (const LocateImage& image : far.images) {
    SCOPED_TRACE(image.order);
    const CurvedRay ray = follow_curved_ray(hole, image.direction);
    if (ray.end != CurvedRayEnd::kSky) continue;  // the disk is in front of this one
    EXPECT_EQ(ray.order, image.order);
    EXPECT_NEAR(length(ray.sky_direction - sky.value), 0, 1e-8);
    EXPECT_NEAR(ray.shift, image.shift, 1e-12);
  }
  EXPECT_EQ(follow_curved_ray(hole, far.images[0].direction).end, CurvedRayEnd::kSky);
  // A point on the disk's far side: its primary image is where the disk is drawn at that radius.
  LocateQuery point;
  point.kind = LocateQuery::Kind::WorldPoint;
  point.value = {4, 0, -14};
  const LocateResult near = locate(s, point);
  ASSERT_FALSE(near.images.empty());
  int matched = 0;
  for (const LocateImage& image : near.images) {
    const CurvedRay ray = follow_curved_ray(hole, image.direction);
    if (ray.end != CurvedRayEnd::kDisk || ray.order != image.order) continue;
    EXPECT_NEAR(ray.disk_radius, length(point.value), 1e-7);
    ++matched;
  }
  EXPECT_GE(matched, 1);
  EXPECT_TRUE(near.emission_time &&
              *near.emission_time < -length(point.value - s.camera.world_line.position));
}

// What this version does not draw near a hole is refused by name, with status 2 and nothing
// written; `info` reports the hole.
TEST(BlackHoleCli, RefusesWhatItDoesNotDrawYetAndInfoReportsTheHole) {
  const std::filesystem::path dir = test::fresh_temp_dir("black_hole_cli");
  const std::string hole =
      R"("camera": {"position": [0, 0, 30], "width": 32, "height": 18},
         "black_hole": {"mass": 1, "disk": {}})";
  const auto scene_file = [&](const std::string& name, const std::string& extra) {
    const std::filesystem::path p = dir / name;
    test::write_text(p, "{" + hole + extra + "}");
    return test::quoted(p);
  };
  const std::string plain = scene_file("plain.json", "");
  const std::string with_light = scene_file(
      "light.json", R"(, "lights": [{"name": "lamp", "type": "point", "position": [10, 0, 0]}],
                     "render": {"light_source_delay": "camera"})");
  const std::string classical =
      scene_file("classical.json", R"(, "render": {"relativity": false})");
  const std::filesystem::path out = dir / "out.png";
  struct Case {
    std::string arguments, message;
  };
  for (const Case& c : {
           Case{"render " + with_light + " -o " + test::quoted(out), "light_source_delay"},
           Case{"render " + classical + " -o " + test::quoted(out), "render.relativity"},
       }) {
    SCOPED_TRACE(c.arguments);
    const test::CommandResult r = test::run_lightcone(c.arguments);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("black_hole: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  const test::CommandResult rendered =
      test::run_lightcone("render " + plain + " -o " + test::quoted(out) + " --stats");
  EXPECT_EQ(rendered.status, 0) << rendered.err;
  EXPECT_NE(rendered.err.find("mean_image_order"), std::string::npos) << rendered.err;
  const test::CommandResult located =
      test::run_lightcone("locate " + plain + " --world-point 0,0,-20");
  EXPECT_EQ(located.status, 0) << located.err;
  EXPECT_NE(located.out.find(R"("images":[{"order":0,)"), std::string::npos) << located.out;
  EXPECT_NE(located.out.find(R"({"order":1,)"), std::string::npos) << located.out;
  // The raster renderer draws it too (tests/test_raster_black_hole.cpp).
  const test::CommandResult rastered =
      test::run_lightcone("render " + plain + " --renderer raster -o " + test::quoted(out));
  EXPECT_EQ(rastered.status, 0) << rastered.err;
  // A static camera animates in place, on its own clock; a moving one needs a geodesic motion.
  const test::CommandResult animated =
      test::run_lightcone("animate " + plain + " --fps 1 --frames 0-1 -o " +
                          test::quoted(dir / "f%d.png") + " --quiet");
  EXPECT_EQ(animated.status, 0) << animated.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "f1.png"));
  const test::CommandResult refused = test::run_lightcone(
      "animate " + plain + " --set camera.velocity=[0.1,0,0] --fps 1 --frames 0-1 -o " +
      test::quoted(dir / "g%d.png"));
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.err.find("geodesic motion"), std::string::npos) << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "g0.png"));
  const test::CommandResult info = test::run_lightcone("info " + plain);
  EXPECT_EQ(info.status, 0) << info.err;
  EXPECT_NE(info.out.find("photon sphere r = 3"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("innermost stable circular orbit r = 6"), std::string::npos);
  // Synge's shadow from r = 30M: asin(3 sqrt(3) sqrt(1 - 2/30) / 30) = 9.6327 degrees.
  EXPECT_NE(info.out.find("shadow 9.6327 degrees"), std::string::npos) << info.out;
}

}  // namespace
}  // namespace lightcone

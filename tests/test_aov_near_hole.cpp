// Output variables near a black hole (docs/design/black-hole.md, "Output variables"): along the
// curved ray of every image order, the emission time, distance, depth, normal and object of the
// point met are what an independent lens solve (locate's ray_between) says of that point; the
// disk, the shadow and the sky have their own object codes; and a hole too light to bend
// anything gives the flat values.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lightcone/frame/locate.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr int kSide = 15, kCentre = 7;  // the centre pixel's ray is the camera's forward axis

using test::channel;

float at(const Image& image, const std::string& name, int x = kCentre, int y = kCentre) {
  const NamedChannel& c = channel(image, name);
  return c.values.empty() ? NAN : c.values[static_cast<std::size_t>(y) * image.width + x];
}

Vec3 normal_at(const Image& image, int x = kCentre, int y = kCentre) {
  return {at(image, "normal.X", x, y), at(image, "normal.Y", x, y), at(image, "normal.Z", x, y)};
}

const std::vector<Aov> kAll = {Aov::kDoppler, Aov::kEmissionTime, Aov::kDistance,  Aov::kObject,
                               Aov::kDepth,   Aov::kNormal,       Aov::kImageOrder};

// The scene seen along `forward` through a narrow view, kSide pixels square, with every output
// variable.
Image render_along(Scene s, const Vec3& forward) {
  s.camera.forward = forward;
  s.camera.fov_degrees = 0.2;
  s.camera.width = s.camera.height = kSide;
  s.camera.samples = 1;
  RenderOptions options;
  options.aovs = kAll;
  return render_image(s, options);
}

// A static camera at r = 30M and a ball at rest behind the hole, off the axis: the centre ray
// aimed at the image of order k of the ball's centre meets its surface at the point whose normal
// the normal variable gives; that point at rest has its image of order k on the same ray, and
// the emission time, distance and depth are the lens's time of flight for it.
TEST(AovNearHole, ABodyBehindTheHoleIsMetWhereTheLensSendsEachImage) {
  const Scene s = test::scene_from_json(R"({
    "camera": {"position": [0, 0, 30], "time": 4},
    "black_hole": {"mass": 1},
    "objects": [{"name": "ball", "shape": {"sphere": {"radius": 2}}, "position": [3, 1, -14]}]})");
  const Vec3 centre{3, 1, -14};
  const LocateResult ball = locate(s, {LocateQuery::Kind::ObjectPoint, "ball", {}});
  ASSERT_GE(ball.images.size(), 2u);
  for (int order = 0; order < 2; ++order) {
    SCOPED_TRACE(order);
    const Vec3 forward = ball.images[order].direction;
    const Image image = render_along(s, forward);
    EXPECT_EQ(at(image, "object"), 0.0f);
    EXPECT_EQ(at(image, "image_order"), static_cast<float>(order));
    const Vec3 n = normal_at(image);
    EXPECT_NEAR(length(n), 1.0, 1e-6);
    const Vec3 met = centre + n * 2.0;
    const LocateResult point = locate(s, {LocateQuery::Kind::WorldPoint, {}, met});
    ASSERT_GT(point.images.size(), static_cast<std::size_t>(order));
    const LocateImage& image_k = point.images[order];
    // The normal's float rounding moves the point by some 1e-7 of the ball's radius.
    EXPECT_LT(length(image_k.direction - forward), 1e-6);
    const double t_e = *image_k.emission_time, flight = 4 - t_e;
    EXPECT_NEAR(at(image, "emission_time"), t_e, 1e-6 * std::abs(t_e));
    EXPECT_NEAR(at(image, "distance"), flight, 1e-6 * flight);
    EXPECT_NEAR(*image_k.distance, flight, 1e-12 * flight);  // locate's, for a camera at rest
    EXPECT_NEAR(at(image, "depth"), flight, 1e-6 * flight);  // along the forward axis
    // Behind the hole: the light takes longer than the straight way (the Shapiro delay).
    EXPECT_GT(flight, length(met - Vec3{0, 0, 30}));
    EXPECT_NEAR(at(image, "doppler"), image_k.shift, 1e-6);
  }
}

// The disk's points: object -2, the disk's normal on the camera's side, and the emission time of
// each image from the lens's time of flight; the shadow (-3) and the sky (-1) have no surface.
TEST(AovNearHole, TheDiskHasItsCodeNormalAndTimeOfFlight) {
  const Scene s = test::scene_from_json(R"({
    "camera": {"position": [0, 3, 30]},
    "black_hole": {"mass": 1, "disk": {"inner": 6, "outer": 12}}})");
  // r = 9.6M, nearly behind the hole: the secondary's light passes the disk's plane first far
  // beyond its outer edge, on the near side.
  const Vec3 on_disk{1.5, 0, -9.5};
  const LocateResult point = locate(s, {LocateQuery::Kind::WorldPoint, {}, on_disk});
  ASSERT_GE(point.images.size(), 2u);
  for (int order = 0; order < 2; ++order) {
    SCOPED_TRACE(order);
    const Image image = render_along(s, point.images[order].direction);
    ASSERT_EQ(at(image, "image_order"), static_cast<float>(order));
    EXPECT_EQ(at(image, "object"), kObjectDisk);
    const double t_e = *point.images[order].emission_time;
    EXPECT_NEAR(at(image, "emission_time"), t_e, 1e-6 * std::abs(t_e));
    EXPECT_NEAR(at(image, "distance"), -t_e, 1e-6 * std::abs(t_e));
    // The primary image is seen from above; the secondary's light passed under the hole and
    // left the disk's underside.
    EXPECT_EQ(normal_at(image).y, order == 0 ? 1.0f : -1.0f);
  }
  const Image shadow = render_along(s, {0, -0.1, -1});
  EXPECT_EQ(at(shadow, "object"), kObjectShadow);
  EXPECT_EQ(at(shadow, "distance"), INFINITY);
  EXPECT_EQ(at(shadow, "emission_time"), -INFINITY);
  EXPECT_EQ(normal_at(shadow).x, 0.0f);
  const Image sky = render_along(s, {1, 0, 0});
  EXPECT_EQ(at(sky, "object"), kObjectSky);
  EXPECT_EQ(at(sky, "depth"), INFINITY);
}

// A hole of 1e-9 units, 866 away: every variable is the flat one, for a moving camera and a
// moving ball (the distance is in the camera's frame either way).
TEST(AovNearHole, ANegligibleHoleGivesTheFlatValues) {
  const std::string bodies = R"(
    "camera": {"position": [0, 1, 5], "velocity": [0.3, 0, -0.2], "time": 2, "fov": 40,
               "width": 24, "height": 16, "samples": 1},
    "objects": [
      {"name": "floor", "shape": {"box": {"size": [20, 0.5, 20]}}, "position": [0, -1, -8]},
      {"name": "ball", "shape": {"sphere": {"radius": 1.5}}, "position": [1, 1, -8],
       "velocity": [-0.5, 0, 0.2]}])";
  const Scene flat = test::scene_from_json("{" + bodies + "}");
  const Scene near = test::scene_from_json(
      "{" + bodies + R"(, "black_hole": {"mass": 1e-9, "position": [500, 500, 500]}})");
  RenderOptions options;
  options.aovs = kAll;
  const Image a = render_image(flat, options), b = render_image(near, options);
  int surface = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      ASSERT_EQ(at(a, "object", x, y), at(b, "object", x, y)) << x << ", " << y;
      if (at(a, "object", x, y) < 0) continue;
      ++surface;
      for (const char* name : {"emission_time", "distance", "depth", "doppler"}) {
        const double v = at(a, name, x, y);
        EXPECT_NEAR(at(b, name, x, y), v, 1e-5 * std::abs(v)) << name << " at " << x << ", " << y;
      }
      EXPECT_LT(length(normal_at(a, x, y) - normal_at(b, x, y)), 1e-5);
    }
  EXPECT_GT(surface, 100);
}

}  // namespace
}  // namespace lightcone

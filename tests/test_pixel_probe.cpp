// locate --pixel (probe_pixel): what the camera sees through a point of its picture, the exact
// inverse of locate's --object/--point and --direction. From the pixel where locate sees a
// point, the probe gives back that point, its emission event and clock and its shift, in flat
// spacetime and for each image near a black hole; from a pixel of the sky, the direction that
// locate takes back to that pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/pixel_probe.hpp"
#include "lightcone/frame/request_rules.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

// The probe at the pixel where `seen` (a locate answer or one of its images) is, checked to
// give back what locate started from: the object's point, the emission event, the clock, the
// shift. `size` is the object's size, against which the point's error is measured.
void expect_probe_gives_back(const Scene& scene, const std::string& object, const Vec3& shape_point,
                             double size, double pixel_x, double pixel_y, double emission_time,
                             double proper_time, double shift, int order) {
  SCOPED_TRACE(object + " at pixel (" + std::to_string(pixel_x) + ", " + std::to_string(pixel_y) +
               ")");
  ASSERT_EQ(probe_refused(scene, pixel_x, pixel_y), std::nullopt);
  const PixelProbe probe = probe_pixel(scene, pixel_x, pixel_y);
  ASSERT_EQ(probe.meets, ProbeMeets::kObject);
  EXPECT_EQ(scene.objects[probe.object].name, object);
  EXPECT_LT(length(probe.point - shape_point), 1e-12 * size);
  ASSERT_TRUE(probe.emission_time && probe.emission_proper_time && probe.distance);
  EXPECT_NEAR(*probe.emission_time, emission_time, 1e-12 * std::abs(emission_time));
  EXPECT_NEAR(*probe.emission_proper_time, proper_time, 1e-12 * std::abs(emission_time));
  EXPECT_NEAR(probe.doppler, shift, 1e-12);
  EXPECT_EQ(probe.order, order);
}

TEST(PixelProbe, GivesBackThePointLocateSeesInFlatSpacetime) {
  // The Terrell scene: a ball and a box crossing the view at 0.9c, seen where their light left
  // them some 9 units of time earlier. Points on the box's front face and on its trailing face
  // (which the rotation shows), and on the ball.
  const Scene scene = test::load_repository_scene("terrell.json");
  struct Case {
    std::string object;
    Vec3 point;
    double size;
  };
  for (const Case& c : {Case{"crate", {0.3, 0.2, 1.2}, 2.4}, Case{"crate", {-1.2, -0.5, 0.7}, 2.4},
                        Case{"ball", {0, 0, 1.4}, 1.4},
                        Case{"ball", normalize(Vec3{-0.6, 0.5, 1.16}) * 1.4, 1.4}}) {
    const LocateResult seen = locate(scene, {LocateQuery::Kind::ObjectPoint, c.object, c.point});
    ASSERT_TRUE(seen.in_view) << c.object;
    expect_probe_gives_back(scene, c.object, c.point, c.size, seen.pixel_x, seen.pixel_y,
                            *seen.emission_time, *seen.emission_proper_time, seen.doppler, 0);
  }
}

TEST(PixelProbe, GivesBackThePointOfEachImageNearABlackHole) {
  // A clock behind the hole, seen round both sides: each image's pixel meets the same point, on
  // that image's own ray, with its own (earlier) emission time and clock.
  const Scene scene = test::load_repository_scene("lensed-clock.json");
  const Vec3 point{0.5, 0.3, 2};
  const LocateResult seen = locate(scene, {LocateQuery::Kind::ObjectPoint, "clock", point});
  int probed = 0;
  for (const LocateImage& image : seen.images) {
    if (!image.in_view || image.order > 1) continue;  // order 2 is a sliver beside the shadow
    expect_probe_gives_back(scene, "clock", point, 4, image.pixel_x, image.pixel_y,
                            *image.emission_time, *image.emission_proper_time, image.shift,
                            image.order);
    ++probed;
  }
  EXPECT_EQ(probed, 2);
}

TEST(PixelProbe, GivesTheSkyDirectionThatLocateTakesBackToThePixel) {
  // The sky above the Terrell scene's bodies, and round the hole in black-hole.json.
  for (const auto& [name, x, y] :
       {std::tuple{"terrell.json", 900.25, 20.5}, {"black-hole.json", 900.25, 420.5}}) {
    SCOPED_TRACE(name);
    Scene scene = test::load_repository_scene(name);
    // With the sky's pattern turned too: the direction is the one locate takes, not the
    // pattern's.
    for (const double turn : {0.0, 0.7}) {
      scene.sky.rotation = Mat3::rotation(normalize(Vec3{1, 2, 3}), turn);
      const PixelProbe probe = probe_pixel(scene, x, y);
      ASSERT_EQ(probe.meets, ProbeMeets::kSky);
      EXPECT_FALSE(probe.emission_time || probe.emission_position || probe.distance);
      const LocateResult back =
          locate(scene, {LocateQuery::Kind::SkyDirection, "", probe.sky_direction});
      double pixel_x = back.pixel_x, pixel_y = back.pixel_y, shift = back.doppler;
      for (const LocateImage& image : back.images)
        if (image.order == probe.order)
          pixel_x = image.pixel_x, pixel_y = image.pixel_y, shift = image.shift;
      EXPECT_NEAR(pixel_x, x, 1e-8);
      EXPECT_NEAR(pixel_y, y, 1e-8);
      EXPECT_NEAR(probe.doppler, shift, 1e-12);
    }
  }
}

TEST(PixelProbe, MeetsTheDiskAtItsRadiusAndFindsNothingInTheShadow) {
  const Scene scene = test::load_repository_scene("black-hole.json");
  const PixelProbe disk = probe_pixel(scene, 640, 300);
  ASSERT_EQ(disk.meets, ProbeMeets::kDisk);
  EXPECT_GT(disk.disk_radius, 6);
  EXPECT_LT(disk.disk_radius, 20);
  // The emission event lies on the disk (the hole at the origin, the disk in y = 0), at the
  // radius met.
  ASSERT_TRUE(disk.emission_position && disk.emission_time);
  EXPECT_NEAR(length(*disk.emission_position), disk.disk_radius, 1e-12 * disk.disk_radius);
  EXPECT_NEAR(disk.emission_position->y, 0, 1e-12);
  EXPECT_LT(*disk.emission_time, -50);  // the camera is 60M away
  EXPECT_EQ(disk.object, -1);

  // Straight at the hole: its shadow, where no light comes from.
  const Scene clock = test::load_repository_scene("lensed-clock.json");
  const PixelProbe shadow = probe_pixel(clock, 480, 270);
  EXPECT_EQ(shadow.meets, ProbeMeets::kShadow);
  EXPECT_EQ(shadow.doppler, 0);
  EXPECT_FALSE(shadow.emission_time || shadow.emission_position || shadow.distance ||
               shadow.emission_proper_time);
}

TEST(PixelProbe, RefusesARequestThatIsNotOnePixel) {
  const double two[] = {1, 2}, three[] = {1, 2, 3};
  EXPECT_EQ(probe_request_refused(two, false), std::nullopt);
  EXPECT_EQ(probe_request_refused(three, false), "locate: pixel must be two numbers x, y, got 3");
  EXPECT_EQ(probe_request_refused(std::span<const double>(two, 1), false),
            "locate: pixel must be two numbers x, y, got 1");
  EXPECT_EQ(probe_request_refused(two, true),
            "locate: pixel takes no object: it finds what is seen");
}

TEST(PixelProbe, RefusesPointsOutsideThePicture) {
  const Scene scene = test::load_repository_scene("terrell.json");  // 960 x 540
  EXPECT_EQ(probe_refused(scene, 0, 0), std::nullopt);
  EXPECT_EQ(probe_refused(scene, 959.999, 539.999), std::nullopt);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [x, y] : {std::pair{960.0, 1.0},
                             {1.0, 540.0},
                             {-0.001, 1.0},
                             {nan, 1.0},
                             {1.0, std::numeric_limits<double>::infinity()}}) {
    const auto refused = probe_refused(scene, x, y);
    ASSERT_TRUE(refused) << x << ", " << y;
    EXPECT_NE(refused->find("pixel: "), std::string::npos) << *refused;
    EXPECT_NE(refused->find("is not in the 960 x 540 picture"), std::string::npos) << *refused;
  }
}

}  // namespace
}  // namespace lightcone

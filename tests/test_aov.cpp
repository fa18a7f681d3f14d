// Output variables (`--aov`, `--map`): the Doppler factor, emission time and travel distance a
// pixel reports are what `locate` says of the point seen there; the other channels and the
// colour map.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/false_colour.hpp"
#include "lightcone/frame/locate.hpp"
#include "lightcone/trace/aov.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

using test::make_object;

using test::channel;

float at(const NamedChannel& c, int width, int x, int y) {
  return c.values[static_cast<std::size_t>(y) * width + x];
}

TEST(Aov, DopplerEmissionTimeAndDistanceAreWhatLocateSaysOfThePointSeen) {
  const struct {
    Vec3 camera_velocity, ball_position, ball_velocity;
  } cases[] = {{{0.2, 0.0, -0.4}, {1.0, 0.5, -8}, {-0.6, 0.1, 0.3}},
               {{-0.3, 0.1, 0.2}, {-2.0, -0.5, -7}, {0.1, 0.2, -0.6}}};
  for (const auto& c : cases) {
    Scene s;
    s.camera.world_line.velocity = c.camera_velocity;
    s.camera.world_line.time = 3;
    s.objects.push_back(make_object("ball", Sphere{1.0}, c.ball_position, c.ball_velocity,
                                    Material{SolidColor{{1, 1, 1}}, true, {}}));
    s.camera.width = s.camera.height = 15;
    // Aim at the ball's apparent centre: the located pixel is then the centre one.
    const LocateQuery centre{LocateQuery::Kind::ObjectPoint, "ball", {0, 0, 0}};
    s.camera.forward = locate(s, centre).direction;
    s.camera.fov_degrees = 0.5;
    // The near surface point on the line of sight: locate it by the point the centre ray meets.
    RenderOptions options;
    options.aovs = {Aov::kDoppler, Aov::kEmissionTime, Aov::kDistance,
                    Aov::kObject,  Aov::kDepth,        Aov::kNormal};
    const Image image = render_image(s, options);
    ASSERT_EQ(image.channels.size(), 8u);
    const float d = at(channel(image, "doppler"), 15, 7, 7);
    const float t = at(channel(image, "emission_time"), 15, 7, 7);
    const float r = at(channel(image, "distance"), 15, 7, 7);
    // The surface point hit, in the ball's own coordinates, from the rest-frame normal (a unit
    // sphere at the origin: the point is the normal).
    const Vec3 n{at(channel(image, "normal.X"), 15, 7, 7), at(channel(image, "normal.Y"), 15, 7, 7),
                 at(channel(image, "normal.Z"), 15, 7, 7)};
    EXPECT_NEAR(length(n), 1.0, 1e-6);
    const LocateResult l = locate(s, {LocateQuery::Kind::ObjectPoint, "ball", n});
    ASSERT_TRUE(l.in_view);
    ASSERT_NEAR(l.pixel_x, 7.5, 2e-3);
    ASSERT_NEAR(l.pixel_y, 7.5, 2e-3);
    EXPECT_NEAR(d, l.doppler, 1e-5 * l.doppler);
    EXPECT_NEAR(t, *l.emission_time, 1e-5 * std::abs(*l.emission_time));
    EXPECT_NEAR(r, *l.distance, 1e-5 * *l.distance);
    EXPECT_EQ(at(channel(image, "object"), 15, 7, 7), 0.0f);
    // Depth is the distance along the forward axis: at the centre, the distance itself.
    EXPECT_NEAR(at(channel(image, "depth"), 15, 7, 7), r, 1e-4 * r);
  }
}

TEST(Aov, TheSkyHasInfiniteDistanceNoObjectAndItsOwnDoppler) {
  Scene s;
  s.camera.world_line.velocity = {0, 0, -0.6};
  s.camera.width = s.camera.height = 3;
  s.camera.fov_degrees = 1;
  RenderOptions options;
  options.aovs = {Aov::kDoppler, Aov::kDistance, Aov::kEmissionTime, Aov::kObject};
  const Image image = render_image(s, options);
  EXPECT_NEAR(at(channel(image, "doppler"), 3, 1, 1), 2.0, 1e-5);  // toward a sky at rest
  EXPECT_EQ(at(channel(image, "distance"), 3, 1, 1), std::numeric_limits<float>::infinity());
  EXPECT_EQ(at(channel(image, "emission_time"), 3, 1, 1), -std::numeric_limits<float>::infinity());
  EXPECT_EQ(at(channel(image, "object"), 3, 1, 1), -1.0f);
  for (const NamedChannel& c : image.channels)
    for (const float v : c.values) EXPECT_FALSE(std::isnan(v));
}

TEST(FalseColour, TheMapRisesEvenlyInLightnessAndTheBarIsLabelled) {
  // Luminance rises monotonically along the map; ends are dark blue and light yellow.
  double last = -1;
  for (int k = 0; k <= 100; ++k) {
    const LinearRgb c = colour_map(k / 100.0);
    const double y = xyz_from_linear_srgb(c).y;
    EXPECT_GT(y, last) << k;
    last = y;
  }
  EXPECT_GT(colour_map(0).b, colour_map(0).r);
  EXPECT_GT(colour_map(1).r, colour_map(1).b);
  // A 200 x 100 channel: values 0.5 to 0.99 on the left half, the sky (infinite) on the right,
  // and the bottom-left quarter the sky with a finite value (as D is for the sky).
  NamedChannel ramp{"doppler", {}};
  std::vector<float> sky;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 200; ++x) {
      ramp.values.push_back(x < 100 ? 0.5f + x * 0.0049f : INFINITY);
      sky.push_back(x >= 100 || y >= 50 ? 1.0f : 0.0f);
    }
  const Image image = false_colour(ramp, 200, 100, "Doppler factor D", sky);
  // The render's size: the legend is a band along the bottom.
  EXPECT_EQ(image.width, 200);
  EXPECT_EQ(image.height, 100);
  const auto at = [&](int x, int y) {
    return &image.rgb[3 * (static_cast<std::size_t>(y) * 200 + x)];
  };
  // The smallest value is the map's start; the non-finite ones grey.
  const LinearRgb start = colour_map(0);
  EXPECT_NEAR(at(0, 0)[0], start.r, 1e-6);
  EXPECT_NEAR(at(199, 0)[0], at(199, 0)[2], 1e-6);
  // The sky is hatched where its value is finite: along a row, stripes darker than the map.
  int dark = 0, plain = 0;
  for (int x = 0; x < 16; ++x) {
    const float v = at(x, 52)[1],
                want = static_cast<float>(
                    colour_map((0.5 + x * 0.0049 - 0.5) / (0.5 + 99 * 0.0049 - 0.5)).g);
    (std::abs(v - want) < 1e-5f ? plain : dark) += 1;
  }
  EXPECT_EQ(dark, 6);  // 3 of every 8 pixels
  EXPECT_EQ(plain, 10);
  // The legend: white label pixels left of the bar, the bar and its numbers, in the bottom band
  // only.
  int label = 0, above = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 200; ++x) {
      const float* c = at(x, y);
      const bool white = c[0] == 1 && c[1] == 1 && c[2] == 1;
      (y >= 100 - kLegendHeight ? label : above) += white;
    }
  EXPECT_GT(label, 50);
  EXPECT_EQ(above, 0);
}

}  // namespace
}  // namespace lightcone

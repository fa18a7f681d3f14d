// Motion blur over a shutter: each pixel's samples are seen from observation events spread over
// the camera's proper time from camera.proper_time to camera.proper_time + shutter.
#include <gtest/gtest.h>

#include <cmath>

#include "lightcone/frame/locate.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

using test::make_object;
using test::solid;

// The first and last columns of the pixels of row `y` brighter than `threshold` (-1, -1 if
// none).
std::pair<int, int> bright_span(const Image& image, int y, float threshold = 0.3f) {
  int first = -1, last = -1;
  for (int x = 0; x < image.width; ++x) {
    const float* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
    if (p[0] + p[1] + p[2] > threshold) {
      if (first < 0) first = x;
      last = x;
    }
  }
  return {first, last};
}

TEST(MotionBlur, AStreakEndsWhereTheBodyIsSeenAtTheShuttersEnds) {
  // A ball crossing at 0.9c, 10 away, seen by a camera at rest over a shutter of 1.5.
  Scene s;
  s.camera.world_line = {0, {}, {}};
  s.camera.width = 240;
  s.camera.height = 40;
  s.camera.fov_degrees = 8;
  s.camera.samples = 64;
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kOff;
  s.objects.push_back(
      make_object("ball", Sphere{0.2}, {-1.4, 0, -10}, {0.9, 0, 0}, solid({1, 1, 1})));
  s.objects[0].world_line.time = -10;
  const double shutter = 1.5;
  Scene blurred = s;
  blurred.camera.shutter = shutter;
  const Image streak = render_image(blurred, {});
  const int row = s.camera.height / 2;
  // Any pixel the ball covered in one of the 64 observations (each adds 3/64 to a white one).
  const auto [first, last] = bright_span(streak, row, 0.02f);
  ASSERT_GE(first, 0);
  // The ball as seen at the shutter's opening and at its close: the streak's ends.
  Scene opening = s, closing = s;
  closing.camera.world_line.time = shutter;  // at rest: proper time is world time
  const auto [open_first, open_last] = bright_span(render_image(opening, {}), row);
  const auto [close_first, close_last] = bright_span(render_image(closing, {}), row);
  EXPECT_NEAR(first, open_first, 1) << "streak from " << first << " to " << last;
  EXPECT_NEAR(last, close_last, 1);
  EXPECT_GT(last - first, (open_last - open_first) + 40);  // a streak, not a ball
  // And those are where locate puts the ball's centre then.
  const LocateQuery centre{LocateQuery::Kind::ObjectPoint, "ball", {}};
  EXPECT_NEAR(locate(opening, centre).pixel_x, 0.5 * (open_first + open_last + 1), 1);
  EXPECT_NEAR(locate(closing, centre).pixel_x, 0.5 * (close_first + close_last + 1), 1);
}

TEST(MotionBlur, ABodyAtRestRelativeToTheCameraIsUnchangedByTheShutter) {
  for (const Vec3 velocity : {Vec3{}, Vec3{0.3, 0, -0.6}}) {
    Scene s;
    s.camera.world_line = {0, {0, 0, 0}, velocity};
    s.camera.width = 64;
    s.camera.height = 48;
    s.camera.samples = 8;
    Material checker;
    checker.pattern = Checker{0.3, {{1, 0.6, 0.2}, {0.2, 0.3, 0.9}}};
    s.objects.push_back(make_object("box", Box{{2, 1.5, 1}}, {0.3, 0.2, -5}, velocity, checker));
    Scene blurred = s;
    blurred.camera.shutter = 3;
    const Image still = render_image(s, {}), shuttered = render_image(blurred, {});
    ASSERT_EQ(still.rgb.size(), shuttered.rgb.size());
    double largest = 0;
    for (std::size_t i = 0; i < still.rgb.size(); ++i)
      largest = std::max(largest, double(std::abs(still.rgb[i] - shuttered.rgb[i])));
    EXPECT_LT(largest, 1e-5) << velocity.x;
    // The test can fail: a body moving relative to the camera is blurred.
    Scene moving = blurred;
    moving.objects[0].world_line.velocity = velocity + Vec3{0.2, 0, 0};
    Scene moving_still = moving;
    moving_still.camera.shutter = 0;
    EXPECT_GT(test::fraction_differing(render_image(moving, {}), render_image(moving_still, {})),
              0.02);
  }
}

}  // namespace
}  // namespace lightcone

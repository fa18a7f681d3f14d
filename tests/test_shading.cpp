// What a ray sees where it ends: the checker contract, texture and sky-image lookups.
#include <gtest/gtest.h>

#include <cmath>

#include "lightcone/frame/shading.hpp"

namespace lightcone {
namespace {

// A w x h image whose texel (i, j) has red = i, green = j.
std::shared_ptr<Image> coordinate_image(int w, int h) {
  auto image = std::make_shared<Image>();
  image->width = w;
  image->height = h;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) image->rgb.insert(image->rgb.end(), {float(i), float(j), 0.f});
  return image;
}

TEST(Checker, IndexIsFloorSumModTwoInShapeCoordinates) {
  const Checker checker{0.5, {{1, 0, 0}, {0, 0, 1}}};
  auto colour_at = [&](Vec3 p) { return checker.colors[checker_index(checker, p)].r; };
  EXPECT_EQ(colour_at({0.1, 0.1, 0.1}), 1.0f);     // 0+0+0 even
  EXPECT_EQ(colour_at({0.6, 0.1, 0.1}), 0.0f);     // 1+0+0 odd
  EXPECT_EQ(colour_at({-0.1, 0.1, 0.1}), 0.0f);    // -1 is odd, the index is non-negative
  EXPECT_EQ(colour_at({-0.1, -0.1, 0.1}), 1.0f);   // -2 even
  EXPECT_EQ(colour_at({-0.6, -0.1, -0.1}), 1.0f);  // floor(-1.2) = -2: -2 - 1 - 1 = -4, even
  // Far beyond any integer type's range (once an overflowing cast): a valid index all the same.
  for (const Vec3 far : {Vec3{1e300, 0.1, 0.1}, Vec3{-1e19, 3e18, 0.1}, Vec3{1e19 + 0.7, 0, 0}}) {
    const int i = checker_index(checker, far);
    EXPECT_TRUE(i == 0 || i == 1) << far.x;
  }
  EXPECT_EQ(checker_index(checker, {3.0 * 0.5 + 0.1, 0.1, 0.1}), 1);  // 3: odd
}

TEST(Texture, BilinearHitsTexelCentresExactlyAndWrapsInU) {
  const auto image = coordinate_image(4, 2);
  const Rgb centre = sample_bilinear(*image, (2 + 0.5) / 4, (1 + 0.5) / 2, true);
  EXPECT_FLOAT_EQ(centre.r, 2);
  EXPECT_FLOAT_EQ(centre.g, 1);
  // Halfway between the last and the first column (u wraps).
  const Rgb seam = sample_bilinear(*image, 0.0, 0.25, true);
  EXPECT_FLOAT_EQ(seam.r, 1.5f);  // (3 + 0) / 2
}

TEST(SkyImage, EquirectangularMappingFollowsTheContract) {
  // u = 0.5 + atan2(d.x, -d.z)/(2 pi), v = acos(d.y)/pi, from the top-left.
  const SkyImage sky{coordinate_image(360, 180)};
  auto texel = [&](Vec3 d) {
    const Rgb c = sky_image_colour(sky, normalize(d));
    return std::array<double, 2>{c.r, c.g};
  };
  // Straight ahead (-z): u = 0.5, v = 0.5 -> between texels 179/180 and 89/90.
  EXPECT_NEAR(texel({0, 0, -1})[0], 179.5, 1e-3);
  EXPECT_NEAR(texel({0, 0, -1})[1], 89.5, 1e-3);
  // +x: u = 0.75 -> 269.5; a little above the horizon: v < 0.5.
  EXPECT_NEAR(texel({1, 0, 0})[0], 269.5, 1e-3);
  EXPECT_LT(texel({1, 0.2, 0})[1], 89.5);
  // -x: u = 0.25.
  EXPECT_NEAR(texel({-1, 0, 0})[0], 89.5, 1e-3);
}

TEST(SkyGrid, LinesAtMultiplesOfTheSpacing) {
  SkyGrid grid;
  grid.spacing_degrees = 15;
  grid.line_width_degrees = 1;
  auto at = [&](double longitude_deg, double latitude_deg) {
    const double lo = longitude_deg * M_PI / 180, la = latitude_deg * M_PI / 180;
    // longitude measured from -z toward +x
    return on_grid_line(grid,
                        {std::sin(lo) * std::cos(la), std::sin(la), -std::cos(lo) * std::cos(la)});
  };
  EXPECT_FALSE(at(7.5, 7.5));  // between lines
  EXPECT_TRUE(at(15.2, 7.5));  // on a meridian
  EXPECT_TRUE(at(7.5, 30.3));  // on a parallel
  EXPECT_TRUE(at(-44.8, 7.5));
}

}  // namespace
}  // namespace lightcone

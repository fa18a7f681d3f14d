// The seeds' colour models: rgb3 (three lines) and hue (seed 003's shader, transcribed here).
#include <gtest/gtest.h>

#include <cmath>

#include "lightcone/color/colour_models.hpp"

namespace lightcone {
namespace {

// ---- A transcription of seed 003's shader (RGBtoHSV, HSVtoRGB and the shift), with its
// quirks (delta = 0.001 for greys), and the shift 512 log2(D) in place of 512 v/c.
void seed_rgb_to_hsv(float r, float g, float b, float* h, float* s, float* v) {
  const float mini = std::min({r, g, b}), maxi = std::max({r, g, b});
  *v = maxi;
  float delta = maxi - mini;
  if (delta == 0) delta = 0.001f;
  if (maxi != 0) {
    *s = delta / maxi;
  } else {
    *s = 0;
    *h = -1;
    return;
  }
  if (r == maxi)
    *h = (g - b) / delta;
  else if (g == maxi)
    *h = 2 + (b - r) / delta;
  else
    *h = 4 + (r - g) / delta;
  *h *= 60;
  if (*h < 0) *h += 360;
}

void seed_hsv_to_rgb(float* r, float* g, float* b, float h, float s, float v) {
  if (s == 0) {
    *r = *g = *b = v;
    return;
  }
  h /= 60;
  const int i = static_cast<int>(std::floor(h));
  const float f = h - i, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (i) {
    case 0:
      *r = v;
      *g = t;
      *b = p;
      break;
    case 1:
      *r = q;
      *g = v;
      *b = p;
      break;
    case 2:
      *r = p;
      *g = v;
      *b = t;
      break;
    case 3:
      *r = p;
      *g = q;
      *b = v;
      break;
    case 4:
      *r = t;
      *g = p;
      *b = v;
      break;
    default:
      *r = v;
      *g = p;
      *b = q;
      break;
  }
}

LinearRgb seed_shader(LinearRgb in, double d, bool loop_hue) {
  float R = static_cast<float>(in.r), G = static_cast<float>(in.g), B = static_cast<float>(in.b);
  float H, S, V;
  seed_rgb_to_hsv(R, G, B, &H, &S, &V);
  H += static_cast<float>(512 * std::log2(d));
  if (loop_hue) {
    while (H >= 360) H -= 360;
    while (H < 0) H += 360;
  } else {
    if (H > 300) {
      if (H > 360) H = 360;
      V *= 1 - ((H - 300) / 60);
      H = 300;
    }
    if (H < 0) {
      if (H < -60) H = -60;
      V *= (H + 60) / 60;
      H = 0;
    }
  }
  seed_hsv_to_rgb(&R, &G, &B, H, S, V);
  return {R, G, B};
}

TEST(HueModel, MatchesSeed003ShaderOnATableOfInputs) {
  const LinearRgb colours[] = {{1, 0, 0},       {0, 1, 0},       {0, 0, 1},       {0.8, 0.4, 0.1},
                               {0.2, 0.7, 0.9}, {0.5, 0.1, 0.6}, {0.9, 0.9, 0.2}, {0.3, 0.3, 0.8}};
  const double factors[] = {0.25, 0.5, 0.8, 0.95, 1.0, 1.1, 1.3, 2.0, 4.36};
  for (bool loop : {false, true})
    for (const LinearRgb& c : colours)
      for (double d : factors) {
        const LinearRgb ours = hue_shift(c, d, loop), seed = seed_shader(c, d, loop);
        EXPECT_NEAR(ours.r, seed.r, 2e-5) << c.r << "," << c.g << "," << c.b << " D=" << d;
        EXPECT_NEAR(ours.g, seed.g, 2e-5) << c.r << "," << c.g << "," << c.b << " D=" << d;
        EXPECT_NEAR(ours.b, seed.b, 2e-5) << c.r << "," << c.g << "," << c.b << " D=" << d;
      }
}

TEST(HueModel, ShiftsByFiveHundredTwelveDegreesPerDoubling) {
  // Red (H = 0) seen with D = 2^(120/512) lands on green (H = 120).
  const LinearRgb green = hue_shift({1, 0, 0}, std::exp2(120.0 / 512), false);
  EXPECT_NEAR(green.r, 0, 1e-12);
  EXPECT_NEAR(green.g, 1, 1e-12);
  // Blue (240) pushed to 330 is half faded at H = 300; with loop it is magenta-red at 330.
  const double d = std::exp2(90.0 / 512);
  const LinearRgb faded = hue_shift({0, 0, 1}, d, false);
  EXPECT_NEAR(std::max({faded.r, faded.g, faded.b}), 0.5, 1e-12);
  const LinearRgb looped = hue_shift({0, 0, 1}, d, true);
  EXPECT_NEAR(std::max({looped.r, looped.g, looped.b}), 1.0, 1e-12);
  EXPECT_NEAR(hsv_from_rgb(looped).h, 330, 1e-9);
}

TEST(HueModel, NoShiftKeepsEveryVisibleHue) {
  for (const LinearRgb c : {LinearRgb{0.8, 0.4, 0.1}, LinearRgb{0.1, 0.2, 0.9}}) {
    const LinearRgb same = hue_shift(c, 1.0, false);
    EXPECT_NEAR(same.r, c.r, 1e-12);
    EXPECT_NEAR(same.g, c.g, 1e-12);
    EXPECT_NEAR(same.b, c.b, 1e-12);
  }
}

TEST(Rgb3Model, ReproducesTheInputAtRest) {
  for (const LinearRgb c :
       {LinearRgb{1, 1, 1}, LinearRgb{0.8, 0.2, 0.1}, LinearRgb{0.05, 0.6, 0.9}}) {
    const LinearRgb same = rgb3_shift(c, 1.0, 1.0);
    EXPECT_NEAR(same.r, c.r, 1e-9);
    EXPECT_NEAR(same.g, c.g, 1e-9);
    EXPECT_NEAR(same.b, c.b, 1e-9);
  }
}

TEST(Rgb3Model, EachLineVanishesAsItLeavesTheVisibleRange) {
  const LinearRgb c{0.7, 0.5, 0.3};
  const LinearRgb p = rgb3_line_powers(c);
  auto colour_of_lines = [&](double d, bool red, bool green, bool blue) {
    Xyz sum;
    const double powers[3] = {red ? p.r : 0, green ? p.g : 0, blue ? p.b : 0};
    for (int i = 0; i < 3; ++i) {
      const Xyz m = cie_cmf(kRgb3Wavelengths[i] / d);
      sum.x += powers[i] * m.x / cie_y_integral();
      sum.y += powers[i] * m.y / cie_y_integral();
      sum.z += powers[i] * m.z / cie_y_integral();
    }
    return linear_srgb_from_xyz(sum);
  };
  // D = 0.74: red at 846 nm is gone, green 722 and blue 628 remain.
  const LinearRgb shifted = rgb3_shift(c, 0.74, 1.0),
                  expected = colour_of_lines(0.74, false, true, true);
  EXPECT_NEAR(shifted.r, expected.r, 1e-12);
  EXPECT_NEAR(shifted.g, expected.g, 1e-12);
  // D = 1.4: blue at 332 nm is gone.
  const LinearRgb blue_shifted = rgb3_shift(c, 1.4, 1.0);
  const LinearRgb expected_blue = colour_of_lines(1.4, true, true, false);
  EXPECT_NEAR(blue_shifted.b, expected_blue.b, 1e-12);
  // D = 0.3: all three are infrared: black.
  const LinearRgb none = rgb3_shift(c, 0.3, 1.0);
  EXPECT_EQ(none.r, 0);
  EXPECT_EQ(none.g, 0);
  EXPECT_EQ(none.b, 0);
  // The searchlight power factor scales everything.
  const LinearRgb bright = rgb3_shift(c, 1.2, 1.2 * 1.2 * 1.2 * 1.2);
  const LinearRgb plain = rgb3_shift(c, 1.2, 1.0);
  EXPECT_NEAR(bright.g, plain.g * std::pow(1.2, 4), 1e-12);
}

}  // namespace
}  // namespace lightcone

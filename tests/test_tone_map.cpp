// The tone curves: the filmic curve on luminance keeps each colour's hue and saturation, and the
// display pass's GLSL mirror gives the PNG's values.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "lightcone/frame/tone_map.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "support/glsl_eval.hpp"

namespace lightcone {
namespace {

std::array<float, 3> filmic(std::array<float, 3> c) {
  filmic_on_luminance(c.data());
  return c;
}

double luminance(const std::array<float, 3>& c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

// The hue angle of a colour (the hexcone's), from its chroma plane.
double hue(const std::array<float, 3>& c) {
  return std::atan2(std::sqrt(3.0) * (c[1] - c[2]), 2.0 * c[0] - c[1] - c[2]);
}

TEST(ToneMap, FilmicIsNarkowiczsFitOnLuminance) {
  for (const double y : {0.0, 0.01, 0.18, 0.5, 1.0, 3.0}) {
    const double fit = y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14);
    EXPECT_NEAR(filmic_curve(y), std::min(1.0, fit), 1e-12) << y;
    // A grey is the curve itself on each channel.
    const auto grey = filmic({float(y), float(y), float(y)});
    for (const float v : grey) EXPECT_NEAR(v, std::min(1.0, fit), 1e-6) << y;
  }
  EXPECT_EQ(filmic_curve(1e30), 1.0);
}

TEST(ToneMap, FilmicKeepsHueAndSaturationAndNeverExceedsOne) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0, 1);
  for (int i = 0; i < 10000; ++i) {
    const float exposure = std::exp2(16 * u(rng) - 8);
    const std::array<float, 3> c{exposure * u(rng), exposure * u(rng), exposure * u(rng)};
    const auto shown = filmic(c);
    for (const float v : shown) {
      EXPECT_GE(v, 0.0f);
      EXPECT_LE(v, 1.0f);
    }
    const double chroma = std::max({c[0], c[1], c[2]}) - std::min({c[0], c[1], c[2]});
    const double shown_chroma =
        std::max({shown[0], shown[1], shown[2]}) - std::min({shown[0], shown[1], shown[2]});
    if (chroma > 1e-3 * std::max({c[0], c[1], c[2]}) && shown_chroma > 1e-4) {
      const double turn = std::remainder(hue(shown) - hue(c), 2 * M_PI);
      EXPECT_NEAR(turn, 0.0, 2e-3) << c[0] << " " << c[1] << " " << c[2];
    }
    // The luminance shown is the curve's where that keeps the largest channel at or below the
    // curve of that channel; otherwise the largest channel is the curve of itself.
    const float top = std::max({c[0], c[1], c[2]}),
                shown_top = std::max({shown[0], shown[1], shown[2]});
    if (shown_top < filmic_curve(top) - 1e-6)
      EXPECT_NEAR(luminance(shown), filmic_curve(luminance(c)), 1e-5);
    else
      EXPECT_NEAR(shown_top, filmic_curve(top), 1e-5);
    // Saturation (chroma over the largest channel) is kept.
    if (shown_top > 1e-3 && top > 1e-3 && shown_top < 1.0f)
      EXPECT_NEAR(shown_chroma / shown_top, chroma / top, 1e-4);
  }
  // Per channel the curve would have turned a bright red toward orange (its green raised the
  // most); here the channels keep their ratios, and only a colour past where a grey would
  // clip reaches 1.
  const auto red = filmic({3.0f, 0.4f, 0.1f});
  EXPECT_LT(red[0], 1.0f);
  EXPECT_NEAR(red[1] / red[0], 0.4 / 3.0, 1e-6);
  EXPECT_NEAR(red[2] / red[0], 0.1 / 3.0, 1e-6);
  EXPECT_EQ(filmic({20.0f, 0.4f, 0.1f})[0], 1.0f);
  // Nothing is made of nothing, and no NaN passes.
  EXPECT_EQ(filmic({0, 0, 0}), (std::array<float, 3>{0, 0, 0}));
  const auto nan = filmic({NAN, 0.5f, 0.5f});
  for (const float v : nan) EXPECT_FALSE(std::isnan(v));
}

// display.frag's tone curves (tone_map.glsl) give what frame/tone_map.cpp gives.
TEST(ToneMap, TheDisplayPassMirrorsTheCurves) {
  const HeadlessGlContext context;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<std::array<float, 9>> inputs;
  for (int i = 0; i < 3000; ++i) {
    const float exposure = std::exp2(12 * u(rng) - 6);
    inputs.push_back({exposure * u(rng), exposure * u(rng), exposure * u(rng),
                      static_cast<float>(i % 3), 0, 0, 0, 0, 0});
  }
  const auto out =
      evaluate_glsl("vec4(tone_map(a, int(b.x)), 0.0)", inputs, shader_sources::tone_map_glsl);
  const ToneMap curves[] = {ToneMap::kClamp, ToneMap::kReinhard, ToneMap::kFilmic};
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    Image pixel;
    pixel.width = pixel.height = 1;
    pixel.rgb = {inputs[i][0], inputs[i][1], inputs[i][2]};
    const Image want = tone_map(pixel, curves[i % 3]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(out[i][k], want.rgb[k], 2e-5) << i;
  }
}

}  // namespace
}  // namespace lightcone

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
    if (shown_top > 1e-3 && top > 1e-3 && shown_top < 1.0f) {
      EXPECT_NEAR(shown_chroma / shown_top, chroma / top, 1e-4);
    }
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

Image uniform_image(int width, int height, float value) {
  Image image;
  image.width = width, image.height = height;
  image.rgb.assign(3 * static_cast<std::size_t>(width) * height, value);
  return image;
}

// The automatic exposure shows the subject's upper quartile at 0.5, unless the brightest 2 %
// of the picture would then pass the luminance the curve shows as 0.9.
TEST(AutomaticExposure, ShowsTheSubjectUnlessTheHighlightsWouldClip) {
  EXPECT_NEAR(filmic_curve(display_white(ToneMap::kFilmic)), 0.9, 1e-12);
  EXPECT_EQ(display_white(ToneMap::kClamp), 0.9);
  EXPECT_NEAR(display_white(ToneMap::kReinhard) / (1 + display_white(ToneMap::kReinhard)), 0.9,
              1e-12);
  // A uniform grey 0.2 is its own subject: brought to 0.5.
  for (const ToneMap curve : {ToneMap::kClamp, ToneMap::kFilmic})
    EXPECT_NEAR(auto_exposure(uniform_image(8, 8, 0.2f), curve), std::log2(0.5 / 0.2), 1e-6);
  // A dim moving body (0.01) before a wall at rest (0.02, 0.03 in its top 3 %): the body sets
  // the exposure unless the wall's highlights would pass the curve's 0.9 (under clamp they
  // would).
  Image scene = uniform_image(100, 100, 0.02f);
  std::vector<float> subject(100 * 100, 0.0f);
  for (std::size_t p = 0; p < 100 * 100; ++p) {
    if (p < 2500) scene.rgb[3 * p] = scene.rgb[3 * p + 1] = scene.rgb[3 * p + 2] = 0.01f;
    if (p < 2500) subject[p] = 1;
    if (p >= 9700) scene.rgb[3 * p] = scene.rgb[3 * p + 1] = scene.rgb[3 * p + 2] = 0.03f;
  }
  EXPECT_NEAR(auto_exposure(scene, ToneMap::kFilmic, subject), std::log2(0.5 / 0.01), 1e-6);
  EXPECT_NEAR(auto_exposure(scene, ToneMap::kClamp, subject), std::log2(0.9 / 0.03), 1e-6);
  // Without the subject, the wall is the picture.
  EXPECT_NEAR(auto_exposure(scene, ToneMap::kFilmic), std::log2(0.5 / 0.02), 1e-6);
  // A subject pixel weighs the share of its samples that met the body: a quarter body counts a
  // quarter. Less than 0.1 % of the picture's worth does not set the exposure.
  std::vector<float> speck(100 * 100, 0.0f);
  for (std::size_t p = 0; p < 36; ++p) speck[p] = 0.25f;
  EXPECT_NEAR(auto_exposure(scene, ToneMap::kFilmic, speck), std::log2(0.5 / 0.02), 1e-6);
  // A picture without light is left as it is; no NaN or infinity.
  EXPECT_EQ(auto_exposure(uniform_image(4, 4, 0.0f), ToneMap::kFilmic), 0.0);
  Image odd = uniform_image(4, 4, 0.3f);
  odd.rgb[0] = NAN, odd.rgb[4] = INFINITY;
  EXPECT_TRUE(std::isfinite(auto_exposure(odd, ToneMap::kFilmic)));
  // A black subject before a lit wall: the wall's highlights set it.
  Image dark = uniform_image(10, 10, 0.3f);
  std::vector<float> black_subject(100, 0.0f);
  for (std::size_t p = 0; p < 50; ++p) {
    black_subject[p] = 1;
    dark.rgb[3 * p] = dark.rgb[3 * p + 1] = dark.rgb[3 * p + 2] = 0;
  }
  EXPECT_NEAR(auto_exposure(dark, ToneMap::kClamp, black_subject), std::log2(0.9 / 0.3), 1e-6);
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

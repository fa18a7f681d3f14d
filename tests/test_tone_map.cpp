// The tone curves: the filmic curve on luminance keeps each colour's hue and saturation, and the
// display pass's GLSL mirror gives the PNG's values.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "lightcone/frame/exposure_meter.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "support/glsl_eval.hpp"
#include "support/test_support.hpp"

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

// The meter reads a quantile as the geometric middle of its bin of 1/256 of an octave: within
// half a bin of the pixel's own luminance (computed in single precision: 1e-6 more).
const double kMetered = 0.5 * std::log2(1 + 1.0 / 256);

// The automatic exposure shows the subject's upper quartile at 0.5, unless the brightest 2 %
// of the picture would then pass the luminance the curve shows as 0.9.
// The program exposes a picture only shown in its tone map's pass: the same display values, and
// the same count of values not finite, as exposing it first.
TEST(ToneMap, ExposingInTheToneMapsPassIsExposingFirst) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> octaves(-30.0f, 30.0f);
  Image picture;
  picture.width = 97;  // not a multiple of any piece's size
  picture.height = 61;
  for (int v = 0; v < picture.width * picture.height * 3; ++v)
    picture.rgb.push_back(std::exp2(octaves(random)));
  picture.rgb[5] = std::numeric_limits<float>::quiet_NaN();
  picture.rgb[40] = std::numeric_limits<float>::infinity();
  picture.rgb[41] = -1.0f;
  picture.rgb[300] = 3e38f;  // finite, but not once exposed at +2 EV
  for (const ToneMap curve : {ToneMap::kClamp, ToneMap::kReinhard, ToneMap::kFilmic})
    for (const double ev : {0.0, -3.25, 2.0}) {
      Image exposed = picture;
      const std::size_t expected_non_finite = expose(exposed, ev);
      const Image expected = tone_map(exposed, curve);
      std::size_t non_finite = 0;
      const Image fused = expose_and_tone_map(Image(picture), ev, curve, non_finite);
      EXPECT_EQ(non_finite, expected_non_finite) << ev;
      EXPECT_EQ(non_finite, ev == 2.0 ? 3u : 2u) << ev;
      ASSERT_EQ(fused.rgb.size(), expected.rgb.size());
      EXPECT_EQ(std::memcmp(fused.rgb.data(), expected.rgb.data(), 4 * fused.rgb.size()), 0)
          << static_cast<int>(curve) << " at EV " << ev;
    }
}

TEST(AutomaticExposure, ShowsTheSubjectUnlessTheHighlightsWouldClip) {
  EXPECT_NEAR(filmic_curve(display_white(ToneMap::kFilmic)), 0.9, 1e-12);
  EXPECT_EQ(display_white(ToneMap::kClamp), 0.9);
  EXPECT_NEAR(display_white(ToneMap::kReinhard) / (1 + display_white(ToneMap::kReinhard)), 0.9,
              1e-12);
  // A uniform grey 0.2 is its own subject: brought to 0.5.
  for (const ToneMap curve : {ToneMap::kClamp, ToneMap::kFilmic})
    EXPECT_NEAR(auto_exposure(uniform_image(8, 8, 0.2f), curve), std::log2(0.5 / 0.2),
                kMetered + 1e-6);
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
  EXPECT_NEAR(auto_exposure(scene, ToneMap::kFilmic, subject), std::log2(0.5 / 0.01),
              kMetered + 1e-6);
  EXPECT_NEAR(auto_exposure(scene, ToneMap::kClamp, subject), std::log2(0.9 / 0.03),
              kMetered + 1e-6);
  // Without the subject, the wall is the picture.
  EXPECT_NEAR(auto_exposure(scene, ToneMap::kFilmic), std::log2(0.5 / 0.02), kMetered + 1e-6);
  // A subject pixel weighs the share of its samples that met the body: a quarter body counts a
  // quarter. Less than 0.1 % of the picture's worth does not set the exposure.
  std::vector<float> speck(100 * 100, 0.0f);
  for (std::size_t p = 0; p < 36; ++p) speck[p] = 0.25f;
  EXPECT_NEAR(auto_exposure(scene, ToneMap::kFilmic, speck), std::log2(0.5 / 0.02),
              kMetered + 1e-6);
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
  EXPECT_NEAR(auto_exposure(dark, ToneMap::kClamp, black_subject), std::log2(0.9 / 0.3),
              kMetered + 1e-6);
}

// The rule as its description reads, by sorting every pixel: the independent derivation that
// auto_exposure's selections are checked against.
double exposure_by_sorting(const Image& linear, ToneMap curve, std::span<const float> subject) {
  const std::size_t n = linear.rgb.size() / 3;
  if (n == 0) return 0;
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) {
    const float* c = &linear.rgb[3 * i];
    const double v = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    y[i] = std::isfinite(v) ? std::max(0.0, v) : 0.0;
  }
  std::vector<double> ascending = y;
  std::sort(ascending.begin(), ascending.end());
  const double highlights = ascending[static_cast<std::size_t>(0.98 * static_cast<double>(n - 1))];
  if (!(highlights > 0)) return 0;
  std::vector<std::pair<double, double>> weighted;
  double total = 0;
  if (subject.size() == n)
    for (std::size_t i = 0; i < n; ++i)
      if (subject[i] > 0) {
        weighted.emplace_back(y[i], subject[i]);
        total += subject[i];
      }
  if (total < 1e-3 * static_cast<double>(n)) {
    weighted.clear();
    for (const double v : y) weighted.emplace_back(v, 1.0);
    total = static_cast<double>(n);
  }
  std::sort(weighted.begin(), weighted.end());
  double below = 0, level = weighted.back().first;
  for (const auto& [value, w] : weighted)
    if ((below += w) >= 0.75 * total) {
      level = value;
      break;
    }
  return std::min(level > 0 ? std::log2(0.5 / level) : INFINITY,
                  std::log2(display_white(curve) / highlights));
}

// Each luminance a float holds falls in the bin whose middle is within half a bin of it (give
// or take the luminance's own rounding to a float); the bins order as the luminances do; black,
// negative, NaN and infinite pixels are in bin 0, worth 0.
TEST(ExposureMeter, BinsByLogLuminance) {
  std::mt19937 random(256);
  std::uniform_real_distribution<double> octave(-125, 127);
  std::vector<float> greys(100000);
  for (float& y : greys) y = static_cast<float>(std::exp2(octave(random)));
  std::sort(greys.begin(), greys.end());
  std::size_t last_bin = 0;
  for (const float y : greys) {
    const float grey[3] = {y, y, y};
    const std::size_t bin = ExposureMeter::bin_of(grey);
    ASSERT_GE(bin, std::max<std::size_t>(last_bin, 1)) << y;
    ASSERT_LT(bin, ExposureMeter::kBins);
    EXPECT_LE(std::abs(std::log2(ExposureMeter::value_of(bin) / y)), kMetered + 1e-6) << y;
    last_bin = bin;
  }
  for (const float odd : {0.0f, -0.0f, -1.0f, NAN, INFINITY, -INFINITY}) {
    const float pixel[3] = {odd, odd, odd};
    EXPECT_EQ(ExposureMeter::bin_of(pixel), 0u) << odd;
  }
  const float largest[3] = {3e38f, 3e38f, 3e38f};
  EXPECT_TRUE(std::isfinite(ExposureMeter::value_of(ExposureMeter::bin_of(largest))));
  EXPECT_EQ(ExposureMeter::value_of(0), 0.0);
}

// Four pixels' bins found at once are each pixel's own, whatever its luminance (every octave a
// float holds, black, negative, NaN, infinite) and wherever among the four it lies.
TEST(ExposureMeter, FindsFourBinsAtOnceAsOneByOne) {
  std::mt19937 random(4);
  std::uniform_real_distribution<double> octave(-149, 128), unit(0, 1);
  const float odd[] = {0.0f, -0.0f, -1.0f, NAN, -NAN, INFINITY, -INFINITY, 1e-45f, 3.4e38f};
  std::vector<float> rgb(3 * 4 * 20000);
  for (float& v : rgb) {
    const double pick = unit(random);
    v = pick < 0.05 ? odd[static_cast<std::size_t>(unit(random) * std::size(odd))]
                    : static_cast<float>((pick < 0.1 ? -1 : 1) * std::exp2(octave(random)));
  }
  for (std::size_t p = 0; p < rgb.size() / 3; p += 4) {
    const auto four = ExposureMeter::bins_of_four(&rgb[3 * p]);
    for (std::size_t k = 0; k < 4; ++k)
      ASSERT_EQ(four[k], ExposureMeter::bin_of(&rgb[3 * (p + k)])) << p + k;
  }
}

// A meter's EV does not depend on how its pixels were shared among meters (threads): its sums
// are integers.
TEST(ExposureMeter, IsTheSameHoweverThePixelsAreShared) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> unit(0, 1);
  std::vector<float> rgb(3 * 5000), share(5000);
  for (float& v : rgb) v = std::exp2(20 * unit(random) - 10);
  for (float& s : share) s = unit(random) < 0.3f ? unit(random) : 0.0f;
  ExposureMeter whole, first, second;
  whole.add(rgb.data(), share.size(), share.data());
  for (std::size_t p = 0; p < share.size(); ++p)
    (p % 3 ? first : second).add(&rgb[3 * p], 1, &share[p]);
  first.add(second);
  EXPECT_EQ(first.pixels(), 5000u);
  EXPECT_EQ(first.ev(ToneMap::kFilmic), whole.ev(ToneMap::kFilmic));
}

// auto_exposure reads (from its meter's histograms) what sorting finds: the same EV within half
// a bin, on pictures that stress the selection, with subjects of every size.
TEST(AutomaticExposure, ReadsWhatSortingFinds) {
  std::mt19937 random(54);
  std::uniform_real_distribution<double> unit(0, 1);
  const int width = 480, height = 270;  // two of the parallel passes' pieces
  const std::size_t n = static_cast<std::size_t>(width) * height;
  const auto grey = [](Image& image, std::size_t p, double v) {
    for (int k = 0; k < 3; ++k) image.rgb[3 * p + k] = static_cast<float>(v);
  };
  std::vector<std::pair<const char*, Image>> pictures;
  pictures.emplace_back("uniform", uniform_image(width, height, 0.2f));
  pictures.emplace_back("black", uniform_image(width, height, 0.0f));
  Image bimodal = uniform_image(width, height, 0.01f);
  for (std::size_t p = 0; p < n; ++p)
    if (unit(random) < 0.5) grey(bimodal, p, 1.0);
  pictures.emplace_back("bimodal", bimodal);
  Image bright = uniform_image(width, height, 0.1f);
  grey(bright, n / 2, 1e4);
  pictures.emplace_back("one bright pixel", bright);
  Image wide = uniform_image(width, height, 0);  // 2^-60 to 2^60, in colour
  for (float& v : wide.rgb) v = static_cast<float>(std::exp2(120 * unit(random) - 60));
  pictures.emplace_back("huge dynamic range", wide);
  Image rendered = uniform_image(width, height, 0);  // a sky, bodies, black, NaN, infinity
  for (std::size_t p = 0; p < n; ++p) {
    const double u = unit(random);
    grey(rendered, p, u < 0.3 ? 0.2 + 0.01 * unit(random) : u < 0.4 ? 0 : std::exp2(8 * u - 7));
    rendered.rgb[3 * p] *= static_cast<float>(unit(random));
  }
  rendered.rgb[0] = NAN, rendered.rgb[4] = INFINITY, rendered.rgb[8] = -1;
  pictures.emplace_back("rendered", rendered);

  // Subjects: none, 0.05 % (too small: the whole picture), 50 % and 100 % of the pixels, whole
  // or shares of a pixel's samples.
  std::vector<std::pair<std::string, std::vector<float>>> subjects;
  subjects.emplace_back("none", std::vector<float>{});
  for (const double share : {0.0005, 0.5, 1.0}) {
    std::vector<float> whole(n, 0.0f), shares(n, 0.0f);
    for (std::size_t p = 0; p < static_cast<std::size_t>(share * n); ++p) {
      whole[p] = 1;
      shares[p] = static_cast<float>(std::ceil(16 * unit(random)) / 16);
    }
    std::shuffle(whole.begin(), whole.end(), random);
    std::shuffle(shares.begin(), shares.end(), random);
    const std::string name = std::to_string(100 * share) + " %";
    subjects.emplace_back(name + " whole", whole);
    subjects.emplace_back(name + " in shares", shares);
  }
  for (const auto& [picture, image] : pictures)
    for (const auto& [subject, weights] : subjects)
      for (const ToneMap curve : {ToneMap::kClamp, ToneMap::kReinhard, ToneMap::kFilmic}) {
        const double ev = auto_exposure(image, curve, weights),
                     sorted = exposure_by_sorting(image, curve, weights);
        EXPECT_TRUE(std::isfinite(ev));
        EXPECT_NEAR(ev, sorted, kMetered + 1e-6)
            << picture << ", subject " << subject << ", curve " << static_cast<int>(curve);
      }
}

// The program's automatic EV on each bundled scene (its other settings at their defaults, at
// 320x180 and 1 sample) is the one the sort-based rule gave, within half a meter's bin:
// recorded with it, before the meter replaced it (the issue asks for 0.01 EV). infall.json's and
// orbit.json's were recorded again, from the meter, when their subject changed (bodies near a
// black hole became the subject, as in flat space, and infall.json's first clock a lamp): the
// rule's input changed there, not the meter, which the other scenes and ReadsWhatSortingFinds
// hold to the sort.
using AutomaticExposureOfScenes = test::TempDirTest;
TEST_F(AutomaticExposureOfScenes, IsWhatTheSortBasedRuleGave) {
  const std::map<std::string, double> recorded = {
      {"black-hole.json", 0.04862244693480582},
      {"cubes.json", -3.343049023149224},
      {"doppler-swatches.json", -0.9989273626127232},
      {"headlight.json", 3.4100665361079137},
      {"infall.json", 0.10064386800686985},
      {"interceptor.json", 3.720117873536755},
      {"lensed-clock.json", 1.2863973746154793},
      {"orbit.json", -1.3901673540619475},
      {"plunge.json", -3.0391264205852315},
      {"rainbow.json", 0.7027769992981585},
      {"rocket.json", -1.5943364625085998},
      {"sky.json", -0.2993551127286244},
      {"slow-light.json", 0.040985982195487373},
      {"stars.json", 7.635266069497199},
      {"street-lit.json", -2.2468720482443474},
      {"street-searchlight.json", -3.5660409969064886},
      {"street.json", -2.0881669183174445},
      {"sun-flyby.json", -1.5975704868340581},
      {"terrell.json", 5.600950540202986},
      {"texture-mapping.json", 0.7599025376858278},
      {"twin-paradox.json", -1.364420877097537},
      {"wheel.json", 0.9311345009251284},
  };
  for (const auto& [name, ev] : recorded) {
    const test::CommandResult r = test::run_lightcone(
        "render " + std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/" + name + " -o " +
        (dir_ / "image.png").string() +
        " --width 320 --height 180 --samples 1 --stats --set render.exposure=auto");
    ASSERT_EQ(r.status, 0) << name << ": " << r.err;
    const std::string last = r.err.substr(r.err.rfind('{'));
    EXPECT_NEAR(nlohmann::json::parse(last).at("exposure").get<double>(), ev, kMetered + 1e-6)
        << name;
  }
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

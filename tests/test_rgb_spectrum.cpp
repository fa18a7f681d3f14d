// Tests of RGB-to-spectrum upsampling (Jakob-Hanika sigmoid-quadratic model, table fitted at
// build time by tools/rgb2spec_gen): RGB -> spectrum -> RGB round trips with the 1 nm CIE
// table, the policy outside 360-830 nm, the bounds of reflectances, black and white, and that
// the table built into the library is exactly what the fit produces now (determinism).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/color/spectrum.hpp"
#include "rgb2spec_fit.hpp"

namespace lightcone {
namespace {

double max_abs_difference(const LinearRgb& a, const LinearRgb& b) {
  return std::max({std::fabs(a.r - b.r), std::fabs(a.g - b.g), std::fabs(a.b - b.b)});
}

template <class Spectrum>
LinearRgb rgb_of(const Spectrum& s) {
  return linear_srgb_from_xyz(xyz_from_spectrum(s));
}

// The grid of n^3 colours in [0, 1]^3.
std::vector<LinearRgb> gamut_grid(int n) {
  std::vector<LinearRgb> out;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < n; ++c) out.push_back({a / (n - 1.0), b / (n - 1.0), c / (n - 1.0)});
  return out;
}

TEST(SigmoidPolynomial, SigmoidShape) {
  EXPECT_DOUBLE_EQ(sigmoid(0), 0.5);
  EXPECT_DOUBLE_EQ(sigmoid(1), 0.5 + 0.5 / std::sqrt(2.0));
  EXPECT_NEAR(sigmoid(-1), 0.5 - 0.5 / std::sqrt(2.0), 1e-15);
  EXPECT_EQ(sigmoid(std::numeric_limits<double>::infinity()), 1.0);
  EXPECT_EQ(sigmoid(-std::numeric_limits<double>::infinity()), 0.0);
  EXPECT_EQ(sigmoid(1e200), 1.0);
  EXPECT_EQ(sigmoid(-1e200), 0.0);
  // Small values keep their relative precision: S(x) ~ 1 / (4 x^2) for x -> -inf.
  EXPECT_NEAR(sigmoid(-1e6) * 4e12, 1.0, 1e-9);
  // The normalised wavelength maps [360, 830] onto [-1, 1].
  EXPECT_DOUBLE_EQ(sigmoid_normalised_wavelength(360), -1.0);
  EXPECT_DOUBLE_EQ(sigmoid_normalised_wavelength(830), 1.0);
  EXPECT_DOUBLE_EQ(sigmoid_normalised_wavelength(595), 0.0);
  const SigmoidPolynomial p{0.3, -2.0, 0.7};
  const double u = sigmoid_normalised_wavelength(500);
  EXPECT_DOUBLE_EQ(p(500), sigmoid((0.3 * u - 2.0) * u + 0.7));
}

TEST(ReferenceIlluminant, IsA6504KBlackbodyWithUnitLuminance) {
  const Xyz xyz = xyz_from_spectrum([](double l) { return reference_illuminant(l); });
  EXPECT_NEAR(xyz.y, 1.0, 1e-12);
  // Chromaticity of the Planckian locus at 6504 K: near D65 (0.3127, 0.3290), not at it.
  const double x = xyz.x / (xyz.x + xyz.y + xyz.z), y = xyz.y / (xyz.x + xyz.y + xyz.z);
  EXPECT_NEAR(x, 0.3135, 0.002);
  EXPECT_NEAR(y, 0.3236, 0.002);
  for (double l : {100.0, 300.0, 555.0, 1000.0, 5000.0}) {
    EXPECT_GT(reference_illuminant(l), 0) << l;
    const double planck = planck_radiance(l, 6504) / planck_radiance(555, 6504);
    EXPECT_NEAR(reference_illuminant(l) / reference_illuminant(555), planck, 1e-12 * planck) << l;
  }
}

// The headline requirement: an RGB emitter of any colour in the sRGB cube, integrated with the
// 1 nm CIE table at rest (D = 1), gives its RGB back exactly (the emitter nodes are fitted
// exactly and blending two neighbours blends their colours linearly).
TEST(RgbEmitterSpectrum, RoundTripOverTheSrgbCube) {
  double worst = 0;
  LinearRgb worst_rgb;
  for (const LinearRgb& rgb : gamut_grid(11)) {
    const double e = max_abs_difference(rgb_of(RgbEmitterSpectrum::from_rgb(rgb)), rgb);
    if (e > worst) worst = e, worst_rgb = rgb;
  }
  std::cout << "illuminant round trip, 11^3 grid: max error " << worst << " at (" << worst_rgb.r
            << ", " << worst_rgb.g << ", " << worst_rgb.b << ")\n";
  EXPECT_LT(worst, 1e-7);
}

TEST(RgbEmitterSpectrum, RoundTripOfBrighterEmitters) {
  for (const LinearRgb& rgb : {LinearRgb{3, 0.5, 0.2}, LinearRgb{10, 10, 10},
                               LinearRgb{0.2, 5, 0.1}, LinearRgb{0.5, 1.5, 4}}) {
    const LinearRgb back = rgb_of(RgbEmitterSpectrum::from_rgb(rgb));
    EXPECT_LT(max_abs_difference(back, rgb), 1e-7 * std::max({rgb.r, rgb.g, rgb.b}))
        << rgb.r << " " << rgb.g << " " << rgb.b << " -> " << back.r << " " << back.g << " "
        << back.b;
  }
}

TEST(RgbEmitterSpectrum, ScalesLinearlyAndIsBlackForBlack) {
  const RgbEmitterSpectrum black = RgbEmitterSpectrum::from_rgb({0, 0, 0});
  const RgbEmitterSpectrum negative = RgbEmitterSpectrum::from_rgb({-1, 0, -2});
  for (double l = 100; l <= 3000; l += 7) {
    EXPECT_EQ(black(l), 0.0);
    EXPECT_EQ(negative(l), 0.0);
  }
  // Twice the colour is twice the spectrum (the scale carries the brightness).
  const RgbEmitterSpectrum a = RgbEmitterSpectrum::from_rgb({0.3, 0.6, 0.1});
  const RgbEmitterSpectrum b = RgbEmitterSpectrum::from_rgb({0.6, 1.2, 0.2});
  for (double l = 300; l <= 900; l += 10) EXPECT_NEAR(b(l), 2 * a(l), 1e-12 * b(l)) << l;
}

// Below 300 nm and above 830 nm the emitter is flat reflectances times the blackbody (the
// bands of the RGB white have died out): it falls off as the 6504 K blackbody does.
TEST(RgbEmitterSpectrum, FollowsTheBlackbodyOutsideTheVisibleRange) {
  for (const LinearRgb& rgb : {LinearRgb{3, 0.5, 0.2}, LinearRgb{0.1, 0.2, 1}}) {
    const RgbEmitterSpectrum s = RgbEmitterSpectrum::from_rgb(rgb);
    for (double l : {50.0, 200.0, 250.0, 299.0}) {
      const double planck = planck_radiance(l, 6504) / planck_radiance(300, 6504);
      EXPECT_NEAR(s(l) / s(300), planck, 2e-4 * planck) << l;
    }
    for (double l : {831.0, 1000.0, 3000.0, 1e5}) {
      const double planck = planck_radiance(l, 6504) / planck_radiance(830, 6504);
      EXPECT_NEAR(s(l) / s(830), planck, 2e-4 * planck) << l;
    }
    EXPECT_LT(s(100), s(360));
    EXPECT_LT(s(5000), s(830));
    EXPECT_GT(s(1000), 0);
  }
}

// Reflectances are flat beyond the visible range: the value at 360 nm holds into the
// ultraviolet and the value at 830 nm into the infrared.
TEST(RgbAlbedoSpectrum, IsFlatOutsideTheVisibleRange) {
  for (const LinearRgb& rgb : gamut_grid(5)) {
    const RgbAlbedoSpectrum s = RgbAlbedoSpectrum::from_rgb(rgb);
    EXPECT_EQ(s(300), s(360));
    EXPECT_EQ(s(1), s(360));
    EXPECT_EQ(s(1000), s(830));
    EXPECT_EQ(s(1e6), s(830));
  }
  // A red stays red-reflecting into the infrared and dark into the ultraviolet, a blue the
  // other way round, a green dark on both sides. (What a fit does at the ends of the visible
  // range, where the eye is nearly blind, is the model's choice: a bright or pale red turns up
  // again towards 360 nm, see docs/design/spectral.md.)
  const RgbAlbedoSpectrum red = RgbAlbedoSpectrum::from_rgb({0.5, 0, 0});
  EXPECT_GT(red(1000), 0.95);
  EXPECT_LT(red(300), 0.05);
  const RgbAlbedoSpectrum blue = RgbAlbedoSpectrum::from_rgb({0, 0, 1});
  EXPECT_LT(blue(1000), 0.05);
  EXPECT_GT(blue(300), 0.9);
  const RgbAlbedoSpectrum green = RgbAlbedoSpectrum::from_rgb({0, 0.5, 0});
  EXPECT_LT(green(1000), 0.05);
  EXPECT_LT(green(300), 0.05);
}

TEST(RgbAlbedoSpectrum, StaysWithinTheUnitInterval) {
  for (const LinearRgb& rgb : gamut_grid(9)) {
    const RgbAlbedoSpectrum s = RgbAlbedoSpectrum::from_rgb(rgb);
    for (double l = 200; l <= 1200; l += 3.5) {
      const double v = s(l);
      ASSERT_GE(v, 0.0) << rgb.r << " " << rgb.g << " " << rgb.b << " at " << l;
      ASSERT_LE(v, 1.0) << rgb.r << " " << rgb.g << " " << rgb.b << " at " << l;
    }
  }
  // Out-of-range inputs are clamped to [0, 1] first.
  const RgbAlbedoSpectrum clamped = RgbAlbedoSpectrum::from_rgb({2, -1, 0.5});
  const RgbAlbedoSpectrum same = RgbAlbedoSpectrum::from_rgb({1, 0, 0.5});
  for (double l = 360; l <= 830; l += 10) EXPECT_EQ(clamped(l), same(l));
}

TEST(RgbAlbedoSpectrum, BlackIsZeroAndWhiteIsNearlyOne) {
  const RgbAlbedoSpectrum black = RgbAlbedoSpectrum::from_rgb({0, 0, 0});
  const RgbAlbedoSpectrum unset;
  for (double l = 100; l <= 2000; l += 5) {
    EXPECT_EQ(black(l), 0.0);
    EXPECT_EQ(unset(l), 0.0);
  }
  // White is the flat reflectance 1 (RGB reflectances are white-balanced to the reference
  // illuminant), and greys are flat.
  const RgbAlbedoSpectrum white = RgbAlbedoSpectrum::from_rgb({1, 1, 1});
  double worst = 0;
  for (double l = 400; l <= 700; l += 1) worst = std::max(worst, std::fabs(white(l) - 1));
  std::cout << "white albedo: max |s - 1| over 400-700 nm " << worst << "\n";
  EXPECT_LT(worst, 0.02);
  // (Flat to 1e-6; the level is the interpolated table's, within 2%.)
  for (double v : {0.02, 0.2, 0.5, 0.9}) {
    const RgbAlbedoSpectrum grey = RgbAlbedoSpectrum::from_rgb({v, v, v});
    for (double l = 360; l <= 830; l += 10) {
      EXPECT_NEAR(grey(l), grey(595), 1e-6 * v) << v << " " << l;
      EXPECT_NEAR(grey(l), v, 0.02 * v) << v << " " << l;
    }
  }
}

TEST(ReferenceIlluminant, WhiteIsTheColourOfAFlatReflectance) {
  const LinearRgb w = reference_white();
  const LinearRgb flat = rgb_of([](double l) { return reference_illuminant(l); });
  EXPECT_EQ(w.r, flat.r);
  EXPECT_EQ(w.g, flat.g);
  EXPECT_EQ(w.b, flat.b);
  // Near, not at, (1, 1, 1): the 6504 K blackbody is a little more magenta than D65.
  EXPECT_NEAR(w.r, 1.04, 0.02);
  EXPECT_NEAR(w.g, 0.98, 0.02);
  EXPECT_NEAR(w.b, 1.04, 0.02);
}

// As reflectances under the reference illuminant, white-balanced to it, colours come back.
TEST(RgbAlbedoSpectrum, RoundTripUnderTheReferenceIlluminant) {
  const LinearRgb w = reference_white();
  double worst = 0;
  for (const LinearRgb& rgb : gamut_grid(11)) {
    const RgbAlbedoSpectrum s = RgbAlbedoSpectrum::from_rgb(rgb);
    const LinearRgb seen = rgb_of([&](double l) { return s(l) * reference_illuminant(l); });
    worst = std::max(worst, max_abs_difference({seen.r / w.r, seen.g / w.g, seen.b / w.b}, rgb));
  }
  std::cout << "albedo round trip (white-balanced), 11^3 grid: max error " << worst << "\n";
  EXPECT_LT(worst, 0.01);
}

// The table built into the library is bit for bit what the fit gives now: the generator is
// deterministic (its columns are independent of each other and of the threads).
TEST(RgbToSpectrumTable, IsWhatTheFitProduces) {
  const int res = kRgbToSpectrumRes;
  const float* built = detail::rgb_to_spectrum_table(0, 0, 0);  // (all of it, natively)
  std::vector<float> refit(kRgbToSpectrumTableFloats, std::numeric_limits<float>::quiet_NaN());
  const rgb2spec::Fitter fitter;
  const int columns[][3] = {{0, 0, 0},
                            {0, res - 1, res - 1},
                            {1, 7, 40},
                            {2, res - 1, 0},
                            {2, 0, res - 1},
                            {1, res / 2, res / 3},
                            {0, res / 5, 3 * res / 4}};
  for (const auto& column : columns) {
    const int l = column[0], j = column[1], i = column[2];
    fitter.fit_column(res, l, j, i, refit.data());
    for (int k = 0; k < res; ++k) {
      const std::size_t at = rgb_to_spectrum_cell(l, k, j, i, res);
      EXPECT_EQ(std::memcmp(&refit[at], &built[at], 3 * sizeof(float)), 0)
          << "l " << l << " k " << k << " j " << j << " i " << i;
    }
  }
  for (int n = 0; n < kRgbToSpectrumTableFloats; n += 997) {
    ASSERT_TRUE(std::isfinite(built[n])) << n;
  }
}

TEST(RgbToSpectrumTable, FitsItsNodes) {
  // Nodes in the reachable middle of the scale axis are fitted essentially exactly.
  const rgb2spec::Fitter fitter;
  for (const LinearRgb& rgb :
       {LinearRgb{0.5, 0.2, 0.1}, LinearRgb{0.1, 0.4, 0.05}, LinearRgb{0.02, 0.03, 0.3}}) {
    const rgb2spec::FitResult r = fitter.fit(rgb, {0, 0, 0});
    EXPECT_LT(r.lab_error, 1e-5);
    const Xyz xyz = fitter.xyz(r.c);
    EXPECT_LT(max_abs_difference(linear_srgb_from_xyz(xyz), rgb), 1e-6);
  }
}

TEST(ReferenceIlluminant, IsPlancksLawItself) {
  const BlackbodySpectrum exact =
      BlackbodySpectrum::with_luminance(kReferenceIlluminantTemperature, 1.0);
  for (double lambda = 10; lambda < 2e6; lambda *= 1.07)
    EXPECT_EQ(reference_illuminant(lambda), exact(lambda)) << lambda;
}

// The cells rgb_to_sigmoid reads for a blend of colours (the table l whose channel is largest,
// ties to the earlier; row and column the cells of the other two channels over it, in order)
// lie in the rectangles rgb_to_spectrum_cells_of_blends gives for those colours: random blends
// of four random colours, with black, saturated, grey and tied colours among them.
TEST(RgbToSpectrumCells, HoldEveryCellABlendReads) {
  std::mt19937 random(17);
  std::uniform_real_distribution<double> unit(0, 1);
  const auto channel = [&]() {
    const double u = unit(random);
    return u < 0.15 ? 0.0 : u < 0.25 ? 1.0 : u < 0.3 ? 1.5 : unit(random);
  };
  const auto cell = [](double t) {
    return std::min(static_cast<int>(t * (kRgbToSpectrumRes - 1)), kRgbToSpectrumRes - 2);
  };
  int tested = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    std::array<LinearRgb, 4> colours;
    for (LinearRgb& c : colours) {
      c = {channel(), channel(), channel()};
      if (unit(random) < 0.1) c.g = c.b = c.r;  // grey: every channel tied
    }
    std::array<RgbToSpectrumCells, 3> cells;
    const int n = rgb_to_spectrum_cells_of_blends(colours, cells);
    for (int blend = 0; blend < 50; ++blend) {
      double w[4], total = 0;
      for (double& x : w) total += x = unit(random) < 0.2 ? 0.0 : unit(random);
      if (total == 0) continue;
      double c[3] = {0, 0, 0};
      for (int k = 0; k < 4; ++k) {
        const LinearRgb& v = colours[static_cast<std::size_t>(k)];
        c[0] += w[k] * std::clamp(v.r, 0.0, 1.0);
        c[1] += w[k] * std::clamp(v.g, 0.0, 1.0);
        c[2] += w[k] * std::clamp(v.b, 0.0, 1.0);
      }
      int l = 0;
      if (c[1] > c[l]) l = 1;
      if (c[2] > c[l]) l = 2;
      if (c[l] <= 0) continue;  // black reads no cell
      const int i = cell(c[(l + 1) % 3] / c[l]), j = cell(c[(l + 2) % 3] / c[l]);
      const bool held = std::any_of(cells.begin(), cells.begin() + n, [&](const auto& r) {
        return r.l == l && r.j0 <= j && j <= r.j1 && r.i0 <= i && i <= r.i1;
      });
      ASSERT_TRUE(held) << "table " << l << " cell (" << j << ", " << i << ") of trial " << trial;
      ++tested;
    }
  }
  EXPECT_GT(tested, 100000);
  // A smooth texture's four texels need a few cells, not the table.
  std::array<RgbToSpectrumCells, 3> cells;
  const LinearRgb near[4] = {{0.5, 0.3, 0.2}, {0.51, 0.3, 0.2}, {0.5, 0.31, 0.2}, {0.5, 0.3, 0.21}};
  ASSERT_EQ(rgb_to_spectrum_cells_of_blends(near, cells), 1);
  EXPECT_EQ(cells[0].l, 0);
  EXPECT_LE(cells[0].j1 - cells[0].j0, 4);
  EXPECT_LE(cells[0].i1 - cells[0].i0, 4);
}

}  // namespace
}  // namespace lightcone

// Tests of the colour kernels (src/lightcone/color): the CIE 1931 table against its published
// integrals and values, the sRGB matrices against IEC 61966-2-1, Planck's law against Wien's
// displacement law, the Stefan-Boltzmann law and a long double evaluation, blackbody
// chromaticities against published CIE values, the D^5 searchlight identity of PHYSICS.md
// ("Searchlight", "Colour"), and tabulated spectra.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/spectrum.hpp"

namespace lightcone {
namespace {

// ---------------------------------------------------------------------------------------------
// Helpers and independent constants.

// Exact SI constants, written out again here so the tests do not borrow the kernel's.
constexpr long double kH = 6.62607015e-34L;  // J s
constexpr long double kC = 299792458.0L;     // m / s
constexpr long double kK = 1.380649e-23L;    // J / K
// Stefan-Boltzmann constant, CODATA 2018 (exact in the 2019 SI; given to 10 digits).
constexpr double kSigma = 5.670374419e-8;  // W m^-2 K^-4
// Wien's displacement constant b, CODATA 2018.
constexpr double kWienNmK = 2.897771955e6;  // nm K

struct Xy {
  double x, y;
};
Xy chromaticity(const Xyz& c) {
  const double s = c.x + c.y + c.z;
  return {c.x / s, c.y / s};
}
// CIE 1960 UCS (u, v), the space of Robertson's table.
Xy uv_1960(const Xy& c) {
  const double d = -2 * c.x + 12 * c.y + 3;
  return {4 * c.x / d, 6 * c.y / d};
}

// Planck's law in long double straight from its textbook form, per nm of wavelength:
// 2 h c^2 / lambda^5 / (exp(h c / (lambda k T)) - 1), lambda in metres, times 1e-9 m / nm.
long double planck_reference(double lambda_nm, double t) {
  const long double lambda = static_cast<long double>(lambda_nm) * 1e-9L;
  const long double x = kH * kC / (lambda * kK * static_cast<long double>(t));
  return 2 * kH * kC * kC / std::pow(lambda, 5.0L) / std::expm1(x) * 1e-9L;
}

// integral of f(lambda) dlambda over [lo, hi] nm as the trapezoid rule in ln(lambda) with n
// intervals (f(lambda) lambda is smooth and decays at both ends, so this converges fast).
template <class F>
double log_grid_integral(const F& f, double lo, double hi, int n) {
  const double a = std::log(lo), h = (std::log(hi) - a) / n;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double lambda = std::exp(a + i * h);
    sum += (i == 0 || i == n ? 0.5 : 1.0) * f(lambda) * lambda;
  }
  return sum * h;
}

std::array<double, 3> table_sums() {
  std::array<double, 3> s{0, 0, 0};
  for (int i = 0; i < kCieTableSize; ++i) {
    const Xyz c = cie_cmf(kCieMinWavelength + i);
    s[0] += c.x;
    s[1] += c.y;
    s[2] += c.z;
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// CIE 1931 colour matching functions (CIE, DOI 10.25039/CIE.DS.xvudnb9b).

TEST(CieTable, SumsOfTheOneNanometreTable) {
  const auto s = table_sums();
  // The double-precision sums of the published 1 nm table. (pbrt quotes 106.856895 for y; that
  // figure is 2.2e-5 below the exact sum of the published numbers, 106.8569171.)
  EXPECT_NEAR(s[1], 106.8569171, 1e-6);
  EXPECT_NEAR(s[1], 106.856895, 3e-5);
  EXPECT_NEAR(s[0], 106.8654695, 1e-6);
  EXPECT_NEAR(s[2], 106.8922513, 1e-6);
  EXPECT_NEAR(cie_y_integral(), s[1], 1e-12);
}

TEST(CieTable, PublishedValues) {
  // Spot values of the published table (x-bar, y-bar, z-bar).
  struct Row {
    double nm, x, y, z;
  };
  const Row rows[] = {
      {360, 0.0001299, 0.000003917, 0.0006061},
      {380, 0.001368, 0.000039, 0.006450001},
      {450, 0.3362, 0.038, 1.77211},
      {505, 0.0024, 0.4073, 0.2123},
      {555, 0.5120501, 1.0, 0.005749999},
      {599, 1.0629096, 0.6438448, 0.00084256},
      {600, 1.0622, 0.631, 0.0008},
      {700, 0.01135916, 0.004102, 0.0},
      {830, 0.000001251141, 0.00000045181, 0.0},
  };
  for (const Row& r : rows) {
    const Xyz c = cie_cmf(r.nm);
    EXPECT_DOUBLE_EQ(c.x, r.x) << r.nm;
    EXPECT_DOUBLE_EQ(c.y, r.y) << r.nm;
    EXPECT_DOUBLE_EQ(c.z, r.z) << r.nm;
  }
  // y-bar peaks at 555 nm with exactly 1; x-bar's long-wave lobe peaks at 599 nm.
  int y_peak = 0, x_peak = 0;
  for (int i = 0; i < kCieTableSize; ++i) {
    if (cie_cmf(360.0 + i).y > cie_cmf(360.0 + y_peak).y) y_peak = i;
    if (cie_cmf(360.0 + i).x > cie_cmf(360.0 + x_peak).x) x_peak = i;
  }
  EXPECT_EQ(360 + y_peak, 555);
  EXPECT_EQ(360 + x_peak, 599);
}

TEST(CieTable, LinearInterpolationAndZeroOutside) {
  const Xyz a = cie_cmf(555), b = cie_cmf(556), m = cie_cmf(555.25);
  EXPECT_NEAR(m.x, 0.75 * a.x + 0.25 * b.x, 1e-15);
  EXPECT_NEAR(m.y, 0.75 * a.y + 0.25 * b.y, 1e-15);
  EXPECT_NEAR(m.z, 0.75 * a.z + 0.25 * b.z, 1e-15);
  EXPECT_GT(cie_cmf(360).x, 0);
  EXPECT_GT(cie_cmf(830).y, 0);
  for (double lambda : {359.999, 830.001, 0.0, -500.0, 1e9, std::numeric_limits<double>::infinity(),
                        std::numeric_limits<double>::quiet_NaN()}) {
    const Xyz c = cie_cmf(lambda);
    EXPECT_EQ(c.x, 0) << lambda;
    EXPECT_EQ(c.y, 0) << lambda;
    EXPECT_EQ(c.z, 0) << lambda;
  }
}

TEST(CieTable, EqualEnergyWhite) {
  const Xyz w = xyz_from_spectrum([](double) { return 1.0; });
  EXPECT_NEAR(w.y, 1.0, 1e-12);
  const Xy c = chromaticity(w);
  EXPECT_NEAR(c.x, 1.0 / 3.0, 1e-4);
  EXPECT_NEAR(c.y, 1.0 / 3.0, 1e-4);
}

// ---------------------------------------------------------------------------------------------
// sRGB (IEC 61966-2-1).

TEST(Srgb, WhiteIsD65WithUnitLuminance) {
  const Xyz w = xyz_from_linear_srgb({1, 1, 1});
  EXPECT_NEAR(w.y, 1.0, 1e-12);
  const Xy c = chromaticity(w);
  EXPECT_NEAR(c.x, 0.3127, 1e-9);
  EXPECT_NEAR(c.y, 0.3290, 1e-9);
}

TEST(Srgb, PrimariesAndThePrintedMatrix) {
  // The matrix printed in IEC 61966-2-1 (four places).
  const double printed[3][3] = {
      {0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
  const Xy primaries[3] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
  for (int j = 0; j < 3; ++j) {
    LinearRgb rgb;
    (j == 0 ? rgb.r : j == 1 ? rgb.g : rgb.b) = 1;
    const Xyz col = xyz_from_linear_srgb(rgb);
    EXPECT_NEAR(col.x, printed[0][j], 5.01e-5) << j;
    EXPECT_NEAR(col.y, printed[1][j], 5.01e-5) << j;
    EXPECT_NEAR(col.z, printed[2][j], 5.01e-5) << j;
    const Xy c = chromaticity(col);
    EXPECT_NEAR(c.x, primaries[j].x, 1e-12) << j;
    EXPECT_NEAR(c.y, primaries[j].y, 1e-12) << j;
  }
}

TEST(Srgb, MatricesAreInverses) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2, 3);
  for (int i = 0; i < 100; ++i) {
    const LinearRgb rgb{u(rng), u(rng), u(rng)};
    const LinearRgb back = linear_srgb_from_xyz(xyz_from_linear_srgb(rgb));
    EXPECT_NEAR(back.r, rgb.r, 1e-12);
    EXPECT_NEAR(back.g, rgb.g, 1e-12);
    EXPECT_NEAR(back.b, rgb.b, 1e-12);
    const Xyz xyz{u(rng), u(rng), u(rng)};
    const Xyz back2 = xyz_from_linear_srgb(linear_srgb_from_xyz(xyz));
    EXPECT_NEAR(back2.x, xyz.x, 1e-12);
    EXPECT_NEAR(back2.y, xyz.y, 1e-12);
    EXPECT_NEAR(back2.z, xyz.z, 1e-12);
  }
}

// ---------------------------------------------------------------------------------------------
// Planck's law.

TEST(Planck, AgreesWithLongDoubleEvaluation) {
  int compared = 0;
  for (double t : {1.0, 3.0, 77.0, 300.0, 2856.0, 6504.0, 3e4, 1e6, 1e8}) {
    for (double e = -2; e <= 9; e += 0.05) {
      const double lambda = std::pow(10.0, e);
      const long double ref = planck_reference(lambda, t);
      const double got = planck_radiance(lambda, t);
      if (ref > 1e-290L) {
        EXPECT_NEAR(got / static_cast<double>(ref), 1.0, 1e-12) << lambda << " nm, " << t << " K";
        ++compared;
      } else {
        EXPECT_LE(got, 1e-289) << lambda << " nm, " << t << " K";
      }
    }
  }
  EXPECT_GT(compared, 1000);
}

TEST(Planck, WienDisplacementLaw) {
  for (double t : {300.0, 2856.0, 5778.0, 1e4, 1e5}) {
    // Golden-section search for the maximum in ln(lambda) over a decade either side.
    const double expected = kWienNmK / t;
    double a = std::log(expected / 10), b = std::log(expected * 10);
    const double g = (std::sqrt(5.0) - 1) / 2;
    while (b - a > 1e-9) {
      const double c = b - g * (b - a), d = a + g * (b - a);
      if (planck_radiance(std::exp(c), t) > planck_radiance(std::exp(d), t))
        b = d;
      else
        a = c;
    }
    const double peak = std::exp(0.5 * (a + b));
    EXPECT_NEAR(peak / expected, 1.0, 1e-6) << t << " K";
  }
}

TEST(Planck, StefanBoltzmannLaw) {
  for (double t : {1.0, 300.0, 5778.0, 1e6}) {
    const double peak = kWienNmK / t;
    const double radiance = log_grid_integral(
        [t](double lambda) { return planck_radiance(lambda, t); }, peak * 1e-3, peak * 1e6, 200000);
    const double exitance = std::numbers::pi * radiance;  // W m^-2
    EXPECT_NEAR(exitance / (kSigma * std::pow(t, 4)), 1.0, 1e-8) << t << " K";
  }
}

TEST(Planck, FiniteAndNonNegativeEverywhere) {
  const double inf = std::numeric_limits<double>::infinity();
  for (double lambda : {1e-300, 1e-30, 1e-3, 1.0, 550.0, 1e9, 1e30, 1e300, inf}) {
    for (double t : {1e-300, 1e-6, 1.0, 300.0, 1e6, 1e30, 1e300}) {
      const double b = planck_radiance(lambda, t);
      EXPECT_TRUE(std::isfinite(b)) << lambda << " nm, " << t << " K";
      EXPECT_GE(b, 0.0) << lambda << " nm, " << t << " K";
    }
  }
  EXPECT_EQ(planck_radiance(1e-3, 1.0), 0.0);  // exp(-1.4e10) underflows
  EXPECT_EQ(planck_radiance(0.0, 300.0), 0.0);
  EXPECT_EQ(planck_radiance(-500.0, 300.0), 0.0);
  EXPECT_EQ(planck_radiance(500.0, 0.0), 0.0);
  EXPECT_EQ(planck_radiance(500.0, -300.0), 0.0);
  // Far infrared of a hot body: the Rayleigh-Jeans limit 2 c k T / lambda^4 (per nm).
  const double lambda = 1e9, t = 1e6;
  const double rayleigh_jeans = static_cast<double>(
      2 * kC * kK * t / std::pow(static_cast<long double>(lambda) * 1e-9L, 4) * 1e-9L);
  EXPECT_NEAR(planck_radiance(lambda, t) / rayleigh_jeans, 1.0, 1e-6);
}

// PHYSICS.md "Colour": seen with Doppler factor D, a blackbody at T is exactly a blackbody at
// D T, because D^5 B(D lambda, T) = B(lambda, D T).
TEST(Planck, DopplerShiftedBlackbodyIsABlackbodyAtDT) {
  int compared = 0;
  for (double t : {300.0, 2856.0, 6504.0, 1e4}) {
    for (double d : {0.2, 0.5, 0.9, 1.0, 1.7, 3.0, 4.36, 5.0}) {
      for (double e = 0; e <= 6; e += 0.01) {
        const double lambda = std::pow(10.0, e);
        const double shifted = std::pow(d, 5) * planck_radiance(d * lambda, t);
        const double hotter = planck_radiance(lambda, d * t);
        if (hotter > 1e-280) {
          EXPECT_NEAR(shifted / hotter, 1.0, 1e-12) << lambda << " nm, " << t << " K, D " << d;
          ++compared;
        } else {
          EXPECT_LE(shifted, 1e-279);
        }
      }
    }
  }
  EXPECT_GT(compared, 10000);
  // The same through BlackbodySpectrum, and the integrated radiance grows by D^4.
  const BlackbodySpectrum s = BlackbodySpectrum::with_luminance(5000, 2.0);
  for (double d : {0.2, 0.6, 2.5, 5.0}) {
    const BlackbodySpectrum hot{d * s.temperature_k, s.scale};
    for (double lambda : {200.0, 360.0, 555.0, 830.0, 2000.0})
      EXPECT_NEAR(std::pow(d, 5) * s(d * lambda) / hot(lambda), 1.0, 1e-12);
    const double peak = kWienNmK / s.temperature_k;
    const double rest = log_grid_integral(s, peak * 1e-3, peak * 1e6, 100000);
    const double seen =
        log_grid_integral([&](double lambda) { return std::pow(d, 5) * s(d * lambda); },
                          peak * 1e-3 / d, peak * 1e6 / d, 100000);
    EXPECT_NEAR(seen / rest, std::pow(d, 4), 1e-8 * std::pow(d, 4));
  }
}

// ---------------------------------------------------------------------------------------------
// Blackbody chromaticities against published values.

Xy blackbody_xy(double t) {
  return chromaticity(xyz_from_spectrum([t](double lambda) { return planck_radiance(lambda, t); }));
}

TEST(BlackbodyColour, IlluminantA) {
  // CIE standard illuminant A (ISO 11664-2 / CIE S 014-2) is defined by Planck's law at
  // 2848 K with c2 = 1.435e-2 m K, i.e. at 2848 K * c2 / 1.435e-2 = 2855.5 K with today's c2;
  // "2856 K" is that temperature with c2 = 1.4388e-2. Its chromaticity, CIE 15:2004 Table T.3
  // (2 degree observer): x = 0.44757, y = 0.40745 (five places).
  const double c2 = static_cast<double>(kH * kC / kK);
  const Xy a = blackbody_xy(2848.0 * c2 / 1.435e-2);
  EXPECT_NEAR(a.x, 0.44757, 3e-5);
  EXPECT_NEAR(a.y, 0.40745, 3e-5);
  const Xy a2856 = blackbody_xy(2856);
  EXPECT_NEAR(a2856.x, 0.44757, 2e-4);
  EXPECT_NEAR(a2856.y, 0.40745, 2e-4);
}

TEST(BlackbodyColour, PlanckianLocusAgainstRobertson) {
  // Planckian locus points in CIE 1960 (u, v) from Robertson, "Computation of correlated color
  // temperature and distribution temperature", JOSA 58 (1968) 1528, Table 1 (also Wyszecki and
  // Stiles, Color Science, 2nd ed. 1982, Table 1(3.11)), five places; T = 1e6 / mired.
  struct Point {
    double mired, u, v;
  };
  for (const Point& p : {Point{150, 0.19962, 0.30921}, Point{200, 0.21142, 0.32312},
                         Point{300, 0.24010, 0.34308}, Point{400, 0.27218, 0.35407}}) {
    const Xy uv = uv_1960(blackbody_xy(1e6 / p.mired));
    EXPECT_NEAR(uv.x, p.u, 1e-5) << p.mired;
    EXPECT_NEAR(uv.y, p.v, 1e-5) << p.mired;
  }
  // The same 5000 K point in (x, y), four places: x = 0.3451, y = 0.3516.
  const Xy c5000 = blackbody_xy(5000);
  EXPECT_NEAR(c5000.x, 0.3451, 1e-4);
  EXPECT_NEAR(c5000.y, 0.3516, 1e-4);
  // The locus at D65's correlated colour temperature, 6504 K (four places).
  const Xy c6504 = blackbody_xy(6504);
  EXPECT_NEAR(c6504.x, 0.3135, 1e-4);
  EXPECT_NEAR(c6504.y, 0.3236, 1e-4);
}

TEST(BlackbodyColour, WithLuminance) {
  for (double t : {800.0, 2856.0, 6504.0, 2e4, 1e6}) {
    for (double luminance : {1.0, 0.25, 100.0}) {
      const BlackbodySpectrum s = BlackbodySpectrum::with_luminance(t, luminance);
      EXPECT_EQ(s.temperature_k, t);
      EXPECT_GT(s.scale, 0);
      EXPECT_NEAR(xyz_from_spectrum(s).y, luminance, 1e-12 * luminance) << t;
      EXPECT_NEAR(s(700.0), s.scale * planck_radiance(700.0, t), 0.0);
    }
  }
  // Too cold to have any visible radiance in double precision: black, not NaN.
  const BlackbodySpectrum cold = BlackbodySpectrum::with_luminance(5.0, 1.0);
  EXPECT_EQ(cold.scale, 0.0);
  EXPECT_EQ(cold(10000.0), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Tabulated spectra.

TEST(Tabulated, PiecewiseLinearWithHeldEnds) {
  const TabulatedSpectrum s{{300, 400, 700, 2000}, {1.0, 3.0, 0.0, 2.0}};
  EXPECT_DOUBLE_EQ(s(300), 1.0);
  EXPECT_DOUBLE_EQ(s(400), 3.0);
  EXPECT_DOUBLE_EQ(s(700), 0.0);
  EXPECT_DOUBLE_EQ(s(2000), 2.0);
  EXPECT_DOUBLE_EQ(s(350), 2.0);
  EXPECT_DOUBLE_EQ(s(325), 1.5);
  EXPECT_DOUBLE_EQ(s(500), 2.0);
  EXPECT_DOUBLE_EQ(s(1350), 1.0);
  EXPECT_DOUBLE_EQ(s(100), 1.0);  // below: first value held
  EXPECT_DOUBLE_EQ(s(1e-3), 1.0);
  EXPECT_DOUBLE_EQ(s(5000), 2.0);  // above: last value held
  EXPECT_DOUBLE_EQ(s(1e12), 2.0);
  // Against a brute-force search on a non-uniform table.
  std::vector<double> w, v;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> step(0.1, 40), val(0, 5);
  double lambda = 200;
  for (int i = 0; i < 60; ++i) {
    w.push_back(lambda += step(rng));
    v.push_back(val(rng));
  }
  const TabulatedSpectrum t{w, v};
  for (double x = w.front() + 0.01; x < w.back(); x += 0.37) {
    std::size_t k = 0;
    while (w[k + 1] <= x) ++k;
    const double expected = v[k] + (x - w[k]) / (w[k + 1] - w[k]) * (v[k + 1] - v[k]);
    EXPECT_NEAR(t(x), expected, 1e-12) << x;
  }
}

TEST(Tabulated, DegenerateTables) {
  EXPECT_EQ((TabulatedSpectrum{})(500), 0.0);
  const TabulatedSpectrum one{{500}, {0.7}};
  EXPECT_EQ(one(100), 0.7);
  EXPECT_EQ(one(500), 0.7);
  EXPECT_EQ(one(900), 0.7);
}

}  // namespace
}  // namespace lightcone

// Carlson's reductions of the cubic elliptic integrals (physics/carlson_integrals.hpp) against
// the integrals themselves, summed by adaptive Gauss-Kronrod quadrature: an independent
// derivation that knows nothing of R_F, R_D, R_J or R_C.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/ellint_rc.hpp>
#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <utility>

#include "lightcone/physics/carlson_integrals.hpp"
#include "lightcone/physics/math_policy.hpp"

namespace lightcone::carlson {
namespace {

template <class F>
double quadrature(F f, double a, double b) {
  return boost::math::quadrature::gauss_kronrod<double, 31>::integrate(f, a, b, 15, 1e-14);
}

// L_i = a_i + b_i t.
struct Linear {
  double a, b;
  double operator()(double t) const { return a + b * t; }
};
double cross(const Linear& i, const Linear& j) {
  return i.a * j.b - j.a * i.b;
}
LinearFactors at(const Linear& l1, const Linear& l2, const Linear& l3, double t) {
  return {l1(t), l2(t), l3(t)};
}

TEST(CarlsonIntegrals, BatchedRfIsBoostsToTheBit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(1e-3, 10), decade(-12, 12);
  // General arguments, near and far apart (their steps end at different counts in one vector),
  // and those Boost treats apart: a zero, two equal; batches of every size.
  RfArgs args[kMaxBatch];
  for (int i = 0; i < kMaxBatch; ++i)
    args[i] = {u(rng), std::pow(10.0, decade(rng)), std::pow(10.0, decade(rng))};
  args[1] = {0, 1.5, 2.5};
  args[2] = {2, 2, 3};
  args[3] = {u(rng), 1e-9, 5};
  args[kMaxBatch - 2] = {1, 1 + 1e-15, 1 - 1e-15};
  for (int n = 1; n <= kMaxBatch; ++n) {
    double out[kMaxBatch];
    rf_batch(args, out, n);
    for (int i = 0; i < n; ++i)
      EXPECT_EQ(out[i], rf(args[i].x, args[i].y, args[i].z)) << i << " of " << n;
  }
}

// Boost iterates on a NaN or an infinite argument until it gives up with an exception of its
// own (whose message names it); here a NaN argument gives NaN, an infinite one the integrals'
// limit 0, and one outside their domain NaN, none of them an exception.
// rj is Boost's duplication with R_C(1, 1 + e) of its small terms summed as a series: within a
// few ulps of Boost's ellint_rj over arguments spread over twenty decades, p among them or apart,
// and for p < 0 (a Cauchy principal value, DLMF 19.20.14, a sum of three terms that may cancel)
// within 8 ulps of the largest term, with R_F(x, y, z) given or not; equal arguments are
// Boost's own.
TEST(CarlsonIntegrals, RjWithinUlpsOfBoosts) {
  std::mt19937 rng(55);
  std::uniform_real_distribution<double> decade(-10, 10), near(0.5, 2);
  double worst = 0, worst_principal = 0;  // p > 0, p < 0
  for (int i = 0; i < 200000; ++i) {
    double x = std::pow(10.0, decade(rng)), y = std::pow(10.0, decade(rng));
    double z = i % 3 == 0 ? y * near(rng) : std::pow(10.0, decade(rng));
    const double p = i % 4 == 0   ? z * near(rng)
                     : i % 4 == 1 ? -x * near(rng)
                                  : std::pow(10.0, decade(rng));
    const double boost = boost::math::ellint_rj(x, y, z, p, MathPolicy());
    double scale = std::abs(boost);
    if (p < 0) {
      if (x > y) std::swap(x, y);
      if (y > z) std::swap(y, z);
      if (x > y) std::swap(x, y);
      const double q = -p, pp = (z * (x + y + q) - x * y) / (z + q);
      const double xy = x * y + pp * q;
      scale = std::max({std::abs(pp - z) * boost::math::ellint_rj(x, y, z, pp, MathPolicy()),
                        3 * boost::math::ellint_rf(x, y, z, MathPolicy()),
                        3 * std::sqrt(x * y * z / xy) *
                            boost::math::ellint_rc(xy, pp * q, MathPolicy())}) /
              (z + q);
    }
    // With R_F(x, y, z) given too, as the third kind's reductions give theirs.
    double& w = p < 0 ? worst_principal : worst;
    w = std::max({w, std::abs(rj(x, y, z, p) - boost) / scale,
                  std::abs(rj(x, y, z, p, rf(z, x, y)) - boost) / scale});
  }
  EXPECT_LT(worst, 4 * std::numeric_limits<double>::epsilon()) << worst;
  EXPECT_LT(worst_principal, 8 * std::numeric_limits<double>::epsilon()) << worst_principal;
  EXPECT_EQ(rj(2, 2, 3, 4), boost::math::ellint_rj(2.0, 2.0, 3.0, 4.0, MathPolicy()));
}

TEST(CarlsonIntegrals, NanInfiniteAndNegativeArgumentsThrowNothing) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isnan(rf(kNaN, 1, 2)));
  EXPECT_TRUE(std::isnan(rd(1, kNaN, 2)));
  EXPECT_TRUE(std::isnan(rj(1, 2, 3, kNaN)));
  EXPECT_TRUE(std::isnan(rc(kNaN, 1)));
  EXPECT_EQ(rf(1, 2, kInf), 0);
  EXPECT_EQ(rd(1, kInf, 2), 0);
  EXPECT_EQ(rj(1, 2, 3, kInf), 0);
  EXPECT_EQ(rc(kInf, 1), 0);
  EXPECT_TRUE(std::isnan(rf(-1, 1, 2)));
  EXPECT_TRUE(std::isnan(rj(-1, 1, 2, 3)));
  double out[2];
  const RfArgs args[2] = {{kNaN, 1, 2}, {1, kInf, 2}};
  rf_batch(args, out, 2);
  EXPECT_TRUE(std::isnan(out[0]));
  EXPECT_EQ(out[1], 0);
}

TEST(CarlsonIntegrals, RealCubicIntegralsOfEveryKind) {
  const Linear l1{1, 2}, l2{3, -1}, l3{0.5, 1}, l4{2, 0.5};
  const double y = 0.2, x = 1.5;
  const auto cubic = [&](double t) { return l1(t) * l2(t) * l3(t); };
  const RealCubic c =
      real_cubic(x - y, at(l1, l2, l3, x), at(l1, l2, l3, y), cross(l1, l2), cross(l1, l3), l1.b);
  const double first = quadrature([&](double t) { return 1 / std::sqrt(cubic(t)); }, y, x);
  EXPECT_NEAR(first_kind(c), first, 1e-13 * first);
  EXPECT_NEAR(cubic_integral(x - y, at(l1, l2, l3, x), at(l1, l2, l3, y)), first, 1e-13 * first);
  const double second =
      quadrature([&](double t) { return std::sqrt(l1(t) / (l2(t) * l3(t))); }, y, x);
  EXPECT_NEAR(second_kind(c), second, 1e-13 * second);
  const double third =
      quadrature([&](double t) { return 1 / (l4(t) * std::sqrt(cubic(t))); }, y, x);
  const Pole pole{l4.b, l4(x), l4(y), cross(l1, l4), cross(l2, l4), cross(l3, l4)};
  EXPECT_NEAR(third_kind(c, pole, false), third, 1e-13 * third);
}

// A factor that vanishes at a limit (a turning point): with t = x - s^2 the integrand is smooth.
TEST(CarlsonIntegrals, RealCubicWithAFactorVanishingAtALimit) {
  const Linear l1{1, 2}, l2{1.5, -1}, l3{0.5, 1};
  const double y = 0.2, x = 1.5;
  const double expected = quadrature(
      [&](double s) {
        const double t = x - s * s;
        return 2 / std::sqrt(l1(t) * l3(t));
      },
      0, std::sqrt(x - y));
  const double got = cubic_integral(x - y, at(l1, l2, l3, x), at(l1, l2, l3, y));
  EXPECT_NEAR(got, expected, 1e-13 * expected);
}

// `regular`: the pole L4 = t at the lower limit 0, with L1 L2 L3 = 1 there. What comes back is
// lim_{y -> 0} (int_y^x dt / (t sqrt(L1 L2 L3)) + ln y) = int_0^x (1/sqrt(L1 L2 L3) - 1) dt / t
// + ln x.
TEST(CarlsonIntegrals, RegularPoleAtTheLowerLimit) {
  const Linear l1{2, 1}, l2{0.25, 0.5}, l3{2, -1}, l4{0, 1};
  const double x = 1.2;
  const double expected =
      quadrature([&](double t) { return (1 / std::sqrt(l1(t) * l2(t) * l3(t)) - 1) / t; }, 0, x) +
      std::log(x);
  const RealCubic c =
      real_cubic(x, at(l1, l2, l3, x), at(l1, l2, l3, 0), cross(l1, l2), cross(l1, l3), l1.b);
  const Pole pole{l4.b, l4(x), l4(0), cross(l1, l4), cross(l2, l4), cross(l3, l4)};
  EXPECT_NEAR(third_kind(c, pole, true), expected, 1e-12 * std::abs(expected));
}

TEST(CarlsonIntegrals, QuadraticCubicIntegralsOfEveryKind) {
  const double c = 0.7, n = 0.4, y = 0.1, x = 2.3;
  const auto q = [&](double z) { return (z - c) * (z - c) + n * n; };
  const QuadraticCubic k = quadratic_cubic(x, y, c, n);
  const double first = quadrature([&](double z) { return 1 / std::sqrt(z * q(z)); }, y, x);
  EXPECT_NEAR(first_kind(k), first, 1e-13 * first);
  const double second = quadrature([&](double z) { return 1 / (z * std::sqrt(z * q(z))); }, y, x);
  EXPECT_NEAR(second_kind(k), second, 1e-13 * second);
  for (const Linear l4 : {Linear{1.5, -0.5}, Linear{0.3, 2}}) {
    const double third =
        quadrature([&](double z) { return 1 / (l4(z) * std::sqrt(z * q(z))); }, y, x);
    EXPECT_NEAR(third_kind(k, l4.a, l4.b, l4(x), l4(y), false), third, 1e-13 * third)
        << l4.a << " " << l4.b;
  }
}

}  // namespace
}  // namespace lightcone::carlson

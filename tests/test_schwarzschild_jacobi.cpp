// Jacobi's elliptic functions at a fixed modulus (schwarzschild.hpp: jacobi_modulus,
// jacobi_functions) against Boost.Math's jacobi_elliptic: in double, taken after three Landen
// steps as radius_after_angle took them before the modulus was prepared once per orbit, and in
// long double after as many steps as the double ones take, the reference for the error; and
// against the inverse of Boost's incomplete integral of the first kind, F(am(u), k) = u.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

#include "lightcone/physics/math_policy.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

template <class T>
struct Functions {
  T sn, cn, dn;
};

// One Landen step up (DLMF 22.7.1-3), as the kernel writes it.
template <class T>
Functions<T> landen_up(const Functions<T>& j, T k1, T c1) {
  const T s2 = j.sn * j.sn, n = 1 + k1 * s2;
  return {(1 + k1) * j.sn / n, j.cn * j.dn / n, (j.cn * j.cn + c1 * s2) / n};
}

// Boost's functions at the modulus after `steps` of the modulus's Landen steps, at argument y
// there, stepped back up in T: in double with three steps this is what radius_after_angle
// evaluated before; in long double, with the very moduli of the double steps, the reference.
template <class T>
Functions<T> boost_after_steps(const JacobiModulus& m, int steps, T y) {
  Functions<T> j;
  j.sn =
      boost::math::jacobi_elliptic(static_cast<T>(m.k[steps - 1]), y, &j.cn, &j.dn, MathPolicy());
  for (int i = steps - 1; i >= 0; --i) j = landen_up<T>(j, m.k[i], m.c[i]);
  return j;
}

// K(k) = pi / (2 AGM(1, k')), in long double from k' itself, so that k -> 1 loses nothing.
long double quarter_period(double kc2) {
  long double a = 1, g = std::sqrt(static_cast<long double>(kc2));
  for (int i = 0; i < 40; ++i) {
    const long double next = (a + g) / 2;
    g = std::sqrt(a * g), a = next;
  }
  return std::numbers::pi_v<long double> / (2 * a);
}

// A modulus from k'^2, and the argument y of its last step at x = u K(k), |u| <= 4 (two periods
// of sn, either side of 0).
struct Sample {
  double k2, kc2;
  JacobiModulus modulus;
  double y;
};
Sample sample(std::mt19937_64& rng, double kc2) {
  Sample s{1 - kc2, kc2, jacobi_modulus(1 - kc2, kc2), 0};
  s.y = std::uniform_real_distribution<double>(-4, 4)(rng) *
        static_cast<double>(quarter_period(kc2)) * s.modulus.rate;
  return s;
}

TEST(JacobiFunctions, AreBoostsAfterThreeLandenStepsToTheBitWhereThoseReachItsAsymptoticForm) {
  std::mt19937_64 rng(55);
  std::uniform_real_distribution<double> log_kc2(-3, 0);
  int compared = 0;
  for (int i = 0; i < 200000; ++i) {
    // Moduli from 0 (b far beyond b_c) to within 1e-3 of 1.
    const Sample s = sample(rng, i % 8 == 0 ? 1.0 : std::pow(10.0, log_kc2(rng)));
    if (s.modulus.steps > 3) continue;
    const JacobiValues j = jacobi_functions(s.modulus, s.y);
    const Functions<double> boost = boost_after_steps(s.modulus, 3, s.y);
    ASSERT_EQ(j.sn, boost.sn) << s.kc2 << " " << s.y;
    ASSERT_EQ(j.cn, boost.cn) << s.kc2 << " " << s.y;
    ASSERT_EQ(j.dn, boost.dn) << s.kc2 << " " << s.y;
    ++compared;
  }
  EXPECT_GT(compared, 20000);
}

// The largest error of sn, cn and dn over many moduli up to k'^2 = 1e-17 (b within some 1e-16 of
// b_c) and arguments over two periods, in units of eps (1 + |y|): the argument itself is rounded
// to eps |y|, which moves each function by up to that much. Boost's functions after three Landen
// steps, as radius_after_angle took them before, are measured alike at the same argument.
TEST(JacobiFunctions, AsAccurateAsBoostsAfterThreeStepsUpToTheCriticalModulus) {
  std::mt19937_64 rng(56);
  std::uniform_real_distribution<double> log_kc2(-17, 0);
  double worst = 0, worst_before = 0;
  int more_steps = 0;
  for (int i = 0; i < 1000000; ++i) {
    const Sample s = sample(rng, std::pow(10.0, log_kc2(rng)));
    const int steps = s.modulus.steps;
    if (steps == 3) continue;  // Boost's to the bit (the test above)
    ++more_steps;
    const double unit = kEps * (1 + std::abs(s.y));
    const auto error = [&](const auto& j, const Functions<long double>& ref) {
      return static_cast<double>(std::max(
                 {std::abs(j.sn - ref.sn), std::abs(j.cn - ref.cn), std::abs(j.dn - ref.dn)})) /
             unit;
    };
    // The references: as many steps in long double, then Boost in long double there.
    worst = std::max(worst, error(jacobi_functions(s.modulus, s.y),
                                  boost_after_steps<long double>(s.modulus, steps, s.y)));
    double y3 = s.y;  // the third modulus's argument
    for (int k = 3; k < steps; ++k) y3 *= 1 + s.modulus.k[k];
    worst_before = std::max(worst_before, error(boost_after_steps<double>(s.modulus, 3, y3),
                                                boost_after_steps<long double>(s.modulus, 3, y3)));
  }
  EXPECT_GT(more_steps, 100000);
  EXPECT_LT(worst, 10) << "before: " << worst_before;
  EXPECT_LE(worst, worst_before) << worst;
  std::printf("worst error / eps (1 + |y|): %.3g (Boost after three steps: %.3g)\n", worst,
              worst_before);
}

// A published value: sn(K/2) = 1 / sqrt(1 + k'), cn(K/2) = sqrt(k' / (1 + k')), dn(K/2) = sqrt(k')
// (DLMF 22.5.2), and at K 1, 0, k'; with K = pi / (2 AGM(1, k')) in long double from k' itself.
TEST(JacobiFunctions, HalfAndQuarterPeriodValuesUpToTheCriticalModulus) {
  for (double kc2 = 0.9; kc2 > 1e-300; kc2 /= 7.3) {
    const JacobiModulus modulus = jacobi_modulus(1 - kc2, kc2);
    const long double kc = std::sqrt(static_cast<long double>(kc2)), quarter = quarter_period(kc2);
    const double y = static_cast<double>(quarter / 2 * modulus.rate);
    const double tolerance = 4 * kEps * (1 + std::abs(y));
    const JacobiValues half = jacobi_functions(modulus, y);
    EXPECT_NEAR(half.sn, static_cast<double>(1 / std::sqrt(1 + kc)), tolerance) << kc2;
    EXPECT_NEAR(half.cn, static_cast<double>(std::sqrt(kc / (1 + kc))), tolerance) << kc2;
    EXPECT_NEAR(half.dn, static_cast<double>(std::sqrt(kc)), tolerance) << kc2;
    const JacobiValues full = jacobi_functions(modulus, 2 * y);
    EXPECT_NEAR(full.sn, 1, 2 * tolerance) << kc2;
    EXPECT_NEAR(full.cn, 0, 2 * tolerance) << kc2;
    EXPECT_NEAR(full.dn, static_cast<double>(kc), 2 * tolerance) << kc2;
  }
}

// Every orbit's modulus but b = b_c's reaches the asymptotic form within kMaxSteps, even b within
// an ulp of b_c on either side, where k'^2 is smallest.
TEST(JacobiFunctions, EveryOrbitsModulusReachesTheAsymptoticForm) {
  const double bc = critical_impact_parameter(1);
  for (int ulps = -8; ulps <= 8; ++ulps) {
    const double b = bc + ulps * bc * kEps;
    const JacobiModulus& m = photon_orbit(1, b).jacobi;
    if (b == bc) {
      EXPECT_TRUE(m.unit);
      continue;
    }
    EXPECT_LT(m.k[m.steps - 1], std::pow(kEps, 0.25)) << ulps << " " << m.kc2;
  }
}

// k = 1 (b = b_c exactly): no step changes it, and the functions are tanh, sech, sech.
TEST(JacobiFunctions, UnitModulusIsTheHyperbolicLimit) {
  const JacobiModulus modulus = jacobi_modulus(1, 0);
  EXPECT_TRUE(modulus.unit);
  for (double y : {0.0, 0.3, -2.0, 20.0}) {
    const JacobiValues j = jacobi_functions(modulus, y);
    const Functions<double> boost = boost_after_steps(modulus, modulus.steps, y);
    EXPECT_EQ(j.sn, boost.sn);
    EXPECT_EQ(j.cn, boost.cn);
    EXPECT_EQ(j.dn, boost.dn);
    EXPECT_NEAR(j.sn, std::tanh(y / modulus.rate), 4 * kEps);
  }
}

}  // namespace
}  // namespace lightcone

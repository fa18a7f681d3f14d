#include "lightcone/physics/carlson_integrals.hpp"

#include <algorithm>
#include <boost/math/special_functions/ellint_rc.hpp>
#include <boost/math/special_functions/ellint_rd.hpp>
#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <utility>

#include "lightcone/physics/math_policy.hpp"

namespace lightcone::carlson {
namespace {

// Boost's duplication runs until its arguments agree, which a NaN or an infinite one never does
// (for a million steps, then an evaluation error): an integral of a NaN argument is NaN, and each
// tends to 0 as one argument grows without bound. Whether `args` settle it so, and its value.
bool settled(std::initializer_list<double> args, double& value) {
  for (const double a : args)
    if (std::isnan(a)) return value = std::numeric_limits<double>::quiet_NaN(), true;
  for (const double a : args)
    if (a == std::numeric_limits<double>::infinity()) return value = 0, true;
  return false;
}

}  // namespace

double rf(double x, double y, double z) {
  double value;
  return settled({x, y, z}, value) ? value : boost::math::ellint_rf(x, y, z, MathPolicy());
}
double rd(double x, double y, double z) {
  double value;
  return settled({x, y, z}, value) ? value : boost::math::ellint_rd(x, y, z, MathPolicy());
}
namespace {

// R_C(1, 1 + e) for |e| <= kSmallTerm, which each of R_J's duplication steps adds: Boost takes an
// arctangent or two logarithms for it every step, but e falls some 64-fold a step, and once
// |e| <= 2^-8 the series sum (-e)^n / (2n + 1) to e^6 leaves under e^7 / 15 < 2^-59 of it.
constexpr double kSmallTerm = 1.0 / 256;
double rc_one_plus_small(double e) {
  return 1 -
         e * (1.0 / 3 - e * (1.0 / 5 - e * (1.0 / 7 - e * (1.0 / 9 - e * (1.0 / 11 - e / 13)))));
}

}  // namespace

// Boost's algorithm for double (ellint_rj_imp: the duplication theorem until 4^-n Q < A_n, then
// its series), operation for operation but for rc_one_plus_small, for four distinct positive
// finite arguments, and its Cauchy principal value for p < 0 from one of them; Boost itself for
// the rest (a zero, equal arguments).
double rj(double x, double y, double z, double p) {
  return rj(x, y, z, p, std::numeric_limits<double>::quiet_NaN());
}

double rj(double x, double y, double z, double p, double rf_xyz) {
  double value;
  if (settled({x, y, z, p}, value)) return value;
  const bool positive = x > 0 && y > 0 && z > 0 && std::isfinite(x) && std::isfinite(y) &&
                        std::isfinite(z) && std::isfinite(p) && x != y && x != z && y != z;
  if (positive && p < 0) {
    // Boost's (DLMF 19.20.14) with x < y < z: R_J at p' = (z (x + y + q) - x y) / (z + q) > 0,
    // q = -p.
    if (x > y) std::swap(x, y);
    if (y > z) std::swap(y, z);
    if (x > y) std::swap(x, y);
    const double q = -p, pp = (z * (x + y + q) - x * y) / (z + q);
    if (std::isnan(rf_xyz)) rf_xyz = rf(x, y, z);
    return ((pp - z) * rj(x, y, z, pp) - 3 * rf_xyz +
            3 * std::sqrt((x * y * z) / (x * y + pp * q)) * rc(x * y + pp * q, pp * q)) /
           (z + q);
  }
  if (!(positive && p > 0 && x != p && y != p && z != p)) {
    return boost::math::ellint_rj(x, y, z, p, MathPolicy());
  }
  static const double kTolerance = std::pow(std::numeric_limits<double>::epsilon() / 5, -1.0 / 8);
  double xn = x, yn = y, zn = z, pn = p;
  double an = (x + y + z + 2 * p) / 5;
  const double a0 = an;
  double delta = (p - x) * (p - y) * (p - z);
  const double q = kTolerance * std::max(std::max(std::abs(an - x), std::abs(an - y)),
                                         std::max(std::abs(an - z), std::abs(an - p)));
  double fmn = 1, rc_sum = 0;
  for (;;) {
    const double rx = std::sqrt(xn), ry = std::sqrt(yn), rz = std::sqrt(zn), rp = std::sqrt(pn);
    const double dn = (rp + rx) * (rp + ry) * (rp + rz);
    double en = delta / dn;
    en /= dn;
    double rc_term;
    if (std::abs(en) <= kSmallTerm) {
      rc_term = rc_one_plus_small(en);
    } else if (en < -0.5 && en > -1.5) {  // 1 + e_n without cancellation, as Boost takes it
      rc_term = rc(1, 2 * rp * (pn + rx * (ry + rz) + ry * rz) / dn);
    } else {
      rc_term = boost::math::detail::ellint_rc1p_imp(en, MathPolicy());
    }
    rc_sum += fmn / dn * rc_term;
    const double lambda = rx * ry + rx * rz + ry * rz;
    an = (an + lambda) / 4;
    fmn /= 4;
    if (fmn * q < an) break;
    xn = (xn + lambda) / 4;
    yn = (yn + lambda) / 4;
    zn = (zn + lambda) / 4;
    pn = (pn + lambda) / 4;
    delta /= 64;
  }
  const double xd = fmn * (a0 - x) / an, yd = fmn * (a0 - y) / an, zd = fmn * (a0 - z) / an;
  const double pd = (-xd - yd - zd) / 2;
  const double e2 = xd * yd + xd * zd + yd * zd - 3 * pd * pd;
  const double e3 = xd * yd * zd + 2 * e2 * pd + 4 * pd * pd * pd;
  const double e4 = (2 * xd * yd * zd + e2 * pd + 3 * pd * pd * pd) * pd;
  const double e5 = xd * yd * zd * pd * pd;
  const double result = fmn * std::pow(an, -3.0 / 2) *
                        (1 - 3 * e2 / 14 + e3 / 6 + 9 * e2 * e2 / 88 - 3 * e4 / 22 -
                         9 * e2 * e3 / 52 + 3 * e5 / 26 - e2 * e2 * e2 / 16 + 3 * e3 * e3 / 40 +
                         3 * e2 * e4 / 20 + 45 * e2 * e2 * e3 / 272 - 9 * (e3 * e4 + e2 * e5) / 68);
  return result + 6 * rc_sum;
}
double rc(double x, double y) {
  double value;
  return settled({x, y}, value) ? value : boost::math::ellint_rc(x, y, MathPolicy());
}

namespace {

// Two doubles and a lane mask (all bits set where true), as vectors of the compiler's (SSE2 on
// x86, SIMD128 in the browser; wider ones were split into scalar comparisons through memory):
// each operation is the scalar one lane by lane, rounded alike.
using Doubles2 = double __attribute__((vector_size(16)));
using Lanes2 = std::int64_t __attribute__((vector_size(16)));
constexpr int kLanes = 2;
static_assert(kMaxBatch % kLanes == 0);

inline Doubles2 sqrt2(Doubles2 v) {
  return Doubles2{std::sqrt(v[0]), std::sqrt(v[1])};
}
inline Doubles2 abs2(Doubles2 v) {  // the sign bit cleared
  return reinterpret_cast<Doubles2>(reinterpret_cast<Lanes2>(v) &
                                    (Lanes2{} + std::numeric_limits<std::int64_t>::max()));
}
// `next` where `keep_old` is false, else `old`.
inline Doubles2 select2(Lanes2 keep_old, Doubles2 old, Doubles2 next) {
  return reinterpret_cast<Doubles2>((reinterpret_cast<Lanes2>(old) & keep_old) |
                                    (reinterpret_cast<Lanes2>(next) & ~keep_old));
}
inline Doubles2 max2(Doubles2 a, Doubles2 b) {  // std::max's: a unless a < b
  return select2(~(a < b), a, b);
}
inline bool any2(Lanes2 m) {
  return (m[0] | m[1]) != 0;
}

}  // namespace

// Boost's algorithm for double (ellint_rf_imp: the duplication theorem until Q / 4^n < |A_n|,
// then its seventh-order series), operation for operation, so that the values are Boost's to the
// bit. The batch runs as vectors of two lanes, all of them in each step, so that the chains of
// square roots (a step's latency, the duplication's whole cost for one argument) overlap; each
// lane stops where its own test says (a settled lane keeps its values while the others go on).
// Arguments that Boost treats apart (a zero, two equal, anything not positive and finite) go to
// Boost itself.
void rf_batch(const RfArgs* args, double* out, int n) {
  static const double kTolerance = std::pow(3 * std::numeric_limits<double>::epsilon(), -1.0 / 8);
  constexpr int kGroups = kMaxBatch / kLanes;
  Doubles2 x[kGroups], y[kGroups], z[kGroups], an[kGroups], q[kGroups], fn[kGroups];
  Doubles2 x0[kGroups], y0[kGroups], a0[kGroups];  // the arguments and their mean
  Lanes2 active[kGroups], general[kGroups];
  const int groups = (n + kLanes - 1) / kLanes;
  // Lanes outside the batch or given to Boost run on harmless values, settled from the start.
  for (int g = 0; g < groups; ++g) {
    x[g] = Doubles2{} + 1, y[g] = Doubles2{} + 2, z[g] = Doubles2{} + 3;
    active[g] = Lanes2{};
  }
  bool any = false;
  for (int i = 0; i < n; ++i) {
    const RfArgs& a = args[i];
    const bool lane_general = a.x > 0 && a.y > 0 && a.z > 0 && std::isfinite(a.x) &&
                              std::isfinite(a.y) && std::isfinite(a.z) && a.x != a.y &&
                              a.x != a.z && a.y != a.z;
    if (!lane_general) {
      out[i] = rf(a.x, a.y, a.z);
      continue;
    }
    const int g = i / kLanes, l = i % kLanes;
    x[g][l] = a.x, y[g][l] = a.y, z[g][l] = a.z;
    active[g][l] = -1;
    any = true;
  }
  if (!any) return;
  for (int g = 0; g < groups; ++g) {
    general[g] = active[g];
    an[g] = (x[g] + y[g] + z[g]) / 3;
    q[g] = kTolerance * max2(max2(abs2(an[g] - x[g]), abs2(an[g] - y[g])), abs2(an[g] - z[g]));
    fn[g] = Doubles2{} + 1;
    x0[g] = x[g], y0[g] = y[g], a0[g] = an[g];
  }
  while (any) {
    any = false;
    for (int g = 0; g < groups; ++g) {
      if (!any2(active[g])) continue;
      const Doubles2 rx = sqrt2(x[g]), ry = sqrt2(y[g]), rz = sqrt2(z[g]);
      const Doubles2 lambda = rx * ry + rx * rz + ry * rz;
      const Lanes2 settled = ~active[g];
      an[g] = select2(settled, an[g], (an[g] + lambda) / 4);
      x[g] = select2(settled, x[g], (x[g] + lambda) / 4);
      y[g] = select2(settled, y[g], (y[g] + lambda) / 4);
      z[g] = select2(settled, z[g], (z[g] + lambda) / 4);
      q[g] = select2(settled, q[g], q[g] / 4);
      fn[g] = select2(settled, fn[g], fn[g] * 4);
      active[g] &= ~(q[g] < abs2(an[g]));
      any |= any2(active[g]);
    }
  }
  for (int g = 0; g < groups; ++g) {
    const Doubles2 dx = (a0[g] - x0[g]) / (an[g] * fn[g]), dy = (a0[g] - y0[g]) / (an[g] * fn[g]);
    const Doubles2 dz = -dx - dy;
    const Doubles2 e2 = dx * dy - dz * dz, e3 = dx * dy * dz;
    const Doubles2 value =
        (1 + e3 * (1.0 / 14 + 3 * e3 / 104) +
         e2 * (-1.0 / 10 + e2 / 24 - (3 * e3) / 44 - 5 * e2 * e2 / 208 + e2 * e3 / 16)) /
        sqrt2(an[g]);
    for (int l = 0; l < kLanes && kLanes * g + l < n; ++l)
      if (general[g][l]) out[kLanes * g + l] = value[l];
  }
}

double cubic_integral(double d, const LinearFactors& x, const LinearFactors& y) {
  if (d == 0) return 0;
  const RfArgs u = cubic_args(d, roots(x), roots(y));
  return 2 * rf(u.x, u.y, u.z);
}

RealCubic real_cubic(double dx, const LinearFactors& fx, const LinearFactors& fy, double d12,
                     double d13, double b1) {
  RealCubic c{};
  c.x = roots(fx), c.y = roots(fy);
  const RfArgs u = cubic_args(dx, c.x, c.y);
  c.u1s = u.z, c.u2s = u.y, c.u3s = u.x;
  c.d12 = d12, c.d13 = d13, c.b1 = b1;
  c.rf = rf(c.u1s, c.u2s, c.u3s);
  return c;
}
// int_y^x dw / sqrt(L1 L2 L3) = 2 R_F.
double first_kind(const RealCubic& c) {
  return 2 * c.rf;
}
// int_y^x sqrt(L1) dw / sqrt(L2 L3) = (2/3) d12 d13 R_D(U3^2, U2^2, U1^2) + 2 X1 Y1 / U1.
double second_kind(const RealCubic& c) {
  return 2.0 / 3 * c.d12 * c.d13 * rd(c.u3s, c.u2s, c.u1s) + 2 * c.x.s1 * c.y.s1 / std::sqrt(c.u1s);
}

namespace {

// 2 R_C(P^2, Q^2), Q^2 = (X4 Y4 / (X1 Y1))^2 W^2, or, when `regular` (Y4 = 0: the pole at the
// lower limit), its finite part 2 R_C + ln(Y4^2) / P as Y4 -> 0, which is
// (2/P) (ln 2P - ln |X4 W / (X1 Y1)|) with P^2 = pq (Q^2 -> 0); both signs of W^2 alike (a
// negative Q^2 is R_C's Cauchy principal value, DLMF 19.2.20, with the same limit).
double pole_rc(double w2, double x4s, double y4s, double x1y1s, double pq, bool regular) {
  if (regular) {
    const double p = std::sqrt(pq);
    return 2 / p * (std::log(2 * p) - 0.5 * std::log(x4s * std::abs(w2) / x1y1s));
  }
  const double q2 = x4s * y4s / x1y1s * w2;
  return 2 * rc(q2 + pq, q2);
}

}  // namespace

// int_y^x dw / (L4 sqrt(L1 L2 L3)) (Carlson 1989): with W^2 = U1^2 - b4 d12
// d13 / d14, Q^2 = (X4 Y4 / (X1 Y1))^2 W^2, P^2 = Q^2 + b4 d24 d34 / d14,
//   I3 = 2 R_C(P^2, Q^2) - (2 b1 d12 d13 / 3 d14) R_J(U3^2, U2^2, U1^2, W^2)
// is int (L1 / L4) / sqrt(L1 L2 L3), and the integral is (b4 I3 - b1 I1) / d14. `regular`: the
// pole is at y (L4(y) = 0, only used with L4 = w at w = 0, where the integrand is 1/w + O(1)), and
// what comes back is the finite limit of the integral + ln(L4(y)) (see pole_rc: the factor
// b4 / (d14 P) in front of the logarithm is 1 there, since P(w = 0) = 1).
double third_kind(const RealCubic& c, const Pole& p, bool regular) {
  const double w2 = c.u1s - p.b4 * c.d12 * c.d13 / p.d14;
  const double x1y1s = c.x.s1 * c.x.s1 * c.y.s1 * c.y.s1;
  const double i3 = pole_rc(w2, p.l4x, p.l4y, x1y1s, p.b4 * p.d24 * p.d34 / p.d14, regular) -
                    2 * c.b1 * c.d12 * c.d13 / (3 * p.d14) * rj(c.u3s, c.u2s, c.u1s, w2, c.rf);
  return (p.b4 * i3 - c.b1 * first_kind(c)) / p.d14;
}

QuadraticCubic quadratic_cubic(double x, double y, double c, double n) {
  QuadraticCubic k{};
  const double dx = x - y, a = std::hypot(c, n);
  k.x1 = std::sqrt(x), k.y1 = std::sqrt(y);
  const double xc = x - c, yc = y - c;
  k.xi = std::sqrt(xc * xc + n * n), k.eta = std::sqrt(yc * yc + n * n);
  // (xi + eta)^2 - dx^2 = 2 (xi eta + (x - c)(y - c) + n^2); when c lies between x and y the
  // first two nearly cancel (b -> b_c), and xi eta - |(x-c)(y-c)| is written as a quotient.
  const double prod = xc * yc;
  const double sum =
      prod >= 0 ? k.xi * k.eta + prod : n * n * (xc * xc + yc * yc + n * n) / (k.xi * k.eta - prod);
  const double s = 2 * (sum + n * n);
  k.m2 = (k.x1 + k.y1) * (k.x1 + k.y1) * s / (dx * dx);
  // L_+-^2 = M^2 - beta1 +- sqrt(2h) c11 with beta1 = -2c, c11 = sqrt(2) A; A - c = n^2/(A + c).
  k.lp2 = k.m2 + 2 * (a + c);
  k.lm2 = k.m2 - 2 * n * n / (a + c);
  k.u = (k.x1 * k.eta + k.y1 * k.xi) / dx;
  k.a = a, k.c = c;
  k.rf = rf(k.m2, k.lm2, k.lp2);
  return k;
}
// int_y^x dz / sqrt(z q) = 4 R_F(M^2, L_-^2, L_+^2).
double first_kind(const QuadraticCubic& k) {
  return 4 * k.rf;
}
// int_y^x z^(-3/2) q^(-1/2) dz = (2/3) (sqrt(2h) / c11) (4 rho R_D(M^2, L_-^2, L_+^2) - 6 R_F +
// 3 / U) + 2 / (X1 Y1 U), rho = sqrt(2h) c11 - beta1 = 2 (A + c) (Carlson 1991).
double second_kind(const QuadraticCubic& k) {
  const double rho = 2 * (k.a + k.c);
  return 2.0 / 3 / k.a * (4 * rho * rd(k.m2, k.lm2, k.lp2) - 6 * k.rf + 3 / k.u) +
         2 / (k.x1 * k.y1 * k.u);
}
// int_y^x dz / (L4 sqrt(z q)), L4 = a4 + b4 z (Carlson 1991): with d14 = -a4,
// c44^2 = 2 (f b4^2 - g a4 b4 + h a4^2), c14^2 = 2 f b4 - g a4, W_+^2 = M^2 - (c14^2 + c11 c44) /
// d14, W^2 = U^2 - c11^2 b4 / (2 d14), Q^2 = (X4 Y4 / (X1 Y1))^2 W^2, P^2 = Q^2 + c44^2 b4 /
// (2 d14),
//   I3 = (2 c11 / 3 c44) ((-4 / d14)(c14^2 + c11 c44) R_J(M^2, L_-^2, L_+^2, W_+^2) - 6 R_F
//        + 3 R_C(U^2, W^2)) + 2 R_C(P^2, Q^2),
// and the integral is (b4 I3 - I1) / d14. `regular` as for the real case.
double third_kind(const QuadraticCubic& k, double a4, double b4, double l4x, double l4y,
                  bool regular) {
  const double a = k.a, c = k.c, d14 = -a4;
  const double c11 = std::sqrt(2.0) * a;
  const double c44 = std::sqrt(2 * (a * a * b4 * b4 + 2 * c * a4 * b4 + a4 * a4));
  const double c14s = 2 * a * a * b4 + 2 * c * a4;
  const double wp2 = k.m2 - (c14s + c11 * c44) / d14;
  const double w2 = k.u * k.u - c11 * c11 * b4 / (2 * d14);
  const double x1y1s = k.x1 * k.x1 * k.y1 * k.y1;
  const double i3 = 2 * c11 / (3 * c44) *
                        (-4 / d14 * (c14s + c11 * c44) * rj(k.m2, k.lm2, k.lp2, wp2, k.rf) -
                         6 * k.rf + 3 * rc(k.u * k.u, w2)) +
                    pole_rc(w2, l4x, l4y, x1y1s, c44 * c44 * b4 / (2 * d14), regular);
  return (b4 * i3 - first_kind(k)) / d14;
}

}  // namespace lightcone::carlson

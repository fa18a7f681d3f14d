#include "lightcone/physics/schwarzschild.hpp"

#include <algorithm>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <boost/math/tools/precision.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "lightcone/physics/carlson_integrals.hpp"
#include "lightcone/physics/math_policy.hpp"

namespace lightcone {
namespace {

using namespace carlson;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSqrt3 = std::numbers::sqrt3;

// w = b / r, 0 at infinity.
double w_of(const PhotonOrbit& o, double r) {
  return std::isinf(r) ? 0.0 : o.impact / r;
}

// Turning orbit: 1 - w^2 + 2 (M/b) w^3 = scale (w - w_1) (w_2 - w) (1 - w / w_3) with
// w_2 = b / r_p, w_3 = b / r_3. The three factors at radius r, each as a ratio that stays
// accurate near its root, and exact at the turning points themselves. In the inner region
// (r <= r_3) the last two change sign.
LinearFactors turning_factors(const PhotonOrbit& o, double r, bool inner) {
  const double w2 = 1 / o.v_pos;
  LinearFactors f{w_of(o, r) + o.w_neg, 0, 0};
  if (!inner) {
    f.f2 = r == o.periapsis ? 0.0 : w2 * (1 - o.periapsis / r);
    f.f3 = r == o.periapsis ? o.v_gap / o.v_pos : 1 - o.inner_turning / r;
  } else {
    const double v3 = o.v_pos - o.v_gap;
    f.f2 = r == o.inner_turning ? w2 * o.v_gap / v3 : w2 * (o.periapsis / r - 1);
    f.f3 = r == o.inner_turning ? 0.0 : o.inner_turning / r - 1;
  }
  return f;
}

// Captured orbit (b <= b_c): one real root w_1 < 0, and 1 - w^2 + 2 (M/b) w^3 =
// (2M/b) z ((z - c)^2 + n^2) with z = w - w_1 > 0 (c, n: pair_c, pair_n). Byrd & Friedman (1971)
// 239.00 give int_0^z = F(phi, k) / sqrt(A), cos(phi) = (A - z) / (A + z), A^2 = c^2 + n^2; written
// with R_F (Carlson 1995, F = sin(phi) R_F(cos^2 phi, 1 - k^2 sin^2 phi, 1)) for z <= A (phi <=
// pi/2) it is 2 sqrt(z) R_F((A - z)^2, (A - z)^2 + 4 k'^2 A z, (A + z)^2). Past A, phi -> pi -
// phi is z -> A^2 / z, and F(pi - phi) = 2K - F(phi).
// That integral at up to kMaxHalves values z (the two or three terms of an integral between two
// radii and a sweep's start), in two halves so that several rays' R_F can run in one batch:
// half_args appends their R_F's arguments to a batch, half_values reads the batch's results.
constexpr int kMaxHalves = 4;
struct Halves {
  int n = 0;
  double z[kMaxHalves];
  int slot[kMaxHalves];  // the R_F's place in the batch, -1 where the integral is infinite
};
void half_args(const PhotonOrbit& o, Halves& h, RfArgs* args, int& used) {
  const double a = o.quad_a;
  for (int i = 0; i < h.n; ++i) {
    h.slot[i] = -1;
    if (h.z[i] == a && o.modulus_c2 == 0) continue;  // b = b_c: the double root r = 3M
    const double d = (a - h.z[i]) * (a - h.z[i]);
    args[used] = {d, d + 4 * o.modulus_c2 * a * h.z[i], (a + h.z[i]) * (a + h.z[i])};
    h.slot[i] = used++;
  }
}
void half_values(const Halves& h, const double* rfs, double* out) {
  for (int i = 0; i < h.n; ++i)
    out[i] = h.slot[i] < 0 ? kInf : 2 * std::sqrt(h.z[i]) * rfs[h.slot[i]];
}

// The integral between za and zb from two or three half-integrals, and with `with_half` also the
// half-integral at z = at (another term of the batch, or one of those when it is the same z).
struct CapturedPlan {
  Halves halves;
  int extra = -1;  // the term at `at`
  bool empty = false, straddles = false;
};
CapturedPlan captured_plan(const PhotonOrbit& o, double za, double zb, bool with_half, double at) {
  CapturedPlan p;
  const double a = o.quad_a;
  const double lo = std::min(za, zb), hi = std::max(za, zb);
  double* z = p.halves.z;
  int& n = p.halves.n;
  p.empty = lo == hi;
  p.straddles = !(hi <= a || lo >= a);
  if (!p.empty) {
    if (hi <= a) {
      z[0] = hi, z[1] = lo, n = 2;
    } else if (lo >= a) {
      z[0] = a * a / lo, z[1] = a * a / hi, n = 2;
    } else {
      z[0] = a, z[1] = lo, z[2] = a * a / hi, n = 3;
    }
  }
  if (with_half) {
    for (int i = 0; i < n; ++i)
      if (z[i] == at) p.extra = i;
    if (p.extra < 0) z[p.extra = n++] = at;
  }
  return p;
}
double captured_value(const CapturedPlan& p, const double* h, double* half_at) {
  if (half_at) *half_at = h[p.extra];
  if (p.empty) return 0;
  if (!p.straddles) return h[0] - h[1];
  return (h[0] - h[1]) + (h[0] - h[2]);  // (K - F(lo)) + (K - F(A^2 / hi))
}
void half_integrals(const PhotonOrbit& o, Halves& h, double* out) {
  RfArgs args[kMaxHalves] = {};
  double rfs[kMaxHalves];
  int used = 0;
  half_args(o, h, args, used);
  rf_batch(args, rfs, used);
  half_values(h, rfs, out);
}
double captured_integral(const PhotonOrbit& o, double za, double zb, double* half_at = nullptr,
                         double at = 0) {
  CapturedPlan p = captured_plan(o, za, zb, half_at != nullptr, at);
  double h[kMaxHalves];
  half_integrals(o, p.halves, h);
  return captured_value(p, h, half_at);
}

// A radius in the forbidden gap (r_3, r_p) whose orbit equation 1 - w^2 + 2 (M/b) w^3 fails
// only by rounding (a ray sent tangentially, b = r / sqrt(f) computed with a few ulps of error)
// is the nearer turning point; any other radius is returned as it is.
double snap_to_turning_point(const PhotonOrbit& o, double r) {
  if (!(r > o.inner_turning && r < o.periapsis)) return r;
  const double w = o.impact / r, cubic = 2 * o.mass / o.impact * w * w * w;
  const double residual = 1 - w * w + cubic;
  if (residual < -16 * std::numeric_limits<double>::epsilon() * (1 + w * w + cubic)) return r;
  return r - o.inner_turning < o.periapsis - r ? o.inner_turning : o.periapsis;
}

// --- Coordinate time along a ray ---
//
// With w = b/r, dt/dphi = r^2 / (b f) and dphi = dw / sqrt(P(w)), P = 1 - w^2 + e w^3, e = 2M/b:
//   t = b int dw / (w^2 (1 - e w) sqrt(P)),  1 / (w^2 (1 - e w)) = 1/w^2 + e/w + e^2/(1 - e w),
// and d/dw (sqrt(P) / w) = -1 / (w^2 sqrt(P)) + (e/2) w / sqrt(P) turns the double pole into a
// boundary term. Between w_lo < w_hi (radii r_lo = b/w_lo > r_hi = b/w_hi):
//   t = r_lo sqrt(P(w_lo)) - r_hi sqrt(P(w_hi)) + M J1 + 2M J2 + (4M^2/b) J3,
//   J1 = int w dw / sqrt(P),  J2 = int dw / (w sqrt(P)),  J3 = int dw / ((1 - e w) sqrt(P)):
// a second-kind integral and two of the third kind, with poles at infinity (w = 0) and at the
// horizon (w = 1/e), where P = 1.

// The radial tortoise coordinate r_* = r + 2M ln(r/2M - 1).
double tortoise(double m, double r) {
  return m == 0 ? r : r + 2 * m * std::log((r - 2 * m) / (2 * m));
}

// The time between w_lo < w_hi (r_lo > r_hi, both > 2M) on one stretch; `regular`: w_lo = 0
// and the answer is lim [t - r_*(R)] as R -> infinity (see coordinate_time_to_infinity).
double ray_time(const PhotonOrbit& o, double r_lo, double r_hi, bool inner, bool regular) {
  const double m = o.mass, b = o.impact, e = 2 * m / b;
  const double w_lo = w_of(o, r_lo), w_hi = w_of(o, r_hi), dx = w_hi - w_lo;
  const double f_lo = regular ? 1.0 : 1 - 2 * m / r_lo, f_hi = 1 - 2 * m / r_hi;
  double sqrt_p_lo = 1, sqrt_p_hi, j1, j2, j3;
  if (o.turning) {
    const LinearFactors fx = turning_factors(o, r_hi, inner), fy = turning_factors(o, r_lo, inner);
    const double w2 = 1 / o.v_pos, inv_w3 = o.inner_turning / b, s = inner ? -1.0 : 1.0;
    // L1 = w + w_neg, L2 = s (w2 - w), L3 = s (1 - w / w3).
    const double a1 = o.w_neg, a2 = s * w2, a3 = s;
    const RealCubic c = real_cubic(dx, fx, fy, -s * (a1 + w2), -s * (a1 * inv_w3 + 1), 1);
    const double root_scale = std::sqrt(o.scale);
    sqrt_p_hi = root_scale * std::sqrt(fx.f1 * fx.f2 * fx.f3);
    if (!regular) sqrt_p_lo = root_scale * std::sqrt(fy.f1 * fy.f2 * fy.f3);
    j1 = (second_kind(c) - o.w_neg * first_kind(c)) / root_scale;
    // The pole at infinity, L4 = w: d_i4 = a_i. At the horizon, L4 = 1 - e w: d_i4 = -e a_i -
    // b_i, i.e. -(1 + e w_neg), s f(r_p), s (r_3 - 2M) / b.
    j2 = third_kind(c, {1, w_hi, w_lo, a1, a2, a3}, regular) / root_scale;
    j3 = third_kind(c,
                    {-e, f_hi, f_lo, -(1 + e * a1), s * (1 - 2 * m / o.periapsis),
                     s * (o.inner_turning - 2 * m) / b},
                    false) /
         root_scale;
  } else {
    // P = e z q(z), z = w + w_neg, q = (z - c)^2 + n^2.
    const double c = o.pair_c, n = o.pair_n, z_hi = w_hi + o.w_neg, z_lo = w_lo + o.w_neg;
    const QuadraticCubic k = quadratic_cubic(z_hi, z_lo, c, n);
    const double root_e = std::sqrt(e);
    sqrt_p_hi = root_e * k.x1 * k.xi;
    if (!regular) sqrt_p_lo = root_e * k.y1 * k.eta;
    // d/dw (sqrt(P) / z) = (e z - e A^2 / z) / (2 sqrt(P)) gives int z / sqrt(P).
    const double i1 = first_kind(k);
    j1 = 2 / root_e * (k.xi / k.x1 - k.eta / k.y1) +
         (k.a * k.a * second_kind(k) - o.w_neg * i1) / root_e;
    // w = z - w_neg; 1 - e w = (1 + e w_neg) - e z.
    j2 = third_kind(k, -o.w_neg, 1, w_hi, w_lo, regular) / root_e;
    j3 = third_kind(k, 1 + e * o.w_neg, -e, f_hi, f_lo, false) / root_e;
  }
  const double middle = m * j1 + 2 * m * j2 + 4 * m * m / b * j3;
  if (regular) return -r_hi * sqrt_p_hi + middle + 2 * m * std::log(e);
  return r_lo * sqrt_p_lo - r_hi * sqrt_p_hi + middle;
}

// --- The path r(phi): radius_after_angle ---
//
// In w = b/r, (dw/dphi)^2 = P(w) = 1 - w^2 + e w^3 (e = 2M/b). Each form measures its argument
// from an end of the cubic's interval that the ray never reaches (w = w_1 < 0, or w = infinity),
// so that the Jacobi functions it needs are never small where the radius depends on them, and the
// argument at r0 is a Carlson integral from that end.
//
// b > b_c: P = e (w - w_1)(w - w_2)(w - w_3), w_1 < 0 < w_2 <= w_3. Outer region (the ray lives
// on 0 <= w <= w_2): Byrd & Friedman (1971) 233.00, w = w_1 + (w_2 - w_1) sn^2(x, k) with
// k^2 = (w_2 - w_1) / (w_3 - w_1) and dphi = dx / c, c = sqrt(e (w_3 - w_1)) / 2, x the angle from
// w_1 times c; that is
//   w = w_2 sn^2(x) - (-w_1) cn^2(x),  r = r_p / (sn^2 - (-w_1)(r_p / b) cn^2),
// with the periapsis at x = K and the ray escaping where w = 0 on either side. M = 0: k = 0,
// c = 1/2, w_1 = -1 and w = -cos(2x), the straight line r = r_p / cos(psi), psi = 2x - pi the angle
// from the periapsis. Inner region (w >= w_3): with sn^2(x) = (w_3 - w_1) / (w - w_1) and the
// same k, w - w_2 = (w_3 - w_1) dn^2 / sn^2 and w - w_3 = (w_3 - w_1) cn^2 / sn^2, so dphi = dx / c
// again, x is c times the angle from w = infinity (r = 0), x = K at r_3, and
//   w = w_3 + (-w_1) cn^2 / sn^2,  r = r_3 sn^2 / (1 + (-w_1)(r_3 / b) cn^2).
// Both are even about x = K, so the argument runs straight through the turning point.
//
// b <= b_c: P = e z ((z - c')^2 + n^2), z = w - w_1 >= 0 (pair_c, pair_n): 239.00, cn(u, k) =
// (A - z) / (A + z), k^2 = (A + c') / 2A, u = sqrt(e A) times the angle from z = 0, so
//   z = A (1 - cn u) / (1 + cn u) = A sn^2 / (1 + cn)^2 = A (1 - cn)^2 / sn^2,
// the form without cancellation taken by the sign of cn. From z = infinity instead (the ray
// starting inside z > A, and b = b_c exactly, where u = infinity at the photon sphere z = A): the
// same with cn -> -cn gives z, since the integral is symmetric under z -> A^2 / z.
//
// As b -> b_c, k -> 1 and K grows like ln(1/k'); Boost's sn, cn, dn take k alone and rebuild k'
// from it, losing eps / k'^2 (k'^2 ~ sqrt(1 - b_c/b) above b_c, ~ (1 - b/b_c) below), which
// shifts the path's phase by that much. So they are taken through descending Landen (Gauss)
// transformations (DLMF 22.7.1-4) with k' from the roots' gaps: k_1 = (1 - k') / (1 + k'),
// k_1' = 2 sqrt(k') / (1 + k'), and from the functions of (y = x / (1 + k_1), k_1), with
// N = 1 + k_1 sn^2,
//   sn(x, k) = (1 + k_1) sn / N,  cn(x, k) = cn dn / N,  dn(x, k) = (cn^2 + (1 - k_1) sn^2) / N
// (the last is (1 - k_1 sn^2) / N without cancellation). The steps go on from the exact k' down to
// a modulus small enough for sin and cos with their terms in k^2 (jacobi_modulus), which are
// Boost's own last steps: the moduli are the arithmetic-geometric mean that Boost would run on
// every call, here once per orbit, and each evaluation is one sine and cosine and a division or
// so per step, where Boost's takes a sine and an arcsine per level.

// One Landen step up: from the functions of modulus k_1 (1 - k_1 = c_1) at x / (1 + k_1) to those
// of k at x.
JacobiValues landen_up(const JacobiValues& j, double k1, double c1) {
  const double s2 = j.sn * j.sn, n = 1 + k1 * s2;
  return {(1 + k1) * j.sn / n, j.cn * j.dn / n, (j.cn * j.cn + c1 * s2) / n};
}

// At least this many Landen steps, though a modulus far from 1 needs fewer: radius_after_angle
// took three before Boost's jacobi_elliptic at the third modulus, and so its values stay the same
// to the bit wherever Boost took its asymptotic form there.
constexpr int kMinLandenSteps = 3;

// Below this modulus Boost's jacobi_elliptic takes sin and cos with their terms in k^2 (A&S 16.13).
const double kAsymptoticModulus = boost::math::tools::forth_root_epsilon<double>();

}  // namespace

namespace {

// jacobi_modulus's arguments, for moduli taken together.
struct ModulusArgs {
  double k2, kc2, rate;
};

// jacobi_modulus for n moduli, step by step over all of them: each step's division and square
// roots wait on the step before, and the moduli's chains overlap where one's alone would wait.
void jacobi_moduli(const ModulusArgs* args, JacobiModulus* const* out, int n) {
  double k2[kMaxSweeps], kc[kMaxSweeps], rate[kMaxSweeps];
  bool going[kMaxSweeps];
  for (int i = 0; i < n; ++i) {
    JacobiModulus& m = *out[i];
    m = JacobiModulus{};
    m.unit = args[i].kc2 == 0;
    m.k2 = args[i].k2, m.kc2 = args[i].kc2;
    k2[i] = args[i].k2, rate[i] = args[i].rate;
    kc[i] = std::sqrt(args[i].kc2);
    going[i] = true;
  }
  for (bool any = n > 0; any;) {
    any = false;
    for (int i = 0; i < n; ++i) {
      if (!going[i]) continue;
      JacobiModulus& m = *out[i];
      const double inv = 1 / (1 + kc[i]);
      m.k[m.steps] = k2[i] * inv * inv;  // (1 - k') / (1 + k'), 1 - k' = k^2 / (1 + k')
      m.c[m.steps] = 2 * kc[i] * inv;
      rate[i] *= (1 + kc[i]) / 2;  // / (1 + k_i), 1 + k_i = 2 / (1 + k')
      k2[i] = m.k[m.steps] * m.k[m.steps];
      kc[i] = 2 * std::sqrt(kc[i]) * inv;  // k_i'
      ++m.steps;
      going[i] = m.steps < kMinLandenSteps || (!m.unit && m.k[m.steps - 1] >= kAsymptoticModulus &&
                                               m.steps < JacobiModulus::kMaxSteps);
      if (!going[i]) m.rate = rate[i];
      any |= going[i];
    }
  }
}

}  // namespace

JacobiModulus jacobi_modulus(double k2, double kc2, double rate) {
  JacobiModulus m;
  JacobiModulus* const out = &m;
  const ModulusArgs args{k2, kc2, rate};
  jacobi_moduli(&args, &out, 1);
  return m;
}

JacobiValues jacobi_functions(const JacobiModulus& m, double y) {
  JacobiValues j;
  const double last = m.k[m.steps - 1];
  if (m.unit) {
    j.sn = std::tanh(y);
    j.cn = j.dn = 1 / std::cosh(y);
  } else if (last >= kAsymptoticModulus) {  // k'^2 below some 1e-20 (see kMaxSteps)
    j.sn = boost::math::jacobi_elliptic(last, y, &j.cn, &j.dn, MathPolicy());
  } else {
    // Boost's asymptotic form (A&S 16.13), operation for operation.
    const double q = last * last, s = std::sin(y), c = std::cos(y);
    j.dn = 1 - q * s * s / 2;
    j.cn = c + q * (y - s * c) * s / 4;
    j.sn = s - q * (y - s * c) * c / 4;
  }
  for (int i = m.steps - 1; i >= 0; --i) j = landen_up(j, m.k[i], m.c[i]);
  if (m.steps > kMinLandenSteps) {
    // Where cn and dn are near 1 each step up adds their errors (cn dn / N), doubling them, while
    // sn's stay a fraction of an ulp; past three steps cn and dn are taken from sn instead,
    // cn^2 = (1 - sn)(1 + sn) (exact factors) unless cn is so small that sn's error would
    // dominate, and dn^2 = k'^2 + k^2 cn^2, terms that cannot cancel.
    if (j.sn * j.sn <= 0.99) j.cn = std::copysign(std::sqrt((1 - j.sn) * (1 + j.sn)), j.cn);
    j.dn = std::sqrt(m.kc2 + m.k2 * j.cn * j.cn);
  }
  return j;
}

double critical_impact_parameter(double mass) {
  return 3 * kSqrt3 * mass;
}

namespace {

// photon_orbit but for its Landen moduli, whose arguments it gives (false for b = 0, which has
// none), so that several orbits' can be taken together.
bool orbit_before_modulus(double mass, double impact, PhotonOrbit& o, ModulusArgs& modulus) {
  o = PhotonOrbit{};
  o.mass = mass;
  o.impact = impact;
  if (impact == 0) return false;  // radial: no angle is swept
  const double bc = critical_impact_parameter(mass);
  const double gap = (impact - bc) / impact;  // 1 - b_c / b, without cancellation
  o.critical = gap == 0;
  if (gap > 0) {
    // arccos(b_c / b) = 2 arcsin(sqrt(gap / 2)), accurate as b -> b_c.
    const double a = 2 * std::asin(std::sqrt(gap / 2)) / 3;
    o.turning = true;
    // a in [0, pi/6]: (2/sqrt 3) cos(pi/3 - a) = cos(a) / sqrt 3 + sin(a), a sum of positive terms,
    // so one sine and cosine serve all three.
    const double sin_a = std::sin(a), cos_a = std::cos(a);
    o.v_pos = cos_a / kSqrt3 + sin_a;
    const double v_neg = 2 / kSqrt3 * cos_a;  // |v_1|
    o.v_gap = 2 * sin_a;                      // v_p - v_3, by the cosines' difference
    // v_3 from the roots' product v_p v_3 v_1 = -2M/b, accurate as M/b -> 0.
    const double v3 = 2 * mass / impact / (o.v_pos * v_neg);
    o.w_neg = 1 / v_neg;
    o.scale = o.v_pos * v_neg;
    o.periapsis = impact * o.v_pos;
    o.inner_turning = impact * v3;
    // radius_after_angle: k^2 = (w_2 - w_1) / (w_3 - w_1), k'^2 = (w_3 - w_2) / (w_3 - w_1), the
    // argument's rate sqrt((M/b)(w_3 - w_1) / 2) (schwarzschild.cpp, "The path r(phi)").
    const double spread = 1 + o.w_neg * v3;  // (w_3 - w_1) / w_3
    modulus = {(1 / o.v_pos + o.w_neg) * v3 / spread, o.v_gap / o.v_pos / spread,
               std::sqrt(o.scale * spread) / 2};
    return true;
  }
  // One real root v_1 = -(2/sqrt 3) cosh(h), 3h = arccosh(b_c / b) = 2 asinh(sqrt(-gap / 2)),
  // and the pair v = -v_1/2 +- i sinh(h) (the roots sum to 0); in w = 1/v the pair is m +- i n.
  const double h = 2 * std::asinh(std::sqrt(-gap / 2)) / 3;
  const double x = std::cosh(h) / kSqrt3, y = std::sinh(h);
  const double norm = x * x + y * y;
  const double m = x / norm, n = y / norm;
  o.w_neg = 1 / (2 * x);
  o.scale = 2 * mass / impact;
  const double c = o.w_neg + m;  // the z of the pair's real part, -(w_1 - m)
  o.pair_c = c, o.pair_n = n;
  o.quad_a = std::hypot(c, n);
  o.modulus_c2 = n * n / (2 * o.quad_a * (o.quad_a + c));  // (A - c') / 2A, no cancellation
  // radius_after_angle: k^2 = (A + c) / 2A, and the argument of Byrd & Friedman 239.00 is
  // sqrt(2 (M/b) A) per radian.
  modulus = {(o.quad_a + c) / (2 * o.quad_a), o.modulus_c2, std::sqrt(o.scale * o.quad_a)};
  return true;
}

}  // namespace

void photon_orbits(double mass, const double* impacts, PhotonOrbit* const* out, int n) {
  ModulusArgs args[kMaxSweeps];
  JacobiModulus* moduli[kMaxSweeps];
  int m = 0;
  for (int i = 0; i < n; ++i)
    if (orbit_before_modulus(mass, impacts[i], *out[i], args[m])) moduli[m++] = &out[i]->jacobi;
  jacobi_moduli(args, moduli, m);
}

PhotonOrbit photon_orbit(double mass, double impact) {
  PhotonOrbit o;
  PhotonOrbit* const out = &o;
  photon_orbits(mass, &impact, &out, 1);
  return o;
}

double swept_angle(const PhotonOrbit& o, double r_a, double r_b) {
  if (o.impact == 0 || r_a == r_b) return 0;
  if (o.turning) {
    r_a = snap_to_turning_point(o, r_a), r_b = snap_to_turning_point(o, r_b);
    if (r_a == r_b) return 0;  // both at one turning point
    const bool inner = r_a <= o.inner_turning;
    const auto in_region = [&](double r) {
      return inner ? r <= o.inner_turning : r >= o.periapsis;
    };
    if (!in_region(r_a) || !in_region(r_b)) return kNaN;
    const LinearFactors x = turning_factors(o, r_a, inner), y = turning_factors(o, r_b, inner);
    const double d = std::abs(w_of(o, r_a) - w_of(o, r_b));
    return cubic_integral(d, x, y) / std::sqrt(o.scale);
  }
  const double za = w_of(o, r_a) + o.w_neg, zb = w_of(o, r_b) + o.w_neg;
  return captured_integral(o, za, zb) / std::sqrt(o.scale);
}

namespace {

// ray_course for a turning orbit from r0 (snapped to a turning point) at or beyond the periapsis,
// and with from_end also prepare_sweep's integral from w = w_1 to r0 (kOuter; not yet divided by
// sqrt(scale)). The integrals are swept_angle's, term for term, but they share the factors' square
// roots at r0 and at the periapsis, and their R_F run together: outer_args appends their arguments
// to a batch (perhaps several rays'), outer_course_of reads the batch's results.
struct OuterSlots {
  int to_turn = -1, beyond = -1, from_end = -1;  // places in the batch (-1: none)
};
OuterSlots outer_args(const PhotonOrbit& o, double r0, bool outward, bool with_from_end,
                      RfArgs* args, int& n) {
  OuterSlots s;
  const double w0 = w_of(o, r0), w_p = w_of(o, o.periapsis);
  const LinearFactors f0 = turning_factors(o, r0, false);
  const LinearFactors fp = turning_factors(o, o.periapsis, false),
                      fi = turning_factors(o, kInf, false);
  const FactorRoots at_r0 = roots(f0), at_inf = roots(fi);
  // Outward r0 -> inf; inward r0 -> r_p and r_p -> inf; then from_end.
  if (outward) {
    if (w0 != 0) args[s.beyond = n++] = cubic_args(w0, at_r0, at_inf);
  } else {
    const FactorRoots at_p = roots(fp);
    const double d = std::abs(w0 - w_p);
    if (r0 != o.periapsis && d != 0) args[s.to_turn = n++] = cubic_args(d, at_r0, at_p);
    args[s.beyond = n++] = cubic_args(w_p, at_p, at_inf);
  }
  if (with_from_end) {
    const double v3 = o.inner_turning / o.impact;
    args[s.from_end = n++] =
        cubic_args(f0.f1, at_r0, roots({0, 1 / o.v_pos + o.w_neg, 1 + o.w_neg * v3}));
  }
  return s;
}
RayCourse outer_course_of(const PhotonOrbit& o, bool outward, const OuterSlots& s,
                          const double* rfs, double* from_end) {
  RayCourse c;
  c.fate = RayFate::kEscapes;
  const double root_scale = std::sqrt(o.scale);
  if (from_end) *from_end = 2 * rfs[s.from_end];
  if (outward) {
    c.angle_total = s.beyond < 0 ? 0.0 : 2 * rfs[s.beyond] / root_scale;
  } else {
    c.turning_radius = o.periapsis;
    c.angle_to_turn = s.to_turn < 0 ? 0.0 : 2 * rfs[s.to_turn] / root_scale;
    c.angle_total = c.angle_to_turn + 2 * rfs[s.beyond] / root_scale;
  }
  return c;
}
RayCourse outer_course(const PhotonOrbit& o, double r0, bool outward, double* from_end) {
  RfArgs args[3];
  double rfs[3];
  int n = 0;
  const OuterSlots s = outer_args(o, r0, outward, from_end != nullptr, args, n);
  rf_batch(args, rfs, n);
  return outer_course_of(o, outward, s, rfs, from_end);
}

// ray_course, and what prepare_sweep needs besides: from_end, the integral from the end that
// its form measures from, where that shares work with the course (NaN where it does not).
RayCourse course_of(const PhotonOrbit& o, double r0, bool outward, double* from_end) {
  RayCourse c;
  const double horizon = 2 * o.mass;
  if (from_end) *from_end = kNaN;
  if (o.turning) {
    r0 = snap_to_turning_point(o, r0);
    if (r0 >= o.periapsis) {
      return outer_course(o, r0, outward, from_end);
    } else if (r0 <= o.inner_turning) {
      c.fate = RayFate::kCaptured;
      if (outward) {
        c.turning_radius = o.inner_turning;
        c.angle_to_turn = swept_angle(o, r0, o.inner_turning);
        c.angle_total = c.angle_to_turn + swept_angle(o, o.inner_turning, horizon);
      } else {
        c.angle_total = swept_angle(o, r0, horizon);
      }
    } else {
      c.angle_to_turn = c.angle_total = kNaN;  // no ray of this b passes r0
    }
    return c;
  }
  const double sphere = 3 * o.mass;
  if (o.critical && (outward ? r0 <= sphere : r0 >= sphere)) {
    c.fate = RayFate::kPhotonSphere;
    c.angle_total = kInf;
    return c;
  }
  c.fate = outward ? RayFate::kEscapes : RayFate::kCaptured;
  const double r_end = outward ? kInf : horizon;
  if (o.impact == 0 || r0 == r_end) {
    c.angle_total = 0;
    return c;
  }
  // swept_angle's captured integral; from_end is one of its half-integrals, or joins its batch.
  const double za = w_of(o, r0) + o.w_neg, zb = w_of(o, r_end) + o.w_neg;
  const double big_a = o.quad_a, at = za > big_a ? big_a * big_a / za : za;
  double half = 0;
  c.angle_total = captured_integral(o, za, zb, from_end ? &half : nullptr, at) / std::sqrt(o.scale);
  if (from_end) *from_end = half;
  return c;
}

}  // namespace

RayCourse ray_course(const PhotonOrbit& o, double r0, bool outward) {
  return course_of(o, r0, outward, nullptr);
}

double deflection_angle(double mass, double impact) {
  const PhotonOrbit o = photon_orbit(mass, impact);
  if (!o.turning) return kInf;
  return 2 * swept_angle(o, kInf, o.periapsis) - std::numbers::pi;
}

double static_impact_parameter(double mass, double r, double sin_alpha) {
  return r * sin_alpha / std::sqrt(1 - 2 * mass / r);
}

double static_shadow_angle(double mass, double r) {
  const double s = critical_impact_parameter(mass) * std::sqrt(1 - 2 * mass / r) / r;
  const double alpha = std::asin(std::min(s, 1.0));
  return r >= 3 * mass ? alpha : std::numbers::pi - alpha;
}

double static_frequency_shift(double mass, double r_emitter, double r_observer) {
  return std::sqrt((1 - 2 * mass / r_emitter) / (1 - 2 * mass / r_observer));
}

double tortoise_coordinate(double mass, double r) {
  return tortoise(mass, r);
}

double coordinate_time(const PhotonOrbit& o, double r_a, double r_b) {
  const double m = o.mass, b = o.impact;
  if (r_a == r_b) return 0;
  if (!(r_a > 2 * m && r_b > 2 * m)) return kNaN;
  if (std::isinf(r_a) || std::isinf(r_b)) return kInf;
  if (b == 0) return std::abs(tortoise(m, r_a) - tortoise(m, r_b));
  bool inner = false;
  if (o.turning) {
    r_a = snap_to_turning_point(o, r_a), r_b = snap_to_turning_point(o, r_b);
    if (r_a == r_b) return 0;  // both at one turning point
    inner = r_a <= o.inner_turning;
    const auto in_region = [&](double r) {
      return inner ? r <= o.inner_turning : r >= o.periapsis;
    };
    if (!in_region(r_a) || !in_region(r_b)) return kNaN;
  }
  const double far = std::max(r_a, r_b), near = std::min(r_a, r_b);
  if (m == 0) {  // a straight line: the Euclidean distance along it
    const auto chord = [&](double r) {
      return r == o.periapsis ? 0.0 : std::sqrt(std::max(0.0, (r - b) * (r + b)));
    };
    return chord(far) - chord(near);
  }
  if (o.critical && near <= 3 * m && far >= 3 * m) return kInf;
  return ray_time(o, far, near, inner, false);
}

double coordinate_time_to_infinity(const PhotonOrbit& o, double r) {
  const double m = o.mass, b = o.impact;
  if (!(r > 2 * m)) return kNaN;
  if (std::isinf(r)) return -kInf;
  if (b == 0) return -tortoise(m, r);
  if (o.turning) {
    r = snap_to_turning_point(o, r);
    if (r < o.periapsis) return kNaN;  // the inner region or the gap: no stretch to infinity
  }
  if (m == 0) return r == o.periapsis ? 0.0 : -std::sqrt(std::max(0.0, (r - b) * (r + b)));
  if (o.critical && r <= 3 * m) return kInf;
  return ray_time(o, kInf, r, false, true);
}

namespace {

// prepare_sweep's rest, from the ray's course and from_end (`shared`: NaN where the course did not
// compute it).
void sweep_from_course(const PhotonOrbit& o, double r0, bool outward, const RayCourse& course,
                       double shared, AngleSweep& a) {
  a = AngleSweep{};
  a.r0 = r0;
  const double horizon = 2 * o.mass;
  if (std::isnan(course.angle_total)) return;
  a.angle_total = course.angle_total;
  a.turning_radius = course.turning_radius;
  a.angle_to_turn = course.angle_to_turn;
  a.horizon = horizon;
  a.end = course.fate == RayFate::kEscapes    ? kInf
          : course.fate == RayFate::kCaptured ? horizon
                                              : 3 * o.mass;  // the photon sphere, as phi -> inf
  // On the photon sphere itself (b = b_c) the ray stays there; a radius off it by rounding would
  // leave it, the orbit being unstable.
  if (o.critical && r0 == 3 * o.mass) a.angle_total = 0;
  if (o.impact == 0 || a.angle_total == 0) {
    a.form = AngleSweep::Form::kAt;
    return;
  }
  a.jacobi = o.jacobi;
  a.impact = o.impact, a.w_neg = o.w_neg;
  const double rate = o.jacobi.rate;
  if (o.turning) {
    // The argument is the angle from the far end (w = w_1 outside, r = 0 inside) times the rate;
    // it grows as w grows outside (inward), and as w falls inside (outward).
    r0 = snap_to_turning_point(o, r0);
    const bool outer = r0 >= o.periapsis;
    const double v3 = o.inner_turning / o.impact;
    const LinearFactors f = turning_factors(o, r0, !outer);
    double from_end;
    if (outer) {
      // int_{w_1}^{w_0} dw / sqrt(P): Carlson's cubic integral with the factors at w_1 (computed
      // with the course, outer_course).
      from_end = shared;
    } else {
      // int_{w_0}^inf dw / sqrt(P) = 2 sqrt(w_3) R_F(w_0 - w_1, w_0 - w_2, w_0 - w_3) / sqrt(scale)
      // (the factor 1 - w / w_3 of P is -(w_0 - w_3) / w_3 here).
      from_end = 2 * std::sqrt(1 / v3) * rf(f.f1, f.f2, f.f3 / v3);
    }
    a.phase = rate * from_end / std::sqrt(o.scale);
    a.rate = outer == outward ? -rate : rate;
    a.form = outer ? AngleSweep::Form::kOuter : AngleSweep::Form::kInner;
    a.scale = outer ? o.periapsis : o.inner_turning;
    a.coef = outer ? o.w_neg * o.v_pos : o.w_neg * v3;
    return;
  }
  // b <= b_c: the angle from z = 0, or (inside z > A) from z = infinity; z grows inward.
  const double z0 = w_of(o, r0) + o.w_neg, big_a = o.quad_a, root_scale = std::sqrt(o.scale);
  const bool far = z0 > big_a;
  a.form = far ? AngleSweep::Form::kCapturedFar : AngleSweep::Form::kCaptured;
  // The half-integral at z0 (or A^2 / z0), computed with the course unless the ray winds onto
  // the photon sphere (b = b_c exactly).
  if (std::isnan(shared)) {
    Halves at;
    at.n = 1;
    at.z[0] = far ? big_a * big_a / z0 : z0;
    half_integrals(o, at, &shared);
  }
  const double from_end = shared / root_scale;
  a.phase = rate * from_end;
  a.rate = (outward != far) ? -rate : rate;
  a.scale = big_a;
  return;
}

void prepare_sweep_alone(const PhotonOrbit& o, double r0, bool outward, AngleSweep& a) {
  // kInvalid. Inside the horizon r falls along every future-directed ray: a backward ray from
  // there moves outward.
  if (!(r0 > 0) || (r0 < 2 * o.mass && !outward)) {
    a = AngleSweep{};
    a.r0 = r0;
    return;
  }
  double shared = kNaN;  // from_end, where the course computed it
  const RayCourse course = course_of(o, r0, outward, &shared);
  sweep_from_course(o, r0, outward, course, shared, a);
}

// One ray's sweep while its course's R_F wait in a batch with other rays' (prepare_sweeps): those
// of a turning orbit from beyond its periapsis (outer_course's) or of a captured one (its
// captured_integral's, with the half-integral at the start), the course_of of nearly every
// camera ray; any other is prepared alone.
struct PendingSweep {
  enum class Kind : unsigned char { kAlone, kOuter, kCaptured };
  Kind kind = Kind::kAlone;
  OuterSlots outer;
  CapturedPlan captured;
};
PendingSweep pending_sweep(const PhotonOrbit& o, double r0, bool outward, RfArgs* args, int& n) {
  PendingSweep p;
  const double horizon = 2 * o.mass;
  if (!(r0 > 0) || (r0 < horizon && !outward)) return p;
  if (o.turning) {
    const double snapped = snap_to_turning_point(o, r0);
    if (snapped >= o.periapsis) {
      p.kind = PendingSweep::Kind::kOuter;
      p.outer = outer_args(o, snapped, outward, true, args, n);
    }
    return p;
  }
  const double r_end = outward ? kInf : horizon;
  if (o.critical || o.impact == 0 || r0 == r_end) return p;
  const double za = w_of(o, r0) + o.w_neg, zb = w_of(o, r_end) + o.w_neg;
  const double big_a = o.quad_a, at = za > big_a ? big_a * big_a / za : za;
  p.kind = PendingSweep::Kind::kCaptured;
  p.captured = captured_plan(o, za, zb, true, at);
  half_args(o, p.captured.halves, args, n);
  return p;
}
void finished_sweep(const PhotonOrbit& o, double r0, bool outward, const PendingSweep& p,
                    const double* rfs, AngleSweep& a) {
  double shared = kNaN;
  RayCourse course;
  switch (p.kind) {
    case PendingSweep::Kind::kAlone:
      return prepare_sweep_alone(o, r0, outward, a);
    case PendingSweep::Kind::kOuter:
      course = outer_course_of(o, outward, p.outer, rfs, &shared);
      break;
    case PendingSweep::Kind::kCaptured: {
      double h[kMaxHalves];
      half_values(p.captured.halves, rfs, h);
      course.fate = outward ? RayFate::kEscapes : RayFate::kCaptured;
      course.angle_total = captured_value(p.captured, h, &shared) / std::sqrt(o.scale);
      break;
    }
  }
  sweep_from_course(o, r0, outward, course, shared, a);
}

// prepare_sweeps with room for `kRays` rays' integrals.
template <int kRays>
void sweeps_together(const SweepStart* starts, AngleSweep* const* out, int n) {
  static_assert(kRays * kMaxHalves <= kMaxBatch && kMaxHalves >= 3);
  RfArgs args[kRays * kMaxHalves] = {};
  double rfs[kRays * kMaxHalves];
  PendingSweep pending[kRays];
  int used = 0;
  for (int i = 0; i < n; ++i)
    pending[i] = pending_sweep(*starts[i].orbit, starts[i].r0, starts[i].outward, args, used);
  rf_batch(args, rfs, used);
  for (int i = 0; i < n; ++i)
    finished_sweep(*starts[i].orbit, starts[i].r0, starts[i].outward, pending[i], rfs, *out[i]);
}

}  // namespace

void prepare_sweeps(const SweepStart* starts, AngleSweep* const* out, int n) {
  sweeps_together<kMaxSweeps>(starts, out, n);
}

AngleSweep prepare_sweep(const PhotonOrbit& o, double r0, bool outward) {
  AngleSweep a;
  const SweepStart start{&o, r0, outward};
  AngleSweep* const out = &a;
  sweeps_together<1>(&start, &out, 1);
  return a;
}

double radius_after_angle(const AngleSweep& a, double phi) {
  using Form = AngleSweep::Form;
  if (a.form == Form::kInvalid || !(phi >= 0)) return kNaN;
  if (phi == 0) return a.r0;
  if (phi >= a.angle_total) return a.end;  // kAt: angle_total is 0
  const JacobiValues j = jacobi_functions(a.jacobi, a.phase + a.rate * phi);
  const double s2 = j.sn * j.sn, c2 = j.cn * j.cn;
  double r = 0;
  switch (a.form) {
    case Form::kOuter: {  // r_p / (sn^2 - w_neg v_p cn^2)
      const double den = s2 - a.coef * c2;
      r = den > 0 ? a.scale / den : kInf;
      break;
    }
    case Form::kInner:  // r_3 sn^2 / (1 + w_neg v_3 cn^2)
      r = a.scale * s2 / (1 + a.coef * c2);
      break;
    default: {  // z = A (1 - cn) / (1 + cn), or with -cn from z = infinity
      const double c = a.form == Form::kCaptured ? j.cn : -j.cn;
      const double z =
          c >= 0 ? a.scale * s2 / ((1 + c) * (1 + c)) : a.scale * (1 - c) * (1 - c) / s2;
      const double w = z - a.w_neg;
      r = w > 0 ? a.impact / w : kInf;
      break;
    }
  }
  // Rounding at the very end of the path cannot carry it past the horizon (nor, from inside it,
  // below where it started: its r only grows until it is out).
  return std::max(r, std::min(a.r0, a.horizon));
}

double radius_after_angle(const PhotonOrbit& o, double r0, bool outward, double phi) {
  return radius_after_angle(prepare_sweep(o, r0, outward), phi);
}

}  // namespace lightcone

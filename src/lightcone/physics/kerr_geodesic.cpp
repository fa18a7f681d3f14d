#include "lightcone/physics/kerr_geodesic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "lightcone/physics/carlson_integrals.hpp"

namespace lightcone::kerr {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = std::numbers::pi;

// Legendre's integrals of parameter m (= k^2) at an amplitude in [-pi/2, pi/2], from its sine s
// and cosine squared c2, in Carlson's forms (DLMF 19.25.5, 19.25.7, 19.25.14):
//   F = s R_F(c2, 1 - m s^2, 1),  Pi(n) = F + (n/3) s^3 R_J(c2, 1 - m s^2, 1, 1 - n s^2),
// and (F - E) / m = (1/3) s^3 R_D(c2, 1 - m s^2, 1) = int sn^2, without cancellation as m -> 0.
double legendre_f(double s, double c2, double m) {
  return s * carlson::rf(c2, 1 - m * s * s, 1);
}
double legendre_d(double s, double c2, double m) {
  return s * s * s * carlson::rd(c2, 1 - m * s * s, 1) / 3;
}
// Several integrals at one amplitude share R_F.
struct Amplitude {
  double s, c2, y, rf;  // y = 1 - m s^2
};
Amplitude amplitude(double s, double c2, double m) {
  const double y = 1 - m * s * s;
  return {s, c2, y, carlson::rf(c2, y, 1)};
}
double legendre_pi(const Amplitude& a, double n) {
  const double s3 = a.s * a.s * a.s;
  return a.s * a.rf + n * s3 * carlson::rj(a.c2, a.y, 1, 1 - n * a.s * a.s, a.rf) / 3;
}
double legendre_d(const Amplitude& a) {
  return a.s * a.s * a.s * carlson::rd(a.c2, a.y, 1) / 3;
}
int sense_of(int sign) {
  return sign < 0 ? -1 : 1;
}

// ---- The polar motion. With x = cos(theta), (dx/dtau)^2 = a^2 (u_+ - x^2)(x^2 - u_-):
// ordinary (u_- < 0 < u_+): x = sqrt(u_+) cn(w | m), m = u_+ / (u_+ - u_-),
//   dw/dtau = a sqrt(u_+ - u_-) = (B^2 + 4 a^2 eta)^(1/4), B = eta + lambda^2 - a^2;
// vortical (0 < u_- < u_+): x = h sqrt(u_+) dn(w | m), m = (u_+ - u_-) / u_+, dw/dtau = a
//   sqrt(u_+).
// Both: 1 - x^2 = (1 - u_+)(1 - n sn^2), so int dtau / sin^2 theta = Pi(n; w) / ((1 - u_+) rate),
// and a^2 int x^2 dtau = a^2 u_+ int cn^2 (or dn^2) dw / rate. Over w = 2jK + w', w' in [-K, K],
// each integral is 2j times its complete value plus its principal value at w'.

struct PolarState {
  double cos_theta, g_phi, g_t;  // g_*: the antiderivatives in Mino time
};
PolarState polar_state(const PolarMotion& p, double w, bool integrals) {
  const double j = std::nearbyint(w / (2 * p.quarter));
  const JacobiValues v = jacobi_functions(p.jacobi, (w - 2 * j * p.quarter) * p.jacobi.rate);
  const double odd = std::fmod(j, 2.0) == 0 ? 1 : -1;  // cn(w) = (-1)^j cn(w')
  PolarState state;
  state.cos_theta =
      p.vortical ? p.hemisphere * std::sqrt(p.u_plus) * v.dn : std::sqrt(p.u_plus) * odd * v.cn;
  if (!integrals) return state;
  const Amplitude a = amplitude(v.sn, v.cn * v.cn, p.m);
  state.g_phi = p.lambda == 0 ? 0.0 : p.pi_scale * (2 * j * p.complete_pi + legendre_pi(a, p.pi_n));
  const double d = 2 * j * p.complete_d + legendre_d(a);
  // int cn^2 dw = w - int sn^2 dw; int dn^2 dw = w - m int sn^2 dw.
  state.g_t = p.a2 * p.u_plus * (w - (p.vortical ? p.m : 1) * d) / p.rate;
  return state;
}

PolarMotion polar_motion(double a, const PhotonConstants& c, double x, int sign_theta) {
  PolarMotion p;
  p.lambda = c.lambda, p.a2 = a * a;
  const double b = c.eta + c.lambda * c.lambda - p.a2;
  const double spread = std::sqrt(b * b + 4 * p.a2 * c.eta);  // a^2 (u_+ - u_-)
  double kc2;
  // The source's amplitude: w_s = sign f there, or sign (2K - f) where turned.
  Amplitude source;
  bool turned = false;
  double sign = 1;
  if (c.eta >= 0) {
    p.u_plus = b > 0 ? 2 * c.eta / (b + spread) : (spread - b) / (2 * p.a2);
    const double a2_u_minus = p.u_plus > 0 ? -c.eta / p.u_plus : -spread;
    p.rate = std::sqrt(spread);
    p.m = p.a2 * p.u_plus / spread;
    kc2 = -a2_u_minus / spread;
    p.jacobi = jacobi_modulus(p.m, kc2);
    p.quarter = carlson::rf(0, kc2, 1);
    const double ratio = p.u_plus > 0 ? std::clamp(x / std::sqrt(p.u_plus), -1.0, 1.0) : 0.0;
    source = amplitude(std::sqrt((1 - ratio) * (1 + ratio)), ratio * ratio, p.m);
    turned = ratio < 0;  // w_s = +-(2K - f)
    sign = sense_of(sign_theta);
    p.pi_n = -p.u_plus / (1 - p.u_plus);
  } else {
    p.vortical = true;
    p.u_plus = (spread - b) / (2 * p.a2);
    const double u_minus = -c.eta / (p.a2 * p.u_plus);
    p.rate = std::sqrt(p.a2 * p.u_plus);
    p.m = spread / (p.a2 * p.u_plus);
    kc2 = u_minus / p.u_plus;
    p.jacobi = jacobi_modulus(p.m, kc2);
    p.quarter = carlson::rf(0, kc2, 1);
    p.hemisphere = x < 0 ? -1 : 1;
    const double s2 = std::clamp((p.u_plus - x * x) * p.a2 / spread, 0.0, 1.0);
    source = amplitude(std::sqrt(s2), 1 - s2, p.m);
    sign = sense_of(sign_theta) * p.hemisphere;
    p.pi_n = -p.u_plus * p.m / (1 - p.u_plus);
  }
  p.pi_scale = 1 / ((1 - p.u_plus) * p.rate);
  const Amplitude complete{1, 0, kc2, p.quarter};
  p.complete_pi = legendre_pi(complete, p.pi_n);
  p.complete_d = legendre_d(complete);
  const auto at_source = [&](double principal, double whole) {
    return sign * (turned ? 2 * whole - principal : principal);
  };
  p.w_source = at_source(source.s * source.rf, p.quarter);
  const double pi = at_source(legendre_pi(source, p.pi_n), p.complete_pi);
  const double d = at_source(legendre_d(source), p.complete_d);
  p.g_phi_source = c.lambda == 0 ? 0.0 : p.pi_scale * pi;
  p.g_t_source = p.a2 * p.u_plus * (p.w_source - (p.vortical ? p.m : 1) * d) / p.rate;
  return p;
}

// ---- The radial motion, four real roots (r >= r4): with n = (r4 - r1) / (r3 - r1),
// m = (r3 - r2)(r4 - r1) / ((r3 - r1)(r4 - r2)), r = r3 + (r4 - r3) / (1 - n sn^2(X | m)) and
// dX/dtau = sqrt((r3 - r1)(r4 - r2)) / 2; sn^2 = (r - r4)(r3 - r1) / ((r - r3)(r4 - r1)).
// The integrals of r, r^2 and 1 / (r - r_+-) over tau are then those of 1 / (1 - n sn^2) (Pi),
// its square (V2 below) and 1 / (1 - n_+- sn^2), n_+- = n (r3 - r_+-) / (r4 - r_+-).

struct SquaredAmplitude {
  double s2, c2;
};
SquaredAmplitude four_real_amplitude(const double* r, double radius) {
  if (std::isinf(radius)) return {(r[2] - r[0]) / (r[3] - r[0]), (r[3] - r[2]) / (r[3] - r[0])};
  const double d = (radius - r[2]) * (r[3] - r[0]);
  return {std::max((radius - r[3]) * (r[2] - r[0]) / d, 0.0), (radius - r[0]) * (r[3] - r[2]) / d};
}

// int dX / (1 - n sn^2)^2 (Byrd & Friedman 1971, 336.02), from Pi(n; X), E(X), sn, cn, dn.
double pi_squared(double n, double m, double x, double s, double cn, double dn, double pi,
                  double e) {
  return (n * n * s * cn * dn / (1 - n * s * s) + (n * n - 2 * n - 2 * m * n + 3 * m) * pi +
          (n - m) * x - n * e) /
         (2 * (n - 1) * (n - m));
}

// Bound (r2 <= r <= r3): sn^2 = (r3 - r1)(r - r2) / ((r3 - r2)(r - r1)), r = r1 + (r2 - r1) /
// (1 - n sn^2), n = (r3 - r2) / (r3 - r1), the same m and rate (Byrd & Friedman 1971, 255.00);
// X runs past K (r3) and the integrals are then 2j times their complete values plus their
// principal values at X - 2jK.
SquaredAmplitude bound_amplitude(const double* r, double radius) {
  const double d = (r[2] - r[1]) * (radius - r[0]);
  return {std::max((r[2] - r[0]) * (radius - r[1]) / d, 0.0), (r[1] - r[0]) * (r[2] - radius) / d};
}

struct FourRealSums {
  double pi, pi_plus, pi_minus, v2;
};
// At X = 2jK + X', given the amplitude of X' and sn, cn, dn at X.
FourRealSums four_real_sums(const RadialMotion& m, double x, const Amplitude& a, double j,
                            const JacobiValues& at) {
  FourRealSums f;
  f.pi = 2 * j * m.complete_pi[0] + legendre_pi(a, m.n);
  f.pi_plus = 2 * j * m.complete_pi[1] + legendre_pi(a, m.n_plus);
  f.pi_minus = 2 * j * m.complete_pi[2] + legendre_pi(a, m.n_minus);
  const double e = x - m.m * (2 * j * m.complete_d + legendre_d(a));
  f.v2 = pi_squared(m.n, m.m, x, at.sn, at.cn, at.dn, f.pi, e);
  return f;
}

// ---- Two real roots r1 < r2 and a pair u +- iv: z = (r - r2) / (r - r1) in [0, 1) maps the
// quartic to a cubic, dr / sqrt(R) = dz / sqrt(z Q(z)), Q = h ((z - c)^2 + n^2), which
// carlson::quadratic_cubic integrates; and z = A (1 - cn) / (1 + cn) with A^2 = c^2 + n^2,
// k^2 = (A + c) / (2A), int_0^z dz / sqrt(z ((z - c)^2 + n^2)) = F(phi | k^2) / sqrt(A)
// (Byrd & Friedman 1971, 239.00), cos(phi) = (A - z) / (A + z).

double two_real_argument(const RadialMotion& m, double quarter, double z) {
  const double cos_phi = (m.big_a - z) / (m.big_a + z);
  const double sin_phi = 2 * std::sqrt(m.big_a * z) / (m.big_a + z);
  const double f = legendre_f(sin_phi, cos_phi * cos_phi, m.m);
  return cos_phi >= 0 ? f : 2 * quarter - f;
}
double z_of(const RadialRoots& roots, double r) {
  return std::isinf(r) ? 1.0 : (r - roots.r[1]) / (r - roots.r[0]);
}

// ---- No real root: pairs u1 +- i v1 and u2 +- i v2. x = (r - u1) / v1 turns pair 1 into +-i;
// the rotation x = (s + h) / (1 - h s), which keeps 1 + x^2 a multiple of 1 + s^2, is chosen to
// take pair 2 to +-i g; then dr / sqrt(R) = sqrt(1 + h^2) / sqrt(C) ds / sqrt((1 + s^2)(s^2 +
// g^2)), and with G = max(1, g), g' = min(1, g), s = g' sc(u | 1 - g'^2 / G^2) and u = G times
// that integral (Byrd & Friedman 1971, 221.00).

double none_real_argument(const RadialMotion& m, double quarter, double r) {
  const RadialRoots& q = m.roots;
  const double x = std::isinf(r) ? 0.0 : (r - q.pair_re) / q.pair_im;
  const double phi = std::isinf(r) ? std::atan2(1.0, m.g_small * m.rot_h)
                                   : std::atan2(x - m.rot_h, m.g_small * (1 + m.rot_h * x));
  const double j = std::nearbyint(phi / kPi), rest = phi - j * kPi;
  const double s = std::sin(rest), c = std::cos(rest);
  return 2 * j * quarter + legendre_f(s, c * c, m.m);
}

// The integrals over the ray's Mino time tau of r, r^2 and 1 / (r - r_+-) (Gralla & Lupsasca's
// I_1, I_2, I_+-).
struct RadialIntegrals {
  double i1, i2, i_plus, i_minus;
};

// The integrals over w of r, r^2 and 1 / (r - r_+-) then come from, with t = sc(w) = tan(phi),
// phi = am(w), N = 1 + kappa^2, y = sin^2 phi, Delta = dn(w) = sqrt(1 - m y):
//   T1(kappa) = int t dw / (1 + kappa t) = H / 2 - kappa (Pi(N; w) - w) / N,
//   H = int sin(2 phi) dphi / ((1 - N y) Delta) = -2 L, L = int dDelta / (N Delta^2 - (N - m))
//     = ln|(sqrt(N) Delta - sqrt(N - m)) / (sqrt(N) Delta + sqrt(N - m))| / (2 sqrt(N (N - m))),
// (multiplying t / (1 + kappa t) by cos(phi) - kappa sin(phi) over itself), and
//   T2(gamma) = int t^2 dw / (1 + gamma t)^2 = -dT1/dgamma,
// with dPi/dN = (V2 - Pi) / N (V2 = int dw / (1 - N sn^2)^2, pi_squared) and
// dH/dN = (1/N + 1/(N - m)) L + Delta / (N (N - m)(1 - N y)). Where the path passes 1 - N y = 0
// (t = 1/kappa, where 1 + kappa t does not vanish) Pi is a Cauchy principal value (N > 1) and L's
// logarithm is singular too, cancelling it. So int r dw = c0 w + c1 T1(gamma), int r^2 dw = c0^2 w
// + 2 c0 c1 T1(gamma) + c1^2 T2(gamma), int dw / (r - rho) = (w - c1 / (c0 - rho) T1(kappa)) / (c0
// - rho).
struct NoneRealSums {
  double t[4];  // T1(gamma), T2(gamma), T1(kappa_+), T1(kappa_-)
};
NoneRealSums none_real_sums(const RadialMotion& m, double w, const JacobiValues& at, bool inner) {
  const double j = std::nearbyint(w / (2 * m.quarter));
  const double odd = std::fmod(j, 2.0) == 0 ? 1 : -1;  // sn, cn at w' = w - 2jK
  const Amplitude a = amplitude(odd * at.sn, at.cn * at.cn, m.m);
  const double y = at.sn * at.sn, delta = at.dn;
  const double e = w - m.m * (2 * j * m.complete_d + legendre_d(a));
  NoneRealSums sums{};
  for (int i = 0; i < 3; ++i) {
    if (i == 2 && !inner) continue;
    const double kappa = m.kappa[i], n = 1 + kappa * kappa, d = n - m.m;
    const double pi = 2 * j * m.complete_pi[i] + legendre_pi(a, n);
    const double sn_root = std::sqrt(n) * delta, sd = std::sqrt(d);
    const double l = std::log(std::abs((sn_root - sd) / (sn_root + sd))) / (2 * std::sqrt(n * d));
    const double t1 = -l - kappa * (pi - w) / n;
    sums.t[i == 0 ? 0 : i + 1] = t1;
    if (i > 0) continue;
    const double v2 = pi_squared(n, m.m, w, at.sn, at.cn, at.dn, pi, e);
    const double dpi = (v2 - pi) / n;
    const double dh = (1 / n + 1 / d) * l + delta / (n * d * (1 - n * y));
    const double k2 = kappa * kappa;
    sums.t[1] = -(kappa * dh - (pi - w) / n - 2 * k2 / n * dpi + 2 * k2 / (n * n) * (pi - w));
  }
  return sums;
}

RadialIntegrals none_real_integrals(const RadialMotion& m, double w, const JacobiValues& at,
                                    double r_plus, double r_minus) {
  const NoneRealSums f = none_real_sums(m, w, at, r_minus >= 0);
  const double scale = m.sense / m.rate, dw = w - m.x_source;
  double d[4];
  for (int i = 0; i < 4; ++i) d[i] = f.t[i] - m.none_real_source[i];
  RadialIntegrals i;
  i.i1 = scale * (m.c0 * dw + m.c1 * d[0]);
  i.i2 = scale * (m.c0 * m.c0 * dw + 2 * m.c0 * m.c1 * d[0] + m.c1 * m.c1 * d[1]);
  const auto pole = [&](double rho, double dt1) {
    const double gap = m.c0 - rho;
    return scale * (dw - m.c1 / gap * dt1) / gap;
  };
  i.i_plus = pole(r_plus, d[2]);
  i.i_minus = r_minus < 0 ? 0.0 : pole(r_minus, d[3]);
  return i;
}

RadialMotion radial_motion(double a, const PhotonConstants& c, double r_s, int sign_r) {
  RadialMotion m;
  m.roots = radial_roots(a, c);
  m.r_source = r_s;
  const double r_plus = outer_horizon(a), r_minus = inner_horizon(a);
  const RadialRoots& q = m.roots;
  if (q.kind == RadialCase::FourReal) {
    const double* r = q.r;
    const double d = (r[2] - r[0]) * (r[3] - r[1]), kc2 = (r[1] - r[0]) * (r[3] - r[2]) / d;
    m.m = (r[2] - r[1]) * (r[3] - r[0]) / d;
    m.jacobi = jacobi_modulus(m.m, kc2);
    m.rate = std::sqrt(d) / 2;
    m.bound = r_s <= r[2] && r[2] > r_plus;
    m.base = m.bound ? r[0] : r[2];
    m.gap = m.bound ? r[1] - r[0] : r[3] - r[2];
    m.n = m.bound ? (r[2] - r[1]) / (r[2] - r[0]) : (r[3] - r[0]) / (r[2] - r[0]);
    const double top = m.base + m.gap;
    m.n_plus = m.n * (m.base - r_plus) / (top - r_plus);
    m.n_minus = m.n * (m.base - r_minus) / (top - r_minus);
    SquaredAmplitude source;
    if (m.bound) {
      m.sense = sense_of(sign_r);
      source = bound_amplitude(r, r_s);
      m.quarter = carlson::rf(0, kc2, 1);
      const Amplitude complete{1, 0, kc2, m.quarter};
      m.complete_d = legendre_d(complete);
      m.complete_pi[0] = legendre_pi(complete, m.n);
      m.complete_pi[1] = legendre_pi(complete, m.n_plus);
      m.complete_pi[2] = legendre_pi(complete, m.n_minus);
      const SquaredAmplitude h = bound_amplitude(r, r_plus);
      const double x_horizon = legendre_f(std::sqrt(h.s2), h.c2, m.m);
      m.x_end = m.sense > 0 ? 2 * m.quarter - x_horizon : x_horizon;
    } else {
      // X < 0 on the way in, 0 at r4, so that X always grows.
      source = four_real_amplitude(r, r_s);
      const SquaredAmplitude far = four_real_amplitude(r, kInf);
      m.x_end = legendre_f(std::sqrt(far.s2), far.c2, m.m);
      if (r[3] < r_plus && sign_r < 0) {
        const SquaredAmplitude h = four_real_amplitude(r, r_plus);
        m.x_end = -legendre_f(std::sqrt(h.s2), h.c2, m.m);
      }
    }
    const double s = (m.bound ? 1 : sense_of(sign_r)) * std::sqrt(source.s2);
    const Amplitude at = amplitude(s, source.c2, m.m);
    m.x_source = at.s * at.rf;
    const FourRealSums f =
        four_real_sums(m, m.x_source, at, 0, {s, std::sqrt(source.c2), std::sqrt(at.y)});
    m.pi_source = f.pi, m.pi_plus_source = f.pi_plus, m.pi_minus_source = f.pi_minus;
    m.v2_source = f.v2;
    return m;
  }
  m.sense = sense_of(sign_r);
  if (q.kind == RadialCase::TwoReal) {
    const double u = q.pair_re, v = q.pair_im, r1 = q.r[0], r2 = q.r[1];
    m.quad_h = (r1 - u) * (r1 - u) + v * v;
    m.quad_c = ((r2 - u) * (r1 - u) + v * v) / m.quad_h;
    m.quad_n = v * (r2 - r1) / m.quad_h;
    m.big_a = std::hypot(m.quad_c, m.quad_n);
    const double n2 = m.quad_n * m.quad_n;
    double kc2;
    if (m.quad_c >= 0) {
      m.m = (m.big_a + m.quad_c) / (2 * m.big_a);
      kc2 = n2 / (2 * m.big_a * (m.big_a + m.quad_c));
    } else {
      kc2 = (m.big_a - m.quad_c) / (2 * m.big_a);
      m.m = n2 / (2 * m.big_a * (m.big_a - m.quad_c));
    }
    m.jacobi = jacobi_modulus(m.m, kc2);
    m.rate = std::sqrt(m.big_a * m.quad_h);
    const double quarter = carlson::rf(0, kc2, 1);
    m.z_source = z_of(q, r_s);
    m.x_source = two_real_argument(m, quarter, m.z_source);
    m.x_end = two_real_argument(m, quarter, z_of(q, m.sense > 0 ? kInf : r_plus));
    return m;
  }
  const double p = (q.pair2_re - q.pair_re) / q.pair_im, s = q.pair2_im / q.pair_im;
  const double big_p = p * p + s * s - 1, root = std::hypot(big_p, 2 * p);
  m.rot_h = p == 0 ? 0.0 : big_p >= 0 ? -2 * p / (big_p + root) : 2 * p / (root - big_p);
  const double h = m.rot_h;
  const double g = s * (1 + h * h) / ((1 + h * p) * (1 + h * p) + h * h * s * s);
  m.g_big = std::max(1.0, g), m.g_small = std::min(1.0, g);
  const double r0 = q.pair_re + q.pair_im * h - q.pair2_re;
  const double big_c = (r0 * r0 + q.pair2_im * q.pair2_im) / (g * g);
  const double kc2 = m.g_small * m.g_small / (m.g_big * m.g_big);
  m.m = (m.g_big - m.g_small) * (m.g_big + m.g_small) / (m.g_big * m.g_big);
  m.jacobi = jacobi_modulus(m.m, kc2);
  m.rate = m.g_big * std::sqrt(big_c / (1 + h * h));
  const double quarter = carlson::rf(0, kc2, 1);
  m.quarter = quarter;
  m.x_source = none_real_argument(m, quarter, r_s);
  m.x_end = none_real_argument(m, quarter, m.sense > 0 ? kInf : r_plus);
  // (s + h) / (1 - h s) = h + g'(1 + h^2) t / (1 + gamma t), gamma = -h g'; r - rho =
  // (c0 - rho)(1 + kappa t) / (1 + gamma t), kappa = gamma + c1 / (c0 - rho).
  m.c0 = q.pair_re + q.pair_im * h;
  m.c1 = q.pair_im * m.g_small * (1 + h * h);
  m.kappa[0] = -h * m.g_small;
  m.kappa[1] = m.kappa[0] + m.c1 / (m.c0 - r_plus);
  m.kappa[2] = m.kappa[0] + m.c1 / (m.c0 - r_minus);
  const Amplitude complete{1, 0, kc2, quarter};
  m.complete_d = legendre_d(complete);
  for (int i = 0; i < 3; ++i) m.complete_pi[i] = legendre_pi(complete, 1 + m.kappa[i] * m.kappa[i]);
  const NoneRealSums source =
      none_real_sums(m, m.x_source, jacobi_functions(m.jacobi, m.x_source * m.jacobi.rate), true);
  std::copy(source.t, source.t + 4, m.none_real_source);
  return m;
}

double radial_radius(const RadialMotion& m, const JacobiValues& v) {
  const RadialRoots& q = m.roots;
  switch (q.kind) {
    case RadialCase::FourReal:
      return m.base + m.gap / (1 - m.n * v.sn * v.sn);
    case RadialCase::TwoReal: {
      const double z = m.big_a * (1 - v.cn) / (1 + v.cn);
      return (q.r[1] - q.r[0] * z) / (1 - z);
    }
    case RadialCase::NoneReal:
      return q.pair_re +
             q.pair_im * (m.g_small * v.sn + m.rot_h * v.cn) / (v.cn - m.rot_h * m.g_small * v.sn);
  }
  return kNaN;
}

// r_minus < 0: I_- is not needed (see point_with_polar) and left 0.
RadialIntegrals four_real_integrals(const RadialMotion& m, double x, const JacobiValues& v,
                                    double tau, double r_plus, double r_minus) {
  const double j = m.bound ? std::nearbyint(x / (2 * m.quarter)) : 0;
  const double odd = std::fmod(j, 2.0) == 0 ? 1 : -1;  // sn, cn at X - 2jK
  const FourRealSums f = four_real_sums(m, x, amplitude(odd * v.sn, v.cn * v.cn, m.m), j, v);
  const double scale = m.sense / m.rate, dpi = scale * (f.pi - m.pi_source);
  RadialIntegrals i;
  i.i1 = m.base * tau + m.gap * dpi;
  i.i2 = m.base * m.base * tau + 2 * m.base * m.gap * dpi +
         m.gap * m.gap * scale * (f.v2 - m.v2_source);
  const auto pole = [&](double n_pole, double sum, double sum_source, double r_pole) {
    const double ratio = m.n / n_pole;
    return (ratio * tau + (1 - ratio) * scale * (sum - sum_source)) / (m.base + m.gap - r_pole);
  };
  i.i_plus = pole(m.n_plus, f.pi_plus, m.pi_plus_source, r_plus);
  i.i_minus = r_minus < 0 ? 0.0 : pole(m.n_minus, f.pi_minus, m.pi_minus_source, r_minus);
  return i;
}

RadialIntegrals two_real_integrals(const RadialMotion& m, double z, double r_plus, double r_minus) {
  const RadialRoots& q = m.roots;
  const double r1 = q.r[0], r2 = q.r[1];
  const double hi = std::max(z, m.z_source), lo = std::min(z, m.z_source);
  const carlson::QuadraticCubic k = carlson::quadratic_cubic(hi, lo, m.quad_c, m.quad_n);
  const double j0 = carlson::first_kind(k);
  const double j1 = carlson::third_kind(k, 1, -1, 1 - hi, 1 - lo, false);
  const auto quad = [&](double w) { return (w - m.quad_c) * (w - m.quad_c) + m.quad_n * m.quad_n; };
  const double a2 = m.big_a * m.big_a;
  // int z dz / sqrt(z q) = A^2 int z^(-3/2) q^(-1/2) dz + 2 [sqrt(q / z)], from
  // d sqrt(q / z) / dz = (z^2 - A^2) / (2 z^(3/2) sqrt(q)).
  const double jz =
      a2 * carlson::second_kind(k) + 2 * (std::sqrt(quad(hi) / hi) - std::sqrt(quad(lo) / lo));
  // int dz / ((1 - z)^2 sqrt(P)), P = z q: d(sqrt(P) / (1 - z)) / dz = N / (2 (1 - z)^2 sqrt(P)),
  // N = 2 q(1) - (3 + A^2 - 4c)(1 - z) + (1 - z)^3.
  const auto lifted = [&](double w) { return std::sqrt(w * quad(w)) / (1 - w); };
  const double j2 =
      (2 * (lifted(hi) - lifted(lo)) + (3 + a2 - 4 * m.quad_c) * j1 - (j0 - jz)) / (2 * quad(1));
  const double scale = 1 / std::sqrt(m.quad_h), gap = r2 - r1;
  RadialIntegrals i;
  i.i1 = scale * (r1 * j0 + gap * j1);
  i.i2 = scale * (r1 * r1 * j0 + 2 * r1 * gap * j1 + gap * gap * j2);
  const auto pole = [&](double r_pole) {
    const double b4 = r_pole - r1;  // L = (r2 - r_pole) + (r_pole - r1) z > 0 outside it
    const double jp = carlson::third_kind(k, r2 - r_pole, b4, r2 - r_pole + b4 * hi,
                                          r2 - r_pole + b4 * lo, false);
    return scale * (j0 - gap * jp) / (r1 - r_pole);
  };
  i.i_plus = pole(r_plus);
  i.i_minus = r_minus < 0 ? 0.0 : pole(r_minus);
  return i;
}

}  // namespace

RadialRoots radial_roots(double a, const PhotonConstants& c) {
  const double big_a = a * a - c.eta - c.lambda * c.lambda;
  const double big_b = 2 * (c.eta + (c.lambda - a) * (c.lambda - a));
  const double big_c = -a * a * c.eta;
  const double p = -big_a * big_a / 12 - big_c;
  const double q = -big_a / 3 * ((big_a / 6) * (big_a / 6) - big_c) - big_b * big_b / 8;
  const double disc = (p / 3) * (p / 3) * (p / 3) + (q / 2) * (q / 2);
  double omegas;  // omega_+ + omega_-
  if (disc >= 0) {
    const double root = std::sqrt(disc);
    omegas = std::cbrt(-q / 2 + root) + std::cbrt(-q / 2 - root);
  } else {
    // The principal cube roots of the conjugates -q/2 +- i sqrt(-disc), of modulus (-p/3)^(3/2).
    omegas = 2 * std::sqrt(-p / 3) * std::cos(std::atan2(std::sqrt(-disc), -q / 2) / 3);
  }
  const double z = std::sqrt(std::max(omegas / 2 - big_a / 6, 0.0));
  const double base = -big_a / 2 - z * z, tilt = big_b / (4 * z);
  const double q12 = base + tilt, q34 = base - tilt;
  RadialRoots roots;
  if (q34 < 0 && q12 < 0) {
    roots.kind = RadialCase::NoneReal;
    roots.pair_re = z, roots.pair_im = std::sqrt(-q34);
    roots.pair2_re = -z, roots.pair2_im = std::sqrt(-q12);
    return roots;
  }
  // r1 and r2 (simple roots) polished by Newton's method on R, and the other two from the sum
  // and the sum of pairwise products of all four (0 and A): r3 + r4 = -(r1 + r2), r3 r4 =
  // A - r1 r2 + (r1 + r2)^2, which keeps a pair that nearly coincides (a ray near the critical
  // curve) as accurate as r1 and r2.
  const auto polish = [&](double r) {
    for (int i = 0; i < 2; ++i) {
      const double value = ((r * r + big_a) * r + big_b) * r + big_c;
      const double slope = (4 * r * r + 2 * big_a) * r + big_b;
      if (slope != 0) r -= value / slope;
    }
    return r;
  };
  const double s12 = std::sqrt(std::max(q12, 0.0));
  roots.r[0] = polish(-z - s12), roots.r[1] = polish(-z + s12);
  const double sum = roots.r[0] + roots.r[1];
  const double centre = -sum / 2, product = big_a - roots.r[0] * roots.r[1] + sum * sum;
  const double half_gap2 = centre * centre - product;
  if (q34 >= 0) {
    roots.kind = RadialCase::FourReal;
    const double half_gap = std::sqrt(std::max(half_gap2, 0.0));
    roots.r[2] = centre - half_gap, roots.r[3] = centre + half_gap;
    std::sort(roots.r, roots.r + 4);
  } else {
    roots.kind = RadialCase::TwoReal;
    roots.pair_re = centre, roots.pair_im = std::sqrt(std::max(-half_gap2, 0.0));
  }
  return roots;
}

KerrRay kerr_ray(double a, const PhotonConstants& c, double r_source, double cos_theta_source,
                 int sign_r, int sign_theta) {
  KerrRay ray;
  ray.a = a;
  ray.constants = c;
  ray.polar = polar_motion(a, c, cos_theta_source, sign_theta);
  ray.radial = radial_motion(a, c, r_source, sign_r);
  const RadialMotion& m = ray.radial;
  ray.mino_time_limit = m.sense * (m.x_end - m.x_source) / m.rate;
  return ray;
}

double radius_after(const KerrRay& ray, double tau) {
  const RadialMotion& m = ray.radial;
  const double x = m.x_source + m.sense * m.rate * tau;
  return radial_radius(m, jacobi_functions(m.jacobi, x * m.jacobi.rate));
}

double cos_theta_after(const KerrRay& ray, double tau) {
  const PolarMotion& p = ray.polar;
  return polar_state(p, p.w_source + p.rate * tau, false).cos_theta;
}

namespace {

// The point at Mino time tau, given the polar motion's state there.
KerrPoint point_with_polar(const KerrRay& ray, double tau, const PolarState& polar) {
  const RadialMotion& m = ray.radial;
  const PolarMotion& p = ray.polar;
  const double a = ray.a, lambda = ray.constants.lambda;
  const double x = m.x_source + m.sense * m.rate * tau;
  const JacobiValues v = jacobi_functions(m.jacobi, x * m.jacobi.rate);
  KerrPoint point;
  point.r = tau == 0 ? m.r_source : radial_radius(m, v);
  point.cos_theta = polar.cos_theta;
  if (tau == 0) return point;
  const double r_plus = outer_horizon(a), r_minus = inner_horizon(a);
  const double wp = 2 * r_plus - a * lambda, wm = 2 * r_minus - a * lambda;
  // The inner horizon's terms carry a (2 r_- - a lambda), of order a^2 lambda, and I_- is at
  // most tau / (r_+ - r_-): below 1e-17 they are under the rounding of what they add to, and at
  // spins of 1e-12 its integral's pole at r_- ~ a^2 / 2 would underflow (NaN); so are left out.
  const bool inner = std::abs(a * wm) >= 1e-17;
  RadialIntegrals i;
  if (m.roots.kind == RadialCase::FourReal) {
    i = four_real_integrals(m, x, v, tau, r_plus, inner ? r_minus : -1);
  } else if (m.roots.kind == RadialCase::TwoReal) {
    i = two_real_integrals(m, z_of(m.roots, point.r), r_plus, inner ? r_minus : -1);
  } else {
    i = none_real_integrals(m, x, v, r_plus, inner ? r_minus : -1);
  }
  // dphi/dtau = a (2r - a lambda) / Delta + lambda / sin^2 theta, and dt/dtau = r^2 + 2r + 4 +
  // (2 r_+ (2 r_+ - a lambda) / (r - r_+) - 2 r_- (2 r_- - a lambda) / (r - r_-)) / (r_+ - r_-)
  // + a^2 cos^2 theta (partial fractions of PHYSICS.md's forms, M = 1).
  const double gap = r_plus - r_minus;
  point.phi = a * (wp * i.i_plus - wm * i.i_minus) / gap + lambda * (polar.g_phi - p.g_phi_source);
  point.t = i.i2 + 2 * i.i1 + 4 * tau +
            2 * (r_plus * wp * i.i_plus - r_minus * wm * i.i_minus) / gap + polar.g_t -
            p.g_t_source;
  return point;
}

// The crossing's Jacobi argument w = (2i + 1) K, i = the index returned.
double equator_index(const PolarMotion& p, int crossing) {
  return std::floor((p.w_source / p.quarter - 1) / 2) + crossing;
}

}  // namespace

KerrPoint point_after(const KerrRay& ray, double tau) {
  const PolarMotion& p = ray.polar;
  return point_with_polar(ray, tau, polar_state(p, p.w_source + p.rate * tau, tau != 0));
}

KerrPoint point_at_equator(const KerrRay& ray, int crossing) {
  const PolarMotion& p = ray.polar;
  if (p.vortical || p.u_plus == 0) return {kNaN, kNaN, kNaN, kNaN};
  // At w = (2i + 1) K each polar integral is 2i + 1 times its complete value.
  const double odd = 2 * equator_index(p, crossing) + 1, w = odd * p.quarter;
  PolarState polar{0, p.lambda == 0 ? 0.0 : p.pi_scale * odd * p.complete_pi, 0};
  polar.g_t = p.a2 * p.u_plus * (w - odd * p.complete_d) / p.rate;
  return point_with_polar(ray, (w - p.w_source) / p.rate, polar);
}

double mino_time_to_equator(const KerrRay& ray, int crossing) {
  const PolarMotion& p = ray.polar;
  if (p.vortical || p.u_plus == 0) return kInf;
  return ((2 * equator_index(p, crossing) + 1) * p.quarter - p.w_source) / p.rate;
}

}  // namespace lightcone::kerr

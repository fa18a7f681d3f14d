#include "lightcone/physics/schwarzschild.hpp"

#include <algorithm>
#include <boost/math/special_functions/ellint_rf.hpp>
#include <cmath>
#include <limits>
#include <numbers>

namespace lightcone {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSqrt3 = std::numbers::sqrt3;

double rf(double x, double y, double z) {
  return boost::math::ellint_rf(x, y, z);
}

// Carlson's reduction of int_y^x dt / sqrt(prod_i (a_i + b_i t)) for three real linear factors
// positive between the limits (Carlson 1988; DLMF 19.29(i), the fourth factor 1): given the
// factors' values X_i^2 at one end, Y_i^2 at the other and the distance d = |x - y|, it is
// 2 R_F(U12^2, U13^2, U23^2) with U12 = (X1 X2 Y3 + Y1 Y2 X3) / d and so on. Every term is
// positive, so nothing cancels, and a factor that vanishes at an end (a turning point) is fine.
double cubic_integral(double d, double x1, double x2, double x3, double y1, double y2, double y3) {
  if (d == 0) return 0;
  x1 = std::sqrt(x1), x2 = std::sqrt(x2), x3 = std::sqrt(x3);
  y1 = std::sqrt(y1), y2 = std::sqrt(y2), y3 = std::sqrt(y3);
  const double u12 = (x1 * x2 * y3 + y1 * y2 * x3) / d;
  const double u13 = (x1 * x3 * y2 + y1 * y3 * x2) / d;
  const double u23 = (x2 * x3 * y1 + y2 * y3 * x1) / d;
  return 2 * rf(u12 * u12, u13 * u13, u23 * u23);
}

// w = b / r, 0 at infinity.
double w_of(const PhotonOrbit& o, double r) {
  return std::isinf(r) ? 0.0 : o.impact / r;
}

// Turning orbit: 1 - w^2 + 2 (M/b) w^3 = scale (w - w_1) (w_2 - w) (1 - w / w_3) with
// w_2 = b / r_p, w_3 = b / r_3. The three factors at radius r, each as a ratio that stays
// accurate near its root, and exact at the turning points themselves. In the inner region
// (r <= r_3) the last two change sign.
struct Factors {
  double f1, f2, f3;
};
Factors turning_factors(const PhotonOrbit& o, double r, bool inner) {
  const double w2 = 1 / o.v_pos;
  Factors f{w_of(o, r) + o.w_neg, 0, 0};
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
// (2M/b) z ((z + c)^2 + n^2) with z = w - w_1 > 0. Byrd & Friedman (1971) 239.00 give
// int_0^z = F(phi, k) / sqrt(A), cos(phi) = (A - z) / (A + z), A^2 = c^2 + n^2; written with
// R_F (Carlson 1995, F = sin(phi) R_F(cos^2 phi, 1 - k^2 sin^2 phi, 1)) for z <= A (phi <=
// pi/2) it is 2 sqrt(z) R_F((A - z)^2, (A - z)^2 + 4 k'^2 A z, (A + z)^2). Past A, phi -> pi -
// phi is z -> A^2 / z, and F(pi - phi) = 2K - F(phi).
double half_integral(const PhotonOrbit& o, double z) {
  const double a = o.quad_a;
  if (z == a && o.modulus_c2 == 0) return kInf;  // b = b_c: the double root r = 3M
  const double d = (a - z) * (a - z);
  return 2 * std::sqrt(z) * rf(d, d + 4 * o.modulus_c2 * a * z, (a + z) * (a + z));
}
double captured_integral(const PhotonOrbit& o, double za, double zb) {
  const double a = o.quad_a;
  double lo = std::min(za, zb), hi = std::max(za, zb);
  if (lo == hi) return 0;
  if (hi <= a) return half_integral(o, hi) - half_integral(o, lo);
  if (lo >= a) return half_integral(o, a * a / lo) - half_integral(o, a * a / hi);
  const double full = half_integral(o, a);
  return (full - half_integral(o, lo)) + (full - half_integral(o, a * a / hi));
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

}  // namespace

double critical_impact_parameter(double mass) {
  return 3 * kSqrt3 * mass;
}

PhotonOrbit photon_orbit(double mass, double impact) {
  PhotonOrbit o;
  o.mass = mass;
  o.impact = impact;
  if (impact == 0) return o;  // radial: no angle is swept
  const double bc = critical_impact_parameter(mass);
  const double gap = (impact - bc) / impact;  // 1 - b_c / b, without cancellation
  o.critical = gap == 0;
  if (gap > 0) {
    // arccos(b_c / b) = 2 arcsin(sqrt(gap / 2)), accurate as b -> b_c.
    const double a = 2 * std::asin(std::sqrt(gap / 2)) / 3;
    o.turning = true;
    o.v_pos = 2 / kSqrt3 * std::cos(std::numbers::pi / 3 - a);
    const double v_neg = 2 / kSqrt3 * std::cos(a);  // |v_1|
    o.v_gap = 2 * std::sin(a);                      // v_p - v_3, by the cosines' difference
    // v_3 from the roots' product v_p v_3 v_1 = -2M/b, accurate as M/b -> 0.
    const double v3 = 2 * mass / impact / (o.v_pos * v_neg);
    o.w_neg = 1 / v_neg;
    o.scale = o.v_pos * v_neg;
    o.periapsis = impact * o.v_pos;
    o.inner_turning = impact * v3;
    return o;
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
  o.quad_a = std::hypot(c, n);
  o.modulus_c2 = n * n / (2 * o.quad_a * (o.quad_a + c));  // (A - c') / 2A, no cancellation
  return o;
}

double swept_angle(const PhotonOrbit& o, double r_a, double r_b) {
  if (o.impact == 0 || r_a == r_b) return 0;
  const double d = std::abs(w_of(o, r_a) - w_of(o, r_b));
  if (o.turning) {
    r_a = snap_to_turning_point(o, r_a), r_b = snap_to_turning_point(o, r_b);
    const bool inner = r_a <= o.inner_turning;
    const auto in_region = [&](double r) {
      return inner ? r <= o.inner_turning : r >= o.periapsis;
    };
    if (!in_region(r_a) || !in_region(r_b)) return kNaN;
    const Factors x = turning_factors(o, r_a, inner), y = turning_factors(o, r_b, inner);
    return cubic_integral(d, x.f1, x.f2, x.f3, y.f1, y.f2, y.f3) / std::sqrt(o.scale);
  }
  const double za = w_of(o, r_a) + o.w_neg, zb = w_of(o, r_b) + o.w_neg;
  return captured_integral(o, za, zb) / std::sqrt(o.scale);
}

RayCourse ray_course(const PhotonOrbit& o, double r0, bool outward) {
  RayCourse c;
  const double horizon = 2 * o.mass;
  if (o.turning) {
    r0 = snap_to_turning_point(o, r0);
    if (r0 >= o.periapsis) {
      c.fate = RayFate::kEscapes;
      if (outward) {
        c.angle_total = swept_angle(o, r0, kInf);
      } else {
        c.turning_radius = o.periapsis;
        c.angle_to_turn = swept_angle(o, r0, o.periapsis);
        c.angle_total = c.angle_to_turn + swept_angle(o, o.periapsis, kInf);
      }
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
  c.angle_total = swept_angle(o, r0, outward ? kInf : horizon);
  return c;
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

}  // namespace lightcone

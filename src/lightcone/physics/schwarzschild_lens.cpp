#include "lightcone/physics/schwarzschild_lens.hpp"

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "lightcone/physics/math_policy.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

double image_sweep(double psi, int order) {
  return order % 2 == 0 ? psi + order * kPi : (order + 1) * kPi - psi;
}

std::optional<RayBetween> ray_between(double mass, double r_a, double r_b, double psi, int order) {
  const double target = image_sweep(psi, order);
  const bool a_inner = r_a <= r_b;
  const double rho = a_inner ? r_a : r_b, outer = a_inner ? r_b : r_a;
  const double f_rho = 1 - 2 * mass / rho;
  const auto look_angle = [&](double impact) {
    return std::asin(std::min(1.0, impact * std::sqrt(f_rho) / rho));
  };
  // The critical look angle at the inner point, where the sweep to a radius beyond the photon
  // sphere diverges: inward outside it, outward inside it.
  const double alpha_critical = look_angle(critical_impact_parameter(mass));
  const double alpha_max = rho < 3 * mass ? alpha_critical : kPi - alpha_critical;
  // Both ends inside the photon sphere: past the critical angle the ray turns at r_3 < 3M and
  // falls back, crossing the outer radius twice until it only touches it (b = R / sqrt(f(R)));
  // the sweep grows along the first crossing, then back along the second, without bound as b
  // returns to b_c.
  const bool inside = outer < 3 * mass;
  const double alpha_touch = inside ? look_angle(outer / std::sqrt(1 - 2 * mass / outer)) : 0.0;
  const auto orbit_at = [&](double alpha) {
    return photon_orbit(mass, static_impact_parameter(mass, rho, std::sin(alpha)));
  };
  // The angle swept from the inner point, looking at alpha, to the outer radius: outward at
  // once, inward through the periapsis (outside the photon sphere, b > b_c), or (inside) out
  // to r_3 and back.
  const auto sweep = [&](double alpha, bool turned_inside) {
    const PhotonOrbit o = orbit_at(alpha);
    if (turned_inside)
      return swept_angle(o, rho, o.inner_turning) + swept_angle(o, o.inner_turning, outer);
    if (std::cos(alpha) >= 0) return swept_angle(o, rho, outer);
    return swept_angle(o, rho, o.periapsis) + swept_angle(o, o.periapsis, outer);
  };
  // The root on the stretch from `start` (sweep below psi) toward `end` (where it diverges).
  bool turned_inside = false;
  const auto solve = [&](double start, double end, bool turned, double& alpha) {
    const auto miss = [&](double x) { return sweep(x, turned) - target; };
    const double value_start = miss(start);
    if (value_start == 0) return alpha = start, true;
    double hi = start, value_hi = value_start;
    for (int k = 1; k <= 60 && !(value_hi >= 0); ++k) {
      hi = end + (start - end) * std::ldexp(1.0, -k);
      value_hi = miss(hi);
      if (std::isnan(value_hi)) return false;
    }
    if (!(value_hi >= 0)) return false;  // M = 0: no second image, nor a ray through the centre
    if (value_hi == 0) return alpha = hi, true;
    std::uintmax_t iterations = 200;
    const bool rising = start < hi;  // (the second stretch is solved from its upper end down)
    const auto [lo, up] = boost::math::tools::toms748_solve(
        miss, rising ? start : hi, rising ? hi : start, rising ? value_start : value_hi,
        rising ? value_hi : value_start, boost::math::tools::eps_tolerance<double>(), iterations,
        MathPolicy());
    alpha = (lo + up) / 2;
    return true;
  };
  double alpha = 0, stretch_lo = 0, stretch_hi = alpha_max;  // (the second: from alpha_critical)
  if (target > 0) {
    if (!inside || sweep(alpha_touch, false) >= target) {
      if (inside) stretch_hi = alpha_touch;
      if (!solve(0, inside ? alpha_touch : alpha_max, false, alpha)) return std::nullopt;
    } else {
      turned_inside = true;
      stretch_lo = alpha_critical, stretch_hi = alpha_touch;
      if (!solve(alpha_touch, alpha_critical, true, alpha)) return std::nullopt;
    }
  }
  const PhotonOrbit o = orbit_at(alpha);
  RayBetween ray;
  ray.impact = o.impact;
  ray.sweep = target;
  // At the outer end the ray moves outward (it escapes), or inward after turning inside the
  // photon sphere; the direction toward the inner end is the opposite.
  const double f_outer = std::isinf(outer) ? 1.0 : 1 - 2 * mass / outer;
  const double sin_outer = std::isinf(outer) ? 0.0 : o.impact * std::sqrt(f_outer) / outer;
  const double cos_outer =
      (turned_inside ? 1 : -1) * std::sqrt(std::max(0.0, (1 - sin_outer) * (1 + sin_outer)));
  const double sin_inner = std::sin(alpha), cos_inner = std::cos(alpha);
  if (a_inner) {
    ray.cos_a = cos_inner, ray.sin_a = sin_inner, ray.cos_b = cos_outer, ray.sin_b = sin_outer;
  } else {
    ray.cos_a = cos_outer, ray.sin_a = sin_outer, ray.cos_b = cos_inner, ray.sin_b = sin_inner;
  }
  if (std::isinf(outer))
    ray.time = kInf;
  else if (turned_inside)
    ray.time =
        coordinate_time(o, rho, o.inner_turning) + coordinate_time(o, o.inner_turning, outer);
  else if (cos_inner >= 0)
    ray.time = coordinate_time(o, rho, outer);
  else
    ray.time = coordinate_time(o, rho, o.periapsis) + coordinate_time(o, o.periapsis, outer);
  // |dsweep / dalpha|, a central difference well inside the stretch; for rays near the radial
  // one, the sweep continued to negative angles as the mirror image, -sweep(-alpha).
  const double h =
      1e-5 * std::min({1.0, stretch_hi - alpha, turned_inside ? alpha - stretch_lo : 1.0});
  const auto signed_sweep = [&](double x) {
    return x < 0 ? -sweep(-x, turned_inside) : sweep(x, turned_inside);
  };
  const double rate = std::abs(signed_sweep(alpha + h) - signed_sweep(alpha - h)) / (2 * h);
  // sin(psi) / sin(alpha), which tends to dsweep / dalpha for the radial ray; there, at a sweep
  // within 1e-6, the limit is taken (off by its square), not the ratio of two angles whose
  // sweep is accurate only to some 1e-14 absolutely.
  const double ratio = target > 1e-6 ? std::sin(psi) / sin_inner : rate;
  ray.sweep_rate = rate;
  if (std::isinf(outer)) {
    ray.focusing = ratio > 0 ? 1 / (f_rho * ratio * rate) : 0.0;
    return ray;
  }
  const double spread_out = outer * outer * std::abs(cos_outer) * rate * ratio;
  const double spread_in = f_rho / f_outer * spread_out;
  ray.spread_a_to_b = a_inner ? spread_out : spread_in;
  ray.spread_b_to_a = a_inner ? spread_in : spread_out;
  return ray;
}

FarImageTable::FarImageTable(double mass, double r0, int orders, int nodes)
    : mass_(mass), r0_(r0), step_(kPi / (nodes - 1)), nodes_(nodes) {
  present_.assign(orders, true);
  alpha_.assign(static_cast<std::size_t>(orders) * nodes, kNaN);
  slope_.assign(alpha_.size(), kNaN);
  for (int k = 0; k < orders; ++k)
    for (int i = 0; i < nodes; ++i) {
      const double psi = std::min(i * step_, kPi);
      const std::size_t at = static_cast<std::size_t>(k) * nodes + i;
      if (mass == 0 && k == 0) {  // straight lines, the one through the centre too
        alpha_[at] = psi;
        slope_[at] = 1;
        continue;
      }
      const auto ray = ray_between(mass, r0, kInf, psi, k);
      if (!ray) {
        present_[k] = false;
        break;
      }
      alpha_[at] = std::atan2(ray->sin_a, ray->cos_a);
      slope_[at] = (k % 2 == 0 ? 1 : -1) / ray->sweep_rate;
    }
}

std::optional<FarImageTable::Image> FarImageTable::at(double psi, int order) const {
  if (order >= static_cast<int>(present_.size()) || !present_[order] || !(psi >= 0 && psi <= kPi))
    return std::nullopt;
  const double x = psi / step_;
  const int i = std::min(static_cast<int>(x), nodes_ - 2);
  const double t = x - i;
  const std::size_t at = static_cast<std::size_t>(order) * nodes_ + i;
  const double a0 = alpha_[at], a1 = alpha_[at + 1];
  const double m0 = slope_[at] * step_, m1 = slope_[at + 1] * step_;
  // Cubic Hermite on [0, 1], and its derivative.
  const double t2 = t * t, t3 = t2 * t;
  const double alpha = (2 * t3 - 3 * t2 + 1) * a0 + (t3 - 2 * t2 + t) * m0 +
                       (-2 * t3 + 3 * t2) * a1 + (t3 - t2) * m1;
  const double slope = ((6 * t2 - 6 * t) * a0 + (3 * t2 - 4 * t + 1) * m0 + (-6 * t2 + 6 * t) * a1 +
                        (3 * t2 - 2 * t) * m1) /
                       step_;
  const double sin_psi = std::sin(psi), sin_alpha = std::sin(alpha);
  Image image;
  image.alpha = alpha;
  if (sin_psi > 1e-12) {
    image.solid_angle_ratio = sin_alpha * std::abs(slope) / sin_psi;
  } else if (std::abs(sin_alpha) < 1e-9) {
    image.solid_angle_ratio = slope * slope;
  } else {
    return std::nullopt;
  }
  return image;
}

}  // namespace lightcone

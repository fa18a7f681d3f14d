#include "lightcone/physics/schwarzschild_lens.hpp"

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The stretches of a ray on which it can pass r_e: before its turning point (or with none), and
// after it. Each gives the angle swept from the observer to r_e on that stretch, NaN where the
// ray does not pass r_e there.
enum class Stretch { kBeforeTurn, kAfterTurn };

struct Reach {
  double sweep = kNaN, time = kNaN;
};

Reach reach(double mass, double r0, double r_e, double alpha, Stretch stretch) {
  const double sin_alpha = std::sin(alpha), cos_alpha = std::cos(alpha);
  const PhotonOrbit o = photon_orbit(mass, static_impact_parameter(mass, r0, sin_alpha));
  const RayCourse c = ray_course(o, r0, cos_alpha > 0);
  Reach out;
  const auto time = [&](double a, double b) {
    return std::isinf(a) || std::isinf(b) ? kInf : coordinate_time(o, a, b);
  };
  if (stretch == Stretch::kBeforeTurn) {
    // From r0 toward the turning point (or to the end): r_e between r0 and where it goes.
    const double end = c.turning_radius > 0          ? c.turning_radius
                       : c.fate == RayFate::kEscapes ? kInf
                                                     : 2 * mass;
    if (!(std::min(r0, end) <= r_e && r_e <= std::max(r0, end)) || r_e == r0) return out;
    out.sweep = swept_angle(o, r0, r_e);
    out.time = time(r0, r_e);
    return out;
  }
  if (c.turning_radius <= 0) return out;
  const double end = c.fate == RayFate::kEscapes ? kInf : 2 * mass;
  const double turn = c.turning_radius;
  if (!(std::min(turn, end) <= r_e && r_e <= std::max(turn, end))) return out;
  out.sweep = c.angle_to_turn + swept_angle(o, turn, r_e);
  out.time = time(r0, turn) + time(turn, r_e);
  return out;
}

// Look angles alpha in (0, pi) to bracket on: evenly spaced, crowding toward 0 and pi, and
// toward the critical angle from both sides, where the sweep grows like -ln |alpha - alpha_c|.
std::vector<double> alpha_grid(double mass, double r0) {
  std::vector<double> grid;
  constexpr int kEven = 720;
  for (int i = 1; i < kEven; ++i) grid.push_back(kPi * i / kEven);
  // And toward 0 and pi (nearly radial rays: a point nearly in line with the hole).
  for (double d = 1e-12; d < kPi / kEven; d *= 2) grid.push_back(d), grid.push_back(kPi - d);
  const double s = critical_impact_parameter(mass) * std::sqrt(1 - 2 * mass / r0) / r0;
  if (s <= 1) {
    const double a = std::asin(s);
    for (const double critical : {a, kPi - a})
      for (double d = 1e-15; d < 0.05; d *= 1.5)
        for (const double x : {critical - d, critical + d})
          if (x > 0 && x < kPi) grid.push_back(x);
  }
  std::sort(grid.begin(), grid.end());
  return grid;
}

}  // namespace

double image_sweep(double psi, int order) {
  return order % 2 == 0 ? psi + order * kPi : (order + 1) * kPi - psi;
}

std::optional<LensImage> lens_image(double mass, double r0, double r_e, double psi, int order) {
  const double target = image_sweep(psi, order);
  const std::vector<double> grid = alpha_grid(mass, r0);
  for (const Stretch stretch : {Stretch::kBeforeTurn, Stretch::kAfterTurn}) {
    const auto miss = [&](double alpha) {
      return reach(mass, r0, r_e, alpha, stretch).sweep - target;
    };
    // Where the stretch begins or ends between two grid angles (r_e at the turning point), the
    // last angle on it, to double precision: a root between it and the grid is not lost.
    const auto edge = [&](double on, double off) {
      for (int i = 0; i < 64; ++i) {
        const double mid = (on + off) / 2;
        if (mid == on || mid == off) break;
        (std::isfinite(miss(mid)) ? on : off) = mid;
      }
      return on;
    };
    double previous_alpha = kNaN, previous = kNaN;
    for (const double grid_alpha : grid) {
      const double grid_value = miss(grid_alpha);
      double alpha = grid_alpha, value = grid_value;
      if (std::isfinite(value) && std::isnan(previous) && !std::isnan(previous_alpha)) {
        // Entering the stretch: start from its edge.
        previous_alpha = edge(alpha, previous_alpha);
        previous = miss(previous_alpha);
      } else if (std::isnan(value) && std::isfinite(previous)) {
        // Leaving it: end at its edge.
        alpha = edge(previous_alpha, alpha);
        value = miss(alpha);
      }
      if (value == 0 ||
          (std::isfinite(previous) && std::isfinite(value) && (previous < 0) != (value < 0))) {
        double root = alpha;
        if (value != 0) {
          std::uintmax_t iterations = 200;
          const auto [lo, hi] = boost::math::tools::toms748_solve(
              miss, previous_alpha, alpha, previous, value,
              boost::math::tools::eps_tolerance<double>(), iterations);
          root = (lo + hi) / 2;
        }
        const Reach r = reach(mass, r0, r_e, root, stretch);
        if (!std::isfinite(r.sweep)) continue;
        LensImage image;
        image.cos_alpha = std::cos(root);
        image.sin_alpha = std::sin(root);
        image.impact = static_impact_parameter(mass, r0, image.sin_alpha);
        image.sweep = r.sweep;
        image.time = r.time;
        return image;
      }
      previous_alpha = grid_alpha;
      previous = grid_value;
    }
  }
  return std::nullopt;
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
        rising ? value_hi : value_start, boost::math::tools::eps_tolerance<double>(), iterations);
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

}  // namespace lightcone

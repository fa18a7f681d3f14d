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

// The root of miss, bracketed by x_a and x_b (either order) where it takes m_a and m_b.
template <class Miss>
double root_between(const Miss& miss, double x_a, double x_b, double m_a, double m_b) {
  if (x_a > x_b) std::swap(x_a, x_b), std::swap(m_a, m_b);
  std::uintmax_t iterations = 200;
  const auto [lo, up] = boost::math::tools::toms748_solve(
      miss, x_a, x_b, m_a, m_b, boost::math::tools::eps_tolerance<double>(), iterations,
      MathPolicy());
  return (lo + up) / 2;
}

// The rays from the inner of two radii to the outer, in their look angle alpha at the inner end:
// the angle each sweeps to the outer radius, the stretches of alpha on which that grows
// monotonically, and the one root on a stretch of sweep = image_sweep(psi, order).
class LookAngleSolve {
 public:
  LookAngleSolve(double mass, double r_a, double r_b, double psi, int order,
                 RayBetweenStart* warm_start, const FacingSide* facing)
      : mass_(mass),
        target_(image_sweep(psi, order)),
        a_inner_(r_a <= r_b),
        rho_(a_inner_ ? r_a : r_b),
        outer_(a_inner_ ? r_b : r_a),
        f_rho_(1 - 2 * mass / rho_),
        f_outer_(std::isinf(outer_) ? 1.0 : 1 - 2 * mass / outer_),
        warm_start_(warm_start),
        facing_(facing) {
    // The critical look angle at the inner point, where the sweep to a radius beyond the photon
    // sphere diverges: inward outside it, outward inside it.
    alpha_critical_ = look_angle(critical_impact_parameter(mass));
    alpha_max_ = rho_ < 3 * mass ? alpha_critical_ : kPi - alpha_critical_;
    // Both ends inside the photon sphere: past the critical angle the ray turns at r_3 < 3M and
    // falls back, crossing the outer radius twice until it only touches it (b = R / sqrt(f(R)));
    // the sweep grows along the first crossing, then back along the second, without bound as b
    // returns to b_c.
    inside_ = outer_ < 3 * mass;
    alpha_touch_ = inside_ ? look_angle(outer_ / std::sqrt(1 - 2 * mass / outer_)) : 0.0;
  }

  // The look angle at the root, on the stretch it lies on (false where there is none, or the
  // solve stopped on a surface's back), and that stretch's ends.
  struct Root {
    double alpha = 0;
    bool turned_inside = false;
    double stretch_lo = 0, stretch_hi = 0;
  };
  bool find(Root& root) {
    root.stretch_hi = alpha_max_;  // (the second: from alpha_critical)
    if (!(target_ > 0)) return true;
    if (!inside_ || sweep(alpha_touch_, false) >= target_) {
      if (inside_) root.stretch_hi = alpha_touch_;
      return solve(0, inside_ ? alpha_touch_ : alpha_max_, false, root.alpha);
    }
    root.turned_inside = true;
    root.stretch_lo = alpha_critical_, root.stretch_hi = alpha_touch_;
    return solve(alpha_touch_, alpha_critical_, true, root.alpha);
  }

  double target() const { return target_; }
  bool a_inner() const { return a_inner_; }
  double inner() const { return rho_; }
  double outer() const { return outer_; }
  double f_inner() const { return f_rho_; }
  double f_outer() const { return f_outer_; }

  PhotonOrbit orbit_at(double alpha) const {
    return photon_orbit(mass_, static_impact_parameter(mass_, rho_, std::sin(alpha)));
  }
  // The angle swept from the inner point, looking at alpha, to the outer radius: outward at
  // once, inward through the periapsis (outside the photon sphere, b > b_c), or (inside) out
  // to r_3 and back.
  double sweep(double alpha, bool turned_inside) const {
    const PhotonOrbit o = orbit_at(alpha);
    if (turned_inside)
      return swept_angle(o, rho_, o.inner_turning) + swept_angle(o, o.inner_turning, outer_);
    if (std::cos(alpha) >= 0) return swept_angle(o, rho_, outer_);
    return swept_angle(o, rho_, o.periapsis) + swept_angle(o, o.periapsis, outer_);
  }
  // At the outer end the ray moves outward (it escapes), or inward after turning inside the
  // photon sphere; the direction toward the inner end is the opposite, at sin = b sqrt(f) / R.
  void outer_direction(double impact, bool turned, double& cos_outer, double& sin_outer) const {
    sin_outer = std::isinf(outer_) ? 0.0 : impact * std::sqrt(f_outer_) / outer_;
    cos_outer = (turned ? 1 : -1) * std::sqrt(std::max(0.0, (1 - sin_outer) * (1 + sin_outer)));
  }

 private:
  double look_angle(double impact) const {
    return std::asin(std::min(1.0, impact * std::sqrt(f_rho_) / rho_));
  }

  // Whether every ray with look angle in [x_a, x_b] at the inner end leaves end a on the back
  // of `facing` (by more than rounding: the caller's cos(incidence) from the root is then
  // negative too). Those directions span an arc under pi long, from the look angles at its ends
  // (end a inner) or from the least and the greatest impact parameter over them (end a outer;
  // b grows with sin(alpha)); a sinusoid whose peak lies within such an arc is not negative at
  // one end of it at least: the arc's ends decide.
  bool unwanted_between(double x_a, double x_b, bool turned) const {
    if (!facing_) return false;
    const auto behind = [&](double cos_x, double sin_x) {
      return facing_->outward * cos_x + facing_->round * sin_x < -1e-12;
    };
    if (a_inner_)
      return behind(std::cos(x_a), std::sin(x_a)) && behind(std::cos(x_b), std::sin(x_b));
    const double lo = std::min(x_a, x_b), hi = std::max(x_a, x_b);
    const double sin_least = std::min(std::sin(lo), std::sin(hi));
    const double sin_most =
        lo <= kPi / 2 && kPi / 2 <= hi ? 1.0 : std::max(std::sin(lo), std::sin(hi));
    double cos_least, sin_least_outer, cos_most, sin_most_outer;
    outer_direction(static_impact_parameter(mass_, rho_, sin_least), turned, cos_least,
                    sin_least_outer);
    outer_direction(static_impact_parameter(mass_, rho_, sin_most), turned, cos_most,
                    sin_most_outer);
    return behind(cos_least, sin_least_outer) && behind(cos_most, sin_most_outer);
  }

  // The root on the stretch from `start` (sweep below the target) toward `end` (where it
  // diverges): from the warm start where that brackets it, else from the stretch's start.
  bool solve(double start, double end, bool turned, double& alpha) {
    if (unwanted_between(start, end, turned)) return false;
    const auto miss = [&](double x) { return sweep(x, turned) - target_; };
    bool unwanted = false;
    if (solve_from_warm_start(miss, start, end, turned, alpha, unwanted)) return true;
    if (unwanted) return false;
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
    if (unwanted_between(start, hi, turned)) return false;
    alpha = root_between(miss, start, hi, value_start, value_hi);
    return true;
  }

  // From an earlier solve's look angle, where it lies on this stretch: a Newton step on its
  // rate, a twentieth too long so that the root usually falls short of it, then steps doubling
  // (halfway to the stretch's end where one would leave it) until the miss changes sign. False
  // where that finds no bracket in a few steps, or the light is unwanted (then `unwanted`).
  template <class Miss>
  bool solve_from_warm_start(const Miss& miss, double start, double end, bool turned, double& alpha,
                             bool& unwanted) {
    RayBetweenStart* warm = warm_start_;
    if (!warm || warm->inner_is_a != a_inner_ || warm->turned_inside != turned ||
        !(warm->rate > 0) || !(std::min(start, end) < warm->alpha) ||
        !(warm->alpha < std::max(start, end)))
      return false;
    const double x0 = warm->alpha, m0 = miss(x0);
    if (std::isnan(m0)) return false;
    if (m0 == 0) return alpha = x0, true;
    // The miss grows from `start` toward `end`.
    const double toward = m0 < 0 ? end : start;
    const double direction = toward > x0 ? 1.0 : -1.0;
    double step = 1.05 * std::abs(m0) / warm->rate;
    double x = x0, m = m0;
    for (int k = 0; k < 6; ++k, step *= 2) {
      if (unwanted_between(x, toward, turned)) return unwanted = true, false;
      double next = x + direction * step;
      if (!((next - x) * (toward - next) > 0)) next = (x + toward) / 2;
      const double m_next = miss(next);
      if (std::isnan(m_next)) return false;
      if (m_next == 0) return alpha = next, true;
      if ((m_next > 0) != (m0 > 0)) {
        if (unwanted_between(x, next, turned)) {
          // The next solve starts where the secant through the bracket's ends puts the root.
          warm->alpha = x - m * (next - x) / (m_next - m);
          return unwanted = true, false;
        }
        return alpha = root_between(miss, x, next, m, m_next), true;
      }
      x = next, m = m_next;
    }
    return false;
  }

  double mass_, target_;
  bool a_inner_;
  double rho_, outer_, f_rho_, f_outer_;
  double alpha_critical_ = 0, alpha_max_ = 0, alpha_touch_ = 0;
  bool inside_ = false;
  RayBetweenStart* warm_start_;
  const FacingSide* facing_;
};

// |dsweep / dalpha| at the root, a central difference well inside its stretch; for rays near the
// radial one, the sweep continued to negative angles as the mirror image, -sweep(-alpha).
double sweep_rate(const LookAngleSolve& solve, const LookAngleSolve::Root& root) {
  const double alpha = root.alpha;
  const bool turned = root.turned_inside;
  const double h =
      1e-5 * std::min({1.0, root.stretch_hi - alpha, turned ? alpha - root.stretch_lo : 1.0});
  const auto signed_sweep = [&](double x) {
    return x < 0 ? -solve.sweep(-x, turned) : solve.sweep(x, turned);
  };
  return std::abs(signed_sweep(alpha + h) - signed_sweep(alpha - h)) / (2 * h);
}

// The coordinate time from the inner end, looking at alpha, to the outer one (infinity for an
// outer end far away).
double time_between(const LookAngleSolve& solve, const PhotonOrbit& o, double cos_inner,
                    bool turned_inside) {
  const double rho = solve.inner(), outer = solve.outer();
  if (std::isinf(outer)) return kInf;
  if (turned_inside)
    return coordinate_time(o, rho, o.inner_turning) + coordinate_time(o, o.inner_turning, outer);
  if (cos_inner >= 0) return coordinate_time(o, rho, outer);
  return coordinate_time(o, rho, o.periapsis) + coordinate_time(o, o.periapsis, outer);
}

}  // namespace

double image_sweep(double psi, int order) {
  return order % 2 == 0 ? psi + order * kPi : (order + 1) * kPi - psi;
}

std::optional<RayBetween> ray_between(double mass, double r_a, double r_b, double psi, int order,
                                      RayBetweenStart* warm_start, const FacingSide* facing,
                                      bool timed) {
  LookAngleSolve solve(mass, r_a, r_b, psi, order, warm_start, facing);
  LookAngleSolve::Root root;
  if (!solve.find(root)) return std::nullopt;
  const double alpha = root.alpha;
  const PhotonOrbit o = solve.orbit_at(alpha);
  RayBetween ray;
  ray.impact = o.impact;
  ray.sweep = solve.target();
  double cos_outer, sin_outer;
  solve.outer_direction(o.impact, root.turned_inside, cos_outer, sin_outer);
  const double sin_inner = std::sin(alpha), cos_inner = std::cos(alpha);
  if (solve.a_inner()) {
    ray.cos_a = cos_inner, ray.sin_a = sin_inner, ray.cos_b = cos_outer, ray.sin_b = sin_outer;
  } else {
    ray.cos_a = cos_outer, ray.sin_a = sin_outer, ray.cos_b = cos_inner, ray.sin_b = sin_inner;
  }
  ray.time = timed ? time_between(solve, o, cos_inner, root.turned_inside) : kNaN;
  const double rate = sweep_rate(solve, root);
  // sin(psi) / sin(alpha), which tends to dsweep / dalpha for the radial ray; there, at a sweep
  // within 1e-6, the limit is taken (off by its square), not the ratio of two angles whose
  // sweep is accurate only to some 1e-14 absolutely.
  const double ratio = solve.target() > 1e-6 ? std::sin(psi) / sin_inner : rate;
  ray.sweep_rate = rate;
  if (warm_start) *warm_start = {alpha, rate, solve.a_inner(), root.turned_inside};
  const double f_inner = solve.f_inner(), outer = solve.outer();
  if (std::isinf(outer)) {
    ray.focusing = ratio > 0 ? 1 / (f_inner * ratio * rate) : 0.0;
    return ray;
  }
  const double spread_out = outer * outer * std::abs(cos_outer) * rate * ratio;
  const double spread_in = f_inner / solve.f_outer() * spread_out;
  ray.spread_a_to_b = solve.a_inner() ? spread_out : spread_in;
  ray.spread_b_to_a = solve.a_inner() ? spread_in : spread_out;
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

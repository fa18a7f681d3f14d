#include "lightcone/physics/schwarzschild_geodesics.hpp"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "lightcone/physics/math_policy.hpp"

namespace lightcone {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The root of the increasing g in [lo, hi], g(lo) < 0 <= g(hi) (TOMS 748 to the last bits).
template <class G>
double increasing_root(const G& g, double lo, double hi) {
  const double g_lo = g(lo), g_hi = g(hi);
  if (!(g_lo < 0)) return lo;
  if (!(g_hi > 0)) return hi;
  std::uintmax_t iterations = 200;
  const auto [a, b] = boost::math::tools::toms748_solve(
      g, lo, hi, g_lo, g_hi, boost::math::tools::eps_tolerance<double>(), iterations, MathPolicy());
  return a + (b - a) / 2;
}

// The root of the increasing g on [lo, end), where g -> +infinity at `end`: the bracket's upper
// end is moved halfway to `end` until g is >= 0 there. `end` itself when no double below it
// reaches the root.
template <class G>
double root_before_pole(const G& g, double lo, double end) {
  double hi = lo + (end - lo) / 2;
  while (g(hi) < 0) {
    const double next = hi + (end - hi) / 2;
    if (!(next > hi && next < end)) return end;
    lo = hi;
    hi = next;
  }
  return increasing_root(g, lo, hi);
}

}  // namespace

RadialFall::RadialFall(double mass, double r0, double reference)
    : mass_(mass), r0_(r0), reference_(reference) {}

// Everything below is written in quantities of order 1 (e = sqrt(2M / r0) or
// sqrt(2M / reference), ratios of radii), so that neither a tiny mass far away nor a huge one
// overflows or underflows; e = 0 (2M / r below the smallest double) is the flat limit, the body
// at rest (from r0) or on t = tau.

RadialFall RadialFall::from_rest(double mass, double r0) {
  RadialFall f(mass, r0, r0);
  f.e_ = std::sqrt(2 * (mass / r0));
  f.energy_ = std::sqrt((r0 - 2 * mass) / r0);
  f.eta_horizon_ = 2 * std::atan2(f.energy_, f.e_);  // tan(eta_h / 2) = a = E / e
  return f;
}

RadialFall RadialFall::from_infinity(double mass, double reference) {
  RadialFall f(mass, std::numeric_limits<double>::infinity(), reference);
  f.energy_ = 1;
  f.e_ = std::sqrt(2 * (mass / reference));
  f.one_minus_e_ = (reference - 2 * mass) / (reference * (1 + f.e_));
  return f;
}

double RadialFall::cycloid_eta(double tau) const {
  if (!(tau > 0)) return 0;
  // tau = k (eta + sin eta), k = sqrt(r0^3 / 8M) = r0 / (2e).
  const double target = 2 * e_ * (tau / r0_);
  if (!(target < std::numbers::pi)) return std::numbers::pi;
  return increasing_root([&](double eta) { return eta + std::sin(eta) - target; }, 0.0,
                         std::numbers::pi);
}

double RadialFall::cycloid_time(double eta, double tau) const {
  // MTW's t = 2M [ln((a + s) / (a - s)) + a (eta + r0 / 4M (eta + sin eta))], s = tan(eta/2),
  // a = E / e, 2M = r0 e^2: t = 2M ln((1 + q) / (1 - q)) + r0 e E eta + E tau, q = s / a.
  const double q = std::tan(eta / 2) * e_ / energy_;
  double log_term;
  if (q < 0.5) {
    log_term = 2 * std::atanh(q);
  } else {
    // (1 + q) / (1 - q) = (1 + q)^2 / (1 - q^2), 1 - q^2 = (a^2 - s^2) / a^2 =
    // (r - 2M) / ((r0 - 2M) cos^2(eta/2)), with r - 2M = r0 (cos^2(eta/2) - cos^2(eta_h/2)) =
    // r0 sin((eta_h - eta)/2) sin((eta_h + eta)/2).
    const double c = std::cos(eta / 2);
    const double gap = std::sin((eta_horizon_ - eta) / 2) * std::sin((eta_horizon_ + eta) / 2) /
                       (energy_ * energy_ * c * c);
    log_term = 2 * std::log1p(q) - std::log(gap);
  }
  return r0_ * e_ * e_ * log_term + r0_ * e_ * energy_ * eta + energy_ * tau;
}

double RadialFall::infinity_time(double tau) const {
  // With s = sqrt(r / reference) and x = s / e = sqrt(r / 2M): s^3 = 1 - u, u = 3/2 e tau /
  // reference, and t = -2M [F(x) - F(x_ref)] = tau - 4M (x - x_ref) - 2M ln((x - 1)(x_ref + 1)
  // / ((x + 1)(x_ref - 1))), where 4M (x - x_ref) = 2 reference e (s - 1), 2M = reference e^2
  // and the ratio is (s - e)(1 + e) / ((s + e)(1 - e)): log1p of 2 e (s - 1) / ((s + e)(1 - e))
  // near the reference, ln of the ratio near the horizon (s - e from s^3 - e^3 = 1 - e^3 - u).
  const double e = e_, u = 1.5 * e * (tau / reference_);
  const double s = std::cbrt(1 - u);
  const double s_minus_1 = -u / (s * s + s + 1);
  const double z = 2 * e * s_minus_1 / ((s + e) * one_minus_e_);
  double log_term;
  if (std::abs(z) < 0.5) {
    log_term = std::log1p(z);
  } else {
    const double s_minus_e = (one_minus_e_ * (1 + e + e * e) - u) / (s * s + s * e + e * e);
    log_term = std::log(s_minus_e * (1 + e) / ((s + e) * one_minus_e_));
  }
  return tau - 2 * reference_ * e * s_minus_1 - reference_ * e * e * log_term;
}

RadialFallPoint RadialFall::at_proper_time(double tau) const {
  const double horizon = horizon_proper_time();
  if (!is_from_infinity()) {
    const double eta = std::copysign(cycloid_eta(std::abs(tau)), tau);
    const double c = std::cos(eta / 2);
    const double r = std::abs(eta) < std::numbers::pi ? r0_ * c * c : 0;
    if (!(std::abs(tau) < horizon)) return {r, kNaN, kNaN};
    // v = -tan(eta/2) / a.
    return {r, std::copysign(cycloid_time(std::abs(eta), std::abs(tau)), tau),
            -std::tan(eta / 2) * e_ / energy_};
  }
  const double cube = 1 - 1.5 * e_ * (tau / reference_);  // (r / reference)^(3/2)
  if (!(cube > 0)) return {0, kNaN, kNaN};
  const double s = std::cbrt(cube);
  const double r = reference_ * s * s;
  if (!(tau < horizon)) return {r, kNaN, kNaN};
  return {r, infinity_time(tau), -e_ / s};  // v = -sqrt(2M / r)
}

double RadialFall::proper_time_at_radius(double r) const {
  if (!is_from_infinity()) {
    if (!(r < r0_)) return 0;
    const double eta = 2 * std::atan(std::sqrt((r0_ - r) / r));  // pi at r = 0
    return r0_ * (eta + std::sin(eta)) / (2 * e_);
  }
  // tau = 2/3 reference (1 - s^3) / e, 1 - s^3 = (1 - s)(1 + s + s^2),
  // 1 - s = (reference - r) / (reference (1 + s)).
  const double s = std::sqrt(std::max(r, 0.0) / reference_);
  const double one_minus_s = (reference_ - r) / (reference_ * (1 + s));
  return 2.0 / 3 * reference_ * one_minus_s * (1 + s + s * s) / e_;
}

RadialFallPoint RadialFall::at_radius(double r) const {
  const double tau = proper_time_at_radius(r);
  if (!is_from_infinity()) {
    const double eta = 2 * std::atan(std::sqrt((r0_ - r) / r));
    return {r, cycloid_time(eta, tau), -std::tan(eta / 2) * e_ / energy_};
  }
  return {r, infinity_time(tau), -e_ / std::sqrt(r / reference_)};
}

RadialFallPoint RadialFall::at_coordinate_time_between(double t, double lo, double t_lo, double hi,
                                                       double t_hi) const {
  double r = t_lo > t_hi ? hi + (lo - hi) * ((t - t_hi) / (t_lo - t_hi)) : lo;
  if (!(r >= lo && r <= hi)) r = (lo + hi) / 2;
  const double tolerance = 4 * std::numeric_limits<double>::epsilon() * hi;
  RadialFallPoint p;
  for (int iteration = 0; iteration < 100; ++iteration) {
    p = at_radius(r);
    const double miss = p.coordinate_time - t;
    if (miss == 0) break;
    (miss > 0 ? lo : hi) = r;  // t(r) decreases: a later time is a radius too small
    // -dr/dt, 0 at rest (r0), where a step is no step: the midpoint then.
    const double f = 1 - 2 * mass_ / r, rate = f * std::sqrt(energy_ * energy_ - f) / energy_;
    const double next = r + miss * rate;
    if (rate > 0 && std::abs(next - r) <= tolerance && next >= lo && next <= hi) break;
    r = next > lo && next < hi ? next : (lo + hi) / 2;
    if (!(hi - lo > tolerance)) {
      p = at_radius(r);
      break;
    }
  }
  return p;
}

double RadialFall::proper_time_at_coordinate_time(double t) const {
  if (t == 0) return 0;
  const double horizon = horizon_proper_time();
  if (!is_from_infinity()) {
    // t and tau are odd in eta; t(eta) increases on [0, eta_h) to +infinity.
    const double target = std::abs(t);
    const auto tau_at = [&](double eta) { return r0_ * (eta + std::sin(eta)) / (2 * e_); };
    const double eta = root_before_pole(
        [&](double eta) { return cycloid_time(eta, tau_at(eta)) - target; }, 0.0, eta_horizon_);
    if (!(eta < eta_horizon_)) return std::copysign(horizon, t);
    return std::copysign(tau_at(eta), t);
  }
  const auto g = [&](double tau) { return infinity_time(tau) - t; };
  if (t < 0) {
    // Before the reference r >= reference, so 1 <= dt/dtau = 1/f <= 1/f_ref: t(tau) lies in
    // [tau / f_ref, tau], and the root tau in [t, t f_ref].
    return increasing_root(g, t, t * (1 - e_ * e_));
  }
  // After it, dt/dtau >= 1: tau <= t.
  if (t < horizon) return increasing_root(g, 0.0, t);
  return root_before_pole(g, 0.0, horizon);
}

CircularOrbitPoint circular_orbit_at_proper_time(double mass, double r, double tau) {
  if (!(r > 3 * mass)) return {kNaN, kNaN, kNaN};
  const double t = tau / std::sqrt((r - 3 * mass) / r);
  return {t, std::sqrt(mass / r) / r * t, std::sqrt(mass / (r - 2 * mass))};
}

double circular_orbit_proper_time(double mass, double r, double t) {
  if (!(r > 3 * mass)) return kNaN;
  return t * std::sqrt((r - 3 * mass) / r);
}

}  // namespace lightcone

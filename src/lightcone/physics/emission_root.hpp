// The emission time of light that reaches a receiver at a given time from a moving source, when
// its travel time has no closed form (curved rays near a black hole): the root of
// late(t) = t + T(t) - t_receiver, T(t) the travel time from where the source is at t. late rises
// strictly with t (nothing outruns light), so the root is bracketed by stepping from a start
// toward it and solved with Boost's TOMS 748 to full precision; never a capped fixed point.
#pragma once

#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <optional>

#include "lightcone/physics/math_policy.hpp"

namespace lightcone {

// `late(t)`: as above; +infinity where the source's light never arrives (within a horizon), NaN
// where there is no such light (no ray of the order asked for). `start` (<= t_receiver, its
// value `late_start`) is where the bracket starts: the receiver's time, or a guess near the root.
// Steps of one and a half times |late| (late's slope lies between 0 and 2), doubling, reach past
// the root; an infinite late end is moved back by bisection until it is finite. None where the
// bracket meets NaN or cannot be closed.
template <class Late>
std::optional<double> emission_time_root(const Late& late, double t_receiver, double start,
                                         double late_start) {
  if (std::isnan(late_start)) return std::nullopt;
  if (late_start == 0) return start;
  double lo = start, hi = start, late_lo = late_start, late_hi = late_start;
  const auto first_step = [&](double l) {
    return std::isfinite(l) ? std::max(1.5 * std::abs(l), 1e-9 * (1 + std::abs(start))) : 1.0;
  };
  if (late_start > 0) {
    for (double step = first_step(late_start); late_lo > 0 && step < 1e300; step *= 2) {
      hi = lo, late_hi = late_lo;
      lo = start - step;
      late_lo = late(lo);
    }
    if (!(late_lo <= 0)) return std::nullopt;
  } else {
    for (double step = first_step(late_start); !(late_hi > 0) && hi < t_receiver; step *= 2) {
      lo = hi, late_lo = late_hi;
      hi = std::min(start + step, t_receiver);
      late_hi = late(hi);
    }
    if (!(late_hi > 0)) return std::nullopt;  // (a source inside its own light cone)
  }
  for (int k = 0; !std::isfinite(late_hi) && k < 200; ++k) {
    const double mid = lo + (hi - lo) / 2;
    const double late_mid = late(mid);
    if (std::isnan(late_mid)) return std::nullopt;
    (late_mid <= 0 ? lo : hi) = mid;
    (late_mid <= 0 ? late_lo : late_hi) = late_mid;
  }
  if (!std::isfinite(late_hi)) return std::nullopt;
  if (late_lo == 0) return lo;
  bool failed = false;
  const auto checked = [&](double t) {
    const double value = late(t);
    if (std::isnan(value)) failed = true;
    return std::isnan(value) ? 0.0 : value;
  };
  std::uintmax_t iterations = 200;
  const auto [a, b] = boost::math::tools::toms748_solve(checked, lo, hi, late_lo, late_hi,
                                                        boost::math::tools::eps_tolerance<double>(),
                                                        iterations, MathPolicy());
  if (failed) return std::nullopt;
  return (a + b) / 2;
}

}  // namespace lightcone

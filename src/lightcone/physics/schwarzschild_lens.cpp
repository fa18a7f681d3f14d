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

}  // namespace lightcone

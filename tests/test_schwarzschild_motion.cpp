// The speed the static observers of a Schwarzschild hole measure of a body on a coordinate line
// (schwarzschild_motion.hpp), against derivations made here: the metric in Cartesian
// Schwarzschild coordinates contracted with the body's 4-velocity and the static observer's,
// and the peak along a line found by sampling and golden-section search over t.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "lightcone/physics/schwarzschild_motion.hpp"

namespace lightcone {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The Schwarzschild metric in the coordinates (t, x, y, z), x = r n: with f = 1 - 2M/r,
// ds^2 = -f dt^2 + (n.dx)^2 / f + |dx|^2 - (n.dx)^2 (dr = n.dx, r^2 dOmega^2 the rest).
struct Metric {
  std::array<std::array<double, 4>, 4> g{};

  Metric(double mass, const Vec3& x) {
    const double r = length(x), f = 1 - 2 * mass / r;
    const double n[3] = {x.x / r, x.y / r, x.z / r};
    g[0][0] = -f;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) g[i + 1][j + 1] = (i == j ? 1 : 0) + (1 / f - 1) * n[i] * n[j];
  }
  double operator()(const std::array<double, 4>& a, const std::array<double, 4>& b) const {
    double s = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) s += g[i][j] * a[i] * b[j];
    return s;
  }
};

// The speed that the static observer at x measures of the tangent (1, v): the body's tangent
// split along the observer's 4-velocity u = (1 / sqrt(-g_tt), 0), E = -g(U, u), the rest
// U + g(U, u) u its spatial part in the observer's frame; speed = |spatial part| / E.
double metric_speed(double mass, const Vec3& x, const Vec3& v) {
  const Metric g(mass, x);
  const std::array<double, 4> tangent = {1, v.x, v.y, v.z};
  const std::array<double, 4> u = {1 / std::sqrt(-g.g[0][0]), 0, 0, 0};
  const double energy = -g(tangent, u);
  std::array<double, 4> spatial;
  for (int i = 0; i < 4; ++i) spatial[i] = tangent[i] - energy * u[i];
  return std::sqrt(g(spatial, spatial)) / energy;
}

// The largest metric_speed along x(t) = x0 + v t: sampled over t in a window about the closest
// approach (wide enough that the speed has fallen back towards |v| at its ends), then refined by
// golden-section search about the best sample. Independent of the closed form's cubic.
double sampled_peak(double mass, const Vec3& x0, const Vec3& v) {
  const double t_closest = -dot(x0, v) / dot(v, v);
  const double b = length(x0 + v * t_closest);
  const double half_window = 20 * (b + mass) / length(v);
  const int samples = 20001;
  const auto speed_at = [&](double t) { return metric_speed(mass, x0 + v * t, v); };
  double best_t = t_closest, best = speed_at(t_closest);
  const double step = 2 * half_window / (samples - 1);
  for (int i = 0; i < samples; ++i) {
    const double t = t_closest - half_window + i * step;
    if (const double s = speed_at(t); s > best) best = s, best_t = t;
  }
  double lo = best_t - step, hi = best_t + step;
  const double k = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200; ++i) {
    const double a = hi - k * (hi - lo), c = lo + k * (hi - lo);
    if (speed_at(a) > speed_at(c))
      hi = c;
    else
      lo = a;
  }
  return std::max(best, speed_at((lo + hi) / 2));
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  return normalize(Vec3{normal(rng), normal(rng), normal(rng)});
}

TEST(StaticObserverSpeed, IsTheMetricContractedWithTheFourVelocities) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(0, 1);
  for (int i = 0; i < 2000; ++i) {
    const double mass = 0.1 + 10 * uniform(rng);
    const double r = 2 * mass * (1 + std::pow(10.0, -4 + 7 * uniform(rng)));
    const Vec3 x = random_unit(rng) * r;
    const Vec3 v = random_unit(rng) * (0.99 * uniform(rng));
    const double expected = metric_speed(mass, x, v);
    EXPECT_NEAR(static_observer_speed(mass, x, v), expected, 1e-9 * expected)
        << "M " << mass << " r " << r;
  }
}

TEST(StaticObserverSpeed, RadialAndTangentialParts) {
  // Radial: |v| / f; tangential: |v| / sqrt(f). At r = 4M, f = 1/2.
  const Vec3 x{0, 4, 0};
  EXPECT_DOUBLE_EQ(static_observer_speed(1, x, {0, 0.3, 0}), 0.6);
  EXPECT_DOUBLE_EQ(static_observer_speed(1, x, {0, -0.3, 0}), 0.6);
  EXPECT_DOUBLE_EQ(static_observer_speed(1, x, {0.3, 0, 0}), 0.3 * std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(static_observer_speed(1, x, {0, 0, 0}), 0);
  // The escape speed sqrt(2M/r) locally is, in coordinates, dr/dt = -f sqrt(2M/r).
  EXPECT_NEAR(static_observer_speed(1, x, {0, -0.5 * std::sqrt(0.5), 0}), std::sqrt(0.5), 1e-15);
  // Flat, far away, inside the horizon.
  EXPECT_DOUBLE_EQ(static_observer_speed(0, x, {0.3, 0.4, 0}), 0.5);
  EXPECT_DOUBLE_EQ(static_observer_speed(0, {}, {0.3, 0.4, 0}), 0.5);
  EXPECT_DOUBLE_EQ(static_observer_speed(1, {kInf, 0, 0}, {0.3, 0.4, 0}), 0.5);
  EXPECT_EQ(static_observer_speed(1, {0, 2, 0}, {}), kInf);
  EXPECT_EQ(static_observer_speed(1, {0, 1, 0}, {0.1, 0, 0}), kInf);
  EXPECT_EQ(static_observer_speed(1, {}, {}), kInf);
}

TEST(PeakStaticObserverSpeed, IsTheLargestSpeedSampledAlongTheLine) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uniform(0, 1);
  for (int i = 0; i < 200; ++i) {
    const double mass = 0.5 + 3 * uniform(rng);
    // Closest approaches from just outside the horizon to far away.
    const double b = 2 * mass * (1 + std::pow(10.0, -3 + 6 * uniform(rng)));
    const Vec3 along = random_unit(rng);
    Vec3 across = cross(along, random_unit(rng));
    across = normalize(across);
    const double speed = 0.01 + 0.98 * uniform(rng);
    // The point given is anywhere on the line, not at the closest approach.
    const double offset = (uniform(rng) - 0.5) * 40 * b;
    const Vec3 x0 = across * b + along * offset, v = along * speed;
    const LineSpeedPeak peak = peak_static_observer_speed(mass, x0, v);
    ASSERT_FALSE(peak.reaches_horizon);
    const double expected = sampled_peak(mass, x0, v);
    EXPECT_NEAR(peak.speed, expected, 1e-9 * expected) << "M " << mass << " b " << b;
    // The peak is where the speed is.
    const Vec3 closest = across * b;
    const double t = std::sqrt(peak.radius * peak.radius - b * b) / speed;
    EXPECT_NEAR(metric_speed(mass, closest + v * t, v), peak.speed, 1e-9 * peak.speed);
    EXPECT_NEAR(metric_speed(mass, closest - v * t, v), peak.speed, 1e-9 * peak.speed);
    EXPECT_GE(peak.radius, b);
    EXPECT_LT(peak.radius, std::sqrt(1.5) * b * (1 + 1e-12));
    // Higher than at the closest approach and than far away.
    EXPECT_GT(peak.speed, speed / std::sqrt(1 - 2 * mass / b) * (1 - 1e-12));
    EXPECT_GT(peak.speed, speed);
  }
}

TEST(PeakStaticObserverSpeed, WeakFieldLimit) {
  // b >> M: speed^2 / v^2 = 1 + 2M (2 rho^2 - 1) / (b rho^3) to first order in M/b, largest at
  // rho^2 = 3/2: 1 + (8 sqrt 6 / 9) M / b, at r = sqrt(3/2) b.
  for (const double b : {1e4, 1e6, 1e8}) {
    const LineSpeedPeak peak = peak_static_observer_speed(1, {3, b, 0}, {0.5, 0, 0});
    const double excess = peak.speed * peak.speed / 0.25 - 1;
    EXPECT_NEAR(excess, 8 * std::sqrt(6.0) / 9 / b, 20 / (b * b)) << b;
    EXPECT_NEAR(peak.radius / b, std::sqrt(1.5), 5 / b) << b;
  }
}

TEST(PeakStaticObserverSpeed, KnownLines) {
  // b = 3M: a = 2/3, rho* = sqrt(2) cos(arccos(-sqrt(2)/3) / 3); the speed there is
  // static_observer_speed at that point, and its square is G(rho*) v^2.
  const LineSpeedPeak peak = peak_static_observer_speed(1, {0, 3, 0}, {0.2, 0, 0});
  const double rho = std::sqrt(2.0) * std::cos(std::acos(-std::sqrt(2.0) / 3) / 3);
  EXPECT_NEAR(2 * rho * rho * rho - 3 * rho + 2.0 / 3, 0, 1e-15);
  EXPECT_NEAR(peak.radius, 3 * rho, 1e-14);
  const Vec3 at{std::sqrt(9 * rho * rho - 9), 3, 0};
  EXPECT_NEAR(peak.speed, static_observer_speed(1, at, {0.2, 0, 0}), 1e-14);
  // Any point of the line, either direction: the same peak.
  for (const Vec3& x0 : {Vec3{-50, 3, 0}, Vec3{1e3, 3, 0}})
    for (const double sign : {1.0, -1.0}) {
      const LineSpeedPeak other = peak_static_observer_speed(1, x0, {0.2 * sign, 0, 0});
      EXPECT_NEAR(other.speed, peak.speed, 1e-14);
      EXPECT_NEAR(other.radius, peak.radius, 1e-12);
    }
  // Mass scales out: the same line in units twice as large.
  const LineSpeedPeak scaled = peak_static_observer_speed(2, {0, 6, 0}, {0.2, 0, 0});
  EXPECT_NEAR(scaled.speed, peak.speed, 1e-15);
  EXPECT_NEAR(scaled.radius, 2 * peak.radius, 1e-13);
}

TEST(PeakStaticObserverSpeed, LinesThatReachTheHorizonAndLinesAtRest) {
  // Through the hole (radial), tangent to the horizon, and inside it.
  for (const Vec3& x0 : {Vec3{10, 0, 0}, Vec3{0, 2, 0}, Vec3{0, 1.5, 0}, Vec3{}}) {
    const LineSpeedPeak p = peak_static_observer_speed(1, x0, {0.1, 0, 0});
    EXPECT_TRUE(p.reaches_horizon);
    EXPECT_EQ(p.speed, kInf);
    EXPECT_NEAR(p.radius, std::abs(x0.y), 1e-15);
  }
  // Just outside: finite, and enormous.
  const LineSpeedPeak near = peak_static_observer_speed(1, {0, 2 + 1e-9, 0}, {0.1, 0, 0});
  EXPECT_FALSE(near.reaches_horizon);
  EXPECT_GT(near.speed, 1e3);
  EXPECT_LT(near.speed, kInf);
  // At rest: 0 outside, infinity at or inside the horizon.
  const LineSpeedPeak rest = peak_static_observer_speed(1, {0, 0, 5}, {});
  EXPECT_EQ(rest.speed, 0);
  EXPECT_EQ(rest.radius, 5);
  EXPECT_FALSE(rest.reaches_horizon);
  EXPECT_TRUE(peak_static_observer_speed(1, {0, 0, 2}, {}).reaches_horizon);
  // No mass: |v|.
  EXPECT_DOUBLE_EQ(peak_static_observer_speed(0, {1, 2, 3}, {0.3, 0.4, 0}).speed, 0.5);
  EXPECT_DOUBLE_EQ(peak_static_observer_speed(0, {}, {}).speed, 0);
}

TEST(PeakStaticObserverSpeed, HugeAndTinyValuesNeitherOverflowNorUnderflow) {
  const LineSpeedPeak far = peak_static_observer_speed(1, {1e300, 1e300, 0}, {0.5, 0, 0});
  EXPECT_FALSE(far.reaches_horizon);
  EXPECT_DOUBLE_EQ(far.speed, 0.5);
  EXPECT_NEAR(far.radius / (std::sqrt(1.5) * 1e300), 1, 1e-12);
  const LineSpeedPeak slow = peak_static_observer_speed(1, {0, 3, 0}, {1e-300, 0, 0});
  EXPECT_NEAR(slow.speed / 1e-300,
              peak_static_observer_speed(1, {0, 3, 0}, {0.5, 0, 0}).speed / 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(peak_static_observer_speed(1, {kInf, 0, 0}, {0.5, 0, 0}).speed, 0.5);
  // A hole whose mass is large in absolute terms: only ratios matter.
  const LineSpeedPeak big = peak_static_observer_speed(1e300, {0, 3e300, 0}, {0.2, 0, 0});
  EXPECT_NEAR(big.speed, peak_static_observer_speed(1, {0, 3, 0}, {0.2, 0, 0}).speed, 1e-14);
}

}  // namespace
}  // namespace lightcone

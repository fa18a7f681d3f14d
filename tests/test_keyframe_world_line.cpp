// Keyframed world-lines: the interpolant against the keys and its own derivatives, proper time
// against independent integration, the retarded event against bisection of the light-cone
// condition, the refusal of keys that are not timelike, and the proper acceleration against
// hyperbolic motion and dense sampling.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "lightcone/physics/keyframe_world_line.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

Vec3 velocity(const WorldLinePoint& p) {
  return velocity_of(p.four_velocity);
}

// Random increasing times (gaps 0.2 to 2) and steps of at most 0.4 times the gap: chords below
// 0.4 and, with tangents that average neighbouring chords, speeds below 0.8.
std::vector<Keyframe> random_keys(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Keyframe> keys;
  Keyframe key{5 * u(rng), {10 * u(rng), 10 * u(rng), 10 * u(rng)}};
  for (int i = 0; i < n; ++i) {
    keys.push_back(key);
    const double gap = 0.2 + 1.8 * std::abs(u(rng));
    const Vec3 direction{u(rng), u(rng), u(rng)};
    key.time += gap;
    key.position += direction * (0.4 * gap * std::abs(u(rng)) / std::max(length(direction), 1e-9));
  }
  return keys;
}

// The tangent at key i: the derivative at t_i of the parabola (Lagrange form) through keys j,
// j + 1, j + 2 (the three around i, or the first or last three at the ends); the chord for two
// keys, zero for one: independent of the library's formula.
Vec3 expected_tangent(const std::vector<Keyframe>& keys, std::size_t i) {
  const std::size_t n = keys.size();
  if (n == 1) return {};
  if (n == 2) return (keys[1].position - keys[0].position) / (keys[1].time - keys[0].time);
  const std::size_t j = i == 0 ? 0 : i == n - 1 ? n - 3 : i - 1;
  const double t = keys[i].time;
  Vec3 sum;
  for (std::size_t k = j; k < j + 3; ++k) {
    // d/dt of the Lagrange basis polynomial of node k at t.
    double derivative = 0;
    for (std::size_t m = j; m < j + 3; ++m) {
      if (m == k) continue;
      double term = 1 / (keys[k].time - keys[m].time);
      for (std::size_t l = j; l < j + 3; ++l)
        if (l != k && l != m) term *= (t - keys[l].time) / (keys[k].time - keys[l].time);
      derivative += term;
    }
    sum = sum + keys[k].position * derivative;
  }
  return sum;
}

void expect_near(const Vec3& actual, const Vec3& expected, double tolerance,
                 const std::string& what) {
  EXPECT_LE(length(actual - expected), tolerance)
      << what << ": (" << actual.x << ", " << actual.y << ", " << actual.z << ") vs (" << expected.x
      << ", " << expected.y << ", " << expected.z << ")";
}

TEST(KeyframeWorldLine, PassesThroughEveryKey) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 200; ++trial) {
    const std::vector<Keyframe> keys = random_keys(rng, 1 + trial % 8);
    const KeyframeWorldLine line(keys);
    ASSERT_EQ(line.keys().size(), keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const WorldLinePoint p = line.at_world_time(keys[i].time);
      EXPECT_EQ(p.event.t, keys[i].time);
      expect_near(p.event.x, keys[i].position, 1e-12, "trial " + std::to_string(trial));
      EXPECT_EQ(line.keys()[i].position, keys[i].position);
    }
  }
}

TEST(KeyframeWorldLine, IsC1AtEveryKeyAndIntoTheTails) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 200; ++trial) {
    const std::vector<Keyframe> keys = random_keys(rng, 1 + trial % 8);
    const KeyframeWorldLine line(keys);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const std::string what = "trial " + std::to_string(trial) + " key " + std::to_string(i);
      const double t = keys[i].time;
      const WorldLinePoint at = line.at_world_time(t);
      expect_near(velocity(at), expected_tangent(keys, i), 1e-12, what + " tangent");
      // One-sided differences from either side (a tail is straight, a cubic's error is
      // h |a| / 2 with |a| below about 8).
      const double h = 1e-6;
      const WorldLinePoint before = line.at_world_time(t - h), after = line.at_world_time(t + h);
      expect_near((at.event.x - before.event.x) / h, velocity(at), 1e-5, what + " from the left");
      expect_near((after.event.x - at.event.x) / h, velocity(at), 1e-5, what + " from the right");
      // The velocity and position themselves just either side.
      const double e = 1e-10;
      const WorldLinePoint left = line.at_world_time(t - e), right = line.at_world_time(t + e);
      expect_near(velocity(left), velocity(at), 1e-8, what + " velocity left");
      expect_near(velocity(right), velocity(at), 1e-8, what + " velocity right");
      expect_near(left.event.x, at.event.x, 2e-10, what + " position left");
      expect_near(right.event.x, at.event.x, 2e-10, what + " position right");
      EXPECT_NEAR(left.proper_time, at.proper_time, 2e-10) << what;
      EXPECT_NEAR(right.proper_time, at.proper_time, 2e-10) << what;
    }
    // Far out in the tails the velocity is still the end tangent.
    expect_near(velocity(line.at_world_time(keys.front().time - 50)), expected_tangent(keys, 0),
                1e-12, "past tail");
    expect_near(velocity(line.at_world_time(keys.back().time + 50)),
                expected_tangent(keys, keys.size() - 1), 1e-12, "future tail");
  }
}

TEST(KeyframeWorldLine, FourVelocityIsTheUnitDerivativeWithRespectToProperTime) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  int checked = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const std::vector<Keyframe> keys = random_keys(rng, 2 + trial % 7);
    const KeyframeWorldLine line(keys);
    for (int sample = 0; sample < 20; ++sample) {
      const double t = keys.front().time - 2 + (keys.back().time - keys.front().time + 4) * u(rng);
      const double h = 1e-5;
      // Central differences lose their order across a key, where the acceleration jumps.
      if (std::any_of(keys.begin(), keys.end(),
                      [&](const Keyframe& k) { return std::abs(k.time - t) < 2 * h; }))
        continue;
      const WorldLinePoint p = line.at_world_time(t);
      const WorldLinePoint a = line.at_world_time(t - h), b = line.at_world_time(t + h);
      const double dtau = b.proper_time - a.proper_time;
      const Vec4 derivative = (1 / dtau) * (b.event - a.event);
      const double gamma = p.four_velocity.t;
      EXPECT_NEAR(derivative.t, gamma, 1e-7 * gamma) << trial;
      expect_near(derivative.x, p.four_velocity.x, 1e-7 * gamma, "trial " + std::to_string(trial));
      EXPECT_NEAR(-gamma * gamma + dot(p.four_velocity.x, p.four_velocity.x), -1,
                  1e-13 * gamma * gamma);
      ++checked;
    }
  }
  EXPECT_GT(checked, 1900);
}

// Composite Simpson of dtau/dt = sqrt(1 - |V|^2) over [a, b], V read from the line.
double simpson_proper_time(const KeyframeWorldLine& line, double a, double b, int steps) {
  const auto rate = [&](double t) {
    const Vec3 v = velocity(line.at_world_time(t));
    return std::sqrt(1 - dot(v, v));
  };
  const double h = (b - a) / steps;
  double sum = rate(a) + rate(b);
  for (int k = 1; k < steps; ++k) sum += (k % 2 ? 4 : 2) * rate(a + k * h);
  return sum * h / 3;
}

TEST(KeyframeWorldLine, ProperTimeMatchesSimpsonIntegration) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 12; ++trial) {
    const std::vector<Keyframe> keys = random_keys(rng, 2 + trial % 6);
    const KeyframeWorldLine line(keys);
    EXPECT_EQ(line.at_world_time(keys.front().time).proper_time, 0);
    // Key by key (Simpson keeps its order within a segment, where the motion is smooth).
    double tau = 0;
    for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
      const double a = keys[i].time, b = keys[i + 1].time;
      const double t = a + (b - a) * u(rng);
      EXPECT_NEAR(line.at_world_time(t).proper_time, tau + simpson_proper_time(line, a, t, 100000),
                  1e-9)
          << trial << " segment " << i;
      tau += simpson_proper_time(line, a, b, 100000);
      EXPECT_NEAR(line.at_world_time(b).proper_time, tau, 1e-9) << trial << " key " << i + 1;
    }
    // The tails run at the end speeds.
    const Vec3 first = expected_tangent(keys, 0), last = expected_tangent(keys, keys.size() - 1);
    EXPECT_NEAR(line.at_world_time(keys.front().time - 3).proper_time,
                -3 * std::sqrt(1 - dot(first, first)), 1e-12);
    EXPECT_NEAR(line.at_world_time(keys.back().time + 3).proper_time,
                tau + 3 * std::sqrt(1 - dot(last, last)), 1e-9);
  }
}

TEST(KeyframeWorldLine, ProperTimeStaysAccurateNearTheSpeedOfLight) {
  // Chords 0.95, 0.99 and 0.96: the middle segment peaks at 0.99875, gently. Chords -0.166,
  // 0.766 and -0.166: the middle segment runs from 0.3 up to 0.999 and back, a sharp peak of
  // 1 / gamma that one 20-point rule over the segment misses by about 6e-10.
  for (const std::vector<Keyframe>& keys :
       {std::vector<Keyframe>{{0, {}}, {1, {0.95, 0, 0}}, {2, {1.94, 0, 0}}, {3, {2.9, 0, 0}}},
        std::vector<Keyframe>{
            {0, {}}, {1, {-0.166, 0, 0}}, {2, {0.6, 0, 0}}, {3, {0.434, 0, 0}}}}) {
    const KeyframeWorldLine line(keys);
    double peak = 0;
    for (int k = 0; k <= 1000; ++k)
      peak = std::max(peak, length(velocity(line.at_world_time(1 + k / 1000.0))));
    EXPECT_GT(peak, 0.998);
    // Simpson at two resolutions, Richardson-extrapolated (error of order h^6).
    for (const double t : {0.7, 1.0, 1.3, 1.5, 1.51, 2.0, 2.3, 3.0}) {
      double reference = 0;
      for (double a = 0; a < t; a += 1) {
        const double b = std::min(a + 1, t);
        const double coarse = simpson_proper_time(line, a, b, 20000);
        const double fine = simpson_proper_time(line, a, b, 40000);
        reference += fine + (fine - coarse) / 15;
      }
      EXPECT_NEAR(line.at_world_time(t).proper_time, reference, 1e-13 * reference)
          << keys[1].position.x << " " << t;
    }
  }
}

TEST(KeyframeWorldLine, UniformStraightMotionHasExactProperTime) {
  // Dyadic velocities, times and positions: the keys lie exactly on the line, so that the
  // rounding of the keys themselves (amplified by gamma^2 in 1 - |v|^2) does not blur it.
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> step(1, 16), coordinate(-10, 10);
  for (const Vec3& v : {Vec3{}, Vec3{0.25, 0, 0}, Vec3{0.5, -0.375, 0.25},
                        Vec3{0, 1023.0 / 1024, 0}, Vec3{0.5, 0.5, -0.703125}}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Vec3 start{1.0 * coordinate(rng), 1.0 * coordinate(rng), 1.0 * coordinate(rng)};
      const double t0 = coordinate(rng) / 8.0;
      std::vector<Keyframe> keys;
      double t = t0;
      for (int i = 0; i < 2 + trial % 6; ++i, t += step(rng) / 8.0)
        keys.push_back({t, start + v * (t - t0)});
      const KeyframeWorldLine line(keys);
      EXPECT_EQ(line.max_proper_acceleration(), 0);
      const double rate = std::sqrt(1 - dot(v, v));
      for (double s = t0 - 4; s < t + 4; s += 0.37) {
        const WorldLinePoint p = line.at_world_time(s);
        EXPECT_NEAR(p.proper_time, (s - t0) * rate, 1e-13) << length(v) << " " << trial << " " << s;
        expect_near(velocity(p), v, 1e-15, "velocity");
      }
    }
  }
}

// Bisection of the light-cone gap along the line's world time, on a bracket widened until the
// gap changes sign: the independent reference for the retarded event.
double retarded_by_bisection(const KeyframeWorldLine& line, const Vec4& receiver) {
  const auto gap = [&](double t) {
    return receiver.t - t - length(receiver.x - line.at_world_time(t).event.x);
  };
  double lo = receiver.t - 1, hi = receiver.t;
  while (gap(lo) < 0) lo = receiver.t - 2 * (receiver.t - lo);
  return test::bisect_decreasing(gap, lo, hi);
}

TEST(KeyframeWorldLine, RetardedEventIsOnThePastLightConeOf1000Receivers) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst_gap = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const std::vector<Keyframe> keys = random_keys(rng, 1 + trial % 8);
    const KeyframeWorldLine line(keys);
    const double t0 = keys.front().time, t1 = keys.back().time;
    const Vec3 centre = keys[keys.size() / 2].position;
    Vec4 receiver;
    switch (trial % 4) {
      case 0:  // around the keys
        receiver = {t0 + (t1 - t0) * (0.5 + 0.7 * u(rng)),
                    centre + Vec3{u(rng), u(rng), u(rng)} * 3};
        break;
      case 1:  // far in the past of the first key
        receiver = {t0 - 30 * std::abs(u(rng)), centre + Vec3{u(rng), u(rng), u(rng)} * 20};
        break;
      case 2:  // far in the future of the last key
        receiver = {t1 + 30 * std::abs(u(rng)), centre + Vec3{u(rng), u(rng), u(rng)} * 20};
        break;
      default:  // far away, whenever
        receiver = {1e4 * u(rng), Vec3{u(rng), u(rng), u(rng)} * 1e4};
    }
    const WorldLinePoint p = line.retarded(receiver);
    const double gap = receiver.t - p.event.t - length(receiver.x - p.event.x);
    worst_gap = std::max(worst_gap, std::abs(gap));
    EXPECT_LT(std::abs(gap), 1e-9) << trial;
    EXPECT_LE(p.event.t, receiver.t) << trial;
    const double reference = retarded_by_bisection(line, receiver);
    EXPECT_NEAR(p.event.t, reference, 1e-9 * (1 + std::abs(reference))) << trial;
    // The point is the line's own at that time.
    const WorldLinePoint q = line.at_world_time(p.event.t);
    expect_near(p.event.x, q.event.x, 1e-12 * (1 + length(q.event.x)), "event");
    EXPECT_NEAR(p.proper_time, q.proper_time, 1e-12 * (1 + std::abs(q.proper_time)));
  }
  RecordProperty("worst_gap", std::to_string(worst_gap));
}

TEST(KeyframeWorldLine, OneKeyIsAtRestAndTwoAreUniform) {
  const KeyframeWorldLine still(std::vector<Keyframe>{{2, {1, 2, 3}}});
  const WorldLinePoint p = still.at_world_time(7);
  EXPECT_EQ(p.event.x, (Vec3{1, 2, 3}));
  EXPECT_EQ(p.proper_time, 5);
  EXPECT_EQ(still.retarded({10, {4, 6, 3}}).event.t, 5);
  EXPECT_EQ(still.max_proper_acceleration(), 0);

  const KeyframeWorldLine uniform({{0, {}}, {2, {1.2, 0, 0}}});
  const WorldLinePoint q = uniform.at_world_time(1);
  EXPECT_NEAR(q.event.x.x, 0.6, 1e-15);
  EXPECT_NEAR(q.proper_time, 0.8, 1e-15);
  // Light reaching x = 5 at t = 5.4 left the body (at x = 0.6 t, behind the receiver) at t = 1.
  EXPECT_NEAR(uniform.retarded({5.4, {5, 0, 0}}).event.t, 1, 1e-14);
}

// Expects `keys` to be refused with a KeyframeError naming (first, second) and saying `says`.
void expect_refused(const std::vector<Keyframe>& keys, std::size_t first, std::size_t second,
                    const std::string& says) {
  try {
    const KeyframeWorldLine line(keys);
    ADD_FAILURE() << "accepted; expected an error naming keys " << first << " and " << second;
  } catch (const KeyframeError& e) {
    EXPECT_EQ(e.first, first) << e.what();
    EXPECT_EQ(e.second, second) << e.what();
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

TEST(KeyframeWorldLine, RefusesKeysThatAreNotTimelikeNamingThem) {
  EXPECT_THROW(KeyframeWorldLine({}), std::invalid_argument);
  // Times out of order, or equal.
  expect_refused({{0, {}}, {1, {}}, {0.5, {}}}, 1, 2, "keyframe times must increase");
  expect_refused({{0, {}}, {1, {}}, {1, {}}, {2, {}}}, 1, 2, "keyframe times must increase");
  expect_refused({{3, {}}, {2, {}}}, 0, 1, "keyframe 1 (time 2) is not after keyframe 0 (time 3)");
  // A chord faster than light, or at it, first or later.
  expect_refused({{0, {}}, {1, {0, 1.5, 0}}}, 0, 1,
                 "the motion between keyframes 0 and 1 reaches speed 1.5 (c = 1)");
  expect_refused({{0, {}}, {1, {1, 0, 0}}}, 0, 1, "reaches speed 1 (c = 1)");
  expect_refused({{0, {}}, {1, {0.1, 0, 0}}, {2, {0.2, 0, 0}}, {3, {1.9, 0, 0}}}, 2, 3,
                 "the motion between keyframes 2 and 3 reaches speed");
  // Slow chords (0.9 and 0.5) whose neighbours' tangents make the cubic overshoot: the long
  // middle segment starts and ends at about -0.89 and peaks near 1.19 halfway.
  const std::vector<Keyframe> overshoot{
      {0, {}}, {0.1, {-0.09, 0, 0}}, {10.1, {4.91, 0, 0}}, {10.2, {4.82, 0, 0}}};
  expect_refused(overshoot, 1, 2, "the motion between keyframes 1 and 2 reaches speed 1.19");
  // Not finite.
  expect_refused({{0, {}}, {1, {}}, {NAN, {}}}, 2, 2, "keyframe 2 has a time or position");
  expect_refused({{0, {0, NAN, 0}}, {1, {}}}, 0, 0, "not finite");
  expect_refused({{0, {}}, {INFINITY, {}}}, 1, 1, "not finite");
  // Just below the speed of light is fine.
  EXPECT_NO_THROW(KeyframeWorldLine({{0, {}}, {1, {0.999, 0, 0}}, {2, {1.998, 0, 0}}}));
}

TEST(KeyframeWorldLine, HyperbolicKeysHaveTheHyperbolaProperAcceleration) {
  // x = sqrt(1/a^2 + t^2) - 1/a has proper acceleration a throughout, speeds up to 0.89 here.
  const double a = 0.5, step = 0.02;
  std::vector<Keyframe> keys;
  for (double t = -4; t <= 4 + 1e-9; t += step)
    keys.push_back({t, {std::sqrt(1 / (a * a) + t * t) - 1 / a, 0, 0}});
  const KeyframeWorldLine line(keys);
  // The proper acceleration |dU/dtau| by central differences of the 4-velocity.
  const auto proper_acceleration = [&](double t) {
    const double h = 1e-6;
    const WorldLinePoint p = line.at_world_time(t - h), q = line.at_world_time(t + h);
    const Vec4 du = q.four_velocity - p.four_velocity;
    return std::sqrt(dot(du.x, du.x) - du.t * du.t) / (q.proper_time - p.proper_time);
  };
  // Within 2% everywhere, the end segments too (tangents from parabolas; a cubic's second
  // derivative is first-order accurate, off by about step |x'''| / |x''| <= 0.75 step here).
  double sampled_max = 0;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i)
    for (const double s : {0.01, 0.25, 0.5, 0.75, 0.99}) {
      const double t = keys[i].time + s * (keys[i + 1].time - keys[i].time);
      const double alpha = proper_acceleration(t);
      sampled_max = std::max(sampled_max, alpha);
      EXPECT_NEAR(alpha, a, 0.02 * a) << t;
    }
  EXPECT_GE(line.max_proper_acceleration(), 0.999 * sampled_max);
  EXPECT_NEAR(line.max_proper_acceleration(), a, 0.02 * a);
}

TEST(KeyframeWorldLine, MaxProperAccelerationMatchesDenseSampling) {
  // gamma^3 sqrt(|a|^2 - |v x a|^2), a by central differences of the velocity, 2001 points per
  // segment. The sharp peak of speed 0.999 puts the maximum inside a segment, where the 65
  // samples miss the top by about 0.6%.
  std::mt19937 rng(8);
  std::vector<std::vector<Keyframe>> cases{
      {{0, {}}, {1, {-0.166, 0, 0}}, {2, {0.6, 0, 0}}, {3, {0.434, 0, 0}}}};
  for (int trial = 0; trial < 20; ++trial) cases.push_back(random_keys(rng, 3 + trial % 5));
  for (const std::vector<Keyframe>& keys : cases) {
    const KeyframeWorldLine line(keys);
    double dense = 0;
    for (std::size_t i = 0; i + 1 < keys.size(); ++i)
      for (int k = 0; k <= 2000; ++k) {
        // The ends too, just inside (the acceleration jumps at a key).
        const double h = 1e-7, from = keys[i].time + 2 * h, to = keys[i + 1].time - 2 * h;
        const double t = from + (to - from) * k / 2000;
        const Vec3 v = velocity(line.at_world_time(t));
        const Vec3 a =
            (velocity(line.at_world_time(t + h)) - velocity(line.at_world_time(t - h))) / (2 * h);
        const Vec3 va = cross(v, a);
        dense = std::max(dense, std::pow(1 - dot(v, v), -1.5) * std::sqrt(dot(a, a) - dot(va, va)));
      }
    EXPECT_GT(line.max_proper_acceleration(), 0.98 * dense) << keys.size();
    EXPECT_LT(line.max_proper_acceleration(), 1.0001 * dense) << keys.size();
  }
}

}  // namespace
}  // namespace lightcone

// World-lines beyond inertial motion: hyperbolic phases against their closed forms and
// against numerical derivatives, and the retarded event against bisection of the light-cone
// condition.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/retarded_time.hpp"
#include "lightcone/physics/world_line.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

double interval(const Vec4& a, const Vec4& b) {
  return -a.t * b.t + dot(a.x, b.x);
}

TEST(HyperbolicMotion, FromRestMatchesTheClosedForms) {
  // From rest at the origin, proper acceleration a along x: t = sinh(a tau) / a,
  // x = (cosh(a tau) - 1) / a, speed tanh(a tau), 4-velocity (cosh, sinh, 0, 0).
  for (const double a : {1e-6, 0.01, 1.0, 37.0}) {
    const AcceleratedWorldLine line(0, {}, {}, {{1e6, {a, 0, 0}}});
    for (const double tau : {0.0, 0.001, 0.5, 1.0, 3.0}) {
      const WorldLinePoint p = line.at_proper_time(tau);
      const double eta = a * tau;
      EXPECT_NEAR(p.event.t, std::sinh(eta) / a, 1e-12 * (1 + std::sinh(eta) / a)) << a << tau;
      EXPECT_NEAR(p.event.x.x, std::expm1(eta) * (1 - std::exp(-eta)) / (2 * a),
                  1e-12 * (1 + std::cosh(eta) / a))
          << a << " " << tau;
      EXPECT_NEAR(length(velocity_of(p.four_velocity)), std::tanh(eta), 1e-14) << a << tau;
      EXPECT_NEAR(p.four_velocity.t, std::cosh(eta), 1e-12 * std::cosh(eta));
      EXPECT_DOUBLE_EQ(p.proper_time, tau);
    }
  }
}

// Random world-lines: a start anywhere, moving, then a few phases in random directions.
AcceleratedWorldLine random_line(std::mt19937& rng, std::vector<AccelerationPhase>* out = nullptr) {
  std::uniform_real_distribution<double> u(-1, 1);
  Vec3 v{u(rng), u(rng), u(rng)};
  v = v * (0.95 * std::abs(u(rng)) / std::max(length(v), 1e-9));
  std::vector<AccelerationPhase> phases;
  const int n = 1 + static_cast<int>(3 * std::abs(u(rng)));
  for (int i = 0; i < n; ++i)
    phases.push_back({0.5 + 2 * std::abs(u(rng)), Vec3{u(rng), u(rng), u(rng)} * 1.5});
  if (out) *out = phases;
  return AcceleratedWorldLine(5 * u(rng), {10 * u(rng), 10 * u(rng), 10 * u(rng)}, v, phases);
}

TEST(HyperbolicMotion, FourVelocityIsTheDerivativeAndTheAccelerationIsTheProperOne) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<AccelerationPhase> phases;
    const AcceleratedWorldLine line = random_line(rng, &phases);
    double start = 0;
    for (const AccelerationPhase& phase : phases) {
      const double tau = start + 0.37 * phase.duration, h = 1e-3;
      const WorldLinePoint p = line.at_proper_time(tau);
      EXPECT_NEAR(interval(p.four_velocity, p.four_velocity), -1, 1e-10);
      const auto at = [&](double t) { return line.at_proper_time(t).event; };
      // Five-point stencils: the 4-acceleration's invariant cancels large components at high
      // gamma, so the derivatives need the accuracy.
      const auto first = [&](double t) {
        return (1 / (12 * h)) * (at(t - 2 * h) - 8.0 * at(t - h) + 8.0 * at(t + h) - at(t + 2 * h));
      };
      const auto second = [&](double t) {
        return (1 / (12 * h * h)) *
               (16.0 * (at(t - h) + at(t + h)) - 30.0 * at(t) - (at(t - 2 * h) + at(t + 2 * h)));
      };
      const Vec4 derivative = first(tau);
      EXPECT_NEAR(derivative.t, p.four_velocity.t, 1e-8 * p.four_velocity.t);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(derivative.x[k], p.four_velocity.x[k], 1e-8 * p.four_velocity.t);
      // |d^2 X / dtau^2| (a spacelike 4-vector) is the proper acceleration's magnitude. Its
      // components grow like gamma while the invariant does not: the stencil's relative error
      // is multiplied by about gamma^2.
      const Vec4 a_world = second(tau);
      const double magnitude = std::sqrt(interval(a_world, a_world));
      const double gamma = p.four_velocity.t;
      EXPECT_NEAR(magnitude, length(phase.acceleration),
                  1e-8 * gamma * gamma * (1 + length(phase.acceleration)))
          << trial << " gamma " << gamma;
      // Just after the phase's start, in the instantaneous rest frame, it points along the
      // given vector.
      const double near_start = start + 3 * h;
      const Vec4 a_rest =
          boost(velocity_of(line.at_proper_time(near_start).four_velocity)) * second(near_start);
      EXPECT_NEAR(a_rest.t, 0, 1e-5 * (1 + length(phase.acceleration)));
      EXPECT_GT(dot(normalize(a_rest.x), normalize(phase.acceleration)), 0.999);
      start += phase.duration;
    }
    // Proper time and world time invert each other, before, during and after the phases.
    for (const double tau : {-3.0, 0.0, 0.3, start * 0.5, start, start + 4}) {
      const WorldLinePoint p = line.at_proper_time(tau);
      const WorldLinePoint q = line.at_world_time(p.event.t);
      EXPECT_NEAR(q.proper_time, tau, 1e-9 * (1 + std::abs(tau))) << trial;
    }
  }
}

// Bisection of the light-cone condition along the world-line's proper time: the independent
// reference for the closed forms.
double retarded_by_bisection(const AcceleratedWorldLine& line, const Vec4& receiver) {
  const auto gap = [&](double tau) {
    const Vec4 e = line.at_proper_time(tau).event;
    return receiver.t - e.t - length(receiver.x - e.x);
  };
  double lo = -1, hi = 1;
  while (gap(lo) < 0) lo *= 2;
  while (gap(hi) > 0) hi *= 2;
  return test::bisect_decreasing(gap, lo, hi);
}

TEST(HyperbolicMotion, RetardedEventMatchesBisectionOfTheLightConeOn1000Cases) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const AcceleratedWorldLine line = random_line(rng);
    const Vec4 receiver{20 * u(rng), {30 * u(rng), 30 * u(rng), 30 * u(rng)}};
    const WorldLinePoint p = line.retarded(receiver);
    const double reference = retarded_by_bisection(line, receiver);
    const double scale = 1 + std::abs(reference);
    worst = std::max(worst, std::abs(p.proper_time - reference) / scale);
    EXPECT_NEAR(p.proper_time, reference, 1e-9 * scale) << trial;
    // The event is on the receiver's past light cone.
    EXPECT_NEAR(receiver.t - p.event.t, length(receiver.x - p.event.x),
                1e-9 * (1 + std::abs(receiver.t - p.event.t)));
  }
  RecordProperty("worst_relative_error", std::to_string(worst));
}

TEST(RetardedWorldTime, NewtonMatchesTheClosedFormsOfInertialAndHyperbolicLines) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 300; ++trial) {
    const Vec4 receiver{10 * u(rng), {20 * u(rng), 20 * u(rng), 20 * u(rng)}};
    // Inertial, up to 0.999c.
    const Vec3 x0{5 * u(rng), 5 * u(rng), 5 * u(rng)};
    Vec3 v{u(rng), u(rng), u(rng)};
    v = v * (0.999 * std::abs(u(rng)) / std::max(length(v), 1e-9));
    const double t = retarded_world_time([&](double s) { return x0 + v * s; },
                                         [&](double) { return v; }, receiver);
    const double closed = receiver.t - retarded_delay(x0 + v * receiver.t - receiver.x, v);
    EXPECT_NEAR(t, closed, 1e-9 * (1 + std::abs(closed))) << trial;
    // Accelerated, read through its world time.
    const AcceleratedWorldLine line = random_line(rng);
    const double th = retarded_world_time(
        [&](double s) { return line.at_world_time(s).event.x; },
        [&](double s) { return velocity_of(line.at_world_time(s).four_velocity); }, receiver);
    const double expected = line.retarded(receiver).event.t;
    EXPECT_NEAR(th, expected, 1e-9 * (1 + std::abs(expected))) << trial;
  }
}

TEST(AcceleratedWorldLine, CarriedAxesAreTheCompositionOfTheRestFrameBoosts) {
  // Independently: constant proper acceleration a for proper time tau takes the rest frame at
  // the phase's start (pure-boost axes P, in which a is given) to the pure boost of it to
  // velocity tanh(|a| tau) a / |a|; the gyroscope frame G, turned from P by a rotation
  // Q = G P^-1, follows with Q held. Its axes, written in the pure-boost rest frame at the end,
  // turn by the Thomas-Wigner rotation.
  std::mt19937 rng(7);
  double largest_turn = 0;
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<AccelerationPhase> phases;
    const AcceleratedWorldLine line = random_line(rng, &phases);
    const Vec3 v0 = velocity_of(line.at_proper_time(-1).four_velocity);
    Mat4 carried = boost(v0);  // W -> the gyroscope frame
    double tau = 0;
    for (const AccelerationPhase& p : phases) {
      const Mat4 pure = boost(velocity_of(line.at_proper_time(tau).four_velocity));
      const Mat4 turn = carried * lorentz_inverse(pure);
      const double a = length(p.acceleration);
      carried = turn * boost(p.acceleration * (std::tanh(a * p.duration) / a)) * pure;
      tau += p.duration;
    }
    const Vec3 v_end = velocity_of(line.at_proper_time(tau).four_velocity);
    const Mat3 expected = (boost(v_end) * lorentz_inverse(carried)).spatial();
    const Mat3 r = line.carried_rotation(tau + 0.5);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.m[i][k], expected.m[i][k], 1e-7) << trial;
    largest_turn =
        std::max(largest_turn,
                 std::acos(std::clamp(0.5 * (r.m[0][0] + r.m[1][1] + r.m[2][2] - 1), -1.0, 1.0)));
  }
  // The rotation is real: random turning paths precess by tens of degrees.
  EXPECT_GT(largest_turn, 0.3);
  // A path that does not turn (acceleration along the velocity) does not precess.
  const AcceleratedWorldLine straight(0, {}, {0.3, 0, 0}, {{2, {0.7, 0, 0}}, {1, {-0.2, 0, 0}}});
  const Mat3 r = straight.carried_rotation(3);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.m[i][k], i == k ? 1.0 : 0.0, 1e-12);
}

TEST(AcceleratedWorldLine, RefusesSpeedsOfLightAndBadPhases) {
  EXPECT_THROW(AcceleratedWorldLine(0, {}, {1, 0, 0}, {}), std::invalid_argument);
  EXPECT_THROW(AcceleratedWorldLine(0, {}, {}, {{-1, {1, 0, 0}}}), std::invalid_argument);
  EXPECT_THROW(AcceleratedWorldLine(0, {}, {}, {{1, {NAN, 0, 0}}}), std::invalid_argument);
  // A zero acceleration is an inertial phase.
  const AcceleratedWorldLine still(0, {}, {0.5, 0, 0}, {{2, {0, 0, 0}}});
  EXPECT_NEAR(still.at_proper_time(3).event.x.x, 0.5 * 3 / std::sqrt(0.75), 1e-12);
}

}  // namespace
}  // namespace lightcone

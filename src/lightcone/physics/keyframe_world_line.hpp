// A world-line through given events (keyframes): a C1 piecewise cubic Hermite interpolant in
// world time, refused unless it stays slower than light, inertial before the first key and
// after the last.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "lightcone/physics/vec.hpp"
#include "lightcone/physics/world_line.hpp"

namespace lightcone {

// The body is at `position` at world time `time`.
struct Keyframe {
  double time = 0;
  Vec3 position;
};

// Thrown for keys that do not make a timelike world-line; `first` and `second` are the indices of
// the keyframes (0-based) between which the problem lies (equal when one key alone is at fault),
// so that a scene file can point at the offending entry.
struct KeyframeError : std::invalid_argument {
  KeyframeError(const std::string& what, std::size_t first, std::size_t second);
  std::size_t first, second;
};

// Between keys i and i + 1 the position is the cubic Hermite polynomial in world time through
// both keys with their tangents: at an interior key the derivative of the parabola through it
// and its two neighbours, at an end key the derivative there of the parabola through it and its
// next two (two keys make a straight line). Before the first key and after the last the body moves
// inertially with the end tangent; one key alone is at rest. Proper time is 0 at the first key.
class KeyframeWorldLine final : public TimelikeWorldLine {
 public:
  // Requires at least one key (std::invalid_argument otherwise), finite times and positions,
  // strictly increasing times and a speed below 1 everywhere on the interpolant (KeyframeError).
  explicit KeyframeWorldLine(std::vector<Keyframe> keys);

  WorldLinePoint at_world_time(double t) const override;
  // The segment (or inertial tail) is found by the sign of the light-cone gap at the keys, the
  // event on a segment by Newton's method safeguarded by bisection, on a tail in closed form.
  WorldLinePoint retarded(const Vec4& receiver) const override;
  // Sampled at 65 points per segment, ends included, so not a strict bound: it can fall short of
  // a sharp maximum by a little (0.6% at a speed peak of 0.999), which the warning threshold it
  // feeds tolerates. Zero for one or two keys (a straight line).
  double max_proper_acceleration() const override { return max_proper_acceleration_; }

  // The largest Lorentz factor of the body relative to an observer moving with
  // `observer_velocity` (|observer_velocity| < 1), gamma_o gamma (1 - observer_velocity . v),
  // anywhere on the world-line (the inertial tails move as the end keys do), and the segment
  // (keys `segment` and `segment + 1`) where it is reached. Exact to rounding: the critical
  // points of the quotient of polynomials are the roots of a quintic, isolated between the
  // roots of its derivatives. One key alone is at rest (segment 0).
  struct Fastest {
    double gamma = 1;
    std::size_t segment = 0;
  };
  Fastest max_gamma(const Vec3& observer_velocity = {}) const;

  const std::vector<Keyframe>& keys() const { return keys_; }

 private:
  // Keys i and i + 1, in s = (t - start) / duration in [0, 1].
  struct Segment {
    double start = 0, duration = 0;
    // The Hermite form of the position, exact at the keys: the end positions and the end
    // tangents times the duration.
    Vec3 from, to, from_step, to_step;
    // dX/dt = v0 + v1 s + v2 s^2.
    Vec3 v0, v1, v2;

    Vec3 position(double s) const;
    Vec3 velocity(double s) const { return v0 + (v1 + v2 * s) * s; }
    Vec3 acceleration(double s) const { return (v1 + v2 * (2 * s)) / duration; }
  };
  // Proper time is integrated from the last knot at or before t. Knots sit at every key and
  // wherever the quadrature needed subdividing a segment to stay accurate.
  struct Knot {
    double time = 0, proper_time = 0;
    std::size_t segment = 0;  // of the piece that ends at the knot (0 for the first knot)
  };

  // The proper time from world time `from` to `to` on `segment`, by one Gauss-Legendre rule.
  static double proper_time_on(const Segment& segment, double from, double to);
  // Appends the knots of [from, to] on segment i, halving it (at most `halvings` more times)
  // until one rule over a piece (`whole` for this one) agrees with the sum over its halves.
  void add_knots(std::size_t i, double from, double to, double whole, int halvings);
  WorldLinePoint on_segment(const Segment& segment, const Knot& knot, double t) const;

  std::vector<Keyframe> keys_;
  std::vector<Segment> segments_;
  Vec3 initial_velocity_, final_velocity_;  // of the inertial tails
  std::vector<Knot> knots_;
  double max_proper_acceleration_ = 0;
};

}  // namespace lightcone

#include "lightcone/physics/keyframe_world_line.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <utility>

#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/retarded_time.hpp"

namespace lightcone {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
// A piece of a segment is integrated by one rule once halving it changes the result by less
// than this (relative); then its halves, far more accurate still, become knots.
constexpr double kQuadratureTolerance = 1e-13;
// Halvings of a segment at most: near the speed of light the rounding of 1 - |V|^2 alone can
// exceed the tolerance, and must not subdivide without end.
constexpr int kMaxHalvings = 12;
constexpr int kAccelerationSamples = 64;

// The 20-point Gauss-Legendre rule on [0, 1], its nodes the roots of P_20 by Newton's method.
// The integrand sqrt(1 - |V|^2) is the root of a quartic, smooth while the speed stays below 1.
struct GaussLegendre {
  static constexpr int kOrder = 20;
  std::array<double, kOrder> nodes{}, weights{};

  GaussLegendre() {
    for (int i = 0; i < kOrder / 2; ++i) {
      double x = std::cos(std::numbers::pi * (i + 0.75) / (kOrder + 0.5)), derivative = 0;
      for (int iteration = 0; iteration < 100; ++iteration) {
        // P_n(x) by the three-term recurrence, P_n'(x) from P_n and P_(n-1).
        double p = 1, previous = 0;
        for (int k = 1; k <= kOrder; ++k) {
          const double next = ((2 * k - 1) * x * p - (k - 1) * previous) / k;
          previous = p;
          p = next;
        }
        derivative = kOrder * (x * p - previous) / (x * x - 1);
        const double step = p / derivative;
        x -= step;
        if (std::abs(step) <= 1e-16) break;
      }
      // 2 / ((1 - x^2) P_n'(x)^2) on [-1, 1], halved for [0, 1].
      nodes[i] = 0.5 * (1 - x);
      nodes[kOrder - 1 - i] = 0.5 * (1 + x);
      weights[i] = weights[kOrder - 1 - i] = 1 / ((1 - x * x) * derivative * derivative);
    }
  }
};

const GaussLegendre& gauss_legendre() {
  static const GaussLegendre rule;
  return rule;
}

// x in the fewest digits that read back as x, or in `digits` significant digits.
std::string to_text(double x, int digits = 0) {
  return digits > 0 ? fmt::format("{:.{}g}", x, digits) : fmt::format("{}", x);
}

bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The real roots of a x^2 + b x + c = 0 without cancellation (NaN where there are fewer).
std::array<double, 2> quadratic_roots(double a, double b, double c) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (a == 0) return {b != 0 ? -c / b : kNaN, kNaN};
  const double discriminant = b * b - 4 * a * c;
  if (discriminant < 0) return {kNaN, kNaN};
  const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
  return {q / a, q != 0 ? c / q : kNaN};
}

// The largest |V(s)|^2 on [0, 1] for V = v0 + v1 s + v2 s^2 (infinite when a coefficient is
// not). The quartic's maxima lie at the ends or where g = V.V' (half its derivative) changes
// sign from + to -; g is a cubic, monotonic between its own critical points, so each such
// change is bracketed between two of them and found by bisection to the last bit.
double max_squared_speed(const Vec3& v0, const Vec3& v1, const Vec3& v2) {
  const auto squared = [&](double s) {
    const Vec3 v = v0 + (v1 + v2 * s) * s;
    return dot(v, v);
  };
  const double g0 = dot(v0, v1), g1 = 2 * dot(v0, v2) + dot(v1, v1), g2 = 3 * dot(v1, v2),
               g3 = 2 * dot(v2, v2);
  if (!std::isfinite(dot(v0, v0) + g0 + g1 + g2 + g3)) return kInfinity;
  const auto g = [&](double s) { return g0 + (g1 + (g2 + g3 * s) * s) * s; };
  std::array<double, 4> ends{0, 1, 1, 1};
  int count = 2;
  for (const double root : quadratic_roots(3 * g3, 2 * g2, g1))
    if (root > 0 && root < 1) ends[count++] = root;
  std::sort(ends.begin(), ends.begin() + count);
  double best = 0;
  for (int k = 0; k < count; ++k) best = std::max(best, squared(ends[k]));
  for (int k = 0; k + 1 < count; ++k) {
    double lo = ends[k], hi = ends[k + 1];
    if (!(g(lo) > 0 && g(hi) < 0)) continue;
    for (double mid = 0.5 * (lo + hi); mid > lo && mid < hi; mid = 0.5 * (lo + hi))
      (g(mid) > 0 ? lo : hi) = mid;
    best = std::max(best, squared(lo));
  }
  return best;
}

// Polynomials by their coefficients, lowest degree first.
using Polynomial = std::vector<double>;

Polynomial operator*(const Polynomial& p, const Polynomial& q) {
  Polynomial out(p.size() + q.size() - 1, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < q.size(); ++j) out[i + j] += p[i] * q[j];
  return out;
}

Polynomial operator-(Polynomial p, const Polynomial& q) {
  if (p.size() < q.size()) p.resize(q.size(), 0.0);
  for (std::size_t i = 0; i < q.size(); ++i) p[i] -= q[i];
  return p;
}

Polynomial derivative(const Polynomial& p) {
  Polynomial out(p.size() > 1 ? p.size() - 1 : 1, 0.0);
  for (std::size_t i = 1; i < p.size(); ++i) out[i - 1] = static_cast<double>(i) * p[i];
  return out;
}

double evaluate(const Polynomial& p, double x) {
  double value = 0;
  for (std::size_t i = p.size(); i-- > 0;) value = value * x + p[i];
  return value;
}

// The real roots of p strictly between lo and hi where it changes sign, each to the last bit:
// p is monotonic between consecutive roots of its derivative (found the same way), so each
// such interval holds at most one, bracketed for bisection.
std::vector<double> sign_changes(const Polynomial& p, double lo, double hi) {
  if (p.size() < 2) return {};
  std::vector<double> ends{lo};
  for (const double r : sign_changes(derivative(p), lo, hi)) ends.push_back(r);
  ends.push_back(hi);
  std::vector<double> roots;
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    double a = ends[k], b = ends[k + 1];
    const double fa = evaluate(p, a), fb = evaluate(p, b);
    if (!((fa < 0 && fb > 0) || (fa > 0 && fb < 0))) continue;
    const bool rising = fa < 0;
    for (double mid = 0.5 * (a + b); mid > a && mid < b; mid = 0.5 * (a + b))
      ((evaluate(p, mid) < 0) == rising ? a : b) = mid;
    roots.push_back(a);
  }
  return roots;
}

WorldLinePoint inertial_point(const Keyframe& key, const Vec3& velocity, double proper_time,
                              double t) {
  const double gamma = lorentz_gamma(velocity), dt = t - key.time;
  return {{t, key.position + velocity * dt}, {gamma, velocity * gamma}, proper_time + dt / gamma};
}

// PHYSICS.md's closed form for an inertial line, from where it is at the receiver's time.
WorldLinePoint retarded_inertial(const Keyframe& key, const Vec3& velocity, double proper_time,
                                 const Vec4& receiver) {
  const Vec3 at_receiver_time = key.position + velocity * (receiver.t - key.time);
  const double delay = retarded_delay(at_receiver_time - receiver.x, velocity);
  return inertial_point(key, velocity, proper_time, receiver.t - delay);
}

}  // namespace

KeyframeError::KeyframeError(const std::string& what, std::size_t first, std::size_t second)
    : std::invalid_argument(what), first(first), second(second) {}

Vec3 KeyframeWorldLine::Segment::position(double s) const {
  const double r = 1 - s;
  return from * ((1 + 2 * s) * r * r) + to * (s * s * (3 - 2 * s)) + from_step * (s * r * r) -
         to_step * (s * s * r);
}

KeyframeWorldLine::KeyframeWorldLine(std::vector<Keyframe> keys) : keys_(std::move(keys)) {
  if (keys_.empty())
    throw std::invalid_argument("a keyframed world-line needs at least one keyframe");
  const std::size_t n = keys_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(keys_[i].time) || !is_finite(keys_[i].position))
      throw KeyframeError(
          "keyframe " + std::to_string(i) + " has a time or position that is not finite", i, i);
    if (i > 0 && !(keys_[i].time > keys_[i - 1].time))
      throw KeyframeError("keyframe times must increase: keyframe " + std::to_string(i) +
                              " (time " + to_text(keys_[i].time) + ") is not after keyframe " +
                              std::to_string(i - 1) + " (time " + to_text(keys_[i - 1].time) + ")",
                          i - 1, i);
  }

  std::vector<Vec3> chords(n - 1), tangents(n);  // one key alone is at rest
  for (std::size_t i = 0; i + 1 < n; ++i)
    chords[i] = (keys_[i + 1].position - keys_[i].position) / (keys_[i + 1].time - keys_[i].time);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double before = keys_[i].time - keys_[i - 1].time;
    const double after = keys_[i + 1].time - keys_[i].time;
    tangents[i] = (chords[i - 1] * after + chords[i] * before) / (before + after);
  }
  // The end keys: the same parabola's slope there (2 d - m of its neighbour), or the chord when
  // there are only two keys.
  if (n == 2) tangents.front() = tangents.back() = chords.front();
  if (n > 2) {
    tangents.front() = chords.front() * 2.0 - tangents[1];
    tangents.back() = chords.back() * 2.0 - tangents[n - 2];
  }
  initial_velocity_ = tangents.front();
  final_velocity_ = tangents.back();

  for (std::size_t i = 0; i + 1 < n; ++i) {
    Segment segment;
    segment.start = keys_[i].time;
    segment.duration = keys_[i + 1].time - keys_[i].time;
    segment.from = keys_[i].position;
    segment.to = keys_[i + 1].position;
    segment.from_step = tangents[i] * segment.duration;
    segment.to_step = tangents[i + 1] * segment.duration;
    // The Hermite velocity about the chord: exactly the chord where the tangents are, so that
    // a straight, uniform motion stays exactly so.
    const Vec3 off_from = tangents[i] - chords[i], off_to = tangents[i + 1] - chords[i];
    segment.v0 = tangents[i];
    segment.v1 = (off_from * 2 + off_to) * -2;
    segment.v2 = (off_from + off_to) * 3;
    const double speed = std::sqrt(max_squared_speed(segment.v0, segment.v1, segment.v2));
    if (!(speed < 1))
      throw KeyframeError("the motion between keyframes " + std::to_string(i) + " and " +
                              std::to_string(i + 1) + " reaches speed " + to_text(speed, 3) +
                              " (c = 1)",
                          i, i + 1);
    segments_.push_back(segment);
  }

  knots_.push_back({keys_.front().time, 0, 0});
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const double from = keys_[i].time, to = keys_[i + 1].time;
    add_knots(i, from, to, proper_time_on(segments_[i], from, to), kMaxHalvings);
  }

  for (const Segment& segment : segments_)
    for (int j = 0; j <= kAccelerationSamples; ++j) {
      const double s = static_cast<double>(j) / kAccelerationSamples;
      const Vec3 v = segment.velocity(s), a = segment.acceleration(s);
      // gamma^3 sqrt(|a|^2 - |v x a|^2), written as a sum of positive terms.
      const double gamma2 = 1 / (1 - dot(v, v)), along = dot(v, a);
      max_proper_acceleration_ = std::max(max_proper_acceleration_,
                                          gamma2 * std::sqrt(dot(a, a) + gamma2 * along * along));
    }
}

double KeyframeWorldLine::proper_time_on(const Segment& segment, double from, double to) {
  const GaussLegendre& rule = gauss_legendre();
  const double width = to - from;
  double sum = 0;
  for (int k = 0; k < GaussLegendre::kOrder; ++k) {
    const Vec3 v =
        segment.velocity((from + width * rule.nodes[k] - segment.start) / segment.duration);
    sum += rule.weights[k] * std::sqrt(1 - dot(v, v));
  }
  return width * sum;
}

void KeyframeWorldLine::add_knots(std::size_t i, double from, double to, double whole,
                                  int halvings) {
  const Segment& segment = segments_[i];
  const double mid = 0.5 * (from + to);
  const double left = proper_time_on(segment, from, mid), right = proper_time_on(segment, mid, to);
  if (halvings > 0 && mid > from && mid < to &&
      std::abs(left + right - whole) > kQuadratureTolerance * (left + right)) {
    add_knots(i, from, mid, left, halvings - 1);
    add_knots(i, mid, to, right, halvings - 1);
    return;
  }
  knots_.push_back({mid, knots_.back().proper_time + left, i});
  knots_.push_back({to, knots_.back().proper_time + right, i});
}

KeyframeWorldLine::Fastest KeyframeWorldLine::max_gamma(const Vec3& observer_velocity) const {
  const Vec3& c = observer_velocity;
  const double observer_gamma = lorentz_gamma(c);
  Fastest fastest{observer_gamma, 0};
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const Segment& g = segments_[i];
    // gamma (1 - c.v) = a / sqrt(b) with a = 1 - c.v(s) and b = 1 - |v(s)|^2; a > 0, so its
    // extremes are those of a^2 / b, where 2 a' b - a b' = 0 (a quintic in s).
    const Polynomial a{1 - dot(c, g.v0), -dot(c, g.v1), -dot(c, g.v2)};
    const Polynomial b{1 - dot(g.v0, g.v0), -2 * dot(g.v0, g.v1),
                       -(dot(g.v1, g.v1) + 2 * dot(g.v0, g.v2)), -2 * dot(g.v1, g.v2),
                       -dot(g.v2, g.v2)};
    const Polynomial critical = Polynomial{2.0} * derivative(a) * b - a * derivative(b);
    std::vector<double> candidates = sign_changes(critical, 0, 1);
    candidates.push_back(0);
    candidates.push_back(1);
    for (const double s : candidates) {
      const Vec3 v = g.velocity(s);
      const double speed = length(v);
      // (1 - |v|)(1 + |v|), not 1 - |v|^2: no cancellation near the speed of light.
      const double gamma = observer_gamma * (1 - dot(c, v)) / std::sqrt((1 - speed) * (1 + speed));
      if (!(gamma <= fastest.gamma)) fastest = {gamma, i};
    }
  }
  return fastest;
}

WorldLinePoint KeyframeWorldLine::on_segment(const Segment& segment, const Knot& knot,
                                             double t) const {
  const double s = (t - segment.start) / segment.duration;
  const Vec3 v = segment.velocity(s);
  const double gamma = lorentz_gamma(v);
  return {{t, segment.position(s)},
          {gamma, v * gamma},
          knot.proper_time + proper_time_on(segment, knot.time, t)};
}

WorldLinePoint KeyframeWorldLine::at_world_time(double t) const {
  if (!(t > keys_.front().time)) return inertial_point(keys_.front(), initial_velocity_, 0, t);
  if (!(t < keys_.back().time))
    return inertial_point(keys_.back(), final_velocity_, knots_.back().proper_time, t);
  // The first knot after t ends the piece that holds t; the piece starts at the knot before.
  const auto next = std::upper_bound(knots_.begin(), knots_.end(), t,
                                     [](double time, const Knot& k) { return time < k.time; });
  return on_segment(segments_[next->segment], *std::prev(next), t);
}

WorldLinePoint KeyframeWorldLine::retarded(const Vec4& receiver) const {
  const auto gap = [&](double t, const Vec3& x) { return receiver.t - t - length(receiver.x - x); };
  // The gap decreases strictly along a timelike world-line: the keys where it is >= 0 come
  // first, and the retarded event follows the last of them.
  const std::size_t after =
      std::partition_point(keys_.begin(), keys_.end(),
                           [&](const Keyframe& key) { return gap(key.time, key.position) >= 0; }) -
      keys_.begin();
  if (after == 0) return retarded_inertial(keys_.front(), initial_velocity_, 0, receiver);
  if (after == keys_.size())
    return retarded_inertial(keys_.back(), final_velocity_, knots_.back().proper_time, receiver);

  // On the segment between, Newton's method in s, falling back to bisection whenever a step
  // would leave the bracket [lo, hi] (gap >= 0 at lo, < 0 at hi).
  const Segment& segment = segments_[after - 1];
  const auto gap_at = [&](double s) {
    return gap(segment.start + s * segment.duration, segment.position(s));
  };
  double lo = 0, hi = 1;
  const double gap_lo = gap_at(lo), gap_hi = gap_at(hi);
  double s = gap_lo / (gap_lo - gap_hi);
  for (int iteration = 0; iteration < 400 && hi - lo > 4 * kEpsilon; ++iteration) {
    const double value = gap_at(s);
    if (value == 0) break;
    (value > 0 ? lo : hi) = s;
    const Vec3 to_receiver = receiver.x - segment.position(s);
    const double distance = length(to_receiver);
    const double slope =  // d gap / ds, in (-2 duration, 0)
        segment.duration *
        (-1 + (distance > 0 ? dot(to_receiver, segment.velocity(s)) / distance : 0.0));
    double next = s - value / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == s) break;
    s = next;
  }
  return at_world_time(segment.start + s * segment.duration);
}

}  // namespace lightcone

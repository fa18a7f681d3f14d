#include "lightcone/physics/world_line.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/retarded_time.hpp"

namespace lightcone {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The interval with PHYSICS.md's signature (- + + +).
double interval(const Vec4& a, const Vec4& b) {
  return -a.t * b.t + dot(a.x, b.x);
}

// How far past the light cone of `receiver` an event lies: positive inside its past (or
// elsewhere before it), zero on the cone, negative after; it decreases along any timelike
// world-line.
double light_cone_gap(const Vec4& receiver, const Vec4& event) {
  return receiver.t - event.t - length(receiver.x - event.x);
}

// The roots of a x^2 + b x + c = 0 without cancellation (either may be NaN when there are
// none; a linear equation gives one).
void quadratic_roots(double a, double b, double c, double& r1, double& r2) {
  if (a == 0) {
    r1 = r2 = b != 0 ? -c / b : std::numeric_limits<double>::quiet_NaN();
    return;
  }
  const double d = b * b - 4 * a * c;
  if (d < 0) {
    r1 = r2 = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  const double q = -0.5 * (b + std::copysign(std::sqrt(d), b));
  r1 = q / a;
  r2 = q != 0 ? c / q : 0.0;
}

// The root of g, a function of world time that grows strictly (evaluate(t, slope) returns g(t)
// and sets g'(t) > 0), near t0: bracketed by steps doubling from |g(t0)| (g moves at least in
// proportion to t), then found by Newton's method safeguarded by bisection to the precision of
// doubles. Never a capped fixed point: the bracket only shrinks.
template <class Evaluate>
double increasing_root(const Evaluate& evaluate, double t0, const char* failure) {
  double slope = 0;
  const double start = evaluate(t0, slope);
  if (start == 0) return t0;
  double lo = t0, hi = t0;
  double step = std::max(std::abs(start), 1e-300);
  for (int doublings = 0;; ++doublings, step *= 2) {
    const double t = start < 0 ? t0 + step : t0 - step;
    if (doublings > 2100 || !std::isfinite(t)) throw std::runtime_error(failure);
    if ((evaluate(t, slope) < 0) != (start < 0)) {
      (start < 0 ? hi : lo) = t;
      break;
    }
  }
  double t = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 400; ++iteration) {
    const double value = evaluate(t, slope);
    if (value == 0) return t;
    (value < 0 ? lo : hi) = t;
    if (hi - lo <= 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t))) break;
    double next = t - value / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == t) break;
    t = next;
  }
  return t;
}

}  // namespace

AcceleratedWorldLine::AcceleratedWorldLine(double time, const Vec3& position, const Vec3& velocity,
                                           const std::vector<AccelerationPhase>& phases) {
  if (!(dot(velocity, velocity) < 1))
    throw std::invalid_argument("a world-line's speed must be below 1");
  const double gamma = lorentz_gamma(velocity);
  Piece past;
  past.start = {{time, position}, {gamma, velocity * gamma}, 0.0};
  past.duration = kInfinity;  // runs back from its start
  pieces_.push_back(past);
  WorldLinePoint at = past.start;
  for (const AccelerationPhase& phase : phases) {
    if (!(phase.duration >= 0) || !std::isfinite(phase.duration))
      throw std::invalid_argument("a phase's duration must be finite and >= 0");
    const double a = length(phase.acceleration);
    if (!std::isfinite(a)) throw std::invalid_argument("a phase's acceleration must be finite");
    Piece piece;
    piece.start = at;
    piece.duration = phase.duration;
    if (a > 0) {
      piece.rho = 1 / a;
      piece.u = at.four_velocity;
      // The unit acceleration in the instantaneous rest frame, carried to W by the inverse of
      // the pure boost to that frame.
      const Vec3 beta = velocity_of(at.four_velocity);
      piece.n = boost(beta * -1.0) * Vec4{0.0, phase.acceleration * (1 / a)};
    }
    pieces_.push_back(piece);
    at = on_piece(piece, phase.duration);
  }
  Piece future;
  future.start = at;
  future.duration = kInfinity;
  pieces_.push_back(future);
}

WorldLinePoint AcceleratedWorldLine::on_piece(const Piece& piece, double dtau) const {
  WorldLinePoint p;
  p.proper_time = piece.start.proper_time + dtau;
  if (piece.rho == 0) {
    p.event = piece.start.event + dtau * piece.start.four_velocity;
    p.four_velocity = piece.start.four_velocity;
    return p;
  }
  // X = X_start + rho (sinh(eta) U + (cosh(eta) - 1) N), with cosh - 1 = 2 sinh^2(eta / 2) so
  // that small accelerations lose nothing.
  const double eta = dtau / piece.rho;
  const double s = std::sinh(eta), half = std::sinh(0.5 * eta);
  p.event = piece.start.event + piece.rho * (s * piece.u + (2 * half * half) * piece.n);
  p.four_velocity = std::cosh(eta) * piece.u + s * piece.n;
  return p;
}

std::size_t AcceleratedWorldLine::piece_at_proper_time(double tau) const {
  if (tau <= 0) return 0;
  for (std::size_t i = 1; i + 1 < pieces_.size(); ++i)
    if (tau < pieces_[i].start.proper_time + pieces_[i].duration) return i;
  return pieces_.size() - 1;
}

WorldLinePoint AcceleratedWorldLine::at_proper_time(double tau) const {
  const Piece& piece = pieces_[piece_at_proper_time(tau)];
  return on_piece(piece, tau - piece.start.proper_time);
}

WorldLinePoint AcceleratedWorldLine::at_world_time(double t) const {
  // The last piece that starts at or before t (the past piece for anything before the start).
  std::size_t i = 0;
  for (std::size_t k = 1; k < pieces_.size(); ++k)
    if (pieces_[k].start.event.t <= t) i = k;
  const Piece& piece = pieces_[i];
  const double dt = t - piece.start.event.t;
  if (piece.rho == 0) return on_piece(piece, dt / piece.start.four_velocity.t);
  // rho (U.t sinh(eta) + N.t (cosh(eta) - 1)) = dt: with E = e^eta - 1 = x,
  // (U.t + N.t) x^2 + 2 (U.t - dt / rho) x - 2 dt / rho = 0 ... solved for the root x > -1.
  const double ut = piece.u.t, nt = piece.n.t, k = dt / piece.rho;
  double x1, x2;
  quadratic_roots(ut + nt, 2 * (ut - k), -2 * k, x1, x2);
  const double x = (x1 >= 0 || !(x2 >= 0)) ? x1 : x2;
  return on_piece(piece, piece.rho * std::log1p(x));
}

WorldLinePoint AcceleratedWorldLine::retarded(const Vec4& receiver) const {
  // The piece where the light-cone gap changes sign: the last whose start is not after the
  // receiver's past light cone.
  std::size_t i = 0;
  for (std::size_t k = 1; k < pieces_.size(); ++k)
    if (light_cone_gap(receiver, pieces_[k].start.event) >= 0) i = k;
  const Piece& piece = pieces_[i];
  const WorldLinePoint& s = piece.start;
  if (piece.rho == 0) {
    // Inertial: PHYSICS.md's closed form, from where the piece's line is at t_R.
    const Vec3 beta = velocity_of(s.four_velocity);
    const Vec3 at_receiver_time = s.event.x + beta * (receiver.t - s.event.t);
    const double delay = retarded_delay(at_receiver_time - receiver.x, beta);
    return on_piece(piece, (receiver.t - delay - s.event.t) / s.four_velocity.t);
  }
  // Hyperbolic: with W = R - X_start, A = W.U, B = W.N + rho, q = W.W / rho, the light-cone
  // condition A sinh(eta) + B (cosh(eta) - 1) = q / 2 becomes, with x = e^eta - 1,
  // (A + B) x^2 + (2 A - q) x - q = 0 (PHYSICS.md's quadratic in e^eta, written about the
  // phase's start so that it keeps its precision for small accelerations).
  const Vec4 w = receiver - s.event;
  const double a = interval(w, piece.u), b = interval(w, piece.n) + piece.rho;
  const double q = interval(w, w) / piece.rho;
  double x1, x2;
  quadratic_roots(a + b, 2 * a - q, -q, x1, x2);
  // Of the (up to) two meetings with the light cone of R, the one in R's past.
  const double eta_end = piece.duration / piece.rho;
  WorldLinePoint best{};
  double best_gap = kInfinity;
  for (const double x : {x1, x2}) {
    if (!(x > -1)) continue;
    const double eta = std::clamp(std::log1p(x), 0.0, eta_end);
    const WorldLinePoint p = on_piece(piece, piece.rho * eta);
    if (p.event.t > receiver.t) continue;
    const double gap = std::abs(light_cone_gap(receiver, p.event));
    if (gap < best_gap) best_gap = gap, best = p;
  }
  return best_gap < kInfinity ? best : s;
}

double AcceleratedWorldLine::max_proper_acceleration() const {
  double a = 0;
  for (const Piece& piece : pieces_)
    if (piece.rho > 0 && piece.duration > 0) a = std::max(a, 1 / piece.rho);
  return a;
}

Mat3 AcceleratedWorldLine::carried_rotation(double tau) const {
  const Vec3 start_velocity = velocity_of(pieces_.front().start.four_velocity);
  Vec4 axes[3];
  for (int i = 0; i < 3; ++i) {
    Vec3 axis;
    axis[i] = 1;
    axes[i] = boost(start_velocity * -1.0) * Vec4{0.0, axis};
  }
  // Fermi-Walker transport on a hyperbola: e = e_perp + (e.N) N goes to e_perp + (e.N) N(eta)
  // with N(eta) = sinh(eta) U + cosh(eta) N.
  for (std::size_t i = 1; i + 1 < pieces_.size() && tau > pieces_[i].start.proper_time; ++i) {
    const Piece& piece = pieces_[i];
    if (piece.rho == 0) continue;
    const double eta = std::min(tau - piece.start.proper_time, piece.duration) / piece.rho;
    const Vec4 n_eta = std::sinh(eta) * piece.u + std::cosh(eta) * piece.n;
    for (Vec4& e : axes) e = e + interval(e, piece.n) * (n_eta - piece.n);
  }
  const Vec3 velocity = velocity_of(at_proper_time(tau).four_velocity);
  Mat3 r;
  for (int i = 0; i < 3; ++i) {
    const Vec3 column = (boost(velocity) * axes[i]).x;
    for (int k = 0; k < 3; ++k) r.m[k][i] = column[k];
  }
  return r;
}

AcceleratedWorldLine::Description AcceleratedWorldLine::described_in(const Mat4& lorentz) const {
  Description d;
  const WorldLinePoint& start = pieces_.front().start;
  const Vec4 event = lorentz * start.event;
  d.time = event.t;
  d.position = event.x;
  d.velocity = velocity_of(lorentz * start.four_velocity);
  for (std::size_t i = 1; i + 1 < pieces_.size(); ++i) {
    const Piece& piece = pieces_[i];
    AccelerationPhase phase{piece.duration, {}};
    if (piece.rho > 0) {
      // The unit 4-acceleration in the new frame, seen in the rest frame of the 4-velocity
      // there (the pure boost), is (0, direction).
      const Vec3 beta = velocity_of(lorentz * piece.u);
      phase.acceleration = (boost(beta) * (lorentz * piece.n)).x / piece.rho;
    }
    d.phases.push_back(phase);
  }
  return d;
}

WorldLinePoint point_at_proper_time(const TimelikeWorldLine& line, double tau) {
  // tau(t) - tau grows with slope 1 / gamma in (0, 1].
  const double t = increasing_root(
      [&](double s, double& slope) {
        const WorldLinePoint p = line.at_world_time(s);
        slope = 1 / p.four_velocity.t;
        return p.proper_time - tau;
      },
      0.0, "no event at that proper time");
  return line.at_world_time(t);
}

WorldLinePoint simultaneous_point(const TimelikeWorldLine& line, const Vec4& event,
                                  const Vec3& frame_velocity) {
  // (t - t_e) - beta.(X(t) - x_e) is the frame's time difference over gamma; its slope
  // 1 - beta.V(t) lies in (0, 2).
  const double t = increasing_root(
      [&](double s, double& slope) {
        const WorldLinePoint p = line.at_world_time(s);
        slope = 1 - dot(frame_velocity, velocity_of(p.four_velocity));
        return (p.event.t - event.t) - dot(frame_velocity, p.event.x - event.x);
      },
      event.t, "no simultaneous event: the world-line is not timelike");
  return line.at_world_time(t);
}

RotatingPointWorldLine::RotatingPointWorldLine(const Vec3& axis, double rate, const Vec3& offset)
    : axis_(axis), offset_(offset), rate_(rate) {
  speed_ = std::abs(rate) * length(offset - axis * dot(axis, offset));
  if (!(speed_ < 1)) throw std::invalid_argument("a turning point's speed must be below 1");
}

WorldLinePoint RotatingPointWorldLine::at_world_time(double t) const {
  const Vec3 x = rotated(axis_, rate_ * t, offset_);
  const Vec3 v = cross(axis_, x) * rate_;
  const double gamma = 1 / std::sqrt((1 - speed_) * (1 + speed_));
  return {{t, x}, {gamma, v * gamma}, t / gamma};
}

WorldLinePoint RotatingPointWorldLine::retarded(const Vec4& receiver) const {
  const double t = retarded_world_time([&](double s) { return at_world_time(s).event.x; },
                                       [&](double s) {
                                         const WorldLinePoint p = at_world_time(s);
                                         return velocity_of(p.four_velocity);
                                       },
                                       receiver);
  return at_world_time(t);
}

double RotatingPointWorldLine::max_proper_acceleration() const {
  const double r = length(offset_ - axis_ * dot(axis_, offset_));
  return r > 0 ? speed_ * speed_ / ((1 - speed_) * (1 + speed_) * r) : 0.0;
}

double retarded_world_time(const std::function<Vec3(double)>& position,
                           const std::function<Vec3(double)>& velocity, const Vec4& receiver) {
  // |x_R - X(t)| - (t_R - t), minus the light-cone gap, grows with slope in (0, 2).
  return increasing_root(
      [&](double t, double& slope) {
        const Vec3 to_receiver = receiver.x - position(t);
        const double distance = length(to_receiver);
        slope = 1 - (distance > 0 ? dot(to_receiver, velocity(t)) / distance : 0.0);
        return distance - (receiver.t - t);
      },
      receiver.t, "no retarded event: the world-line is not timelike");
}
}  // namespace lightcone

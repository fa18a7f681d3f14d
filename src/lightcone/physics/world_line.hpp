// World-lines beyond inertial motion: phases of constant proper acceleration (hyperbolic
// motion) in closed form, and the retarded event of any timelike world-line by a safeguarded
// Newton iteration (docs/physics.md, "World-lines"; PHYSICS.md).
#pragma once

#include <functional>
#include <vector>

#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/vec.hpp"

namespace lightcone {

// Constant proper acceleration for a proper-time `duration`; `acceleration` is the proper
// acceleration in the body's instantaneous rest frame at the start of the phase (axes: W's
// carried by the pure boost), held fixed in the Fermi-Walker sense.
struct AccelerationPhase {
  double duration = 0;
  Vec3 acceleration;
};

// A point of a world-line: its event in W, its 4-velocity (dX/dtau, so that u.t = gamma) and
// its proper time.
struct WorldLinePoint {
  Vec4 event;
  Vec4 four_velocity;
  double proper_time = 0;
};

// A timelike world-line in W, as the renderers read it: its point at a world time, on the past
// light cone of an event, and a bound on its proper acceleration (for the error of rigid-body
// approximations).
class TimelikeWorldLine {
 public:
  virtual ~TimelikeWorldLine() = default;
  // The point at world time t (world time grows strictly along the world-line).
  virtual WorldLinePoint at_world_time(double t) const = 0;
  // The point on the past light cone of `receiver` (exactly one: the world-line is timelike).
  virtual WorldLinePoint retarded(const Vec4& receiver) const = 0;
  // The largest magnitude of the proper acceleration anywhere on the world-line.
  virtual double max_proper_acceleration() const = 0;
  // How a body on this world-line is turned at proper time tau: axes that were its rest
  // frame's at proper time 0 (W's carried by the pure boost), carried along as the world-line
  // says, written in the rest frame at tau whose axes are W's carried by the pure boost. The
  // identity by default: the body keeps its orientation in those axes.
  virtual Mat3 carried_rotation(double proper_time) const { return {}; }
};

// The point of `line` where its proper time is tau (proper time grows along it at the rate
// 1 / gamma of world time): bracketed and solved by Newton's method safeguarded by bisection.
WorldLinePoint point_at_proper_time(const TimelikeWorldLine& line, double proper_time);

// The point of `line` simultaneous with `event` in the frame moving with `frame_velocity`
// (|frame_velocity| < 1): the root of the frame's time difference, which grows strictly along
// a timelike world-line, bracketed and solved by Newton's method safeguarded by bisection.
WorldLinePoint simultaneous_point(const TimelikeWorldLine& line, const Vec4& event,
                                  const Vec3& frame_velocity);

// A world-line through the event (time, position) with velocity `velocity` at proper time 0,
// inertial before it, then each phase in turn, inertial after the last. Each phase is the
// hyperbola X(eta) = C + rho (sinh(eta) U + cosh(eta) N) in the plane of the 4-velocity U and
// the unit 4-acceleration N at its start, rho = 1 / |a|, eta = (tau - tau_start) / rho.
class AcceleratedWorldLine final : public TimelikeWorldLine {
 public:
  // Requires |velocity| < 1, durations >= 0 and finite accelerations (a zero one is an
  // inertial phase).
  AcceleratedWorldLine(double time, const Vec3& position, const Vec3& velocity,
                       const std::vector<AccelerationPhase>& phases);

  WorldLinePoint at_proper_time(double tau) const;
  WorldLinePoint at_world_time(double t) const override;
  // The point on the past light cone of `receiver`: closed form on each piece (retarded_delay
  // on an inertial one, a quadratic in e^eta on a hyperbola), the piece found by the sign of
  // the light-cone function at the pieces' ends.
  WorldLinePoint retarded(const Vec4& receiver) const override;
  double max_proper_acceleration() const override;
  // A body that does not spin keeps gyroscope axes: Fermi-Walker transported, which on each
  // hyperbola is the boost in the plane of U and N. So a path that turns (acceleration not
  // along the velocity) turns the body relative to the pure-boost axes: Thomas precession.
  Mat3 carried_rotation(double proper_time) const override;

  // The same world-line written in the frame whose coordinates are `lorentz` (a proper
  // orthochronous Lorentz matrix) times W's: its start event and velocity there, and each
  // phase's acceleration in the rest frame whose axes are the new frame's carried by the pure
  // boost (they differ from W's by a Wigner rotation, one per phase).
  struct Description {
    double time = 0;
    Vec3 position, velocity;
    std::vector<AccelerationPhase> phases;
  };
  Description described_in(const Mat4& lorentz) const;

 private:
  struct Piece {
    WorldLinePoint start;  // at its first proper time
    double duration = 0;   // infinite for the last piece; the first runs back from start
    // Hyperbolic pieces: rho = 1/|a| > 0, U and N at the start, C = X(start) - rho N.
    double rho = 0;
    Vec4 u, n, centre;
  };
  WorldLinePoint on_piece(const Piece& piece, double tau_from_start) const;
  std::size_t piece_at_proper_time(double tau) const;
  std::vector<Piece> pieces_;  // the inertial past first, then the phases, then the future
};

// A point turning rigidly about the origin of an inertial frame, X(t) = R(axis, rate t) offset
// (R right-handed, `axis` unit, `rate` in radians per unit time): a point of a spinning body in
// the rest frame of its centre. Requires |rate| times the distance from the axis below 1. Its
// proper time is t sqrt(1 - v^2) (the centre's clock is t).
class RotatingPointWorldLine final : public TimelikeWorldLine {
 public:
  RotatingPointWorldLine(const Vec3& axis, double rate, const Vec3& offset);

  WorldLinePoint at_world_time(double t) const override;
  // By retarded_world_time (no closed form for a helix).
  WorldLinePoint retarded(const Vec4& receiver) const override;
  // Centripetal: gamma^2 v^2 / r.
  double max_proper_acceleration() const override;

 private:
  Vec3 axis_, offset_;
  double rate_;
  double speed_;  // |rate| times the distance from the axis
};

// The world time t of the event of a timelike world-line X(t) (velocity V(t), |V| < 1) on the
// past light cone of `receiver`: the root of f(t) = t_R - t - |x_R - X(t)|, which decreases
// strictly, bracketed and solved by Newton's method safeguarded by bisection to the precision
// of doubles.
double retarded_world_time(const std::function<Vec3(double)>& position,
                           const std::function<Vec3(double)>& velocity, const Vec4& receiver);

}  // namespace lightcone

// Bodies met along the ray on the line through the hole and the ray's start (b = 0,
// docs/design/black-hole.md, "The axis ray"). It is a radial null geodesic: it sweeps no angle,
// so CurvedBodies::nearest's windows of angles about the hole do not describe it. In space it is
// the half-line r e1 (r from its start outward to infinity, or inward to the horizon), so a chord
// of it is exact in space; only its coordinate time bends, in closed form:
// t(r) = t_start - |r_*(r) - r_*(r_start)|, with the tortoise coordinate
// r_* = r + 2M ln(r / 2M - 1). A chord's time strays from the path's by at most
// |t''| dr^2 / 8 = M dr^2 / (4 (r - 2M)^2) (t' = 1/f, r f = r - 2M), which moves a body by its
// speed times that: chords are kept short enough for that to stay within the chord error, and
// short enough in time for the body's own acceleration (as CurvedBodies::nearest keeps them).
// The first chord that meets a moving body is then halved about the hit down to rounding, so the
// event met is on the path to double precision.
#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The radius past which an outward radial ray from r0 has outrun a body within `now` of the hole
// at the ray's start that moves at coordinate speed at most v < 1: the body is then within
// now + v (r_*(r) - r_*(r0)) of the hole, which r exceeds for good once it does with
// f(r) > v (the ray's coordinate speed f beats the body's).
double outrun_radius(double m, double r0, double now, double v) {
  const double tortoise0 = tortoise_coordinate(m, r0);
  const auto outran = [&](double r) {
    return r - v * (tortoise_coordinate(m, r) - tortoise0) > now;
  };
  double r = std::max({now, r0, 2 * m / (1 - v)});
  while (!outran(r) && r < kInfinity) r *= 2;  // (NaN: no radius)
  return r;
}

}  // namespace

bool CurvedBodies::nearest_on_axis(const PathStart& start, const CurvedPath& path, double from,
                                   double to, Found& best) const {
  if (bodies_.empty()) return false;
  const double m = HoleView::mass;
  const double horizon = 2 * m * (1 + 1e-12);
  const double r0 = start.radius, tortoise0 = tortoise_coordinate(m, r0);
  const auto event_at = [&](double r) {
    return Vec4{start.time - std::abs(tortoise_coordinate(m, r) - tortoise0), path.e1 * r};
  };
  // Whether radius a comes before b along the path.
  const auto before = [&](double a, double b) { return path.outward ? a < b : a > b; };
  // The stretch ends at `to`, outside the horizon; a body met cuts it short.
  double end = path.outward ? to : std::max(to, horizon);
  for (const Body& body : bodies_) {
    const HoleWorldLine& line = body.line;
    // The radii along the axis at which the path can meet the body: exactly where its ball
    // crosses the axis if it is at rest, else the radii its ball ever reaches (on the way out,
    // only until the path has outrun it).
    double lo = 0, hi = 0;
    if (line.still()) {
      const Vec3& p = std::get<HoleWorldLine::Straight>(line.path()).position;
      const double along = dot(p, path.e1), across = length(p - path.e1 * along);
      if (!(across < body.radius)) continue;
      const double half = std::sqrt((body.radius - across) * (body.radius + across));
      lo = along - half, hi = along + half;
    } else {
      lo = line.nearest() - body.radius;
      hi = line.farthest() + body.radius;
      if (path.outward && std::isinf(hi))
        hi = outrun_radius(m, r0, length(line.at(start.time).position) + body.radius,
                           line.max_coordinate_speed());
    }
    // The stretch of the path over those radii, short of the nearest body met so far.
    const double enter = path.outward ? std::max(lo, from) : std::min(hi, from);
    const double leave = path.outward ? std::min(hi, end) : std::max(lo, end);
    if (!before(enter, leave)) continue;

    const bool moving = !line.still();
    const bool straight = std::holds_alternative<HoleWorldLine::Straight>(line.path());
    const auto state_at = [&](const Vec4& e) {
      return straight ? HoleWorldLineState{} : line.at(e.t);
    };
    const auto shape_of = [&](const Vec4& e, const HoleWorldLineState& state) {
      return body.shape_point(scene_.world_maps[body.index], e, hole_, straight ? nullptr : &state);
    };
    // A chord's radial length: at most (r - 2M) c / (1 + c) from its end at r, which keeps its
    // time's error times the body's speed (in its rest frame, gamma v) within the chord error
    // wherever the chord ends. A body at rest is met by one chord, exact.
    const double error = kChordError * body.radius;
    const double speed = line.max_coordinate_speed();
    const double c =
        moving ? std::sqrt(4 * error * std::sqrt((1 - speed) * (1 + speed)) / (m * speed)) : 0;
    const double step_share = moving ? c / (1 + c) : kInfinity;

    double r_a = enter;
    Vec4 a = event_at(r_a);
    HoleWorldLineState state_a = state_at(a);
    while (before(r_a, leave)) {
      const double step = (r_a - 2 * m) * step_share;
      double r_b = path.outward ? std::min(r_a + step, leave) : std::max(r_a - step, leave);
      Vec4 b = event_at(r_b);
      HoleWorldLineState state_b = state_at(b);
      double acceleration = 0;
      const bool may_meet = body.may_meet_in_space(a.x, b.x, 0) &&
                            body.may_meet_in_time(a, b, state_a, state_b, 0, acceleration);
      if (!may_meet) {
        r_a = r_b, a = b, state_a = state_b;
        continue;
      }
      // Short enough in time for the body's acceleration over it.
      const double max_dt = acceleration > 0 ? std::sqrt(8 * error / acceleration) : kInfinity;
      for (int halving = 0; halving < 64 && !(std::abs(b.t - a.t) <= max_dt); ++halving) {
        r_b = (r_a + r_b) / 2;
        b = event_at(r_b);
        state_b = state_at(b);
      }
      if (r_b == r_a) break;  // no chord short enough: given up, as nearest does
      Vec3 shape_a = shape_of(a, state_a), shape_b = shape_of(b, state_b);
      auto chord = segments_.body_on_shape_segment(body.index, shape_a, shape_b);
      if (!chord) {
        r_a = r_b, a = b, state_a = state_b;
        continue;
      }
      // A moving body: the chord's halves about the hit, down to rounding, so that the hit is on
      // the path (a half that misses on both sides leaves a graze, met at the last chord).
      double r_lo = r_a, r_hi = r_b;
      for (int halving = 0; moving && halving < 64; ++halving) {
        const double r_mid = (r_lo + r_hi) / 2;
        if (r_mid == r_lo || r_mid == r_hi) break;
        const Vec4 mid = event_at(r_mid);
        const Vec3 shape_mid = shape_of(mid, state_at(mid));
        if (const auto first = segments_.body_on_shape_segment(body.index, shape_a, shape_mid)) {
          r_hi = r_mid, shape_b = shape_mid, chord = first;
        } else if (const auto second =
                       segments_.body_on_shape_segment(body.index, shape_mid, shape_b)) {
          r_lo = r_mid, shape_a = shape_mid, chord = second;
        } else {
          break;
        }
      }
      const double r_hit = r_lo + (r_hi - r_lo) * chord->s;
      end = r_hit;
      best.body = body.index;
      best.phi = 0;
      best.event = event_at(r_hit);
      best.shape_point = shape_of(best.event, state_at(best.event));
      best.incoming = shape_b - shape_a;
      best.prim = chord->prim;
      best.turned = false;
      break;
    }
  }
  return best.body >= 0;
}

}  // namespace lightcone

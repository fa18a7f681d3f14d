#include "lightcone/frame/curved_bodies.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/math_policy.hpp"

namespace lightcone {
namespace {

using PathStart = CurvedBodies::PathStart;

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The events of one ray's path, relative to the hole and in units of M: after sweeping phi it is
// at path.offset(phi, r(phi)), at its start's time less the coordinate time the light took.
struct PathEvents {
  const PathStart& start;
  const CurvedPath& path;
  const AngleSweep& course;  // its turning point (prepare_sweep keeps ray_course's)

  PathEvents(const PathStart& s, const CurvedPath& p) : start(s), path(p), course(p.sweep) {}
  mutable bool turn_timed = false;
  mutable double to_turn = 0;

  bool turned(double phi) const { return course.turning_radius > 0 && phi > course.angle_to_turn; }
  double radius(double phi) const { return radius_after_angle(path.sweep, phi); }
  // The coordinate time from the point at phi (radius r) to the start, on the stretches between:
  // the one from the start to the turning point taken once a ray, at its first point past it.
  double delay(double phi, double r) const {
    const double r0 = start.radius;
    if (!turned(phi)) return coordinate_time(path.orbit, r0, r);
    const double turn = course.turning_radius;
    if (!turn_timed) to_turn = coordinate_time(path.orbit, r0, turn), turn_timed = true;
    return to_turn + coordinate_time(path.orbit, turn, r);
  }
  double time(double phi, double r) const { return start.time - delay(phi, r); }
  // The event at phi; its time only when `timed` (a body at rest needs none to be met).
  Vec4 event(double phi, bool timed, double* r_out = nullptr) const {
    const double r = radius(phi);
    if (r_out) *r_out = r;
    return {timed ? time(phi, r) : 0.0, path.offset(phi, r)};
  }
};

// The surface a chord met, as a function whose sign tells the side of it a shape point is on.
struct MetSurface {
  enum class Kind { kSphere, kPlane } kind = Kind::kPlane;
  double radius = 0;  // kSphere
  Vec3 normal;        // kPlane: normal . p = offset
  double offset = 0;
  double at(const Vec3& p) const {
    if (kind == Kind::kPlane) return dot(normal, p) - offset;
    const Vec3 q = p / radius;  // (squares of the scene's lengths need not be doubles)
    return dot(q, q) - 1;
  }
};

MetSurface surface_met(const Object& object, const Vec3& p, unsigned prim) {
  MetSurface s;
  if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
    s.kind = MetSurface::Kind::kSphere;
    s.radius = sphere->radius;
  } else if (const auto* box = std::get_if<Box>(&object.shape)) {
    const Vec3 rel = component_div(p, box->size);
    int axis = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(rel[i]) > std::abs(rel[axis])) axis = i;
    s.normal[axis] = std::copysign(1.0, p[axis]);
    s.offset = box->size[axis] * 0.5;
  } else if (std::holds_alternative<Plane>(object.shape)) {
    s.normal = {0, 1, 0};
  } else if (const auto* m = std::get_if<MeshShape>(&object.shape)) {
    const auto& tri = m->mesh->triangles[prim];
    const Vec3 a = m->mesh->positions[tri[0]];
    s.normal = cross(m->mesh->positions[tri[1]] - a, m->mesh->positions[tri[2]] - a);
    s.offset = dot(s.normal, a);
  }
  return s;
}

// Where a ray in the plane through the hole with normal n (axes e1, e2) can meet a body: within
// delta of each centre angle (every angle for delta = pi), at radii between near and reach;
// inner bounds the radius of a point met from below, for the chord step. No windows: it cannot.
struct Windows {
  int count = 0;
  double centre[2] = {0, 0};  // increasing
  double delta = kPi;
  double near = 0, reach = 0, inner = 0;
  double line_in_plane = 0;  // a fall's: its line's direction projected on the plane, its length
};

// How far out a ray can meet a body that comes no nearer than `now` at the ray's start and
// moves at coordinate speed at most v (< 1): past r, the light's delay T >= r - r0 - 4M ln(1 +
// r / 2M) - 8M (coordinate light speed at most 1, and the Shapiro delay's bound) takes the body
// at most v T farther out, and the ray has outrun it.
double moving_reach(double m, double start_radius, double v, double now) {
  const auto beyond = [&](double r) {
    return (1 - v) * r - v * (start_radius + 4 * m * std::log1p(r / (2 * m)) + 8 * m) > now;
  };
  double reach = std::max(now, start_radius);
  while (!beyond(reach) && reach < kInfinity) reach *= 2;  // (NaN: no reach)
  return reach;
}

Windows body_windows(const HoleWorldLine& line, double radius, const CurvedPath& path,
                     const Vec3& n, const PathStart& start) {
  const double m = HoleView::mass, start_time = start.time;
  Windows w;
  const auto at_angle = [&](const Vec3& v) { return std::atan2(dot(v, path.e2), dot(v, path.e1)); };
  const auto everywhere = [&](double near, double reach) {
    w.count = 1, w.delta = kPi, w.near = std::max(near, 2 * m), w.reach = reach, w.inner = 0;
    return w;
  };
  if (const auto* orbit = std::get_if<HoleWorldLine::Orbit>(&line.path())) {
    // The torus about the orbit cuts the plane where |q . N| <= R: within asin(R / (r s)) of
    // the two directions along which the planes meet (s the sine of the angle between them).
    const Vec3 normal = cross(orbit->axis_x, orbit->axis_y);
    const Vec3 in_plane = normal - n * dot(normal, n);
    const double s = length(in_plane), inner = orbit->radius - radius;
    if (!(s * inner > radius)) return everywhere(inner, orbit->radius + radius);
    const double theta = at_angle(in_plane);
    w.count = 2;
    w.centre[0] = theta - kPi / 2, w.centre[1] = theta + kPi / 2;
    w.delta = std::asin(radius / (inner * s));
    w.near = std::max(inner, 2 * m), w.reach = orbit->radius + radius, w.inner = inner;
    return w;
  }
  if (const auto* fall = std::get_if<HoleWorldLine::Fall>(&line.path())) {
    // The tube along the line of fall (r >= 2M) cuts the plane, at radii rho >= 2M, where
    // rho^2 (1 - p^2 cos^2(theta - theta_d)) <= R^2, p the length of the direction's projection.
    // (Where it is now, which costs the solve of its fall, matters from infinity alone.)
    const double reach = fall->fall.is_from_infinity()
                             ? moving_reach(m, start.radius, line.max_coordinate_speed(),
                                            length(line.at(start_time).position) + radius)
                             : line.farthest() + radius;
    if (!(radius < 2 * m)) return everywhere(2 * m, reach);
    const Vec3 in_plane = fall->direction - n * dot(fall->direction, n);
    w.line_in_plane = length(in_plane);
    const double least_cos =
        std::sqrt((1 - radius / (2 * m)) * (1 + radius / (2 * m))) / w.line_in_plane;
    if (!(least_cos < 1)) return w;
    w.count = 1;
    w.centre[0] = at_angle(in_plane);
    w.delta = std::acos(least_cos);
    w.near = 2 * m, w.reach = reach, w.inner = 2 * m;
    return w;
  }
  // A straight line: the body's ball (or the tube it sweeps) cuts the plane in a disc about cp
  // of radius rho, which the ray can reach only within delta of its angle about the hole.
  const auto& straight = std::get<HoleWorldLine::Straight>(line.path());
  const Vec3& p = straight.position;
  const Vec3& v = straight.velocity;
  Vec3 cp = p;
  double rho = radius;
  if (line.still()) {
    const double h = dot(p, n);
    if (std::abs(h) >= radius) return w;
    cp = p - n * h;
    rho = std::sqrt(radius * radius - h * h);
    w.reach = length(cp) + rho;
  } else {
    const double vn = dot(v, n), speed = length(v);
    // How far out the ray can meet it: past where the body cannot keep up with the ray.
    const double now = length(p + v * (start_time - straight.time)) + radius;
    const double reach = moving_reach(m, start.radius, speed, now);
    // How far in: its line's closest approach.
    const double near = line.nearest() - radius;
    if (std::abs(vn) <= 1e-9 * speed) {
      if (std::abs(dot(p, n)) >= radius) return w;
      return everywhere(near, reach);
    }
    cp = p - v * (dot(p, n) / vn);
    rho = radius * speed / std::abs(vn);
    w.reach = reach;
    w.near = std::max(near, 2 * m);
  }
  const double d = length(cp);
  w.count = 1;
  w.centre[0] = at_angle(cp);
  w.delta = d <= rho ? kPi : std::asin(rho / d);
  if (line.still()) w.near = std::max(d - rho, 2 * m);
  w.inner = w.delta >= kPi ? 0 : d - rho;
  return w;
}

// The tortoise coordinate r* = r + 2M ln(r / 2M - 1), whose variation is a radial null path's
// coordinate time.
double tortoise(double r) {
  const double m = HoleView::mass;
  return r + 2 * m * std::log((r - 2 * m) / (2 * m));
}

}  // namespace

TimeBounds light_cone_bounds(const TimeBounds& a, const Vec3& a_x, const Vec3& b_x, double dphi,
                             double turn, double impact) {
  const double m = HoleView::mass;
  const double r_a = length(a_x), r_b = length(b_x);
  const double least = turn > 0 ? turn : std::min(r_a, r_b);
  const double star_a = tortoise(r_a), star_b = tortoise(r_b),
               star_turn = turn > 0 ? tortoise(turn) : 0.0;
  const double radial =
      turn > 0 ? (star_a - star_turn) + (star_b - star_turn) : std::abs(star_a - star_b);
  // (The tortoise coordinates' rounding, which the difference keeps where the path is nearly
  // radial and its time nearly the radial part alone.)
  const double rounding = 1e-13 * (std::abs(star_a) + std::abs(star_b) + 2 * std::abs(star_turn));
  const double across = std::max(r_a, r_b) * dphi / std::sqrt(1 - 2 * m / least);
  double longest = radial + rounding + across, shortest = radial - rounding;
  if (!(turn > 0)) {
    // Where r is monotone between them, dt/|dr| = 1 / (f sqrt(1 - q)), q = b^2 (r - 2M) / r^3,
    // which is greatest at r = 3M and least at an end. (Not where q nears 1, at a turning point,
    // whose rounding the relative 1e-12 would not cover.)
    const auto q = [&](double r) { return impact * impact * (r - 2 * m) / (r * r * r); };
    const double q_most = q(std::clamp(3 * m, std::min(r_a, r_b), std::max(r_a, r_b)));
    if (q_most < 1 - 1e-3)
      longest = std::min(longest, (radial + rounding) / std::sqrt(1 - q_most) * (1 + 1e-12));
    shortest = shortest / std::sqrt(1 - std::min(q(r_a), q(r_b))) * (1 - 1e-12);
  }
  return {a.early - longest, a.late - std::max(length(b_x - a_x), shortest)};
}

bool CurvedBodies::nearest(const PathStart& start, const CurvedPath& path, double from,
                           double limit, Found& best) const {
  // A ray straight through the hole's centre (b = 0) has no plane: nearest_on_axis meets it.
  if (bodies_.empty() || !(path.impact > 0) || !(limit > from)) return false;
  const double m = HoleView::mass;
  const PathEvents events(start, path);
  const Vec3 n = cross(path.e1, path.e2);
  // The smallest radius the path reaches: the start's or the periapsis for a ray outside the
  // photon sphere that turns or leaves, the horizon otherwise.
  const PhotonOrbit& orbit = path.orbit;
  const double floor = orbit.turning && start.radius >= orbit.periapsis
                           ? (path.outward ? start.radius : orbit.periapsis)
                           : 2 * m;
  const double horizon = 2 * m * (1 + 1e-12);
  // The light cone's bounds on the time of the path's point at phi (at x), from its start.
  const auto bounds_from_start = [&](double phi, const Vec3& x) {
    return light_cone_bounds({start.time, start.time}, path.offset(0, start.radius), x, phi,
                             events.turned(phi) ? events.course.turning_radius : 0.0, path.impact);
  };
  // The same where the path's radius at phi is not yet known (none before it where the path has
  // left for infinity or the horizon).
  const auto bounds_at = [&](double phi) {
    const double r = events.radius(phi);
    return r > horizon && std::isfinite(r) ? bounds_from_start(phi, path.offset(phi, r))
                                           : TimeBounds{-kInfinity, start.time};
  };
  double best_phi = limit;
  for (const Body& body : bodies_) {
    const ResolvedBody& resolved = scene_.bodies[body.index];
    const Windows windows = body_windows(body.line, body.radius, path, n, start);
    if (windows.count == 0) continue;
    const bool moving = !body.line.still();
    const double speed = moving ? body.line.max_coordinate_speed() : 0.0;
    // Chords within kChordError R of the path: its curvature is 3 M u^5 / (1/b^2 + 2 M u^3)^1.5,
    // so a chord over dphi strays at most (3/8) M b dphi^2 / r_min from it; and of the body's
    // path, which a chord over a coordinate time dt leaves by at most a dt^2 / 8.
    const double error = kChordError * body.radius;
    const double r_min = std::max(floor, windows.inner);
    const double step = m > 0 ? std::sqrt(8 * error * r_min / (3 * m * path.impact)) : kTwoPi;
    // Pieces of up to a span of many chords are tested whole, as one chord widened by how far
    // the path can stray from it (a quarter of the body's radius over a span).
    const double span = step * std::sqrt(0.25 / kChordError);
    const auto piece_margin = [&](double piece) {
      return m > 0 ? 0.375 * m * path.impact * piece * piece / r_min : 0.0;
    };
    const auto shape_of = [&](const Vec4& e, const HoleWorldLineState* state = nullptr) {
      return body.shape_point(scene_.world_maps[body.index], e, hole_, state);
    };
    // A moving body's chords are timed only once they come near where it is over the times
    // the light cone allows them.
    const bool straight = std::holds_alternative<HoleWorldLine::Straight>(body.line.path());
    const bool falling = std::holds_alternative<HoleWorldLine::Fall>(body.line.path());
    // The windows of this winding and the next, in order of angle: the first met is nearest.
    for (int winding = -1;; ++winding) {
      bool past = true, met = false;
      for (int w = 0; w < windows.count && !met; ++w) {
        double lo =
            windows.delta >= kPi ? 0.0 : windows.centre[w] - windows.delta + kTwoPi * winding;
        double hi =
            windows.delta >= kPi ? best_phi : windows.centre[w] + windows.delta + kTwoPi * winding;
        if (!(lo < best_phi)) continue;  // (a NaN window is past too)
        past = false;
        lo = std::max(lo, from), hi = std::min(hi, best_phi);
        if (!(lo < hi)) continue;
        // A fall's window narrowed to where its ball can be over the window's times: its origin
        // is between the radii its fall has between the light cone's bounds at the window's
        // ends, so every point of its ball is within asin(R / rho) of its line's direction seen
        // from the hole (rho the least of those radii, or the path's least radius where larger:
        // within acos(sqrt(1 - R^2 / rho^2) / p) of the direction's projection on the plane, p
        // its length), no nearer the hole than the least radius less R, nor farther than the
        // greatest plus R.
        double near = windows.near, reach = windows.reach;
        if (falling && windows.delta < kPi) {
          double lowest, highest;
          if (body.fall_radii_between(bounds_at(hi).early, bounds_at(lo).late, lowest, highest)) {
            near = std::max(near, lowest - body.radius);
            reach = std::min(reach, highest + body.radius);
            const double rho = std::max({2 * m, floor, lowest});
            const double least_cos = std::sqrt((1 - body.radius / rho) * (1 + body.radius / rho)) /
                                     windows.line_in_plane;
            if (!(least_cos < 1)) continue;
            const double delta = std::acos(least_cos),
                         centre = windows.centre[w] + kTwoPi * winding;
            lo = std::max(lo, centre - delta), hi = std::min(hi, centre + delta);
            if (!(lo < hi)) continue;
          }
        }
        double phi_a = lo, r_a;
        Vec4 a = events.event(phi_a, false, &r_a);
        bool a_timed = false;
        // Bounds on a's time, for a moving body: the light cone's from the path's start (timed
        // where a piece needs it), its time once a is timed.
        double a_early = 0, a_late = 0;
        if (moving) {
          const TimeBounds bounds = bounds_from_start(phi_a, a.x);
          a_early = bounds.early, a_late = bounds.late;
        }
        Vec3 shape_a;
        bool shape_known = false;
        // A geodesic body's state at a's time, once known.
        HoleWorldLineState state_a, state_b;
        bool a_state = false;
        // The piece tested next: halved where it may meet the body, down to a chord; doubled,
        // up to a span, past where it cannot.
        double piece = span;
        // The angle a chord sweeps: `step`, or less where the light's coordinate time over a
        // step exceeds what the body's motion allows (a ray near the line through the hole
        // sweeps little angle over a long time): the last chord's, doubled back toward `step`
        // where it took less than half that time.
        double chord = step;
        while (phi_a < hi && !met) {
          // Past the body's reach on the way out, or inside it on the way in with no turning
          // point ahead (toward the horizon): nothing more to meet.
          const bool turned = events.turned(phi_a);
          const bool growing = turned ? !path.outward : path.outward;
          const bool turn_ahead = events.course.turning_radius > 0 && !turned;
          if (growing && r_a > reach) break;
          if (!growing && !turn_ahead && r_a < near) break;
          if (!(r_a > horizon)) break;
          // A chord ends where the path still has a finite radius outside the horizon (the path
          // leaves for infinity, or reaches the horizon, at its total angle).
          const auto chord_end = [&](double end, double& r_end) {
            r_end = events.radius(end);
            for (int halving = 0; halving < 64 && !(r_end > horizon && std::isfinite(r_end));
                 ++halving)
              end = (phi_a + end) / 2, r_end = events.radius(end);
            return r_end > horizon && std::isfinite(r_end) ? end : phi_a;
          };
          // Whether the chord from a to b, widened by `margin`, may meet the body; if not, a
          // moves to b.
          double acceleration = 0;
          const auto may_meet = [&](double phi_b, double r_b, Vec4& b, double margin) {
            // b's time within the light cone's bounds from a's.
            double b_early = 0, b_late = 0;
            if (moving) {
              const bool turn_between = events.turned(phi_b) && !events.turned(phi_a);
              const TimeBounds bounds =
                  light_cone_bounds({a_early, a_late}, a.x, b.x, phi_b - phi_a,
                                    turn_between ? events.course.turning_radius : 0.0, path.impact);
              b_early = bounds.early, b_late = bounds.late;
            }
            bool b_timed = false, b_state = false;
            if (body.may_meet_in_space(a.x, b.x, margin) &&
                (!moving || body.may_meet_between(a.x, b.x, b_early, a_late, margin))) {
              // A piece whose ends' times are known within what moves the body by four times
              // its radius is halved on its bounds alone: its exact times would seldom tell
              // otherwise, and its halves' bounds are tighter (the least time of infall.json and
              // orbit.json at 480x270 among a quarter, 1, 4 and 16 radii, and no exact times).
              if (moving && margin > 0 &&
                  speed * std::max(a_late - a_early, b_late - b_early) <= 4 * body.radius)
                return true;
              if (moving) {
                if (!a_timed) a.t = events.time(phi_a, r_a), a_timed = true, a_early = a_late = a.t;
                b.t = events.time(phi_b, r_b), b_timed = true, b_early = b_late = b.t;
                // (Its bounds first, which spare a fall's solve where they suffice.)
                if (!body.may_meet_between(a.x, b.x, std::min(a.t, b.t), std::max(a.t, b.t),
                                           margin)) {
                  phi_a = phi_b, a = b, r_a = r_b, a_timed = true, shape_known = false;
                  a_early = a_late = b.t, a_state = false;
                  return false;
                }
                if (!straight) {
                  if (!a_state) state_a = body.state_at(a.t), a_state = true;
                  state_b = body.state_at(b.t), b_state = true;
                }
              }
              if (body.may_meet_in_time(a, b, state_a, state_b, margin, acceleration)) return true;
            }
            phi_a = phi_b, a = b, r_a = r_b, a_timed = b_timed, shape_known = false;
            a_early = b_early, a_late = b_late;
            state_a = state_b, a_state = b_state;
            return false;
          };
          if (piece > chord) {
            double r_c;
            const double phi_c = chord_end(std::min(phi_a + piece, hi), r_c);
            if (!(phi_c > phi_a)) break;
            Vec4 c = events.event(phi_c, false);
            piece = may_meet(phi_c, r_c, c, piece_margin(piece)) ? std::max(piece / 2, chord)
                                                                 : std::min(piece * 2, span);
            continue;
          }
          double r_b;
          double phi_b = chord_end(std::min(phi_a + chord, hi), r_b);
          if (!(phi_b > phi_a)) break;
          Vec4 b = events.event(phi_b, false);
          if (!may_meet(phi_b, r_b, b, 0)) {
            piece = std::min(2 * chord, span);
            continue;
          }
          const double max_dt = acceleration > 0 ? std::sqrt(8 * error / acceleration) : kInfinity;
          bool halved = false;
          for (int halving = 0; halving < 64 && !(std::abs(b.t - a.t) <= max_dt); ++halving) {
            phi_b = (phi_a + phi_b) / 2;
            b = events.event(phi_b, moving, &r_b);
            halved = true;
          }
          // No chord short enough in time (a path that cannot be resolved at this angle): give
          // up on this window rather than stand still.
          if (!(phi_b > phi_a)) break;
          if (halved) {
            chord = phi_b - phi_a;
          } else if (2 * std::abs(b.t - a.t) <= max_dt) {
            chord = std::min(2 * chord, step);
          }
          if (!straight && halved) state_b = body.state_at(b.t);
          if (!shape_known) shape_a = shape_of(a, straight ? nullptr : &state_a);
          const Vec3 shape_b = shape_of(b, straight ? nullptr : &state_b);
          shape_known = true;
          if (const auto chord = segments_.body_on_shape_segment(body.index, shape_a, shape_b)) {
            const Vec3 chord_point = shape_a + (shape_b - shape_a) * chord->s;
            const MetSurface surface = surface_met(*resolved.object, chord_point, chord->prim);
            // The surface met, on the true path: its side at phi, solved between the chord's
            // end outside and a point past the surface.
            const auto side = [&](double phi) {
              return surface.at(shape_of(events.event(phi, moving)));
            };
            const double side_a = surface.at(shape_a);
            // The path's angle at the chord's point (the angle does not grow linearly along
            // a chord: a long chord, far from a light hole, would miss the body there).
            const Vec3 chord_at = a.x + (b.x - a.x) * chord->s;
            double phi_c = std::atan2(dot(chord_at, path.e2), dot(chord_at, path.e1));
            phi_c += kTwoPi * std::round((0.5 * (phi_a + phi_b) - phi_c) / kTwoPi);
            phi_c = std::clamp(phi_c, phi_a, phi_b);
            double phi = phi_c;
            double other = phi_b, side_other = surface.at(shape_b);
            if ((side_other < 0) == (side_a < 0)) other = phi_c, side_other = side(phi_c);
            if ((side_other < 0) != (side_a < 0) && side_a != 0) {
              std::uintmax_t iterations = 100;
              const auto [x0, x1] = boost::math::tools::toms748_solve(
                  side, phi_a, other, side_a, side_other,
                  boost::math::tools::eps_tolerance<double>(), iterations, MathPolicy());
              phi = (x0 + x1) / 2;
            }
            // else: a grazing hit, within the chord error of the path; the chord's point stands.
            if (phi < best_phi) {
              best_phi = phi;
              best.body = body.index;
              best.phi = phi;
              best.event = events.event(phi, true);
              best.shape_point = shape_of(best.event);
              best.incoming = shape_b - shape_a;
              best.prim = chord->prim;
              best.turned = events.turned(phi);
            }
            met = true;
          }
          phi_a = phi_b, a = b, r_a = r_b, a_timed = moving, shape_a = shape_b;
          a_early = a_late = b.t;
          state_a = state_b, a_state = moving && !straight;
        }
      }
      if (met || past || windows.delta >= kPi) break;
    }
  }
  return best.body >= 0;
}

bool CurvedBodies::first_hit(const HoleView& hole, const CurvedPath& path, double limit,
                             CurvedRay& ray) const {
  const PathStart start{hole.camera_radius, scene_.observation_event.t / hole.scale};
  Found best;
  const double end = path.outward ? std::numeric_limits<double>::infinity() : 2 * hole.mass;
  const bool met = path.impact > 0 ? nearest(start, path, 0, limit, best)
                                   : nearest_on_axis(start, path, start.radius, end, best);
  if (!met) return false;
  const double m = hole.mass;
  const Body& body = bodies_[best.body];
  ray.end = CurvedRayEnd::kBody;
  ray.phi = best.phi;
  ray.event = in_world(hole, best.event);
  ray.hit = Hit{};
  ray.hit.body = best.body;
  ray.hit.s = best.phi;
  ray.hit.shape_point = best.shape_point;
  complete_surface_hit(scene_, best.incoming, ray.hit, best.prim);
  // The body's clock (its origin's) and velocity when it emitted.
  const HoleWorldLineState state = body.state_at(best.event.t);
  ray.hit.velocity = state.velocity;
  ray.hit.proper_time = state.proper_time * hole.scale;
  // The shift: the energy the point measures for the photon, against the camera's. In the
  // static observer's frame at the point (radial axis rhat, W's axes), the photon has energy
  // 1 / sqrt(f) and travels along nhat (opposite to the backward ray), and the point moves with
  // the velocity w its origin has against the static observer there (a body's points share
  // it: docs/design/black-hole.md, "Bodies"): it measures gamma_w (1 - nhat . w) / sqrt(f).
  const Vec3& x = best.event.x;
  const double r = length(x), f = 1 - 2 * m / r;
  const Vec3 rhat = x / r;
  const Vec3 that = cross(cross(path.e1, path.e2), rhat);  // the direction of growing phi
  const double b = path.impact;
  const bool out = best.turned ? !path.outward : path.outward;
  const double radial = std::sqrt(std::max(0.0, 1 - b * b * f / (r * r)));
  const Vec3 nhat = (rhat * ((out ? 1 : -1) * radial) + that * (b * std::sqrt(f) / r)) * -1.0;
  const Vec3& w = state.local_velocity;
  const double emitted = lorentz_gamma(w) * (1 - dot(nhat, w)) / std::sqrt(f);
  ray.shift = path.camera_energy / emitted;
  ray.to_camera = nhat;
  ray.local_velocity = w;
  return true;
}

bool CurvedBodies::occluded(const CurvedShadowRay& shadow) const {
  const double m = hole_.mass;
  const PathStart start{length((shadow.origin.x - hole_.centre) / hole_.scale),
                        shadow.origin.t / hole_.scale};
  CurvedPath path;
  path.e1 = shadow.e1;
  path.e2 = shadow.e2;
  path.impact = shadow.impact;
  path.outward = shadow.outward;
  path.orbit = photon_orbit(m, shadow.impact);
  path.sweep = prepare_sweep(path.orbit, start.radius, shadow.outward);
  Found found;
  if (!(shadow.impact > 0))
    return nearest_on_axis(start, path, shadow.radius_near, shadow.radius_far, found);
  return nearest(start, path, shadow.sweep_near, shadow.sweep_far, found);
}

namespace {

// The query and the segments it meets bodies through, owned together.
class OwningCurvedShadows final : public CurvedShadowQuery {
 public:
  OwningCurvedShadows(const ResolvedScene& scene, std::unique_ptr<const BodySegments> segments)
      : segments_(std::move(segments)), bodies_(scene, *segments_) {}
  bool occluded(const CurvedShadowRay& ray) const override { return bodies_.occluded(ray); }

 private:
  std::unique_ptr<const BodySegments> segments_;
  CurvedBodies bodies_;
};

}  // namespace

std::unique_ptr<CurvedShadowQuery> curved_body_shadows_met_by(
    const ResolvedScene& scene, std::unique_ptr<const BodySegments> segments) {
  if (!scene.hole || scene.bodies.empty()) return nullptr;
  return std::make_unique<OwningCurvedShadows>(scene, std::move(segments));
}

}  // namespace lightcone

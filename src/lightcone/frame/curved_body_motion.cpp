// A body's motion near a black hole as the curved rays' walk tests it (curved_bodies.hpp): its
// world line prepared (a fall's sampled times, a falling box's prism), whether a chord or a piece
// of a path can come near where it is over the times given, and its state and shape coordinates at
// a time. The walk along each ray, and its hits, are curved_bodies.cpp's.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/physics/accretion_disk.hpp"
#include "lightcone/physics/lorentz.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The distance between segments [a0, a1] and [b0, b1]: their closest points, each clamped to
// its segment in turn (Ericson, "Real-Time Collision Detection", 2005, section 5.1.9).
double segment_distance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  const Vec3 da = a1 - a0, db = b1 - b0, r = a0 - b0;
  const double aa = dot(da, da), bb = dot(db, db), f = dot(db, r);
  double s = 0, t = 0;
  if (aa <= 0) {
    t = bb > 0 ? std::clamp(f / bb, 0.0, 1.0) : 0.0;
  } else {
    const double c = dot(da, r);
    if (bb <= 0) {
      s = std::clamp(-c / aa, 0.0, 1.0);
    } else {
      const double ab = dot(da, db), denominator = aa * bb - ab * ab;
      s = denominator > 0 ? std::clamp((ab * f - c * bb) / denominator, 0.0, 1.0) : 0.0;
      t = (ab * s + f) / bb;
      if (t < 0) {
        t = 0, s = std::clamp(-c / aa, 0.0, 1.0);
      } else if (t > 1) {
        t = 1, s = std::clamp((ab - c) / aa, 0.0, 1.0);
      }
    }
  }
  return length(a0 + da * s - (b0 + db * t));
}

// A fall's radius at kFallSamples coordinate times, from its start (r0, or 10^6 M from
// infinity) to within 10^-7 of the horizon's distance, evenly in ln(r - 2M).
constexpr int kFallSamples = 1024;
void tabulate_fall(const RadialFall& fall, std::vector<double>& times, std::vector<double>& radii) {
  const double m = fall.mass();
  const double top = fall.is_from_infinity() ? 1e6 * m : fall.at_proper_time(0).radius;
  for (int k = 0; k < kFallSamples; ++k) {
    const double r =
        2 * m + (top - 2 * m) * std::pow(1e-7, static_cast<double>(k) / (kFallSamples - 1));
    const double t = fall.at_radius(r).coordinate_time;
    if (!times.empty() && !(t > times.back())) continue;
    times.push_back(t);
    radii.push_back(r);
  }
}

// A falling box's or mesh's prism along its line of fall (the unit d): its box's corners (its
// shape's bounds), in W's axes and units of the hole's mass m, seen across d (their convex hull,
// counter-clockwise, by Andrew's monotone chain) and along it (their extent and the origin).
// Contraction along d moves its points toward the origin along d alone, within the prism.
void outline_prism(const Object& o, const Vec3& d, double m,
                   std::vector<std::array<double, 2>>& outline, Vec3& across_x, Vec3& across_y,
                   double& along_lo, double& along_hi, Vec3& lower, Vec3& upper) {
  if (const auto* box = std::get_if<Box>(&o.shape)) {
    upper = box->size * 0.5, lower = upper * -1.0;
  } else if (const auto* mesh = std::get_if<MeshShape>(&o.shape)) {
    if (mesh->mesh->positions.empty()) return;
    lower = upper = mesh->mesh->positions.front();
    for (const Vec3& p : mesh->mesh->positions)
      for (int k = 0; k < 3; ++k)
        lower[k] = std::min(lower[k], p[k]), upper[k] = std::max(upper[k], p[k]);
  } else {
    return;  // a sphere's ball is its shape, whatever its contraction
  }
  across_x = any_perpendicular(d);
  across_y = cross(d, across_x);
  const Mat3 to_world = o.rotation * Mat3::diagonal(o.scale);
  std::vector<std::array<double, 2>> points;
  along_lo = along_hi = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 c{corner & 1 ? upper.x : lower.x, corner & 2 ? upper.y : lower.y,
                 corner & 4 ? upper.z : lower.z};
    const Vec3 w = to_world * c / m;
    points.push_back({dot(w, across_x), dot(w, across_y)});
    along_lo = std::min(along_lo, dot(w, d)), along_hi = std::max(along_hi, dot(w, d));
  }
  std::sort(points.begin(), points.end());
  const auto turn = [](const auto& o, const auto& a, const auto& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::vector<std::array<double, 2>> hull(2 * points.size());
  std::size_t k = 0;
  for (const auto& p : points) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  // A degenerate outline (a flat box seen edge-on across the line) is no polygon: keep the ball.
  if (hull.size() >= 3) outline = std::move(hull);
}
}  // namespace

CurvedBodies::CurvedBodies(const ResolvedScene& scene, const BodySegments& segments)
    : scene_(scene), hole_(*scene.hole), segments_(segments) {
  const double m = hole_.scale;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Object& o = *scene.bodies[i].object;
    // (R S)^-1 M, not (R S / M)^-1, whose determinant (M^-3) is no double for M far from 1.
    bodies_.push_back({static_cast<int>(i),
                       hole_world_line(hole_, o),
                       origin_radius(o.shape, o.scale) / m * (1 + 1e-9),
                       (o.rotation * Mat3::diagonal(o.scale)).inverse() * Mat3::diagonal({m, m, m}),
                       {},
                       {},
                       {},
                       {},
                       {},
                       0,
                       0,
                       {},
                       {}});
    Body& body = bodies_.back();
    if (const auto* fall = std::get_if<HoleWorldLine::Fall>(&body.line.path())) {
      tabulate_fall(fall->fall, body.fall_times, body.fall_radii);
      outline_prism(o, fall->direction, m, body.outline, body.across_x, body.across_y,
                    body.along_lo, body.along_hi, body.shape_lower, body.shape_upper);
    }
  }
}

bool CurvedBodies::Body::may_meet_in_space(const Vec3& a, const Vec3& b, double margin) const {
  const double reach = radius + margin;  // radius holds its rounding margin already
  if (const auto* orbit = std::get_if<HoleWorldLine::Orbit>(&line.path())) {
    // Both ends on one side of the orbit's plane, beyond the body's radius.
    const Vec3 normal = cross(orbit->axis_x, orbit->axis_y);
    const double ha = dot(a, normal), hb = dot(b, normal);
    return !(std::min(ha, hb) > reach || std::max(ha, hb) < -reach);
  }
  if (const auto* fall = std::get_if<HoleWorldLine::Fall>(&line.path())) {
    // The segment's nearest approach to the line of fall (through the hole).
    const Vec3& d = fall->direction;
    return segment_distance(a - d * dot(a, d), b - d * dot(b, d), {}, {}) <= reach;
  }
  // At rest: the ball itself (a moving line is tested once its chord is timed).
  if (line.still()) {
    const Vec3& p = std::get<HoleWorldLine::Straight>(line.path()).position;
    return segment_distance(a, b, p, p) <= reach;
  }
  return true;
}

bool CurvedBodies::Body::may_meet_in_time(const Vec4& a, const Vec4& b,
                                          const HoleWorldLineState& state_a,
                                          const HoleWorldLineState& state_b, double margin,
                                          double& acceleration) const {
  acceleration = 0;
  if (const auto* straight = std::get_if<HoleWorldLine::Straight>(&line.path())) {
    if (line.still()) return true;  // (tested in space)
    // The segment its origin moves along between the chord's times.
    const auto at = [&](double t) {
      return straight->position + straight->velocity * (t - straight->time);
    };
    return segment_distance(a.x, b.x, at(a.t), at(b.t)) <= radius + margin;
  }
  // Over the chord's times the body's origin stays within `bow` of the segment between where
  // it is at their ends: on its line of fall, or within the sagitta of its orbit's arc.
  const double t0 = std::min(a.t, b.t), t1 = std::max(a.t, b.t);
  const HoleWorldLineState& s0 = a.t <= b.t ? state_a : state_b;
  const HoleWorldLineState& s1 = a.t <= b.t ? state_b : state_a;
  double bow = 0;
  if (const auto* orbit = std::get_if<HoleWorldLine::Orbit>(&line.path())) {
    const double swept = circular_orbit_angular_velocity(line.mass(), orbit->radius) * (t1 - t0);
    bow = swept < kPi ? orbit->radius * (1 - std::cos(swept / 2)) : kInfinity;
    acceleration = line.mass() / (orbit->radius * orbit->radius);
  } else {
    // A fall's d^2r/dt^2 = f f' (s^2 - f/2) / E^2, with s^2 = E^2 - f and f, s^2 in [0, E^2],
    // is at most f' = 2M / r^2, its radius least at the later time.
    const double r = length(s1.position);
    acceleration = 2 * line.mass() / (r * r);
  }
  return segment_distance(a.x, b.x, s0.position, s1.position) <= radius + margin + bow;
}

bool CurvedBodies::Body::may_meet_between(const Vec3& a, const Vec3& b, double t0, double t1,
                                          double margin) const {
  if (!(t0 <= t1 && std::isfinite(t0) && std::isfinite(t1))) return true;  // (no bound)
  const double reach = radius + margin;
  if (const auto* straight = std::get_if<HoleWorldLine::Straight>(&line.path())) {
    const auto at = [&](double t) {
      return straight->position + straight->velocity * (t - straight->time);
    };
    return segment_distance(a, b, at(t0), at(t1)) <= reach;
  }
  if (const auto* orbit = std::get_if<HoleWorldLine::Orbit>(&line.path())) {
    // The arc it sweeps lies within its sagitta of its chord.
    const double omega = circular_orbit_angular_velocity(line.mass(), orbit->radius);
    const double swept = omega * (t1 - t0);
    if (!(swept < kPi)) return true;
    const auto at = [&](double t) {
      const double phi = orbit->phase + omega * t;
      return (orbit->axis_x * std::cos(phi) + orbit->axis_y * std::sin(phi)) * orbit->radius;
    };
    const double bow = orbit->radius * (1 - std::cos(swept / 2));
    return segment_distance(a, b, at(t0), at(t1)) <= reach + bow;
  }
  const auto& fall = std::get<HoleWorldLine::Fall>(line.path());
  double lowest, highest;
  if (!fall_radii_between(t0, t1, lowest, highest)) return true;
  if (!outline.empty())
    return prism_near(a, b, lowest, highest, margin + 1e-9 * radius) &&
           swept_box_near(a, b, lowest, highest, margin);
  return segment_distance(a, b, fall.direction * lowest, fall.direction * highest) <= reach;
}

bool CurvedBodies::Body::fall_radii_between(double t0, double t1, double& lowest,
                                            double& highest) const {
  // A fall's radius does not grow with time: over [t0, t1] it lies between its radii at the
  // sampled times just after t1 and just before t0 (the horizon's after the last, the start's,
  // or none from infinity, before the first).
  const auto& fall = std::get<HoleWorldLine::Fall>(line.path());
  const double u0 = t0 - fall.time, u1 = t1 - fall.time;
  const auto first_after = [&](double u) {
    return std::upper_bound(fall_times.begin(), fall_times.end(), u) - fall_times.begin();
  };
  const auto k1 = static_cast<std::size_t>(first_after(u1)),
             k0 = static_cast<std::size_t>(first_after(u0));
  lowest = k1 < fall_times.size() ? fall_radii[k1] : 2 * line.mass();
  if (k0 == 0 && fall.fall.is_from_infinity()) return false;
  highest = k0 == 0 ? fall_radii.front() : fall_radii[k0 - 1];
  return true;
}

bool CurvedBodies::Body::prism_near(const Vec3& a, const Vec3& b, double lowest, double highest,
                                    double margin) const {
  const Vec3& d = std::get<HoleWorldLine::Fall>(line.path()).direction;
  // The segment's part within the prism's extent along the line, widened by the margin.
  const double za = dot(a, d), zb = dot(b, d);
  const double lo = lowest + along_lo - margin, hi = highest + along_hi + margin;
  double s0 = 0, s1 = 1;
  if (za != zb) {
    const double u = (lo - za) / (zb - za), v = (hi - za) / (zb - za);
    s0 = std::max(s0, std::min(u, v)), s1 = std::min(s1, std::max(u, v));
  } else if (za < lo || za > hi) {
    return false;
  }
  if (!(s0 <= s1)) return false;
  // Across the line: that part against the outline (a convex polygon, counter-clockwise).
  const auto across = [&](double s) {
    const Vec3 p = a + (b - a) * s;
    return Vec3{dot(p, across_x), dot(p, across_y), 0};
  };
  const Vec3 p0 = across(s0), p1 = across(s1);
  const auto inside = [&](const Vec3& p) {
    for (std::size_t i = 0; i < outline.size(); ++i) {
      const auto& e0 = outline[i];
      const auto& e1 = outline[(i + 1) % outline.size()];
      if ((e1[0] - e0[0]) * (p.y - e0[1]) - (e1[1] - e0[1]) * (p.x - e0[0]) < 0) return false;
    }
    return true;
  };
  if (inside(p0) || inside(p1)) return true;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const auto& e0 = outline[i];
    const auto& e1 = outline[(i + 1) % outline.size()];
    if (segment_distance(p0, p1, {e0[0], e0[1], 0}, {e1[0], e1[1], 0}) <= margin) return true;
  }
  return false;
}

bool CurvedBodies::Body::swept_box_near(const Vec3& a, const Vec3& b, double lowest, double highest,
                                        double margin) const {
  const auto& fall = std::get<HoleWorldLine::Fall>(line.path());
  const Vec3& d = fall.direction;
  const double m = line.mass(), e = fall.fall.energy();
  // Its coordinate speed f sqrt(E^2 - f) / E over those radii (f increasing with r): least at an
  // end, greatest at f = 2E^2 / 3 or the end nearest it; its contraction 1 / gamma of that.
  const auto speed = [&](double f) { return f * std::sqrt(std::max(0.0, e * e - f)) / e; };
  const double f_lo = 1 - 2 * m / lowest, f_hi = 1 - 2 * m / highest;
  const double slowest = std::min(speed(f_lo), speed(f_hi));
  const double fastest = speed(std::clamp(2 * e * e / 3, f_lo, f_hi));
  const double gamma_lo = 1 / std::sqrt(1 - slowest * slowest),
               gamma_hi = 1 / std::sqrt(1 - fastest * fastest);
  // A point p, its origin at z d and its contraction 1 / gamma, has the shape coordinates
  // to_shape (p - (d . p) d + lambda d), lambda = gamma (d . p - z): along the segment
  // (p = a + s (b - a)) lambda is bilinear in gamma and in (s, z), so it lies between its values
  // at the corners of s in [0, 1], z in [lowest, highest], gamma in [gamma_lo, gamma_hi].
  const double za = dot(a, d), zb = dot(b, d);
  double least = kInfinity, most = -kInfinity;
  for (const double z_p : {za, zb})
    for (const double z : {lowest, highest})
      for (const double gamma : {gamma_lo, gamma_hi}) {
        least = std::min(least, gamma * (z_p - z));
        most = std::max(most, gamma * (z_p - z));
      }
  const Vec3 along = to_shape * d;
  const Vec3 origin = to_shape * (a - d * za) + along * least;
  const Vec3 e1 = to_shape * ((b - d * zb) - (a - d * za)), e2 = along * (most - least);
  // The margin in shape coordinates: at most stretched by gamma and by to_shape's norm (at most
  // the sum of its entries' sizes, which no square underflows for a hole far lighter than its
  // bodies); and its rounding, as the ball's.
  double norm = 0;
  for (const auto& row : to_shape.m)
    for (const double x : row) norm += std::abs(x);
  const Vec3 size = shape_upper - shape_lower;
  const double widen = margin * gamma_hi * norm + 1e-9 * length(size);
  const Vec3 centre = (shape_lower + shape_upper) * 0.5 - (origin + (e1 + e2) * 0.5);
  const Vec3 half = size * 0.5 + Vec3{widen, widen, widen};
  // Separating axes of a parallelogram and a box: the box's axes, the parallelogram's normal,
  // and each box axis across each of its edges.
  const auto separates = [&](const Vec3& axis) {
    const double reach = 0.5 * (std::abs(dot(axis, e1)) + std::abs(dot(axis, e2))) +
                         std::abs(axis.x) * half.x + std::abs(axis.y) * half.y +
                         std::abs(axis.z) * half.z;
    return std::abs(dot(axis, centre)) > reach;
  };
  const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  if (separates(cross(e1, e2))) return false;
  for (const Vec3& axis : axes)
    if (separates(axis) || separates(cross(axis, e1)) || separates(cross(axis, e2))) return false;
  return true;
}

HoleWorldLineState CurvedBodies::Body::state_at(double t) const {
  const auto* fall = std::get_if<HoleWorldLine::Fall>(&line.path());
  if (!fall) return line.at(t);
  // Between the sampled times about t, its radius is the root of t(r) - t, t(r) in closed form
  // and decreasing: bracketed by their radii, found by Newton's method on t(r). Before the first
  // (held at r0, or from farther than the samples) and after the last, the world-line's own
  // solve.
  const double u = t - fall->time;
  const auto k = static_cast<std::size_t>(
      std::upper_bound(fall_times.begin(), fall_times.end(), u) - fall_times.begin());
  if (k == 0 || k == fall_times.size()) return line.at(t);
  const RadialFall& radial = fall->fall;
  const RadialFallPoint p = radial.at_coordinate_time_between(u, fall_radii[k], fall_times[k],
                                                              fall_radii[k - 1], fall_times[k - 1]);
  const double r = p.radius;
  const double f = 1 - 2 * line.mass() / r;
  const Vec3& d = fall->direction;
  return {d * r, d * (f * p.local_velocity), d * p.local_velocity, radial.proper_time_at_radius(r)};
}

Vec3 CurvedBodies::Body::shape_point(const WorldShapeMap& world, const Vec4& event,
                                     const HoleView& hole, const HoleWorldLineState* known) const {
  if (std::holds_alternative<HoleWorldLine::Straight>(line.path()))
    return world.shape_point(in_world(hole, event));
  // Its rest frame's coordinates of a point simultaneous in W with its origin at offset d:
  // d stretched by gamma along its velocity.
  const HoleWorldLineState state = known ? *known : state_at(event.t);
  return to_shape * rest_offset_of(event.x - state.position, state.velocity);
}

}  // namespace lightcone

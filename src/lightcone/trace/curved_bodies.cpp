#include "lightcone/trace/curved_bodies.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "lightcone/physics/lorentz.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2 * std::numbers::pi;

// The events of one ray's path, in W: after sweeping phi it is at the hole's centre plus
// path.offset(phi, r(phi)), at the camera's time less the coordinate time the light took.
struct PathEvents {
  const HoleView& hole;
  const CurvedPath& path;
  double camera_time;
  RayCourse course;

  PathEvents(const HoleView& h, const CurvedPath& p, double t)
      : hole(h), path(p), camera_time(t), course(ray_course(p.orbit, h.camera_radius, p.outward)) {}

  bool turned(double phi) const { return course.turning_radius > 0 && phi > course.angle_to_turn; }
  double radius(double phi) const { return radius_after_angle(path.sweep, phi); }
  // The coordinate time from the point at phi (radius r) to the camera, on the stretches between.
  double delay(double phi, double r) const {
    const double r0 = hole.camera_radius;
    if (!turned(phi)) return coordinate_time(path.orbit, r0, r);
    const double turn = course.turning_radius;
    return coordinate_time(path.orbit, r0, turn) + coordinate_time(path.orbit, turn, r);
  }
  // The event at phi; its time only when `timed` (a body at rest needs none to be met).
  Vec4 event(double phi, bool timed, double* r_out = nullptr) const {
    const double r = radius(phi);
    if (r_out) *r_out = r;
    return {timed ? camera_time - delay(phi, r) : 0.0, hole.centre + path.offset(phi, r)};
  }
};

// The surface a chord met, as a function whose sign tells the side of it a shape point is on.
struct MetSurface {
  enum class Kind { kSphere, kPlane } kind = Kind::kPlane;
  double radius = 0;  // kSphere
  Vec3 normal;        // kPlane: normal . p = offset
  double offset = 0;
  double at(const Vec3& p) const {
    return kind == Kind::kSphere ? dot(p, p) - radius * radius : dot(normal, p) - offset;
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

}  // namespace

CurvedBodies::CurvedBodies(const ResolvedScene& scene, const Tracer& tracer)
    : scene_(scene), tracer_(tracer) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Object& o = *scene.bodies[i].object;
    Body b;
    b.index = static_cast<int>(i);
    b.position = o.world_line.position - scene.hole->centre;
    b.velocity = o.world_line.velocity;
    b.time = o.world_line.time;
    b.proper_time = o.world_line.proper_time;
    b.radius = origin_radius(o.shape, o.scale) * (1 + 1e-9);
    bodies_.push_back(b);
  }
}

bool CurvedBodies::first_hit(const HoleView& hole, const CurvedPath& path, double limit,
                             CurvedRay& ray) const {
  // A ray straight through the hole's centre (b = 0) has no plane; it does not see bodies.
  if (bodies_.empty() || !(path.impact > 0) || !(limit > 0)) return false;
  const double m = hole.mass;
  const PathEvents events(hole, path, scene_.observation_event.t);
  const Vec3 n = cross(path.e1, path.e2);
  // The smallest radius the path reaches: the camera's or the periapsis for a ray outside the
  // photon sphere that turns or leaves, the horizon otherwise.
  const PhotonOrbit& orbit = path.orbit;
  const double floor = orbit.turning && hole.camera_radius >= orbit.periapsis
                           ? (path.outward ? hole.camera_radius : orbit.periapsis)
                           : 2 * m;
  const double horizon = 2 * m * (1 + 1e-12);
  struct Found {
    int body = -1;
    double phi = 0;
    Vec4 event;
    Vec3 shape_point, incoming;
    unsigned prim = 0;
  } best;
  double best_phi = limit;
  for (const Body& body : bodies_) {
    const bool moving = body.velocity.x != 0 || body.velocity.y != 0 || body.velocity.z != 0;
    // Where the body's ball (or the tube it sweeps) cuts the ray's plane: a disc about cp of
    // radius rho, which the ray can reach only within delta of its angle about the hole.
    Vec3 cp = body.position;
    double rho = body.radius;
    bool everywhere = false;
    if (!moving) {
      const double h = dot(body.position, n);
      if (std::abs(h) >= body.radius) continue;
      cp = body.position - n * h;
      rho = std::sqrt(body.radius * body.radius - h * h);
    } else {
      const double vn = dot(body.velocity, n), speed = length(body.velocity);
      if (std::abs(vn) <= 1e-9 * speed) {
        if (std::abs(dot(body.position, n)) >= body.radius) continue;
        everywhere = true;
      } else {
        cp = body.position - body.velocity * (dot(body.position, n) / vn);
        rho = body.radius * speed / std::abs(vn);
      }
    }
    // How far out the ray can meet the body: its ball's disc for a body at rest; for a moving
    // one, the radius past which the body, within |p| + v T of the hole after the light's delay
    // T, cannot keep up with a ray that has gone out to r >= T - r0 - 4M ln(1 + r/2M) - 8M
    // (coordinate light speed at most 1, and the Shapiro delay's bound).
    double reach = length(cp) + rho;
    if (moving) {
      const double v = length(body.velocity);
      const double now =
          length(body.position + body.velocity * (scene_.observation_event.t - body.time)) +
          body.radius;
      const auto beyond = [&](double r) {
        return (1 - v) * r - v * (hole.camera_radius + 4 * m * std::log1p(r / (2 * m)) + 8 * m) >
               now;
      };
      reach = std::max(now, hole.camera_radius);
      while (!beyond(reach)) reach *= 2;
    }
    const double d = length(cp);
    const double centre = std::atan2(dot(cp, path.e2), dot(cp, path.e1));
    const double delta = everywhere || d <= rho ? kPi : std::asin(rho / d);
    const double r_min = everywhere ? floor : std::max(floor, d - rho);
    // How far in the ray can meet the body (its line's closest approach for a moving one).
    double near = std::max(d - rho, 2 * m);
    if (moving) {
      const double vv = dot(body.velocity, body.velocity);
      const Vec3 closest = body.position - body.velocity * (dot(body.position, body.velocity) / vv);
      near = std::max(length(closest) - body.radius, 2 * m);
    }
    // Chords within kChordError R of the path: its curvature is 3 M u^5 / (1/b^2 + 2 M u^3)^1.5,
    // so a chord over dphi strays at most (3/8) M b dphi^2 / r_min from it.
    const double error = kChordError * body.radius;
    const double step = m > 0 ? std::sqrt(8 * error * r_min / (3 * m * path.impact)) : kTwoPi;
    for (int winding = -1;; ++winding) {
      double lo = delta >= kPi ? 0.0 : centre - delta + kTwoPi * winding;
      double hi = delta >= kPi ? best_phi : centre + delta + kTwoPi * winding;
      if (lo >= best_phi) break;
      lo = std::max(lo, 0.0), hi = std::min(hi, best_phi);
      if (!(lo < hi)) continue;
      bool met = false;
      double phi_a = lo, r_a;
      Vec4 a = events.event(phi_a, moving, &r_a);
      while (phi_a < hi && !met) {
        // Past the body's reach on the way out, or inside it on the way in with no turning point
        // ahead (toward the horizon): nothing more to meet.
        const bool turned = events.turned(phi_a);
        const bool growing = turned ? !path.outward : path.outward;
        const bool turn_ahead = events.course.turning_radius > 0 && !turned;
        if (growing && r_a > reach) break;
        if (!growing && !turn_ahead && r_a < near) break;
        if (!(r_a > horizon)) break;
        // A chord ends where the path still has a finite radius outside the horizon (the path
        // leaves for infinity, or reaches the horizon, at its total angle).
        double phi_b = std::min(phi_a + step, hi), r_b = events.radius(phi_b);
        for (int halving = 0; halving < 64 && !(r_b > horizon && std::isfinite(r_b)); ++halving)
          phi_b = (phi_a + phi_b) / 2, r_b = events.radius(phi_b);
        if (!(r_b > horizon && std::isfinite(r_b))) break;
        const Vec4 b = events.event(phi_b, moving);
        if (const auto chord = tracer_.body_on_world_segment(body.index, a, b)) {
          const ResolvedBody& resolved = scene_.bodies[body.index];
          const Vec4 on_chord = a + chord->s * (b - a);
          const Vec3 chord_point = resolved.shadow_shape_point(on_chord);
          const MetSurface surface = surface_met(*resolved.object, chord_point, chord->prim);
          // The surface met, on the true path: its side at phi, solved between the chord's end
          // outside and a point past the surface.
          const auto side = [&](double phi) {
            return surface.at(resolved.shadow_shape_point(events.event(phi, moving)));
          };
          const double side_a = side(phi_a);
          const double phi_c = phi_a + chord->s * (phi_b - phi_a);
          double phi = phi_c;
          double other = phi_b, side_other = side(phi_b);
          if ((side_other < 0) == (side_a < 0)) other = phi_c, side_other = side(phi_c);
          if ((side_other < 0) != (side_a < 0) && side_a != 0) {
            std::uintmax_t iterations = 100;
            const auto [x0, x1] = boost::math::tools::toms748_solve(
                side, phi_a, other, side_a, side_other, boost::math::tools::eps_tolerance<double>(),
                iterations);
            phi = (x0 + x1) / 2;
          }
          // else: a grazing hit, within the chord error of the path; the chord's point stands.
          if (phi < best_phi) {
            best_phi = phi;
            best.body = body.index;
            best.phi = phi;
            best.event = events.event(phi, true);
            best.shape_point = resolved.shadow_shape_point(best.event);
            best.incoming = resolved.shadow_shape_vector(b - a);
            best.prim = chord->prim;
          }
          met = true;
        }
        phi_a = phi_b, a = b, r_a = r_b;
      }
      if (met || delta >= kPi) break;
    }
  }
  if (best.body < 0) return false;

  const Body& body = bodies_[best.body];
  ray.end = CurvedRayEnd::kBody;
  ray.phi = best.phi;
  ray.event = best.event;
  ray.hit = Hit{};
  ray.hit.body = best.body;
  ray.hit.s = best.phi;
  ray.hit.shape_point = best.shape_point;
  tracer_.surface_at(best.incoming, ray.hit, best.prim);
  ray.hit.velocity = body.velocity;
  // The body's clock (its origin's): the integral of sqrt(f - v_r^2 / f - v_t^2) dt along its
  // coordinate line, from its own event.
  const auto rate = [&](double t) {
    const Vec3 x = body.position + body.velocity * (t - body.time);
    const double r = length(x), f = 1 - 2 * m / r;
    const double v_r = dot(body.velocity, x) / r;
    const double v_t2 = std::max(0.0, dot(body.velocity, body.velocity) - v_r * v_r);
    return std::sqrt(std::max(0.0, f - v_r * v_r / f - v_t2));
  };
  const double t = best.event.t;
  const auto integral = [&](double from, double to) {
    return boost::math::quadrature::gauss_kronrod<double, 21>::integrate(rate, from, to, 12, 1e-13);
  };
  const bool still = body.velocity.x == 0 && body.velocity.y == 0 && body.velocity.z == 0;
  ray.hit.proper_time = body.proper_time + (still            ? rate(body.time) * (t - body.time)
                                            : t >= body.time ? integral(body.time, t)
                                                             : -integral(t, body.time));
  // The shift: the energy the point measures for the photon, against the camera's. In the
  // static observer's frame at the point (radial axis rhat, W's axes), the photon has energy
  // 1 / sqrt(f) and travels along nhat (opposite to the backward ray), and the point moves with
  // w = (v_r / f, v_t / sqrt(f)): it measures gamma_w (1 - nhat . w) / sqrt(f).
  const Vec3 x = best.event.x - hole.centre;
  const double r = length(x), f = 1 - 2 * m / r;
  const Vec3 rhat = x / r;
  const Vec3 that = cross(n, rhat);  // the direction of growing phi
  const double b = path.impact;
  const bool out = events.turned(best.phi) ? !path.outward : path.outward;
  const double radial = std::sqrt(std::max(0.0, 1 - b * b * f / (r * r)));
  const Vec3 nhat = (rhat * ((out ? 1 : -1) * radial) + that * (b * std::sqrt(f) / r)) * -1.0;
  const double v_r = dot(body.velocity, rhat);
  const Vec3 w = rhat * (v_r / f) + (body.velocity - rhat * v_r) / std::sqrt(f);
  const double emitted = lorentz_gamma(w) * (1 - dot(nhat, w)) / std::sqrt(f);
  ray.shift = path.camera_energy / emitted;
  return true;
}

}  // namespace lightcone

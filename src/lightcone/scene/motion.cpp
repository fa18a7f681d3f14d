#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "lightcone/physics/keyframe_world_line.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/schwarzschild_geodesics.hpp"
#include "lightcone/physics/schwarzschild_lens.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

RadialFall radial_fall(const HoleGeodesic& g, const HoleFall& fall) {
  return std::isinf(fall.from) ? RadialFall::from_infinity(g.mass, fall.reference)
                               : RadialFall::from_rest(g.mass, fall.from);
}

// The camera's event, its velocity measured by the local static observer, and its proper time.
WorldLine geodesic_observation(const HoleGeodesic& g, double tau) {
  if (const auto* orbit = std::get_if<HoleOrbit>(&g.path)) {
    const CircularOrbitPoint p = circular_orbit_at_proper_time(g.mass, orbit->radius, tau);
    const double phi = orbit->phase + p.angle, c = std::cos(phi), s = std::sin(phi);
    return {p.coordinate_time, g.hole + (orbit->axis_x * c + orbit->axis_y * s) * orbit->radius,
            (orbit->axis_y * c - orbit->axis_x * s) * p.local_speed, tau};
  }
  const HoleFall& fall = std::get<HoleFall>(g.path);
  const RadialFall path = radial_fall(g, fall);
  const RadialFallPoint p = path.at_proper_time(tau);
  if (p.radius <= 2 * g.mass * (1 + kCameraHorizonMargin)) {
    // At and inside the horizon W's time is not defined and there is no static observer: the
    // time is where it passed 2M (1 + kCameraHorizonMargin), and no velocity is given (the
    // renderers read the camera's fall, falling_camera).
    const double passed = path.proper_time_at_radius(2 * g.mass * (1 + kCameraHorizonMargin));
    return {fall.time + path.at_proper_time(passed).coordinate_time,
            g.hole + fall.direction * p.radius,
            {},
            tau};
  }
  return {fall.time + p.coordinate_time, g.hole + fall.direction * p.radius,
          fall.direction * p.local_velocity, tau};
}

}  // namespace

ProperTimeSpan drawn_proper_times(const HoleGeodesic& g) {
  const auto* fall = std::get_if<HoleFall>(&g.path);
  if (!fall) return {-kInf, kInf};
  const RadialFall path = radial_fall(g, *fall);
  const double latest = path.proper_time_at_radius(kCameraInnermostRadius * g.mass);
  // Before it came to rest at r0 it rose out of the past horizon: not drawn.
  const double earliest =
      std::isinf(fall->from) ? -kInf
                             : -path.proper_time_at_radius(2 * g.mass * (1 + kCameraHorizonMargin));
  return {earliest, latest};
}

std::optional<RadialObserver> falling_camera(const Camera::Motion& motion) {
  if (!motion.geodesic) return std::nullopt;
  const HoleGeodesic& g = *motion.geodesic;
  const auto* fall = std::get_if<HoleFall>(&g.path);
  if (!fall) return std::nullopt;
  const RadialFall path = radial_fall(g, *fall);
  const double r = path.at_proper_time(motion.proper_time).radius, e = path.energy();
  const double speed = std::sqrt(std::max(0.0, e * e - (1 - 2 * g.mass / r)));
  // Rising to rest at r0 before proper time 0, falling after.
  const bool rising = !path.is_from_infinity() && motion.proper_time < 0;
  return RadialObserver{g.mass, r, e, rising ? speed : -speed};
}

bool camera_inside_horizon(const Camera::Motion& motion) {
  const auto falling = falling_camera(motion);
  return falling && falling->radius <= 2 * falling->mass * (1 + kCameraHorizonMargin);
}

std::optional<std::string> geodesic_camera_refused(const Camera::Motion& motion, double c) {
  if (!motion.geodesic) return std::nullopt;
  const HoleGeodesic& g = *motion.geodesic;
  const ProperTimeSpan span = drawn_proper_times(g);
  const double tau = motion.proper_time;
  if (tau > span.earliest && tau < span.latest) {
    const WorldLine w = geodesic_observation(g, tau);
    if (std::isfinite(w.time) && std::isfinite(length(w.position - g.hole))) return std::nullopt;
    return fmt::format(
        "at proper time {} the camera's coordinate time or distance from the black hole is not a "
        "finite number (it is too far along its {})",
        tau / c, std::holds_alternative<HoleOrbit>(g.path) ? "orbit" : "fall");
  }
  const HoleFall& fall = std::get<HoleFall>(g.path);  // an orbit is drawn at every tau
  const RadialFall path = radial_fall(g, fall);
  const double m = g.mass, r = path.at_proper_time(tau).radius;
  // + 0.0: a fall from rest within the margin is drawn after -0, which reads as 0.
  const double earliest = span.earliest + 0.0;
  const std::string drawn =
      !(span.latest > earliest) ? "it starts there, and is drawn at no proper time"
      : std::isinf(earliest)
          ? fmt::format("it is drawn at proper times below {}", span.latest / c)
          : fmt::format("it is drawn at proper times between {} and {}, both excluded",
                        earliest / c, span.latest / c);
  if (tau >= span.latest) {
    if (r == 0)
      return fmt::format(
          "at proper time {} the falling camera has reached the singularity r = 0 (at proper "
          "time {}): the camera is drawn down to r = {}M ({})",
          tau / c, path.proper_time_at_radius(0) / c, kCameraInnermostRadius, drawn);
    return fmt::format(
        "at proper time {} the falling camera is at r = {:.12g} ({:.12g}M), within {}M of the "
        "singularity at r = 0: the camera is drawn down to r = {}M ({})",
        tau / c, r, r / m, kCameraInnermostRadius, kCameraInnermostRadius, drawn);
  }
  // From rest at r0 (from infinity every earlier time is drawn): at r0 itself, or before it
  // came to rest there, on the same geodesic rising out of the past horizon.
  const std::string margin = fmt::format("2M (1 + {:g}) = {:.12g}", kCameraHorizonMargin,
                                         2 * m * (1 + kCameraHorizonMargin));
  if (tau == 0)
    return fmt::format(
        "at proper time 0 the falling camera is at rest at r0 = {:.12g}M (camera.motion.fall.from, "
        "or camera.position's distance from the hole), within {} of the black hole: at rest or "
        "rising the camera is drawn only outside that radius, falling also inside it ({})",
        fall.from / m, margin, drawn);
  const std::string where =
      r > 2 * m ? fmt::format(
                      "is rising at r = {:.12g} ({:.12g}M), within {} of the black hole, "
                      "just out of its past horizon",
                      r, r / m, margin)
      : r > 0 ? fmt::format(
                    "is rising at r = {:.12g} ({:.12g}M), inside the black hole's past "
                    "horizon r = 2M = {}, out of which it comes at proper time {}",
                    r, r / m, 2 * m, -path.horizon_proper_time() / c)
              : fmt::format(
                    "does not exist yet (its geodesic begins at the past singularity r = 0 "
                    "at proper time {})",
                    -path.proper_time_at_radius(0) / c);
  return fmt::format(
      "at proper time {} the falling camera, on its way to rest at r0 = {:.12g}M at proper time "
      "0, {}: rising, the camera is drawn only outside r = {} ({})",
      tau / c, fall.from / m, where, margin, drawn);
}

HoleWorldLine hole_world_line(const Object& object, const BlackHole& hole) {
  const WorldLine& w = object.world_line;
  if (!object.motion.geodesic)
    return HoleWorldLine::straight(hole.mass, w.time, w.position - hole.position, w.velocity,
                                   w.proper_time);
  const HoleGeodesic& g = *object.motion.geodesic;
  if (const auto* orbit = std::get_if<HoleOrbit>(&g.path))
    return HoleWorldLine::orbit(g.mass, orbit->radius, orbit->axis_x, orbit->axis_y, orbit->phase);
  const HoleFall& fall = std::get<HoleFall>(g.path);
  return HoleWorldLine::fall(radial_fall(g, fall), fall.direction, fall.time);
}

double geodesic_proper_time_at(const HoleGeodesic& g, double t) {
  if (const auto* orbit = std::get_if<HoleOrbit>(&g.path))
    return circular_orbit_proper_time(g.mass, orbit->radius, t);
  const HoleFall& fall = std::get<HoleFall>(g.path);
  return radial_fall(g, fall).proper_time_at_coordinate_time(t - fall.time);
}

WorldLine camera_observation(const Camera::Motion& motion) {
  if (motion.geodesic) {
    if (const auto why = geodesic_camera_refused(motion, 1)) throw std::invalid_argument(*why);
    return geodesic_observation(*motion.geodesic, motion.proper_time);
  }
  if (!motion.keyframes.empty())
    return tangent_line(
        point_at_proper_time(KeyframeWorldLine(motion.keyframes), motion.proper_time));
  const AcceleratedWorldLine line(motion.start.time, motion.start.position, motion.start.velocity,
                                  motion.phases);
  return tangent_line(line.at_proper_time(motion.proper_time));
}

double origin_radius(const Shape& shape, const Vec3& scale) {
  struct Visitor {
    static double norm(const Vec3& v) { return std::hypot(v.x, v.y, v.z); }
    const Vec3& k;
    double operator()(const Sphere& s) const {
      return s.radius * std::max({std::abs(k.x), std::abs(k.y), std::abs(k.z)});
    }
    // (std::hypot: the square of a box's half-diagonal need not be a double.)
    double operator()(const Box& b) const { return norm(component_mul(k, b.size * 0.5)); }
    double operator()(const Plane& p) const {
      return norm(component_mul(k, Vec3{p.size_x / 2, 0, p.size_z / 2}));
    }
    double operator()(const MeshShape& m) const {
      double r = 0;
      if (m.mesh)
        for (const Vec3& p : m.mesh->positions) r = std::max(r, length(component_mul(k, p)));
      return r;
    }
  };
  return std::visit(Visitor{scale}, shape);
}

WorldLine observation_after(const Camera& camera, double later) {
  if (later == 0) return camera.world_line;
  if (!camera.motion.phases.empty() || !camera.motion.keyframes.empty() || camera.motion.geodesic) {
    Camera::Motion motion = camera.motion;
    motion.proper_time += later;
    return camera_observation(motion);
  }
  const WorldLine& w = camera.world_line;
  const double gamma = lorentz_gamma(w.velocity);
  return {w.time + gamma * later, w.position + w.velocity * (gamma * later), w.velocity,
          w.proper_time + later};
}

WorldLine tangent_line(const WorldLinePoint& point) {
  return {point.event.t, point.event.x, velocity_of(point.four_velocity), point.proper_time};
}

std::unique_ptr<TimelikeWorldLine> body_world_line(const WorldLine& start,
                                                   const BodyMotion& motion) {
  if (!motion.keyframes.empty()) return std::make_unique<KeyframeWorldLine>(motion.keyframes);
  if (!motion.phases.empty())
    return std::make_unique<AcceleratedWorldLine>(start.time, start.position, start.velocity,
                                                  motion.phases);
  return nullptr;
}

void place_where_seen(WorldLine& start, BodyMotion& motion, const WorldLine& observation,
                      const Vec3& seen) {
  const double emitted = observation.time - length(seen - observation.position);
  const std::unique_ptr<TimelikeWorldLine> line = body_world_line(start, motion);
  const Vec3 there = line ? line->at_world_time(emitted).event.x : start.position_at(emitted);
  const Vec3 shift = seen - there;
  start.position = start.position + shift;
  for (Keyframe& key : motion.keyframes) key.position = key.position + shift;
}

std::optional<std::string> place_where_seen_near_hole(WorldLine& start,
                                                      const WorldLine& observation,
                                                      const BlackHole& hole, const Vec3& seen) {
  // In units of M, as the lens solver measures (the scene's units' squares need not be doubles).
  const Vec3 camera = (observation.position - hole.position) / hole.mass;
  const Vec3 point = (seen - hole.position) / hole.mass;
  const double r_camera = std::hypot(camera.x, camera.y, camera.z);
  const double r_point = std::hypot(point.x, point.y, point.z);
  if (!(r_point > 2))
    return fmt::format(
        "no light leaves ({}, {}, {}): it is {} from the black hole's centre, {} "
        "its horizon r = 2M = {}",
        seen.x, seen.y, seen.z, r_point * hole.mass, r_point == 2 ? "on" : "inside", 2 * hole.mass);
  if (!(r_camera > 2))
    return std::string(
        "the camera is inside the black hole's horizon, where W's time, and so the time the "
        "light left, is not defined");
  const double psi = std::acos(std::clamp(dot(camera / r_camera, point / r_point), -1.0, 1.0));
  const std::optional<RayBetween> ray = ray_between(1, r_camera, r_point, psi, 0);
  if (!ray || !std::isfinite(ray->time))
    return fmt::format("no primary ray of light joins ({}, {}, {}) to the camera", seen.x, seen.y,
                       seen.z);
  const double emitted = observation.time - ray->time * hole.mass;
  start.position = start.position + (seen - start.position_at(emitted));
  return std::nullopt;
}

double relative_gamma(const Vec4& observer, const Vec4& u) {
  return observer.t * u.t - dot(observer.x, u.x);
}

// On a phase of constant proper acceleration the factor is A cosh(eta) + B sinh(eta), a convex
// function of the proper time (it equals its second derivative and is positive), so its largest
// values are at the phases' ends; keyframes have their own exact maximum.
double max_relative_gamma(const WorldLine& start, const BodyMotion& motion, const Vec4& observer) {
  if (!motion.keyframes.empty())
    return KeyframeWorldLine(motion.keyframes).max_gamma(velocity_of(observer)).gamma;
  double largest = relative_gamma(observer, four_velocity(start.velocity));
  const AcceleratedWorldLine line(start.time, start.position, start.velocity, motion.phases);
  double end = 0;
  for (const AccelerationPhase& p : motion.phases) {
    end += p.duration;
    const double g = relative_gamma(observer, line.at_proper_time(end).four_velocity);
    if (!(g <= largest)) largest = g;
  }
  return largest;
}

// A point moving at w relative to the body's centre, which moves at u relative to the observer,
// has gamma_u gamma_w (1 + u.w), u here the observer's velocity in the body's rest frame
// reversed. The rim's points move at `rim` in every direction across the spin axis, so the
// worst is gamma_w (U.t + rim |U across the axis|), U the observer's 4-velocity in the body's
// rest frame. For a body that is not inertial the axis turns with it: then the bound over every
// direction, gamma_w gamma_u (1 + rim u), at the body's largest gamma_u.
double rim_point_gamma(const Object& o, double rim, const Vec4& observer) {
  const double rim_gamma = 1 / std::sqrt((1 - rim) * (1 + rim));
  if (o.motion.inertial()) {
    const Vec4 seen = boost(o.world_line.velocity) * observer;
    const Vec3 across = seen.x - o.spin->axis * dot(o.spin->axis, seen.x);
    return rim_gamma * (seen.t + rim * length(across));
  }
  const double g = max_relative_gamma(o.world_line, o.motion, observer);
  return rim_gamma * (g + rim * std::sqrt(std::max(g - 1, 0.0) * (g + 1)));
}

Fastest fastest_relative_to(const Scene& scene, const Vec4& observer) {
  Fastest fastest;
  const auto consider = [&](const std::string& name, double gamma) {
    if (!(gamma <= fastest.gamma)) fastest = {name, gamma};
  };
  for (const Object& o : scene.objects) {
    consider(o.name, max_relative_gamma(o.world_line, o.motion, observer));
    if (o.spin) {
      const double rim = std::abs(o.spin->rate) * origin_radius(o.shape, o.scale);
      consider(o.name + "'s spin rim", rim < 1 ? rim_point_gamma(o, rim, observer) : HUGE_VAL);
    }
  }
  for (const Light& l : scene.lights)
    consider(l.name, max_relative_gamma(l.world_line, l.motion, observer));
  consider("the sky", relative_gamma(observer, four_velocity(scene.sky.velocity)));
  return fastest;
}

}  // namespace lightcone

// The "black_hole" key of a scene, and what a hole asks of the camera, objects and lights
// (docs/scene-format.md, "black_hole"; PHYSICS.md, "Curved spacetime"). Lengths, the mass among
// them (GM/c^2), are in the scene's units whatever speed_of_light is; only times and speeds are
// converted.
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>

#include "lightcone/io/scene_reader.hpp"
#include "lightcone/physics/schwarzschild_motion.hpp"

namespace lightcone::scene_io {
namespace {

// The renderers follow light near the hole in units of its mass M (frame/hole_view.hpp): a
// point's distance from it must be a finite number of M, and a body's or a light's at most
// kFarthestBody M, since the chords that meet them square such distances (a hole bends nothing
// that far out in double precision).
constexpr double kFarthestBody = 1e150;

// A point's distance from the hole in units of M, from its offset.
double distance_in_mass(const Vec3& offset, double mass) {
  const Vec3 d = offset / mass;
  return std::hypot(d.x, d.y, d.z);
}

// Why `whose` point (a body's or a light's, if `body`), `in_mass` M from the hole, cannot be
// followed, if it cannot.
std::optional<std::string> out_of_reach(std::string_view whose, double in_mass, double mass,
                                        bool body) {
  if (!std::isfinite(in_mass))
    return fmt::format(
        "{} distance from the black hole, in units of its mass M = {}, is not a "
        "finite number: light near the hole is followed in units of M (give a "
        "larger mass or a nearer position)",
        whose, mass);
  if (body && in_mass > kFarthestBody)
    return fmt::format(
        "{} distance from the black hole is {:.6g} M (M = {}): bodies and lights "
        "are drawn within {:g} M of a hole (light near it is followed in units of "
        "M, and the chords that meet them square such distances); that far out the "
        "hole bends nothing in double precision: leave it out, or give a larger "
        "mass",
        whose, in_mass, mass, kFarthestBody);
  return std::nullopt;
}

}  // namespace

BlackHole SceneReader::black_hole(const Node& n) const {
  if (n.value->is_array())
    fail(n, fmt::format("must be an object, got {}: a scene holds one black hole at most (two "
                        "holes are not an exact solution: no closed-form spacetime holds two)",
                        describe(*n.value)));
  object(n, {"position", "mass", "disk"});
  BlackHole hole;
  if (Node p = member(n, "position"); p.value) hole.position = vec3(p);
  const Node mass = member(n, "mass");
  hole.mass = number(mass);
  if (!(hole.mass > 0))
    fail(mass, fmt::format("must be greater than 0 (the gravitational radius GM/c^2, a length), "
                           "got {}",
                           hole.mass));
  if (!std::isfinite(2 * hole.mass))
    fail(mass,
         fmt::format("{} is too large: the horizon's radius 2M is not a finite number", hole.mass));
  if (Node disk = member(n, "disk"); disk.value) hole.disk = accretion_disk(disk, hole.mass);
  return hole;
}

AccretionDisk SceneReader::accretion_disk(const Node& n, double mass) const {
  object(n, {"inner", "outer", "normal", "temperature", "luminance"});
  AccretionDisk disk;
  // In units of M, as the file gives them: by default from the ISCO to 20M.
  double inner = 6, outer = 20;
  const Node inner_node = member(n, "inner"), outer_node = member(n, "outer");
  if (inner_node.value) {
    inner = number(inner_node);
    if (!(inner >= 6))
      fail(inner_node, fmt::format("{} is below the innermost stable circular orbit, 6M: the "
                                   "inner radius (in units of M) must be at least 6",
                                   inner));
  }
  if (outer_node.value) outer = number(outer_node);
  if (!(outer > inner))
    fail(outer_node,
         fmt::format("the outer radius {}{} must be greater than the inner radius {} (in units of "
                     "M)",
                     outer, outer_node.value ? "" : " (the default)", inner));
  disk.inner = inner * mass;
  disk.outer = outer * mass;
  if (!std::isfinite(disk.outer))
    fail(outer_node, fmt::format("the outer radius {} M, with M = {}, is too large (not a finite "
                                 "number)",
                                 outer, mass));
  if (Node normal = member(n, "normal"); normal.value) disk.normal = direction(normal);
  if (Node t = member(n, "temperature"); t.value) {
    disk.temperature_k = number(t);
    if (!(disk.temperature_k > 0))
      fail(t, fmt::format("must be greater than 0 kelvin (the disk's peak temperature), got {}",
                          disk.temperature_k));
  }
  if (Node y = member(n, "luminance"); y.value) disk.luminance = positive(y);
  return disk;
}

void SceneReader::check_camera_near_hole(const Node& n) const {
  const Node m = member(n, "motion");
  if (m.value) {
    if (m.value->is_object() && (m.value->contains("phases") || m.value->contains("keyframes")))
      refuse_near_hole(m, "motion (phases or keyframes) of the camera",
                       ": near one the camera moves on a geodesic, \"orbit\" or \"fall\"");
    one_of(m, {"orbit", "fall"});
  }
  if (Node sh = member(n, "shutter"); sh.value && non_negative(sh) > 0)
    refuse_near_hole(sh, "a shutter open for a while (motion blur)");
  if (Node tau = member(n, "proper_time"); tau.value && number(tau) != 0 && !m.value)
    refuse_near_hole(tau, "a proper time other than 0 without a camera motion",
                     " (the clock of a camera on a straight coordinate line there is not "
                     "modelled): give the observation's world time as \"time\", or a motion "
                     "\"orbit\" or \"fall\"");
  const Node position = member(n, "position");
  // With a motion (now an orbit or a fall) only a fall's position is checked here: an orbit's
  // is refused with the orbit. A fall's position is its event at proper time 0, not a static
  // observer's.
  const bool falls = m.value && m.value->contains("fall");
  if (m.value && !(falls && position.value)) return;
  const double in_mass = distance_in_mass(vec3(position) - hole_->position, hole_->mass);
  if (const auto why = out_of_reach("the camera's", in_mass, hole_->mass, false))
    fail(position, *why);
  const double r = in_mass * hole_->mass, horizon = 2 * hole_->mass;
  if (!(in_mass > 2))
    fail(position,
         fmt::format("the camera is at r = {} from the black hole, inside its horizon r = 2M = {}: "
                     "{}",
                     r, horizon,
                     falls ? "on a fall this is where the camera is at its proper time 0, at "
                             "coordinate time motion.fall.time, and W's time is not defined "
                             "inside the horizon (place it outside, and give a later "
                             "camera.proper_time to see from inside)"
                           : "its velocity is measured by the local static observer, and there "
                             "is none inside the horizon"));
}

bool SceneReader::geodesic_motion(const Node& m) {
  return m.value && m.value->is_object() &&
         (m.value->contains("orbit") || m.value->contains("fall"));
}

HoleGeodesic SceneReader::geodesic(const Node& n, const Node& m, std::string_view noun) const {
  const std::string_view kind = one_of(m, {"orbit", "fall"});
  const Node path = member(m, kind);
  const bool orbit = kind == "orbit";
  if (!hole_)
    fail(path, fmt::format("{} needs a black hole (the top-level \"black_hole\"): without one the "
                           "{} moves inertially, or as \"phases\" or \"keyframes\" say",
                           orbit ? "a circular orbit about a black hole"
                                 : "a free fall toward a black hole",
                           noun));
  const auto refuse = [&](const char* key, std::string_view why) {
    if (Node k = member(n, key); k.value)
      fail(k, fmt::format("must not be given with motion.{} ({})", kind, why));
  };
  if (orbit) {
    for (const char* key : {"position", "time", "velocity"})
      refuse(key, fmt::format("the orbit says where and when the {} is and how it moves: give its "
                              "radius, normal and phase",
                              noun));
  } else {
    refuse("time",
           fmt::format("the coordinate time at the {}'s proper time 0 is motion.fall.time", noun));
    refuse("velocity",
           fmt::format("the {} falls freely from rest, and its velocity follows", noun));
  }
  HoleGeodesic g;
  g.hole = hole_->position;
  g.mass = hole_->mass;
  if (orbit)
    g.path = this->orbit(path, noun);
  else
    g.path = fall(n, path, noun);
  return g;
}

HoleOrbit SceneReader::orbit(const Node& o, std::string_view noun) const {
  object(o, {"radius", "normal", "phase"});
  const double mass = hole_->mass;
  const Node radius = member(o, "radius");
  const double r = number(radius);
  if (!(r > 3))
    fail(radius, fmt::format("{} is not outside the photon sphere, 3M: a circular orbit's radius "
                             "(in units of M) must be greater than 3 (and orbits inside 6M, the "
                             "ISCO, are unstable)",
                             r));
  if (const auto why = out_of_reach(fmt::format("the {}'s", noun), r, mass, noun != "camera"))
    fail(radius, *why);
  HoleOrbit orbit;
  orbit.radius = r * mass;
  if (!std::isfinite(orbit.radius))
    fail(radius,
         fmt::format("the radius {} M, with M = {}, is too large (not a finite number)", r, mass));
  // Its speed measured by the static observer, sqrt(M / (r - 2M)): gamma = sqrt((r - 2) / (r - 3))
  // in units of M, unbounded toward the photon sphere.
  limit_gamma(radius, std::sqrt((r - 2) / (r - 3)),
              fmt::format("on a circular orbit at r = {}M the {}'s speed {} measured by the "
                          "local static observer",
                          r, noun, std::sqrt(1 / (r - 2)) * c_),
              observers_.front());
  Vec3 normal{0, 1, 0};
  if (Node nn = member(o, "normal"); nn.value) normal = direction(nn);
  // The reference axis: W's +x projected on the plane, n x (x x n) = (ny^2 + nz^2, -nx ny,
  // -nx nz); W's +z for a normal along x.
  const double across = std::hypot(normal.y, normal.z);
  orbit.axis_x = across == 0
                     ? Vec3{0, 0, 1}
                     : Vec3{across, -normal.x * normal.y / across, -normal.x * normal.z / across};
  orbit.axis_y = cross(normal, orbit.axis_x);
  if (Node phase = member(o, "phase"); phase.value)
    orbit.phase = number(phase) * std::numbers::pi / 180;
  return orbit;
}

HoleFall SceneReader::fall(const Node& n, const Node& f, std::string_view noun) const {
  object(f, {"from", "direction", "time"});
  const double mass = hole_->mass;
  const Node position = member(n, "position");
  // Where the body is at proper time 0, relative to the hole (outside the horizon: the
  // callers check), when given.
  std::optional<Vec3> at;
  double at_r = 0;
  // The position's path as the file spells it (objects[2].position), for a message.
  const auto position_key = [&] { return position.path(); };
  if (position.value) {
    at = vec3(position) - hole_->position;
    const double in_mass = distance_in_mass(*at, mass);
    if (const auto why =
            out_of_reach(fmt::format("the {}'s", noun), in_mass, mass, noun != "camera"))
      fail(position, *why);
    at_r = in_mass * mass;
  }
  HoleFall fall;
  const Node from = member(f, "from");
  if (from.value && from.value->is_string()) {
    if (string(from) != "infinity")
      fail(from, fmt::format("must be a number (the radius r0 in units of M, > 2, where the {} "
                             "falls from rest) or \"infinity\", got {}",
                             noun, describe(*from.value)));
    if (!at)
      fail(f, fmt::format("a fall from \"infinity\" needs {}: where the {} passes at its proper "
                          "time 0 (at coordinate time motion.fall.time)",
                          position_key(), noun));
    fall.from = std::numeric_limits<double>::infinity();
    fall.reference = at_r;
  } else if (from.value) {
    const double r0 = number(from);
    if (!(r0 > 2))
      fail(from, fmt::format("{} is not outside the horizon, 2M: the radius (in units of M) where "
                             "the {} falls from rest must be greater than 2, or \"infinity\"",
                             r0, noun));
    if (const auto why = out_of_reach(fmt::format("the {}'s", noun), r0, mass, noun != "camera"))
      fail(from, *why);
    fall.from = r0 * mass;
    if (!std::isfinite(fall.from))
      fail(from, fmt::format("the radius {} M, with M = {}, is too large (not a finite number)", r0,
                             mass));
    if (at && !(std::abs(at_r - fall.from) <= 1e-9 * fall.from))
      fail(from, fmt::format("the fall from rest at r0 = {}M starts at r = {} from the black hole, "
                             "but {}, where it is at proper time 0, is at r = {} ({}M): give "
                             "one of them",
                             r0, fall.from, position_key(), at_r, at_r / mass));
  } else {
    if (!at)
      fail(f, fmt::format("needs \"from\": the radius r0 in units of M (> 2) where the {} falls "
                          "from rest, or \"infinity\" (or {}, to fall from rest there)",
                          noun, position_key()));
    fall.from = at_r;
  }
  if (Node d = member(f, "direction"); d.value) {
    fall.direction = direction(d);
    if (at && !(length(cross(fall.direction, *at / at_r)) <= 1e-9 && dot(fall.direction, *at) > 0))
      fail(d, fmt::format("must point from the black hole toward {}, where the {} is at its "
                          "proper time 0 (or be left out: it defaults to that direction)",
                          position_key(), noun));
  } else {
    if (!at)
      fail(f, fmt::format("needs \"direction\" [x, y, z], from the black hole along which the {} "
                          "falls (or {})",
                          noun, position_key()));
    fall.direction = *at / at_r;
  }
  if (Node t = member(f, "time"); t.value) fall.time = time(t);
  return fall;
}

void SceneReader::geodesic_object(const Node& m, Object& o) const {
  const HoleGeodesic& g = *o.motion.geodesic;
  const double reach = origin_radius(o.shape, o.scale), horizon = 2 * g.mass;
  if (const auto* orbit = std::get_if<HoleOrbit>(&g.path);
      orbit && !(orbit->radius - reach > horizon))
    fail(member(member(m, "orbit"), "radius"),
         fmt::format(
             "the object reaches {:.6g} from its origin, so on an orbit at r = {} it crosses "
             "the horizon r = 2M = {}: an orbit's radius must exceed 2M plus the object's "
             "reach (here a radius above {:.6g}, in units of M)",
             reach, orbit->radius, horizon, (horizon + reach) / g.mass));
  const HoleWorldLineState at = hole_world_line(o, *hole_).at(0);
  o.world_line = {0, g.hole + at.position, at.velocity, at.proper_time};
}

void SceneReader::refuse_near_hole(const Node& n, std::string_view what,
                                   std::string_view more) const {
  fail(n, fmt::format("{} is not yet supported near a black hole{}", what, more));
}

void SceneReader::check_line_near_hole(const Node& n, const WorldLine& line,
                                       std::string_view noun) const {
  const double mass = hole_->mass, horizon = 2 * mass;
  const Vec3 from_hole = line.position - hole_->position;
  if (const auto why = out_of_reach(fmt::format("the {}'s", noun),
                                    distance_in_mass(from_hole, mass), mass, true))
    fail(member(n, "position"), *why);
  const LineSpeedPeak peak = peak_static_observer_speed(mass, from_hole, line.velocity);
  if (line.velocity == Vec3{}) {
    if (peak.reaches_horizon)
      fail(member(n, "position"),
           fmt::format("the {} is at rest at r = {} from the black hole, inside its horizon "
                       "r = 2M = {}: nothing stays at rest there (there are no static observers "
                       "inside the horizon)",
                       noun, peak.radius, horizon));
    return;
  }
  const Node velocity = member(n, "velocity");
  if (peak.reaches_horizon)
    fail(velocity,
         fmt::format("the {}'s coordinate line position + velocity (t - time) comes within r = {} "
                     "of the black hole, inside its horizon r = 2M = {}: a body moves on a "
                     "straight line in Schwarzschild coordinates, which cannot cross the horizon",
                     noun, peak.radius, horizon));
  if (!(peak.speed < 1))
    fail(velocity,
         fmt::format(
             "along the {}'s coordinate line position + velocity (t - time), the speed "
             "measured by the local static observers reaches {} at r = {:.6g} from the black "
             "hole: it must stay below the speed of light ({})",
             noun, peak.speed * c_, peak.radius, c_));
  limit_gamma(velocity, 1 / std::sqrt((1 - peak.speed) * (1 + peak.speed)),
              fmt::format("along the {}'s coordinate line, at r = {:.6g} from the black hole, the "
                          "speed {} measured by the local static observer",
                          noun, peak.radius, peak.speed * c_),
              observers_.front());
}

}  // namespace lightcone::scene_io

// The "black_hole" key of a scene, and what a hole asks of the camera, objects and lights
// (docs/scene-format.md, "black_hole"; PHYSICS.md, "Curved spacetime"). Lengths, the mass among
// them (GM/c^2), are in the scene's units whatever speed_of_light is; only times and speeds are
// converted.
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <string_view>

#include "lightcone/io/scene_reader.hpp"
#include "lightcone/physics/schwarzschild_motion.hpp"

namespace lightcone::scene_io {

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
  if (Node m = member(n, "motion"); m.value)
    refuse_near_hole(m, "motion (phases or keyframes) of the camera");
  if (Node sh = member(n, "shutter"); sh.value && non_negative(sh) > 0)
    refuse_near_hole(sh, "a shutter open for a while (motion blur)");
  if (Node tau = member(n, "proper_time"); tau.value && number(tau) != 0)
    refuse_near_hole(tau, "a proper time other than 0",
                     " (the camera's clock and path there are not modelled yet): give the "
                     "observation's world time as \"time\"");
  const Node position = member(n, "position");
  const double r = length(vec3(position) - hole_->position), horizon = 2 * hole_->mass;
  if (!(r > horizon))
    fail(position,
         fmt::format("the camera is at r = {} from the black hole, inside its horizon r = 2M = {}: "
                     "its velocity is measured by the local static observer, and there is none "
                     "inside the horizon",
                     r, horizon));
}

void SceneReader::refuse_near_hole(const Node& n, std::string_view what,
                                   std::string_view more) const {
  fail(n, fmt::format("{} is not yet supported near a black hole{}", what, more));
}

void SceneReader::check_line_near_hole(const Node& n, const WorldLine& line,
                                       std::string_view noun) const {
  const double mass = hole_->mass, horizon = 2 * mass;
  const Vec3 from_hole = line.position - hole_->position;
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

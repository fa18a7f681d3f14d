#include "lightcone/frame/hole_view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lightcone/physics/accretion_disk.hpp"
#include "lightcone/physics/schwarzschild_geodesics.hpp"

namespace lightcone {
namespace {

// A point's offset from the hole in units of M, and its length (std::hypot's: a distance of
// more than 1e154 M, a small hole far away, has no finite square).
Vec3 offset_in_mass(const HoleView& hole, const Vec3& x) {
  return (x - hole.centre) / hole.scale;
}
double radius_of(const Vec3& offset) {
  return std::hypot(offset.x, offset.y, offset.z);
}

}  // namespace

std::optional<HoleView> hole_view(const Scene& scene) {
  if (!scene.black_hole) return std::nullopt;
  const BlackHole& hole = *scene.black_hole;
  HoleView v;
  v.scale = hole.mass;
  v.centre = hole.position;
  const Vec3 from_hole = offset_in_mass(v, scene.camera.world_line.position);
  v.camera_radius = radius_of(from_hole);
  v.outward = from_hole / v.camera_radius;
  v.falling = falling_camera(scene.camera.motion);
  if (v.falling) {
    // Its energy and dr/dtau per unit mass are numbers; its radius is in W's units.
    v.falling->mass = v.mass;
    v.falling->radius /= v.scale;
    v.camera_radius = v.falling->radius;
  }
  v.camera_lapse = std::sqrt(std::max(0.0, 1 - 2 * v.mass / v.camera_radius));
  if (!camera_inside_horizon(scene.camera.motion)) {
    // The static observer's route, which the raster renderer takes (a falling camera's velocity
    // against it is its world-line's, outside the horizon).
    v.camera_rapidity = rapidity(scene.camera.world_line.velocity);
    v.trace_to_static = lorentz_inverse(boost(scene.camera.world_line.velocity));
  }
  if (v.falling) {
    const EnergyRange range = seen_energy_range(*v.falling);
    v.camera_log_energy_lo = std::log(range.lo), v.camera_log_energy_hi = std::log(range.hi);
  } else {
    // 1 / sqrt(f) at the static observer, times its Doppler factor within +-rapidity.
    const double blueshift = -std::log(v.camera_lapse);
    v.camera_log_energy_lo = blueshift - v.camera_rapidity;
    v.camera_log_energy_hi = blueshift + v.camera_rapidity;
  }
  v.world_to_sky = boost(scene.sky.velocity);
  v.to_pattern = scene.sky.rotation.transposed();
  v.sky_rapidity = rapidity(scene.sky.velocity);
  if (hole.disk) {
    v.disk = hole.disk;
    v.disk->inner /= v.scale;
    v.disk->outer /= v.scale;
  }
  return v;
}

Vec4 in_hole_units(const HoleView& hole, const Vec4& world) {
  return {world.t / hole.scale, offset_in_mass(hole, world.x)};
}

Vec4 in_world(const HoleView& hole, const Vec4& near) {
  return {near.t * hole.scale, hole.centre + near.x * hole.scale};
}

HoleWorldLine hole_world_line(const HoleView& hole, const WorldLine& w) {
  return HoleWorldLine::straight(hole.mass, w.time / hole.scale, offset_in_mass(hole, w.position),
                                 w.velocity, w.proper_time / hole.scale);
}

HoleWorldLine hole_world_line(const HoleView& hole, const Object& object) {
  if (!object.motion.geodesic) return hole_world_line(hole, object.world_line);
  const HoleGeodesic& g = *object.motion.geodesic;
  const double m = hole.scale;
  if (const auto* orbit = std::get_if<HoleOrbit>(&g.path))
    return HoleWorldLine::orbit(hole.mass, orbit->radius / m, orbit->axis_x, orbit->axis_y,
                                orbit->phase);
  const HoleFall& fall = std::get<HoleFall>(g.path);
  const RadialFall path = std::isinf(fall.from)
                              ? RadialFall::from_infinity(hole.mass, fall.reference / m)
                              : RadialFall::from_rest(hole.mass, fall.from / m);
  return HoleWorldLine::fall(path, fall.direction, fall.time / m);
}

double camera_photon_energy(const HoleView& hole, const Vec4& in_static) {
  return 1 / (hole.camera_lapse * -in_static.t);
}

double camera_photon_energy(const HoleView& hole, const Vec3& u) {
  if (hole.falling) {
    const double cos_look = dot(u, hole.outward);
    const auto ray = observed_ray(*hole.falling, cos_look, length(u - hole.outward * cos_look));
    return ray ? ray->energy : 0.0;
  }
  return camera_photon_energy(hole, hole.trace_to_static * Vec4{-1, u});
}

double camera_frame_distance(const HoleView& hole, const Vec3& u, double flight) {
  // camera_photon_energy is in units of the energy far away; the static observer's is 1 / lapse.
  return flight * camera_photon_energy(hole, u) * hole.camera_lapse;
}

double sky_photon_energy(const Vec4& in_sky) {
  return -in_sky.t;
}

double sky_photon_energy(const HoleView& hole, const Vec3& far) {
  return sky_photon_energy(hole.world_to_sky * Vec4{-1, far});
}

LogShiftRange sky_log_shift_range(const HoleView& hole) {
  return {hole.camera_log_energy_lo - hole.sky_rapidity,
          hole.camera_log_energy_hi + hole.sky_rapidity};
}

LogShiftRange disk_log_shift_range(const HoleView& hole) {
  if (!hole.disk) return {};
  const double m = hole.mass;
  // ln of the energy the gas at r measures for light of unit energy far away: -ln sqrt(f(r))
  // (the static observer's blueshift) plus its own Doppler term within +-atanh(v(r)).
  const auto gravity = [&](double r) { return -0.5 * std::log1p(-2 * m / r); };
  const double spin = std::atanh(circular_orbit_local_speed(m, hole.disk->inner));
  const double emitted_lo = gravity(hole.disk->outer) - spin;
  const double emitted_hi = gravity(hole.disk->inner) + spin;
  return {hole.camera_log_energy_lo - emitted_hi, hole.camera_log_energy_hi - emitted_lo};
}

namespace {

// object_depth, for the object's world-line `line` and its reach from its origin.
HoleDepth line_depth(const HoleView& hole, const HoleWorldLine& line, double reach) {
  const double m = hole.mass;
  // A fall reaches c at the horizon, where its light is shifted without bound: the range stops
  // at 2M (1 + 1e-6), where its speed is sqrt(1 - f / E^2) (0 for a fall from rest below it,
  // which is never that high: f > E^2 there).
  const double nearest = std::max(line.nearest() - reach, 2 * m * (1 + 1e-6));
  double speed = line.max_local_speed();
  if (const auto* fall = std::get_if<HoleWorldLine::Fall>(&line.path())) {
    const double f = 1 - 2 * m / nearest, e = fall->fall.energy();
    speed = std::sqrt(std::max(0.0, 1 - f / (e * e)));
  }
  return {0.5 * std::log1p(-2 * m / nearest), std::atanh(std::min(speed, 1 - 1e-16))};
}

}  // namespace

HoleDepth object_depth(const HoleView& hole, const Object& object) {
  return line_depth(hole, hole_world_line(hole, object),
                    origin_radius(object.shape, object.scale) / hole.scale);
}

HoleDepth light_depth(const HoleView& hole, const Light& light) {
  const WorldLine& w = light.world_line;
  if (std::holds_alternative<DirectionalLight>(light.kind)) return {0, rapidity(w.velocity)};
  const double m = hole.mass;
  const HoleWorldLine line = hole_world_line(hole, w);
  double reach = 0;
  if (const auto* sphere = std::get_if<SphereLight>(&light.kind))
    reach = sphere->radius / hole.scale;
  const double nearest = std::max(line.nearest() - reach, 2 * m * (1 + 1e-6));
  return {0.5 * std::log1p(-2 * m / nearest),
          std::atanh(std::min(line.max_local_speed(), 1 - 1e-16))};
}

LogShiftRange body_log_shift_range(const HoleView& hole, const Object& object) {
  const double m = hole.mass;
  const HoleWorldLine line = hole_world_line(hole, object);
  const double reach = origin_radius(object.shape, object.scale) / hole.scale;
  const double farthest = line.farthest() + reach;
  const HoleDepth depth = line_depth(hole, line, reach);
  const double far_lapse = std::isinf(farthest) ? 0.0 : 0.5 * std::log1p(-2 * m / farthest);
  return {hole.camera_log_energy_lo + depth.log_lapse - depth.rapidity,
          hole.camera_log_energy_hi + far_lapse + depth.rapidity};
}

}  // namespace lightcone

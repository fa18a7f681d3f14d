#include "lightcone/frame/curved_ray.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/physics/accretion_disk.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;
// A ray whose impact parameter is b_c to the last bit winds onto the photon sphere for ever;
// after this many crossings of the disk's plane it is counted as captured (its radius is then
// within rounding of 3M, inside every disk's inner edge of 6M or more).
constexpr int kMaxDiskCrossings = 64;

// A ray at b_c to the last bit sweeps an infinite angle: its order is counted as this many.
constexpr double kMaxImageOrder = 1e6;

int image_order(double phi) {
  return phi > 0 ? static_cast<int>(std::min(std::ceil(phi / kPi), kMaxImageOrder + 1)) - 1 : 0;
}

// curved_path but for its orbit and sweep (left as they were, but for a dark path's, which are
// reset): the ray's plane and impact parameter, written in place (a path is large, and copies of
// it were a tenth of its cost).
void start_path(const HoleView& hole, const Vec3& u, CurvedPath& p) {
  p.dark = false;
  p.e1 = hole.outward;
  if (hole.falling) {
    // In the falling camera's own frame, whose radial axis is e1 and whose other axes are W's.
    const double cos_look = dot(u, p.e1);
    const Vec3 tangential = u - p.e1 * cos_look;
    const double sin_look = length(tangential);
    p.e2 = sin_look > 0 ? tangential / sin_look : any_perpendicular(p.e1);
    const auto seen = observed_ray(*hole.falling, cos_look, sin_look);
    if (!seen) {
      p.dark = true;
      p.impact = 0;
      p.camera_energy = 1;
      p.outward = false;
      p.orbit = PhotonOrbit{};
      p.sweep = AngleSweep{};
      return;
    }
    p.impact = seen->impact;
    p.camera_energy = seen->energy;
    p.outward = seen->outward;
    return;
  }
  // The backward ray's direction in the static observer's frame: the F event (-1, u) maps to
  // (t, x) with t < 0.
  const Vec4 back = hole.trace_to_static * Vec4{-1, u};
  const Vec3 d = back.x / -back.t;
  p.camera_energy = camera_photon_energy(hole, back);
  // e1 from the hole to the camera, e2 along the look direction's tangential part.
  const double cos_alpha = dot(d, p.e1);
  const Vec3 tangential = d - p.e1 * cos_alpha;
  const double sin_alpha = length(tangential);
  p.e2 = sin_alpha > 0 ? tangential / sin_alpha : any_perpendicular(p.e1);
  p.impact = static_impact_parameter(hole.mass, hole.camera_radius, sin_alpha);
  p.outward = cos_alpha > 0;
}

// The ray along a path, meeting the scene's bodies too when `bodies` is given.
CurvedRay follow_path(const HoleView& hole, const CurvedPath& path, const CurvedBodies* bodies) {
  const Vec3 &e1 = path.e1, &e2 = path.e2;
  const double impact = path.impact, camera_energy = path.camera_energy;
  const AngleSweep& sweep = path.sweep;
  CurvedRay ray;
  if (path.dark) return ray;  // kHorizon, shift 0
  // From inside the horizon the backward ray first climbs out through r = 2M: the disk's plane
  // crossed below it is no disk, and it is not yet captured.
  const bool start_inside = hole.camera_radius < 2 * hole.mass;
  const RayCourse course =
      start_inside ? ray_course(path.orbit, hole.camera_radius, path.outward) : RayCourse{};
  if (hole.disk) {
    const AccretionDisk& disk = *hole.disk;
    const double a = dot(e1, disk.normal), c = dot(e2, disk.normal);
    // The plane holds the position cos(phi) e1 + sin(phi) e2 where a cos(phi) + c sin(phi) = 0:
    // at phi0 + k pi. A ray in the disk's own plane (a = c = 0) sees it edge-on and misses it.
    // A ray that turns outside the disk (r >= periapsis > outer all along) cannot meet it.
    const bool beyond = path.orbit.turning && path.orbit.periapsis > disk.outer;
    if ((a != 0 || c != 0) && !beyond) {
      double phi = std::atan2(-a, c);
      if (phi <= 0) phi += kPi;
      for (int k = 0; k < kMaxDiskCrossings && phi < sweep.angle_total; ++k, phi += kPi) {
        const double r = radius_after_angle(sweep, phi);
        const bool climbing =
            start_inside && !(course.turning_radius > 0 && phi > course.angle_to_turn);
        if (climbing && r <= 2 * hole.mass) continue;
        if (!(r > 2 * hole.mass) || std::isinf(r)) break;
        if (r < disk.inner || r > disk.outer) continue;
        // The gas orbits about the disk's normal; the photon's angular momentum about it per unit
        // energy is -b (e1 x e2) . normal (the backward ray sweeps from e1 toward e2).
        const double lambda = -impact * dot(cross(e1, e2), disk.normal);
        ray.end = CurvedRayEnd::kDisk;
        ray.order = k;
        ray.phi = phi;
        ray.disk_radius = r;
        // Cunningham's g is the shift to a static observer far away, whose energy unit this is.
        ray.shift = camera_energy * circular_orbit_frequency_shift(hole.mass, r, lambda);
        break;
      }
    }
  }
  // A body met before the disk (or before the ray's end) is what the camera sees.
  if (bodies) {
    const double limit = ray.end == CurvedRayEnd::kDisk ? ray.phi : sweep.angle_total;
    if (bodies->first_hit(hole, path, limit, ray)) {
      ray.order = image_order(ray.phi);
      return ray;
    }
  }
  if (ray.end == CurvedRayEnd::kDisk) return ray;
  ray.phi = sweep.angle_total;
  ray.order = image_order(sweep.angle_total);
  // Captured: the horizon, or (b = b_c to the last bit) the photon sphere for ever.
  if (!std::isinf(sweep.end)) return ray;
  // Far away the backward ray runs radially out along its position.
  const Vec3 far = e1 * std::cos(sweep.angle_total) + e2 * std::sin(sweep.angle_total);
  const Vec4 in_sky = hole.world_to_sky * Vec4{-1, far};
  const double inv_sky_t = -1 / in_sky.t;
  ray.end = CurvedRayEnd::kSky;
  ray.sky_direction = hole.to_pattern * (in_sky.x * inv_sky_t);
  ray.shift = camera_energy / sky_photon_energy(in_sky);
  return ray;
}

}  // namespace

CurvedPath curved_path(const HoleView& hole, const Vec3& u) {
  CurvedPath p;
  start_path(hole, u, p);
  if (p.dark) return p;
  p.orbit = photon_orbit(hole.mass, p.impact);
  p.sweep = prepare_sweep(p.orbit, hole.camera_radius, p.outward);
  return p;
}

void curved_paths(const HoleView& hole, std::span<const Vec3> u, std::span<CurvedPath> out) {
  for (std::size_t first = 0; first < u.size(); first += kMaxSweeps) {
    double impacts[kMaxSweeps];
    PhotonOrbit* orbits[kMaxSweeps];
    SweepStart starts[kMaxSweeps];
    AngleSweep* sweeps[kMaxSweeps];
    int n = 0;
    for (std::size_t i = first; i < std::min(first + kMaxSweeps, u.size()); ++i) {
      CurvedPath& p = out[i];
      start_path(hole, u[i], p);
      if (p.dark) continue;
      impacts[n] = p.impact;
      orbits[n] = &p.orbit;
      starts[n] = {&p.orbit, hole.camera_radius, p.outward};
      sweeps[n++] = &p.sweep;
    }
    photon_orbits(hole.mass, impacts, orbits, n);
    prepare_sweeps(starts, sweeps, n);
  }
}

CurvedRay follow_curved_ray(const HoleView& hole, const Vec3& u, const CurvedBodies* bodies) {
  return follow_path(hole, curved_path(hole, u), bodies);
}

void follow_curved_rays(const HoleView& hole, std::span<const Vec3> u, const CurvedBodies* bodies,
                        std::span<CurvedRay> out) {
  CurvedPath paths[kMaxSweeps];
  for (std::size_t first = 0; first < u.size(); first += kMaxSweeps) {
    const std::size_t n = std::min<std::size_t>(kMaxSweeps, u.size() - first);
    curved_paths(hole, u.subspan(first, n), std::span(paths, n));
    for (std::size_t i = 0; i < n; ++i) out[first + i] = follow_path(hole, paths[i], bodies);
  }
}

}  // namespace lightcone

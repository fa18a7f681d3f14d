#include "viewer/flight.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

#include "lightcone/physics/accretion_disk.hpp"
#include "lightcone/physics/lorentz.hpp"

namespace lightcone {

namespace {
constexpr double kMaxSpeed = 0.999;

// The proper time of a free fall from rest at r to r = 0 about a hole of mass m.
double free_fall_time(double r, double m) {
  return std::numbers::pi / 2 * std::sqrt(r * r * r / (2 * m));
}

// The radius at which a geodesic starts: an orbit's, a fall's from rest (or its reference radius,
// from infinity).
double starting_radius(const HoleGeodesic& geodesic) {
  if (const auto* orbit = std::get_if<HoleOrbit>(&geodesic.path)) return orbit->radius;
  const auto& fall = std::get<HoleFall>(geodesic.path);
  return std::isfinite(fall.from) ? fall.from : fall.reference;
}
}  // namespace

Flight::Flight(const Camera& start) : camera(start), speed(length(start.world_line.velocity)) {
  // A scene's camera on a geodesic goes on along it.
  if (start.motion.geodesic)
    mode =
        std::holds_alternative<HoleOrbit>(start.motion.geodesic->path) ? Mode::kOrbit : Mode::kFall;
}

bool Flight::advance(double proper_time, const BlackHole* hole) {
  WorldLine& w = camera.world_line;
  if (mode != Mode::kPowered) {
    Camera::Motion next = camera.motion;
    next.proper_time += proper_time;
    // A fall goes on through the horizon to the last moment the renderers draw, and stays.
    if (mode == Mode::kFall) {
      const double last = std::nextafter(drawn_proper_times(*next.geodesic).latest, -1e300);
      if (!(camera.motion.proper_time < last)) return false;
      next.proper_time = std::min(next.proper_time, last);
    }
    const WorldLine moved = camera_observation(next);
    camera.motion = next;
    w = moved;
    speed = length(w.velocity);
    return true;
  }
  const double dt = proper_time * lorentz_gamma(w.velocity);
  const Vec3 next = w.position + w.velocity * dt;
  if (hole && length(next - hole->position) < kClosestToHole * hole->mass) {
    set_speed(0);
    return false;
  }
  w.position = next;
  w.time += dt;
  return true;
}

std::optional<std::string> Flight::start_orbit(const BlackHole& hole) {
  if (inside_horizon()) return kInsideHorizon;
  const WorldLine& w = camera.world_line;
  const Vec3 from_hole = w.position - hole.position;
  const double r = length(from_hole), m = hole.mass;
  if (!(r > 3 * m * (1 + 1e-6)))
    return "no circular orbit at r = " + std::to_string(r / m) +
           "M: circular geodesics lie outside the photon sphere, r = 3M";
  const Vec3 axis_x = from_hole / r;
  Vec3 along = camera.forward - axis_x * dot(camera.forward, axis_x);
  if (!(length(along) > 1e-9)) along = cross(camera.up, axis_x);
  // Through the current event: at phase + Omega t = 0 now, proper time t sqrt(1 - 3M/r).
  HoleOrbit orbit;
  orbit.radius = r;
  orbit.axis_x = axis_x;
  orbit.axis_y = normalize(along);
  orbit.phase = -circular_orbit_angular_velocity(m, r) * w.time;
  camera.motion = {};
  camera.motion.geodesic = HoleGeodesic{hole.position, m, orbit};
  camera.motion.proper_time = w.time * std::sqrt(1 - 3 * m / r);
  camera.world_line = camera_observation(camera.motion);
  speed = length(camera.world_line.velocity);
  mode = Mode::kOrbit;
  return std::nullopt;
}

std::optional<std::string> Flight::start_fall(const BlackHole& hole) {
  const WorldLine& w = camera.world_line;
  const Vec3 from_hole = w.position - hole.position;
  const double r = length(from_hole), m = hole.mass;
  if (inside_horizon()) return kInsideHorizon;
  if (!(r > kClosestToHole * m))
    return "too near the horizon to fall: the viewer stops the camera at r = " +
           std::to_string(kClosestToHole) + "M";
  HoleFall fall;
  fall.from = r;
  fall.direction = from_hole / r;
  fall.time = w.time;
  camera.motion = {};
  camera.motion.geodesic = HoleGeodesic{hole.position, m, fall};
  camera.world_line = camera_observation(camera.motion);
  speed = 0;
  mode = Mode::kFall;
  return std::nullopt;
}

bool Flight::inside_horizon() const {
  const auto& g = camera.motion.geodesic;
  return mode == Mode::kFall && g &&
         !(length(camera.world_line.position - g->hole) > 2 * g->mass * (1 + kCameraHorizonMargin));
}

void Flight::set_speed(double new_speed) {
  if (inside_horizon()) return;  // no static observer to move against: it can only fall on
  // Leaving a geodesic: powered flight from its current event.
  mode = Mode::kPowered;
  camera.motion.geodesic.reset();
  speed = std::clamp(new_speed, 0.0, kMaxSpeed);
  camera.world_line.velocity = normalize(camera.forward) * speed;
}

void Flight::change_speed(int steps) {
  set_speed(std::tanh(std::atanh(std::min(speed, kMaxSpeed)) + 0.1 * steps));
}

void Flight::turn(double yaw, double pitch) {
  const Vec3 up = normalize(camera.up);
  Vec3 forward = Mat3::rotation(up, yaw) * normalize(camera.forward);
  const Vec3 right = normalize(cross(forward, up));
  const Vec3 pitched = Mat3::rotation(right, pitch) * forward;
  // Never quite straight up or down, where the view's up would be undefined.
  if (std::abs(dot(pitched, up)) < 0.995) forward = pitched;
  camera.forward = forward;
}

double default_time_scale(const Scene& scene) {
  if (!scene.black_hole) return 1;
  const BlackHole& hole = *scene.black_hole;
  double shortest =
      free_fall_time(length(scene.camera.world_line.position - hole.position), hole.mass);
  for (const Object& o : scene.objects)
    if (o.motion.geodesic)
      shortest = std::min(shortest, free_fall_time(starting_radius(*o.motion.geodesic), hole.mass));
  return shortest / kSceneSeconds;
}

}  // namespace lightcone

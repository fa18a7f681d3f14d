#include "viewer/flight.hpp"

#include <algorithm>
#include <cmath>

#include "lightcone/physics/lorentz.hpp"

namespace lightcone {

namespace {
constexpr double kMaxSpeed = 0.999;
}

Flight::Flight(const Camera& start) : camera(start), speed(length(start.world_line.velocity)) {}

bool Flight::advance(double proper_time, const BlackHole* hole) {
  WorldLine& w = camera.world_line;
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

void Flight::set_speed(double new_speed) {
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

}  // namespace lightcone

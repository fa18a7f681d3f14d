// The viewer's camera: where it is and how it moves, as the world-line the scene format gives
// it (an event and a velocity), changed by instantaneous boosts.
#pragma once

#include "lightcone/physics/vec.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct Flight {
  Camera camera;     // world_line: the current event and velocity
  double speed = 0;  // |velocity|

  explicit Flight(const Camera& start);
  // Advances the camera along its world-line by `proper_time` of its own clock. Near a black
  // hole it stops (speed 0) rather than come within kClosestToHole M of it: its velocity is the
  // one the static observer at its event measures, and there is none inside the horizon.
  // Returns false when it stopped so.
  static constexpr double kClosestToHole = 2.01;
  bool advance(double proper_time, const BlackHole* hole = nullptr);
  // An instantaneous boost to `speed` (below 1) along the current view direction, through the
  // current event.
  void set_speed(double new_speed);
  // Steps the speed by `steps` tenths of rapidity (so that steps near c stay even).
  void change_speed(int steps);
  // Turns the view by yaw (about camera.up) and pitch (about the right axis), in radians; the
  // velocity keeps its direction.
  void turn(double yaw, double pitch);
};

}  // namespace lightcone

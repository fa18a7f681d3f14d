// The viewer's camera: where it is and how it moves, as the world-line the scene format gives
// it (an event and a velocity), changed by instantaneous boosts; near a black hole it may also
// move freely, on a circular orbit or a radial fall (the scene format's camera motions).
#pragma once

#include <optional>
#include <string>

#include "lightcone/physics/vec.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct Flight {
  Camera camera;     // world_line: the current event and velocity
  double speed = 0;  // |velocity|
  // Powered: the velocity holds until a boost changes it (near a hole, against the static
  // observer where the camera is: hovering at speed 0). Orbit, fall: on camera.motion's
  // geodesic, advanced in proper time; a boost or a stop returns to powered flight.
  enum class Mode { kPowered, kOrbit, kFall };
  Mode mode = Mode::kPowered;

  explicit Flight(const Camera& start);
  // Advances the camera along its world-line by `proper_time` of its own clock. Near a black
  // hole, powered, it stops (speed 0, hovering) rather than come within kClosestToHole M of it:
  // its velocity is the one the static observer at its event measures, and there is none
  // inside the horizon. Falling, it goes on through the horizon and stays where the renderers
  // stop drawing (r = kCameraInnermostRadius M). Returns false when it stopped so.
  static constexpr double kClosestToHole = 2.01;
  bool advance(double proper_time, const BlackHole* hole = nullptr);
  // Near `hole`, from the current event: the circular geodesic through it (radius r > 3M, in
  // the plane of the hole, the camera and its view direction, turning toward the view), or the
  // radial fall from rest there. Each is refused (the reason returned, nothing changed) where it
  // does not exist: inside 3M (1 + 1e-6) for an orbit; within kClosestToHole M for a fall.
  std::optional<std::string> start_orbit(const BlackHole& hole);
  std::optional<std::string> start_fall(const BlackHole& hole);
  // Whether the camera has fallen through the horizon: then it falls on, and boosts, stops and
  // orbits are refused (set_speed does nothing; the others say why).
  bool inside_horizon() const;
  static constexpr const char* kInsideHorizon =
      "inside the horizon: there is no static observer to hover or boost against, and no orbit; "
      "the camera can only fall on";
  // An instantaneous boost to `speed` (below 1) along the current view direction, through the
  // current event (powered flight from then on).
  void set_speed(double new_speed);
  // Steps the speed by `steps` tenths of rapidity (so that steps near c stay even).
  void change_speed(int steps);
  // Turns the view by yaw (about camera.up) and pitch (about the right axis), in radians; the
  // velocity keeps its direction.
  void turn(double yaw, double pitch);
};

// The viewer's clock (units of the camera's proper time a second) where no --time-scale is
// given: 1, and near a black hole the scene's own time shown in kSceneSeconds. That time is the
// shortest free fall from rest to the centre, (pi/2) sqrt(r^3 / 2M) (the proper time along the
// cycloid r = (r0 / 2)(1 + cos eta)), from where the camera is now and from where each body on a
// geodesic starts (a fall's `from`, or its `reference` when it falls from infinity; an orbit's
// radius): the bodies as they were set going, since what the camera sees of them left them
// earlier. A fall from 10M (35.1M of its own time) then takes 10 s, where at 1 a second it took
// more than half a minute, and one from 60M (516M) most of ten minutes.
inline constexpr double kSceneSeconds = 10;
double default_time_scale(const Scene& scene);

}  // namespace lightcone

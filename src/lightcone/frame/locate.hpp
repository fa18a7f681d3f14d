// Where a point appears: the inverse of the renderer for one point, ignoring occlusion.
#pragma once

#include <optional>
#include <string>

#include "lightcone/physics/vec.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct LocateQuery {
  enum class Kind { ObjectPoint, WorldPoint, SkyDirection };
  Kind kind = Kind::WorldPoint;
  std::string object;  // for ObjectPoint
  Vec3 value;          // point in the object's shape coordinates / point at rest in W / direction
};

struct LocateResult {
  double pixel_x = 0, pixel_y = 0;  // image point (pixel (i, j) has its centre at i+.5, j+.5)
  Vec3 direction;                   // apparent look direction, camera rest frame
  // The emission event in W; absent for a direction at infinity.
  std::optional<double> emission_time;
  std::optional<Vec3> emission_position;
  std::optional<double> distance;  // light travel distance in the camera frame
  // The object's own clock when it emitted the light (for an object's point).
  std::optional<double> emission_proper_time;
  bool in_view = false;
  double doppler = 1;  // D = nu_camera / nu_emitter for light from the located point
};

// Throws std::invalid_argument when the named object does not exist.
LocateResult locate(const Scene& scene, const LocateQuery& query);

}  // namespace lightcone

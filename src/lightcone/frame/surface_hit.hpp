// Where a camera ray (or a rasterised fragment) meets a body: what both renderers hand to the
// emission, pattern and lighting code.
#pragma once

#include <array>

#include "lightcone/physics/vec.hpp"

namespace lightcone {

struct Hit {
  int body = -1;                   // index into ResolvedScene::bodies
  double s = 0;                    // ray parameter: light travel time (or distance) in F
  Vec3 shape_point;                // the point met, in the shape's own coordinates
  std::array<double, 2> uv{0, 0};  // texture coordinates (v from the top of the image)
  Vec3 shape_normal;               // unit, in shape coordinates, facing the incoming ray
  double proper_time = 0;          // the body's own clock at the event met
  Vec3 velocity;                   // of the point met, in F (its body's, turned by any spin)
  double spin_angle = 0;           // a spinning body's turn at the event met (radians)
};

}  // namespace lightcone

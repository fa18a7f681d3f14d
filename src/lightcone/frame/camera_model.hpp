// The pinhole mapping between image points and look directions in the camera's rest frame.
#pragma once

#include "lightcone/physics/vec.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct CameraBasis {
  Vec3 forward, right, up;  // orthonormal, in the camera's rest frame
  double tan_half_fov = 1;  // vertical
  double aspect = 1;        // width / height
  int width = 1, height = 1;
};

CameraBasis camera_basis(const Camera& camera);

// Unit look direction through image point (x, y): pixel (i, j) has its centre at (i+.5, j+.5);
// x grows to the right, y downwards.
Vec3 look_direction(const CameraBasis& basis, double x, double y);

struct ImagePoint {
  double x = 0, y = 0;
  bool in_front = false;  // the direction lies in the forward half-space
};
// Inverse of look_direction: the image point where a look direction lands.
ImagePoint project_direction(const CameraBasis& basis, const Vec3& direction);

// The look directions of the image (its edges included) along which dot(u, b) is smallest and
// largest. Exact: the image is a spherical polygon bounded by four great-circle arcs, so each
// extreme lies at +-b itself (when in view), at a corner, or on an edge where the edge's great
// circle comes nearest to +-b. For b = 0 both are the forward direction.
struct ViewExtremes {
  Vec3 smallest, largest;
};
ViewExtremes view_extremes_along(const CameraBasis& basis, const Vec3& b);

}  // namespace lightcone

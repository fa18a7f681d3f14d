// Camera rays near one Schwarzschild black hole (docs/design/black-hole.md): each is a null
// geodesic in closed form (physics/schwarzschild.hpp), with no step size. A ray leaves the
// camera's event backward in time along its look direction; its plane holds the hole, and in
// that plane it sweeps the angle phi about the hole while its radius follows the orbit equation.
// It ends on the accretion disk (the first crossing of the disk's plane inside its annulus), at
// the horizon, or far away in the sky. This is the walker beside the straight rays of
// tracer.hpp: scenes without a hole never come here.
#pragma once

#include "lightcone/frame/hole_view.hpp"
#include "lightcone/physics/vec.hpp"

namespace lightcone {

enum class CurvedRayEnd { kSky, kDisk, kHorizon };

struct CurvedRay {
  CurvedRayEnd end = CurvedRayEnd::kHorizon;
  // How many times the ray has swept a multiple of pi about the hole before its end: 0 for the
  // primary image, 1 for the secondary (around the far side), and so on (ceil(phi / pi) - 1).
  int order = 0;
  double phi = 0;  // the angle swept about the hole to the end
  // g = nu_camera / nu_emitter for light along the ray: gravitational and kinematic in one
  // factor, (p . u_camera) / (p . u_emitter). 0 at the horizon.
  double shift = 0;
  Vec3 sky_direction;      // kSky: the look direction in the sky's pattern coordinates
  double disk_radius = 0;  // kDisk: the Schwarzschild r where the ray meets the disk
};

// The ray with look direction u (unit, in the camera's rest frame F).
CurvedRay follow_curved_ray(const HoleView& hole, const Vec3& u);

}  // namespace lightcone

// Camera rays near one Schwarzschild black hole (docs/design/black-hole.md): each is a null
// geodesic in closed form (physics/schwarzschild.hpp), with no step size. A ray leaves the
// camera's event backward in time along its look direction; its plane holds the hole, and in
// that plane it sweeps the angle phi about the hole while its radius follows the orbit equation.
// It ends on the accretion disk (the first crossing of the disk's plane inside its annulus), at
// the horizon, or far away in the sky. This is the walker beside the straight rays of
// trace/tracer.hpp: scenes without a hole never come here.
#pragma once

#include <cmath>
#include <span>

#include "lightcone/frame/hole_view.hpp"
#include "lightcone/frame/surface_hit.hpp"
#include "lightcone/physics/schwarzschild.hpp"
#include "lightcone/physics/vec.hpp"

namespace lightcone {

class CurvedBodies;

// A camera ray's path about the hole: in the plane of the hole, the camera (along e1) and the
// look direction (toward e2), its position after sweeping phi is
// centre + M r(phi) (cos(phi) e1 + sin(phi) e2), r(phi) = radius_after_angle(sweep, phi): its
// lengths (r, the impact parameter) are in units of M (hole_view.hpp).
struct CurvedPath {
  Vec3 e1, e2;
  double impact = 0;
  bool outward = false;  // r grows at the camera
  PhotonOrbit orbit;
  AngleSweep sweep;
  // The energy the camera measures for the photon, in units of its conserved energy.
  double camera_energy = 1;
  // No light comes along it: from inside the horizon, light of no positive conserved energy
  // (which nothing outside sends; the walker ends it at the horizon).
  bool dark = false;

  Vec3 offset(double phi, double r) const {
    return e1 * (r * std::cos(phi)) + e2 * (r * std::sin(phi));
  }
};
CurvedPath curved_path(const HoleView& hole, const Vec3& u);
// curved_path of each look direction (out[i] for u[i]), the same to the bit, several at once: their
// sweeps' Carlson integrals run together (prepare_sweeps), which a ray's alone wait on.
void curved_paths(const HoleView& hole, std::span<const Vec3> u, std::span<CurvedPath> out);

enum class CurvedRayEnd { kSky, kDisk, kHorizon, kBody };

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
  double disk_radius = 0;  // kDisk: the Schwarzschild r / M where the ray meets the disk
  Hit hit;                 // kBody: the body and the point met (its s is phi)
  Vec4 event;              // kBody: the event met, in W
  // kBody: the direction in which the light leaves the point toward the camera, and the
  // velocity of the body there, both in the static observer's frame at the event (a lit
  // point's shading reads them).
  Vec3 to_camera, local_velocity;
};

// The ray with look direction u (unit, in the camera's rest frame F), meeting the scene's bodies
// too when `bodies` is given (curved_bodies.hpp).
CurvedRay follow_curved_ray(const HoleView& hole, const Vec3& u,
                            const CurvedBodies* bodies = nullptr);
// follow_curved_ray for each look direction (out[i] for u[i]), the same rays, their paths
// prepared together (curved_paths): a packet of camera rays.
void follow_curved_rays(const HoleView& hole, std::span<const Vec3> u, const CurvedBodies* bodies,
                        std::span<CurvedRay> out);

}  // namespace lightcone

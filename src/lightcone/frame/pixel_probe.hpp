// What the camera sees through a point of its picture (`lightcone locate --pixel`): locate's
// inverse. locate (locate.hpp) answers where a point is seen; a probe follows the exact camera
// ray through an image point, as the ray tracer does, and answers what it meets first and when
// that light left it.
#pragma once

#include <optional>

#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/surface_hit.hpp"
#include "lightcone/physics/vec.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

enum class ProbeMeets { kObject, kSky, kDisk, kShadow };

struct PixelProbe {
  double pixel_x = 0, pixel_y = 0;  // the image point (pixel (i, j) covers [i, i+1) x [j, j+1))
  Vec3 direction;                   // its look direction, in the camera's rest frame
  ProbeMeets meets = ProbeMeets::kSky;
  int object = -1;  // kObject: its index in the scene's objects
  Vec3 point;       // kObject: the point met, in the object's own (shape) coordinates
  // kSky: the direction far away the light comes from, as locate's --direction takes it (the
  // sky's coordinates turned by sky.rotation); kDisk: the disk's radius met (W's units).
  Vec3 sky_direction;
  double disk_radius = 0;
  // On a surface (an object or the disk): the emission event in W, the light's travel distance
  // in the camera's frame (locate's distance), and an object's own clock then.
  std::optional<double> emission_time, distance, emission_proper_time;
  std::optional<Vec3> emission_position;
  double doppler = 1;  // D = nu_camera / nu_emitter; near a hole g (0 in the shadow)
  int order = 0;       // near a hole: the image order (how often the ray swept pi about it)
};

// The probe of image point (x, y) of `scene`, which request_rules' probe_refused lets through:
// `lightcone locate --pixel`, the Python module's locate(pixel=...), the viewer's and the web
// page's clicks. The exact camera ray through the point, meeting each body directly
// (straight_hit.hpp; near a hole along the chords of the curved ray, curved_bodies.hpp) with no
// acceleration structure to build: a probe costs its one ray.
PixelProbe probe_pixel(const Scene& scene, double x, double y);

// The probe of look direction u through image point (x, y), from what the straight ray met
// first (`hit`; none: the sky).
PixelProbe probe_on_straight_ray(const ResolvedScene& scene, double x, double y, const Vec3& u,
                                 const std::optional<Hit>& hit);
// The same near a black hole, from the exact curved ray (follow_curved_ray, with the scene's
// bodies).
PixelProbe probe_on_curved_ray(const ResolvedScene& scene, double x, double y, const Vec3& u,
                               const CurvedRay& ray);

}  // namespace lightcone

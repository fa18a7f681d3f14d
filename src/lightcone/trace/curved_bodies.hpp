// Bodies met along curved camera rays near a black hole (docs/design/black-hole.md, "Bodies").
//
// A body near the hole is at rest or moves on a straight coordinate line; its shape in W's
// coordinates is the flat one (Lorentz-contracted by its coordinate velocity, as in flat space).
// A camera ray's path (curved_ray.hpp) is followed in chords, straight segments of W events,
// only over the angles where it can come near the body: the ray's plane cuts the body's ball
// (or the tube its ball sweeps) in a disc, seen from the hole within a window of angles, once
// a winding. Each chord stays within kChordError times the body's radius of the true path (the
// path's curvature is known in closed form), and is tested against the body exactly, in the
// body's own coordinates. The first chord that meets it brackets the hit, which is then solved on
// the true path, to double precision, with the surface met (a sphere, a face's or triangle's
// plane) and Boost's TOMS 748: a grazing hit within the chord error of the path can be missed,
// nothing else. The event met is on the true path, so its time includes the Shapiro delay.
#pragma once

#include <vector>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/trace/curved_ray.hpp"
#include "lightcone/trace/tracer.hpp"

namespace lightcone {

class CurvedBodies {
 public:
  // The largest distance of a chord from the path, in units of the radius of the body it tests.
  static constexpr double kChordError = 1e-5;

  CurvedBodies(const ResolvedScene& scene, const Tracer& tracer);

  // Whether the ray meets a body before sweeping the angle `limit`; if so, `ray` gets the end
  // kBody, the angle phi, the hit, its event and its shift g.
  bool first_hit(const HoleView& hole, const CurvedPath& path, double limit, CurvedRay& ray) const;

 private:
  struct Body {
    int index = 0;
    Vec3 position;  // of its origin at W-time `time`, relative to the hole
    Vec3 velocity;  // coordinate velocity
    double time = 0, proper_time = 0;
    double radius = 0;  // of its ball about its origin, in its rest frame (holds it in W too)
  };
  const ResolvedScene& scene_;
  const Tracer& tracer_;
  std::vector<Body> bodies_;
};

}  // namespace lightcone

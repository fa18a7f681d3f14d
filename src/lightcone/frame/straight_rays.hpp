// Camera rays that a black hole leaves straight to within the image's resolution
// (docs/design/black-hole.md, "Bodies": "Straight rays"). Such a ray is traced as in flat space,
// through the tracer's packets: a hole of 1e-9 units of mass 866 units away bends light by some
// 5e-12 radians, and its picture is the flat one, at the flat scene's cost.
//
// A ray is straight when the whole of its true path stays within kTolerance of a pixel, as the
// camera sees it, of the straight ray the flat tracer follows, and its light's delay moves no
// body by more: over a length l of path, the path is at most
//   l (delta_0 + alpha + 2M / (r_min - 2M))
// from the straight ray, where delta_0 is the angle between the two rays' directions at the camera
// (exact, in W's coordinates), alpha = pi (1 / sqrt(1 - 3M / r_min) - 1) bounds the path's
// turning (the orbit equation's integrand, (u_p^2 - u^2)(1 - 3M u_p) <= 1/b^2 - u^2 + 2M u^3,
// bounds its total sweep by pi / sqrt(1 - 3M / r_p); the path turns one way only), and the last
// term bounds the Shapiro delay over the length (the coordinate speed of light is at least
// f = 1 - 2M / r), which moves a body at speed below 1 by less. A pixel spans l theta_pixel at
// that length, so the test is independent of the length: the sum at most kTolerance
// theta_pixel.
//
// Only scenes that flat space draws alike ask (and only where the camera is high enough in the
// well that a ray can be straight at all): light delay on, a camera not falling, every body on
// a straight coordinate line (none on an orbit or a fall), and no lit surface (a lit point's
// light legs are not the camera ray's).
#pragma once

#include <optional>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/vec.hpp"

namespace lightcone {

class StraightRays {
 public:
  // The largest distance of a straight ray from its true path, in pixels.
  static constexpr double kTolerance = 1e-6;

  // Null where the scene has no hole, or the flat tracer cannot draw it (above).
  static std::optional<StraightRays> of(const ResolvedScene& scene);

  // Whether the ray with look direction u (unit, in the camera's rest frame F) is straight.
  bool straight(const Vec3& u) const;

 private:
  explicit StraightRays(const ResolvedScene& scene);
  const ResolvedScene* scene_;
  double pixel_angle_ = 0;  // the least angle between neighbouring pixels' centres
};

}  // namespace lightcone

// Bodies met along curved camera rays near a black hole (docs/design/black-hole.md, "Bodies").
//
// A body near the hole is at rest, moves on a straight coordinate line, or on a geodesic (a
// circular orbit or a radial fall: physics/hole_world_line.hpp); at each coordinate time its
// shape in W's coordinates is the flat one, Lorentz-contracted by its coordinate velocity then,
// as in flat space. A camera ray's path (curved_ray.hpp) is followed in chords, straight
// segments of W events, only over the angles where it can come near the body: the ray's plane
// cuts the region the body's ball sweeps (a ball, a tube along its line, a torus about its
// orbit, a tube along its line of fall) within windows of angles about the hole, once a
// winding. Each chord stays within kChordError times the body's radius of the true path (the
// path's curvature is known in closed form, and the body's acceleration bounded), and is tested
// against the body exactly, in the body's own coordinates. The first chord that meets it
// brackets the hit, which is then solved on the true path, to double precision, with the
// surface met (a sphere, a face's or triangle's plane) and Boost's TOMS 748: a grazing hit
// within the chord error of the path can be missed, nothing else. The event met is on the true
// path, so its time includes the Shapiro delay.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "lightcone/frame/body_segments.hpp"
#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/shadow_query.hpp"
#include "lightcone/physics/hole_world_line.hpp"

namespace lightcone {

// Bounds on the W time of the point b of a light path near the hole (positions relative to it,
// lengths and times in units of its mass M) reached backward from point a over the angle
// dphi > 0 about it, given bounds on a's; `turn` is the path's turning radius if it turns
// between them, else 0, and `impact` its impact parameter b. Along a null path
// f dt^2 = dr^2 / f + r^2 dphi^2 (f = 1 - 2M/r), so |dr| / f <= dt <= |dr| / f + r dphi / sqrt(f),
// and dt is at least the coordinate length sqrt(dr^2 + r^2 dphi^2) (f <= 1). The integral of
// |dr| / f is the variation D of the tortoise coordinate r* = r + 2M ln(r / 2M - 1) over the
// stretches where r is monotone: the time taken is at least D and the chord |b - a|, and at most
// D plus the larger radius times dphi over sqrt(f) at the least radius between them. Where r is
// monotone between them, dt / |dr| = 1 / (f sqrt(1 - q)) with q = b^2 f / r^2 (the orbit
// equation), which is greatest at r = 3M and least at an end: the time lies within
// [D / sqrt(1 - q_least), D / sqrt(1 - q_most)] too.
struct TimeBounds {
  double early = 0, late = 0;
};
TimeBounds light_cone_bounds(const TimeBounds& a, const Vec3& a_x, const Vec3& b_x, double dphi,
                             double turn, double impact);

class CurvedBodies : public CurvedShadowQuery {
 public:
  // The largest distance of a chord from the path, in units of the radius of the body it tests.
  static constexpr double kChordError = 1e-5;

  // Where a path starts: its radius and W time, in units of the hole's mass (hole_view.hpp).
  struct PathStart {
    double radius = 0, time = 0;
  };

  // The chords meet the bodies through `segments` (the ray tracer's, or DirectBodySegments); both
  // must outlive this.
  CurvedBodies(const ResolvedScene& scene, const BodySegments& segments);

  // Whether the ray meets a body before sweeping the angle `limit`; if so, `ray` gets the end
  // kBody, the angle phi, the hit, its event and its shift g.
  bool first_hit(const HoleView& hole, const CurvedPath& path, double limit, CurvedRay& ray) const;

  // Whether a body blocks a lit surface's light (frame/shadow_query.hpp), met as camera rays meet
  // them, along the path from the surface event.
  bool occluded(const CurvedShadowRay& ray) const override;

 private:
  // The body a path meets first between swept angles `from` and `limit`: its index, the angle,
  // the event (relative to the hole, in units of its mass) and shape point met, the chord's
  // direction there (shape coordinates), the triangle, and whether the path had passed its turning
  // point.
  struct Found {
    int body = -1;
    double phi = 0;
    Vec4 event;
    Vec3 shape_point, incoming;
    unsigned prim = 0;
    bool turned = false;
  };
  bool nearest(const PathStart& start, const CurvedPath& path, double from, double limit,
               Found& found) const;
  // The same for a path along the line through the hole (b = 0, curved_axis.cpp), which sweeps
  // no angle: the first body met between radii `from` and `to` along it (to its end: infinity
  // outward, the horizon inward).
  bool nearest_on_axis(const PathStart& start, const CurvedPath& path, double from, double to,
                       Found& found) const;

  // Its lengths and times in units of the hole's mass, as the paths'. (Its motion's tests are
  // curved_body_motion.cpp's; the walk along a ray is curved_bodies.cpp's.)
  struct Body {
    int index = 0;
    HoleWorldLine line;  // of its origin
    double radius = 0;   // of its ball about its origin, in its rest frame (holds it in W too)
    Mat3 to_shape;       // its rest frame's axes to its shape's coordinates: M (R S)^-1
    // Whether the chord between points a and b (relative to the hole) can come within the
    // body's radius of where its origin ever is (its orbit's plane, its line of fall): a test
    // before the chord is timed. Always, for a straight line, whose windows are tight. Both
    // tests widen the body by `margin`.
    bool may_meet_in_space(const Vec3& a, const Vec3& b, double margin) const;
    // Whether the chord between events a and b (positions relative to the hole) can come within
    // the body's radius of where its origin is between their times, given its states at
    // them; `acceleration` gets a bound on its coordinate acceleration then (0 on a straight
    // line).
    bool may_meet_in_time(const Vec4& a, const Vec4& b, const HoleWorldLineState& state_a,
                          const HoleWorldLineState& state_b, double margin,
                          double& acceleration) const;
    // Whether the chord between points a and b (relative to the hole) can come within the
    // body's radius, widened by `margin`, of where its origin is at some time in [t0, t1]: a
    // test of a chord whose times are known only within the light cone's bounds, which needs no
    // solve of its path's times nor of the body's motion.
    bool may_meet_between(const Vec3& a, const Vec3& b, double t0, double t1, double margin) const;
    // The radii a fall's origin can be at over the coordinate times [t0, t1] (t0 may be minus
    // infinity), from its sampled times without solving its fall; false where they have no
    // bound (a fall from infinity, before its first sample).
    bool fall_radii_between(double t0, double t1, double& lowest, double& highest) const;
    // A fall's radius at coordinate times (increasing; the radius decreasing with them, from the
    // fall's start), which bound its radius over an interval of times without solving its fall.
    std::vector<double> fall_times, fall_radii;
    // A falling box's or mesh's prism along its line of fall (its box's outline across the line,
    // convex, in the axes across, and its extent along it, the origin's included), which holds
    // it whatever its contraction along the line: tighter than its ball. Empty: its ball.
    std::vector<std::array<double, 2>> outline;
    Vec3 across_x, across_y;
    double along_lo = 0, along_hi = 0;
    // Its box in its shape's coordinates (a mesh's bounds), with the prism.
    Vec3 shape_lower, shape_upper;
    // Whether the segment from a to b comes within `margin` of the prism with its origin at
    // radii in [lowest, highest] on its line.
    bool prism_near(const Vec3& a, const Vec3& b, double lowest, double highest,
                    double margin) const;
    // Whether the segment from a to b can come within `margin` of the box itself with its
    // origin at radii in [lowest, highest] on its line, whatever its contraction there: a
    // segment's shape coordinates over those radii and contractions lie in a parallelogram
    // (docs/design/black-hole.md, "Bodies"), tested against the box by separating axes.
    bool swept_box_near(const Vec3& a, const Vec3& b, double lowest, double highest,
                        double margin) const;
    // Its origin's state at time t: on a fall, its radius solved on t(r) in closed form within
    // the bracket of its sampled times (fall_times) about t, else its world-line's.
    HoleWorldLineState state_at(double t) const;
    // Where the body is at the event's time, in its shape's coordinates: by its resolved
    // (affine) map on a straight line, by its state then on a geodesic (`state`, if known).
    Vec3 shape_point(const WorldShapeMap& world, const Vec4& event, const HoleView& hole,
                     const HoleWorldLineState* state = nullptr) const;
  };
  const ResolvedScene& scene_;
  const HoleView& hole_;
  const BodySegments& segments_;
  std::vector<Body> bodies_;
};

// Shadows near a black hole over the scene's bodies (null where it has no hole or no bodies): the
// paths from lit surfaces met as camera rays meet them, their chords through `segments`, which
// the query owns. The scene must outlive it.
std::unique_ptr<CurvedShadowQuery> curved_body_shadows_met_by(
    const ResolvedScene& scene, std::unique_ptr<const BodySegments> segments);

}  // namespace lightcone

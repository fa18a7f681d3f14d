// Where a ray meets a body: in its shape's coordinates, and for a spinning body, whose shape
// turns while the ray crosses it, on the curve the straight rest-frame ray traces through the
// turning shape (docs/design/spinning-bodies.md).
#pragma once

#include <functional>
#include <limits>
#include <optional>

#include "lightcone/frame/body_segments.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/shape_intersection.hpp"

namespace lightcone {

struct ShapeHit {
  double s = std::numeric_limits<double>::infinity();
  unsigned prim = 0;
  float bary_u = 0, bary_v = 0;
  // On a spinning body: the point met in shape coordinates and in the rest frame, and the
  // body's clock there.
  Vec3 shape_point, rest_point;
  double proper_time = 0;
};

// A spinning body's turn is sampled along each ray so that the chords between samples stay
// within R (1 - cos(angle / 2)) ~ 1.1e-4 R of the true path through the shape's coordinates;
// the hit is then solved on the true path exactly.
constexpr double kSpinChordAngle = 0.03;
constexpr int kMaxSpinChords = 4096;

// Where a chord from `from` to `to` in a mesh's shape coordinates first meets the mesh: the ray
// tracer's Embree scene of it, or a DirectBodySegments' hierarchy (where there is no Embree).
using MeshChordTest = std::function<std::optional<SegmentHit>(const Vec3& from, const Vec3& to)>;

// The first hit, at a parameter in [tnear, tfar], of the ray `frozen` (the ray in the shape's
// coordinates at the spin angle of its origin's clock) on `object` spinning as `spin` says,
// its clock along it tau0 + s tau1. The straight ray in the rest frame is a curve in the
// shape's coordinates, followed in chords (kSpinChordAngle); the first chord that meets the
// shape brackets the hit, which is then found on the curve by bisection of the surface met (a
// face's plane, a triangle's plane, the sphere). A mesh's chords are met by `mesh` (empty for
// an analytic shape).
ShapeHit intersect_spinning_body(const ResolvedSpin& spin, const Object& object,
                                 const MeshChordTest& mesh, const ShapeRay& frozen, double tau0,
                                 double tau1, double tnear, double tfar);

// A camera ray's `hit` (its body, s and shape point set) on a spinning body completed from
// `exact`, the hit intersect_spinning_body found for the camera ray whose frozen ray has
// direction `frozen_direction`: the body's clock and turn at the event met and the point's own
// velocity in F. Returns the direction the ray comes in along, in shape coordinates at that turn
// (for complete_surface_hit's normal).
Vec3 complete_spinning_hit(const ResolvedScene& scene, const ResolvedBody& body,
                           const ShapeHit& exact, const Vec3& frozen_direction, Hit& hit);

}  // namespace lightcone

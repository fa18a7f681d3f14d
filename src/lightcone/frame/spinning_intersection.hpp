// Where a ray meets a body: in its shape's coordinates, and for a spinning body, whose shape
// turns while the ray crosses it, on the curve the straight rest-frame ray traces through the
// turning shape (docs/design/spinning-bodies.md).
#pragma once

#include <embree3/rtcore.h>

#include <limits>

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

// The first hit, at a parameter in [tnear, tfar], of the ray `frozen` (the ray in the shape's
// coordinates at the spin angle of its origin's clock) on `object` spinning as `spin` says,
// its clock along the ray tau0 + s tau1. The straight ray in the rest frame is a curve in the
// shape's coordinates, followed in chords (kSpinChordAngle); the first chord that meets the
// shape brackets the hit, which is then found on the curve by bisection of the surface met (a
// face's plane, a triangle's plane, the sphere). `mesh` is the mesh's Embree scene (null for
// an analytic shape).
ShapeHit intersect_spinning_body(const ResolvedSpin& spin, const Object& object, RTCScene mesh,
                                 const ShapeRay& frozen, double tau0, double tau1, double tnear,
                                 double tfar, RTCIntersectContext* context);

}  // namespace lightcone

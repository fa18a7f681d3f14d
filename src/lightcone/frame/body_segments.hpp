// Where a straight segment first meets a body, in the body's shape coordinates: the test that
// curved rays near a black hole (curved_bodies.hpp) make of each chord of their paths. The ray
// tracer answers it on Embree (trace/tracer.hpp); DirectBodySegments answers it where there is
// no Embree (the browser's page), for the raster renderer's shadows near a black hole.
#pragma once

#include <map>
#include <optional>
#include <vector>

#include "lightcone/frame/mesh_bvh.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/surface_hit.hpp"
#include "lightcone/physics/vec.hpp"

namespace lightcone {

// The parameter s in [0, 1] of the point from + s (to - from) met, and the mesh triangle met
// (its index, and the point's barycentric coordinates of its second and third corners).
struct SegmentHit {
  double s = 0;
  unsigned prim = 0;
  double bary_u = 0, bary_v = 0;
};

class BodySegments {
 public:
  virtual ~BodySegments() = default;
  // Where the segment from `from` to `to` in the shape coordinates of body `body` (which does not
  // spin) first meets it, if it does.
  virtual std::optional<SegmentHit> body_on_shape_segment(int body, const Vec3& from,
                                                          const Vec3& to) const = 0;
};

// Each body met directly: an analytic shape by its closed form, as the tracer meets it
// (shape_intersection.hpp), a mesh through a hierarchy of its triangles (mesh_bvh.hpp), each
// leaf's triangles met in double precision.
class DirectBodySegments final : public BodySegments {
 public:
  // The scene must outlive this.
  explicit DirectBodySegments(const ResolvedScene& scene);
  std::optional<SegmentHit> body_on_shape_segment(int body, const Vec3& from,
                                                  const Vec3& to) const override;

 private:
  const ResolvedScene& scene_;
  std::map<const Mesh*, MeshBvh> hierarchies_;    // one per mesh of the scene
  std::vector<const MeshBvh*> body_hierarchies_;  // per body (null for analytic shapes)
};

// Completes `hit` (its body and shape_point set; `prim` the mesh triangle met) with the texture
// coordinates and the normal facing `incoming` (a direction in shape coordinates), as a camera
// ray's hit has them; a point on a flat face of an analytic shape is put exactly on it.
void complete_surface_hit(const ResolvedScene& scene, const Vec3& incoming, Hit& hit,
                          unsigned prim);

}  // namespace lightcone

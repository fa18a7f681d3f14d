// Nearest-hit queries of camera rays against a resolved scene, on Embree.
//
// The top level is an Embree BVH over one user geometry per body, bounded by the body's
// conservative trace bounds in F. Its callback carries the ray into the body's shape
// coordinates, where the body is static, and intersects there: analytically for spheres, boxes
// and planes (double precision), or through the mesh's own Embree BVH, which is built once per
// mesh however many bodies use it.
#pragma once

#include <array>
#include <memory>
#include <optional>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/shadow_query.hpp"
#include "lightcone/frame/surface_hit.hpp"

namespace lightcone {

class Tracer : public ShadowQuery {
 public:
  explicit Tracer(const ResolvedScene& scene);
  ~Tracer() override;
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  // The nearest body along the ray with look direction u (unit, in F), if any.
  std::optional<Hit> trace(const Vec3& u) const;

  bool occluded(const Vec4& origin, const Vec4& direction, double t_near,
                double t_far) const override;

  // Bytes Embree holds for the acceleration structures (for memory benchmarks).
  std::size_t acceleration_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lightcone

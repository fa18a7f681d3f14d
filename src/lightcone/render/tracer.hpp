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

#include "lightcone/render/resolved_scene.hpp"

namespace lightcone {

struct Hit {
  int body = -1;                   // index into ResolvedScene::bodies
  double s = 0;                    // ray parameter: light travel time (or distance) in F
  Vec3 shape_point;                // the point met, in the shape's own coordinates
  std::array<double, 2> uv{0, 0};  // texture coordinates (v from the top of the image)
  Vec3 shape_normal;               // unit, in shape coordinates, facing the incoming ray
};

class Tracer {
 public:
  explicit Tracer(const ResolvedScene& scene);
  ~Tracer();
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  // The nearest body along the ray with look direction u (unit, in F), if any.
  std::optional<Hit> trace(const Vec3& u) const;

  // Whether a body blocks the spacetime segment origin + sigma direction, sigma in
  // (t_near, t_far), with events and direction in the world frame W (a shadow ray: its events
  // must lie within W-times [ResolvedScene::shadow_time_min, shadow_time_max]). Bodies are met
  // where they are at each event.
  bool occluded(const Vec4& origin, const Vec4& direction, double t_near, double t_far) const;

  // Bytes Embree holds for the acceleration structures (for memory benchmarks).
  std::size_t acceleration_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lightcone

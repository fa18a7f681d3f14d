// Nearest-hit queries of camera rays against a resolved scene, on Embree.
//
// Camera rays in the view go through the image's bins: every body whose conservative trace
// bounds in F lie before the camera is listed, nearest first, in the cells of the image plane
// that their projection covers, and a ray tests the bodies of its cell whose projected bounds
// hold its point, until the next is farther than its hit. Every camera ray leaves the camera's
// event, so these lists replace a tree's traversal, whose cost grows with the crowd a ray passes.
// Other camera rays, and bodies beside or behind the camera, go through an Embree BVH over one
// user geometry per body, bounded by its trace bounds. Shadow rays of a labelled light
// (ShadowLight) traverse the motion-blur BVH of the part of its labels theirs lies in, whose time
// is the label, with bounds at evenly spaced labels interpolated linearly between them; the others
// traverse bounds swept over the shadow window. Rays asked together go through Embree in packets.
// The callback carries each ray into the body's shape coordinates, where the body is static, and
// intersects there: analytically for spheres, boxes and planes (double precision), or through the
// mesh's own Embree BVH, which is built once per mesh however many bodies use it.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <span>

#include "lightcone/frame/body_segments.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/shadow_query.hpp"
#include "lightcone/frame/surface_hit.hpp"

namespace lightcone {

// How shadow rays of labelled lights (ShadowLight) find their bodies: through bounds over
// intervals of their labels (what renders use), or through the bounds swept over the whole
// shadow window that unlabelled rays use (to test the first against).
enum class ShadowBounds { kLabelled, kSwept };

// How camera rays find their bodies: through the image's bins (ImageBins in tracer.cpp: the
// bodies whose trace bounds cover a cell of the image plane, nearest first), falling back to the
// BVH for rays outside the view and bodies the bins cannot hold; or through the BVH alone (to
// test the first against).
enum class CameraRays { kImageBins, kBvh };

class Tracer : public ShadowQuery, public BodySegments {
 public:
  explicit Tracer(const ResolvedScene& scene, ShadowBounds shadow_bounds = ShadowBounds::kLabelled,
                  CameraRays camera_rays = CameraRays::kImageBins);
  ~Tracer() override;
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  // The nearest body along the ray with look direction u (unit, in F), if any.
  std::optional<Hit> trace(const Vec3& u) const;
  // The same for many rays, kPacketSize at a time through Embree's packet traversal, which is
  // faster where neighbouring rays take the same paths (one tile's camera rays). hits has the
  // size of directions.
  static constexpr std::size_t kPacketSize = 8;
  void trace(std::span<const Vec3> directions, std::span<std::optional<Hit>> hits) const;

  // Where a chord of a curved ray near a black hole meets a body (frame/body_segments.hpp): a
  // mesh through its Embree BVH.
  std::optional<SegmentHit> body_on_shape_segment(int body, const Vec3& from,
                                                  const Vec3& to) const override;

  using ShadowQuery::occluded;
  void occluded(std::span<const ShadowRay> rays, std::span<bool> blocked) const override;
  // How many shadow rays occluded() sorts into packets at a time.
  static constexpr std::size_t kMaxShadowBatch = 64;

  // Bytes Embree holds for the acceleration structures (for memory benchmarks).
  std::size_t acceleration_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lightcone

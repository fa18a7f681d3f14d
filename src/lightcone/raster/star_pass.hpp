// The raster renderer's stars (docs/design/stars.md): the frame's star images, found on the CPU
// by the same functions as the ray tracer's (frame/star_field.hpp), drawn over the sky as
// sprites that deposit each star's flux with the same pixel filter.
#pragma once

#include <cstddef>
#include <optional>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/star_field.hpp"
#include "lightcone/raster/gl.hpp"

namespace lightcone {

// Needs a current OpenGL 3.3 context.
class StarPass {
 public:
  StarPass();
  ~StarPass();
  StarPass(const StarPass&) = delete;
  StarPass& operator=(const StarPass&) = delete;

  // The frame's star images (none without sky.stars), uploaded. The photometry is kept from
  // frame to frame while it serves (StarPhotometry::serves), the lens table near a hole while
  // the camera's radius stays.
  void prepare(const ResolvedScene& scene);
  std::size_t count() const { return count_; }

  // Adds the stars to the bound target, whose alpha is 1 where its pixel sees the sky (0 on the
  // disk and the horizon) and whose depth buffer holds the bodies: each pixel's share times its
  // alpha, nothing where a body is in front.
  void draw(const ResolvedScene& scene) const;

 private:
  GLuint program_ = 0, vertex_array_ = 0, buffer_ = 0;
  std::size_t count_ = 0;
  std::optional<StarPhotometry> photometry_;
  std::optional<FarImageTable> lens_;  // near a hole: kept while the camera's radius is
};

}  // namespace lightcone

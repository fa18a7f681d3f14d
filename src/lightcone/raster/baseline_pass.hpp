// The limit a frame's geometry sets on a GL driver (bench/bench_raster.cpp, the raster twin of
// the tracer's raw-Embree baseline): the same tessellated triangles as the renderer's prepared
// frame, drawn by a pass-through program: each vertex at its apparent position, where the frame
// draws it, projected by the camera's pinhole; one colour; the rasterised depth, so that early
// depth tests apply.
#pragma once

#include <cstddef>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/raster_renderer.hpp"

namespace lightcone {

// Needs a current OpenGL 3.3 context.
class BaselinePass {
 public:
  BaselinePass();
  ~BaselinePass();
  BaselinePass(const BaselinePass&) = delete;
  BaselinePass& operator=(const BaselinePass&) = delete;

  // Clears the bound target and draws the renderer's prepared bodies (of `scene`, the frame it
  // was prepared with); returns the number of triangles drawn.
  std::size_t draw(const ResolvedScene& scene, const RasterRenderer& renderer) const;

 private:
  GLuint program_ = 0;
};

}  // namespace lightcone

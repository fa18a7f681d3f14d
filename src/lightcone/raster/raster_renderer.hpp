// The real-time renderer: polygons on OpenGL 3.3 core, every vertex carried back along the
// camera's past light cone and every fragment coloured with its exact Doppler factor, from the
// same resolved scene, emission tables and colour laws as the ray tracer
// (docs/design/raster.md).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/raster/tessellation.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// What the raster renderer cannot show as the ray tracer does, one line each (empty when it
// shows the scene exactly): lit materials, textures and sky images, shadows.
std::vector<std::string> raster_differences(const Scene& scene);

struct RasterFrameStats {
  std::size_t triangles = 0;  // after tessellation, all samples' passes together
};

// The GL programs and buffers of the renderer; needs a current OpenGL 3.3 core context.
class RasterRenderer {
 public:
  RasterRenderer();
  ~RasterRenderer();
  RasterRenderer(const RasterRenderer&) = delete;
  RasterRenderer& operator=(const RasterRenderer&) = delete;

  // Draws one pass of the scene into the bound framebuffer (linear radiance, before exposure),
  // its samples at `pixel_offset` within each pixel ((0.5, 0.5): the centres). The viewport
  // must be the camera's image size.
  RasterFrameStats draw(const ResolvedScene& scene, const EmissionTable& emission,
                        double pixel_offset_x = 0.5, double pixel_offset_y = 0.5,
                        const TessellationLimits& limits = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct RasterStats {
  double seconds = 0;
  double exposure = 0;  // EV applied
  std::size_t triangles = 0;
  std::string gl;  // the OpenGL version and renderer used
};

// The whole image, headless (EGL): camera.samples passes at stratified offsets, averaged, and
// the scene's exposure applied, as render_image does. Throws GlUnavailable without OpenGL 3.3.
Image render_raster(const Scene& scene, RasterStats* stats = nullptr);

}  // namespace lightcone

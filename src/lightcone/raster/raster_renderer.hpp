// The real-time renderer: polygons on OpenGL 3.3 core, every vertex carried back along the
// camera's past light cone and every fragment coloured with its exact Doppler factor, from the
// same resolved scene, emission tables and colour laws as the ray tracer
// (docs/design/raster.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/tessellation.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// What the raster renderer cannot show as the ray tracer does, one line each (empty when it
// shows the scene exactly): lit materials, textures and sky images, shadows.
std::vector<std::string> raster_differences(const Scene& scene);

struct RasterFrameStats {
  std::size_t triangles = 0;  // after tessellation on the CPU; before, on the GPU
};

// Where edges are cut: on the CPU (any OpenGL 3.3), by tessellation shaders on the GPU
// (OpenGL 4), or whichever draws the first pass of the frame faster.
enum class RasterTessellation { kCpu, kGpu, kAuto };

// The GL programs and buffers of the renderer; needs a current OpenGL 3.3 core context.
class RasterRenderer {
 public:
  RasterRenderer();
  ~RasterRenderer();
  RasterRenderer(const RasterRenderer&) = delete;
  RasterRenderer& operator=(const RasterRenderer&) = delete;

  // Tessellates the scene's bodies and tabulates their colours for one frame. The scene and the
  // emission table must outlive the passes drawn from it.
  // `on_gpu` cuts the edges in tessellation shaders (where available), by the same measure
  // with equal pieces (docs/design/raster.md).
  RasterFrameStats prepare(const ResolvedScene& scene, const EmissionTable& emission,
                           const TessellationLimits& limits = {}, bool on_gpu = false);
  bool gpu_tessellation_available() const;
  // Draws one pass of the prepared frame into the bound framebuffer (linear radiance, before
  // exposure), its samples at the offset within each pixel ((0.5, 0.5): the centres). The
  // viewport must be the camera's image size.
  // `shading_offsets` (four floats a pixel, rows from the bottom: the point in the pixel and
  // the point on sphere lights) moves each pixel's shading to its own sample.
  void pass(double pixel_offset_x = 0.5, double pixel_offset_y = 0.5,
            const std::vector<float>* shading_offsets = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Which tessellation path draws: as asked, or (auto) the one whose first drawing took less
// time, after one of each (CPU first). Throws GlUnavailable for the GPU path without OpenGL 4.
class TessellationChoice {
 public:
  TessellationChoice(RasterTessellation mode, bool gpu_available) : mode_(mode) {
    if (mode == RasterTessellation::kGpu && !gpu_available)
      throw GlUnavailable("tessellation on the GPU needs OpenGL 4");
    if (mode == RasterTessellation::kAuto && !gpu_available) mode_ = RasterTessellation::kCpu;
  }
  bool on_gpu() const {
    if (mode_ != RasterTessellation::kAuto) return mode_ == RasterTessellation::kGpu;
    return frames_ < 2 ? frames_ == 1 : seconds_[1] < seconds_[0];
  }
  // Whether the path is settled (auto: once both were timed).
  bool decided() const { return mode_ != RasterTessellation::kAuto || frames_ >= 2; }
  // Records how long the frame just drawn took.
  void frame_took(double seconds) {
    if (frames_ < 2) seconds_[frames_] = seconds;
    ++frames_;
  }

 private:
  RasterTessellation mode_;
  int frames_ = 0;
  double seconds_[2] = {0, 0};
};

struct RasterStats {
  double seconds = 0;
  double exposure = 0;  // EV applied
  std::size_t triangles = 0;
  bool gpu_tessellation = false;  // which path drew it
  std::string gl;                 // the OpenGL version and renderer used
};

// The whole image, headless (EGL): camera.samples passes, averaged, and the scene's exposure
// applied, as render_image does. Pass k covers the pixels at point k of a multi-jittered
// pattern and shades each pixel at the ray tracer's sample k for it (pixel_sample with `seed`),
// so that away from outlines both renderers average the same directions. Throws GlUnavailable
// without OpenGL 3.3.
Image render_raster(const Scene& scene, RasterStats* stats = nullptr,
                    const TessellationLimits& limits = {}, std::uint64_t seed = 0,
                    RasterTessellation mode = RasterTessellation::kAuto);

}  // namespace lightcone

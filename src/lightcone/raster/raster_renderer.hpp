// The real-time renderer: polygons on OpenGL 3.3 core, every vertex carried back along the
// camera's past light cone and every fragment coloured with its exact Doppler factor, from the
// same resolved scene, emission tables and colour laws as the ray tracer
// (docs/design/raster.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/output_variable.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/shadow_query.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/tessellation.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// Near a black hole, what casts the lit bodies' shadows in a frame: a query over the frame's
// bodies, made for each frame and kept while it is drawn. Without one the renderer meets the
// bodies directly (frame/body_segments.hpp); where the program links the ray tracer, its Embree
// scenes are faster on meshes (trace/curved_shadows.hpp).
using CurvedShadowSource =
    std::function<std::unique_ptr<CurvedShadowQuery>(const ResolvedScene& scene)>;

// What the raster renderer cannot show as the ray tracer does, one line each (empty when it
// shows the scene exactly): near a black hole, textures' fine detail.
std::vector<std::string> raster_differences(const Scene& scene);

struct RasterFrameStats {
  std::size_t triangles = 0;   // after tessellation on the CPU; before, on the GPU
  bool rows_tabulated = true;  // false: the colour rows were kept from the frame before
};

// Where edges are cut: on the CPU (any OpenGL 3.3), by tessellation shaders on the GPU
// (OpenGL 4), or (auto) by the GL driver, as tessellate_on_gpu says.
enum class RasterTessellation { kCpu, kGpu, kAuto };

// The modes by name, as every front end takes them: "cpu", "gpu", "auto". Why another name is
// refused, or nothing; and the mode a name that is not refused names.
std::optional<std::string> tessellation_refused(std::string_view name);
RasterTessellation tessellation_named(std::string_view name);

// What the tessellation path is chosen by: facts of the GL driver, the same on every run.
struct GlDriver {
  bool tessellation_shaders = false;  // OpenGL 4 or later
  std::string renderer;               // GL_RENDERER: "llvmpipe (LLVM 15.0.6, 256 bits)", ...
};

// Whether a GL_RENDERER string names a rasteriser that runs on the CPU: Mesa's llvmpipe and
// softpipe (also under zink or the D3D12 driver), swrast, Google's SwiftShader, Microsoft's
// WARP ("Basic Render Driver"), Apple's software renderer.
bool software_rasteriser(const std::string& renderer);

// Whether edges are cut on the GPU: as asked, or (auto) where the driver has tessellation
// shaders and rasterises on a GPU; on a software rasteriser the CPU path is the faster
// (docs/design/raster.md). No timing enters, so one command gives the same image every run.
// Throws GlUnavailable for the GPU path without OpenGL 4.
bool tessellate_on_gpu(RasterTessellation mode, const GlDriver& driver);

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
  // The current context's driver, for tessellate_on_gpu.
  const GlDriver& driver() const;
  // Whether each frame's body programs hold only the features its bodies use (the default) or
  // every feature (the reference the tests hold the specialised ones against).
  void set_specialised_programs(bool specialise);
  // Near a black hole: what casts shadows on the lit bodies (without a source, the bodies met
  // directly).
  void set_curved_shadows(CurvedShadowSource source);
  // Draws one pass of the prepared frame into the bound framebuffer (linear radiance, before
  // exposure), its samples at the offset within each pixel ((0.5, 0.5): the centres). The
  // viewport must be the camera's image size.
  // `shading_offsets` (four floats a pixel, rows from the bottom: the point in the pixel and
  // the point on sphere lights) moves each pixel's shading to its own sample.
  void pass(double pixel_offset_x = 0.5, double pixel_offset_y = 0.5,
            const std::vector<float>* shading_offsets = nullptr);
  // The sky alone (with its stars), one sample a pixel at the centres, behind what the bound
  // framebuffer's depth buffer holds, as pass() draws it after the bodies: with BaselinePass's
  // bodies, the frame as it would be if shading its bodies cost nothing (bench/bench_raster.cpp).
  void sky_pass();
  // The output variables `aovs` of the prepared frame, each from the nearest surface at each
  // pixel's centre as the ray tracer gives them (frame/ray_seen.hpp): their channels
  // (aov_channel_names) appended to `image`. Flat space (render_refused refuses them near a
  // black hole); draws into a target of its own and leaves the bound one bound.
  void surface_variables(std::span<const Aov> aovs, Image& image);
  // The prepared frame's bodies as tessellated on the CPU (none on the GPU path): the vertex
  // array and buffer, its vertices' size in floats (the shape point first), and each body's
  // range of vertices, for BaselinePass.
  struct TessellatedBodies {
    unsigned vertex_array = 0, vertex_buffer = 0;
    int floats_per_vertex = 0;
    struct Draw {
      std::size_t body = 0, first_vertex = 0, vertex_count = 0;
      HiddenFaces hidden = HiddenFaces::kNone;
    };
    std::vector<Draw> draws;
  };
  TessellatedBodies tessellated_bodies() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
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
// so that away from outlines both renderers average the same directions. Near a black hole
// `curved_shadows` casts the shadows. `subject`, when given, receives the automatic exposure's
// subject weight of each pixel whatever the exposure. `aovs`: output variables, as channels
// of the image, from the first pass's frame at the pixels' centres, as the ray tracer's come
// from its first observation. Throws GlUnavailable without OpenGL 3.3.
Image render_raster(const Scene& scene, RasterStats* stats = nullptr,
                    const TessellationLimits& limits = {}, std::uint64_t seed = 0,
                    RasterTessellation mode = RasterTessellation::kAuto,
                    const CurvedShadowSource& curved_shadows = {},
                    std::vector<float>* subject = nullptr, std::span<const Aov> aovs = {});

}  // namespace lightcone

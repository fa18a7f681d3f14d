// The raster renderer's choices: what it draws differently from the ray tracer, and where it
// cuts edges.

#include <algorithm>
#include <cctype>

#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"

namespace lightcone {

std::vector<std::string> raster_differences(const Scene& scene) {
  std::vector<std::string> differences;
  bool textured = false;
  for (const Object& o : scene.objects)
    textured = textured || std::holds_alternative<Texture>(o.material.pattern);
  if (scene.black_hole && textured)
    differences.push_back(
        "textures near a black hole are read at points interpolated between exact vertices (lit "
        "ones lit at the vertices), so that the edges between a box's faces and fine detail "
        "differ by up to half a pixel");
  return differences;
}

bool software_rasteriser(const std::string& renderer) {
  std::string name = renderer;
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* software : {"llvmpipe", "softpipe", "swrast", "swiftshader",
                               "basic render driver", "software renderer"})
    if (name.find(software) != std::string::npos) return true;
  return false;
}

bool tessellate_on_gpu(RasterTessellation mode, const GlDriver& driver) {
  if (mode == RasterTessellation::kGpu && !driver.tessellation_shaders)
    throw GlUnavailable("tessellation on the GPU needs OpenGL 4");
  if (mode != RasterTessellation::kAuto) return mode == RasterTessellation::kGpu;
  return driver.tessellation_shaders && !software_rasteriser(driver.renderer);
}

}  // namespace lightcone

// The raster renderer's choices and its headless picture: what it draws differently from the
// ray tracer, where it cuts edges, and render_raster's passes.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>

#include "lightcone/frame/sampler.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/raster/shadow_maps.hpp"

namespace lightcone {

std::vector<std::string> raster_differences(const Scene& scene) {
  std::vector<std::string> differences;
  bool lit = false, textured = false, lit_textured = false, clock_mesh = false;
  for (const Object& o : scene.objects) {
    const bool has_texture = std::holds_alternative<Texture>(o.material.pattern);
    lit = lit || !o.material.unlit;
    textured = textured || has_texture;
    lit_textured = lit_textured || (has_texture && !o.material.unlit);
    clock_mesh = clock_mesh || (std::holds_alternative<Clock>(o.material.pattern) &&
                                std::holds_alternative<MeshShape>(o.shape));
  }
  if (clock_mesh && scene.black_hole)
    differences.push_back("clocks on meshes near a black hole are drawn as their face alone");

  if (lit_textured && scene.render.doppler == DopplerModel::kSpectral)
    differences.push_back("lit textured materials under the spectral model are drawn black");
  if (lit && scene.render.shadows && !scene.lights.empty()) {
    bool uncast = false, from_centre = false;
    std::size_t exact = 0;
    for (const Object& o : scene.objects) {
      bool any_exact = false;
      for (const Light& light : scene.lights) {
        const RasterShadowCast cast = raster_shadow_cast(o, light, scene.render);
        uncast = uncast || cast == RasterShadowCast::kNone;
        any_exact = any_exact || cast == RasterShadowCast::kExact;
        from_centre = from_centre || (cast == RasterShadowCast::kMap &&
                                      std::holds_alternative<SphereLight>(light.kind));
      }
      exact += any_exact;
    }
    if (scene.black_hole) {
      differences.push_back("no shadows are cast near a black hole");
    } else {
      if (uncast)
        differences.push_back(
            "accelerated, keyframed or spinning bodies and lights, and meshes moving relative to "
            "a light or lit by a directional one, cast no shadows");
      if (exact > static_cast<std::size_t>(kRasterMaxExactCasters))
        differences.push_back(
            fmt::format("only the first {} of the {} bodies moving relative to a light cast "
                        "shadows of it",
                        kRasterMaxExactCasters, exact));
      if (from_centre)
        differences.push_back("sphere lights cast meshes' shadows from their centres");
    }
  }
  if (scene.black_hole && textured)
    differences.push_back("textures near a black hole are drawn black");
  if (scene.black_hole && scene.black_hole->disk && !scene.objects.empty())
    differences.push_back("objects are drawn in front of the accretion disk where it hides them");
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

namespace {

// Pass k of n: the pixels covered at one point of a multi-jittered pattern, each shaded at the
// ray tracer's own sample k for it (one sample: the centres).
void pass_sample(RasterRenderer& renderer, int k, int n, std::uint64_t seed, int width, int height,
                 std::vector<float>& offsets) {
  if (n == 1) return renderer.pass(0.5, 0.5);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const PixelSample p = pixel_sample(x, y, k, n, seed);
      float* o = &offsets[4 * (static_cast<std::size_t>(height - 1 - y) * width + x)];
      o[0] = static_cast<float>(p.x);
      o[1] = static_cast<float>(p.y);
      o[2] = static_cast<float>(p.light[0]);
      o[3] = static_cast<float>(p.light[1]);
    }
  const std::array<double, 2> cover =
      multi_jittered(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(n), 0);
  renderer.pass(cover[0], cover[1], &offsets);
}

}  // namespace

Image render_raster(const Scene& scene, RasterStats* stats, const TessellationLimits& limits,
                    std::uint64_t seed, RasterTessellation mode) {
  const auto start = std::chrono::steady_clock::now();
  const HeadlessGlContext context;
  const ResolvedScene resolved = resolve_scene(scene);
  const EmissionTable emission(resolved);
  RasterRenderer renderer;
  const int width = scene.camera.width, height = scene.camera.height;
  const FloatTarget target(width, height);
  // camera.samples passes: each covers the pixels at one point of a multi-jittered pattern and
  // shades every pixel at the ray tracer's own sample for it (one sample: the centres).
  const int n = std::max(1, scene.camera.samples);
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  std::vector<double> sum(3 * pixels, 0.0);
  // The automatic exposure's subject, as the ray tracer finds it: the share of each pixel's
  // samples that met a body moving relative to the camera.
  std::vector<float> subject(scene.render.auto_exposure ? pixels : 0, 0.0f);
  std::vector<float>* const subject_sum = subject.empty() ? nullptr : &subject;
  const float share = 1.0f / static_cast<float>(n);
  std::vector<float> offsets(n > 1 ? 4 * pixels : 0);
  const bool on_gpu = tessellate_on_gpu(mode, renderer.driver());
  std::size_t triangles = renderer.prepare(resolved, emission, limits, on_gpu).triangles;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int k = 0; k < n; ++k) {
    if (scene.camera.shutter > 0) {
      // Motion blur: pass k is seen from the middle of the k-th of n parts of the shutter, as
      // the ray tracer's sample k is.
      Scene moved = scene;
      moved.camera.world_line =
          observation_after(scene.camera, scene.camera.shutter * (k + 0.5) / n);
      const ResolvedScene seen = resolve_scene(moved);
      const EmissionTable seen_emission(seen);
      triangles =
          std::max(triangles, renderer.prepare(seen, seen_emission, limits, on_gpu).triangles);
      pass_sample(renderer, k, n, seed, width, height, offsets);
      target.add_to(sum, subject_sum, share);
      continue;
    }
    pass_sample(renderer, k, n, seed, width, height, offsets);
    target.add_to(sum, subject_sum, share);
  }
  Image image;
  image.width = width;
  image.height = height;
  image.rgb.resize(3 * pixels);
  for (std::size_t i = 0; i < sum.size(); ++i) image.rgb[i] = static_cast<float>(sum[i] / n);
  const double ev = apply_exposure(image, scene.render, subject);
  if (stats) {
    stats->exposure = ev;
    stats->triangles = triangles;
    stats->gpu_tessellation = on_gpu;
    stats->gl = context.description();
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return image;
}

}  // namespace lightcone

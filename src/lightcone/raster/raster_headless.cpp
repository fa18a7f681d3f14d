// render_raster: the raster renderer's picture without a window, through EGL (not in the browser
// build, which draws into its page's canvas).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <variant>

#include "lightcone/frame/request_rules.hpp"
#include "lightcone/frame/sampler.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"

namespace lightcone {

namespace {

// Pass k of n: the pixels covered at one point of a multi-jittered pattern, each shaded at the
// ray tracer's own sample k for it (one sample: the centres, at the tracer's own point on the
// sphere lights; without `offsets`, a sample and no sphere light, the centres alone).
void pass_sample(RasterRenderer& renderer, int k, int n, std::uint64_t seed, int width, int height,
                 std::vector<float>& offsets) {
  if (offsets.empty()) return renderer.pass(0.5, 0.5);
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
      n > 1 ? multi_jittered(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(n), 0)
            : std::array<double, 2>{0.5, 0.5};
  renderer.pass(cover[0], cover[1], &offsets);
}

}  // namespace

Image render_raster(const Scene& scene, RasterStats* stats, const TessellationLimits& limits,
                    std::uint64_t seed, RasterTessellation mode,
                    const CurvedShadowSource& curved_shadows, std::vector<float>* subject_out,
                    std::span<const Aov> aovs) {
  if (const auto refused = render_refused(scene, {.aovs = aovs}))
    throw std::invalid_argument(*refused);
  const auto start = std::chrono::steady_clock::now();
  const HeadlessGlContext context;
  const ResolvedScene resolved = resolve_scene(scene);
  const EmissionTable emission(resolved);
  RasterRenderer renderer;
  renderer.set_curved_shadows(curved_shadows);
  const int width = scene.camera.width, height = scene.camera.height;
  const FloatTarget target(width, height);
  // camera.samples passes: each covers the pixels at one point of a multi-jittered pattern and
  // shades every pixel at the ray tracer's own sample for it (one sample: the centres).
  const int n = std::max(1, scene.camera.samples);
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  std::vector<double> sum(3 * pixels, 0.0);
  // The automatic exposure's subject, as the ray tracer finds it: the share of each pixel's
  // samples that met a body moving relative to the camera.
  std::vector<float> subject(scene.render.auto_exposure || subject_out ? pixels : 0, 0.0f);
  std::vector<float>* const subject_sum = subject.empty() ? nullptr : &subject;
  const float share = 1.0f / static_cast<float>(n);
  const bool sphere_lights =
      std::any_of(scene.lights.begin(), scene.lights.end(),
                  [](const Light& l) { return std::holds_alternative<SphereLight>(l.kind); });
  std::vector<float> offsets(n > 1 || sphere_lights ? 4 * pixels : 0);
  const bool on_gpu = tessellate_on_gpu(mode, renderer.driver());
  std::size_t triangles = renderer.prepare(resolved, emission, limits, on_gpu).triangles;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  Image image;
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
      if (k == 0 && !aovs.empty()) renderer.surface_variables(aovs, image);
      continue;
    }
    pass_sample(renderer, k, n, seed, width, height, offsets);
    target.add_to(sum, subject_sum, share);
    if (k == 0 && !aovs.empty()) renderer.surface_variables(aovs, image);
  }
  image.width = width;
  image.height = height;
  image.rgb.resize(3 * pixels);
  for (std::size_t i = 0; i < sum.size(); ++i) image.rgb[i] = static_cast<float>(sum[i] / n);
  const AppliedExposure applied = apply_exposure(image, scene.render, subject);
  if (subject_out) *subject_out = std::move(subject);
  if (stats) {
    stats->exposure = applied.ev;
    stats->triangles = triangles;
    stats->gpu_tessellation = on_gpu;
    stats->gl = context.description();
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  if (const auto refused = picture_refused(scene, applied.non_finite, applied.ev))
    throw std::runtime_error(*refused);
  return image;
}

}  // namespace lightcone

#include "lightcone/trace/renderer.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>

#include "lightcone/frame/received_colour.hpp"
#include "lightcone/frame/sampler.hpp"
#include "lightcone/frame/tone_map.hpp"

namespace lightcone {
namespace {

constexpr int kTileSize = 16;

}  // namespace

LinearRgb radiance_along(const ResolvedScene& scene, const EmissionTable& emission,
                         const Tracer& tracer, const Vec3& u, const Lighting* lighting,
                         const std::array<double, 2>& light_sample) {
  const RenderSettings& settings = scene.scene->render;
  if (const auto hit = tracer.trace(u)) {
    const double d = scene.doppler(u, hit->velocity);
    const PointEmission surface = emission.surface(hit->body, *hit);
    if (!scene.bodies[hit->body].object->material.unlit) {
      if (!lighting) return {0, 0, 0};
      return lighting->received(*hit, u, d, surface, light_sample);
    }
    return received_colour(surface, d, settings);
  }
  const double d = scene.doppler(u, scene.sky_velocity);
  return received_colour(emission.sky(scene.sky_direction(u)), d, settings);
}

Image render_image(const Scene& scene, const RenderOptions& options, RenderStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<tbb::global_control> limit;
  if (options.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  options.threads);
  const ResolvedScene resolved = resolve_scene(scene);
  const Tracer tracer(resolved);
  const EmissionTable emission(resolved);
  const Lighting lighting(resolved, &tracer);

  const Camera& cam = scene.camera;
  const PixelWindow window = options.crop.value_or(PixelWindow{0, 0, cam.width, cam.height});
  const int width = window.x1 - window.x0, height = window.y1 - window.y0;
  Image image;
  image.width = width;
  image.height = height;
  image.rgb.assign(static_cast<std::size_t>(width) * height * 3, 0.0f);
  const int tiles_x = (width + kTileSize - 1) / kTileSize;
  const int tiles_y = (height + kTileSize - 1) / kTileSize;
  const std::size_t total = static_cast<std::size_t>(tiles_x) * tiles_y;
  // The output variables' channels, and where each AOV's first channel is among them.
  std::vector<std::size_t> aov_first, aov_count;
  for (const Aov aov : options.aovs) {
    aov_first.push_back(image.channels.size());
    aov_count.push_back(aov_channel_names(aov).size());
    for (const std::string& name : aov_channel_names(aov))
      image.channels.push_back(
          {name, std::vector<float>(static_cast<std::size_t>(width) * height)});
  }
  std::atomic<std::size_t> done{0};
  std::atomic<bool> skipped{false};
  const int n = cam.samples;

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, total, 1), [&](const auto& range) {
    for (std::size_t tile = range.begin(); tile != range.end(); ++tile) {
      if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
        skipped = true;
        continue;
      }
      // Pixel (i, j) of the camera's image; its samples depend on (i, j) alone, so a crop
      // renders exactly the pixels of the whole image.
      const int x0 = window.x0 + static_cast<int>(tile % tiles_x) * kTileSize;
      const int y0 = window.y0 + static_cast<int>(tile / tiles_x) * kTileSize;
      for (int j = y0; j < std::min(y0 + kTileSize, window.y1); ++j)
        for (int i = x0; i < std::min(x0 + kTileSize, window.x1); ++i) {
          double r = 0, g = 0, b = 0;
          for (int k = 0; k < n; ++k) {
            const PixelSample o = pixel_sample(i, j, k, n, options.seed);
            const LinearRgb c = radiance_along(resolved, emission, tracer,
                                               look_direction(resolved.camera, i + o.x, j + o.y),
                                               &lighting, o.light);
            r += c.r;
            g += c.g;
            b += c.b;
          }
          float* px =
              &image.rgb[3 * (static_cast<std::size_t>(j - window.y0) * width + (i - window.x0))];
          px[0] = static_cast<float>(r / n);
          px[1] = static_cast<float>(g / n);
          px[2] = static_cast<float>(b / n);
          if (!options.aovs.empty()) {
            const std::size_t at =
                static_cast<std::size_t>(j - window.y0) * width + (i - window.x0);
            const Vec3 centre = look_direction(resolved.camera, i + 0.5, j + 0.5);
            for (std::size_t a = 0; a < options.aovs.size(); ++a) {
              float values[3];
              aov_values(resolved, tracer, centre, options.aovs[a], values);
              for (std::size_t c = 0; c < aov_count[a]; ++c)
                image.channels[aov_first[a] + c].values[at] = values[c];
            }
          }
        }
      const std::size_t now = ++done;
      if (options.progress) options.progress(now, total);
    }
  });

  const double ev = scene.render.auto_exposure ? auto_exposure(image) : scene.render.exposure;
  const auto scale = static_cast<float>(std::exp2(ev));
  for (float& v : image.rgb) v *= scale;

  if (stats) {
    stats->exposure = ev;
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->rays = static_cast<std::uint64_t>(width) * height * n;
    stats->cancelled = skipped;
  }
  return image;
}

}  // namespace lightcone

#include "lightcone/trace/renderer.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/frame/exposure_meter.hpp"
#include "lightcone/frame/pixel_lattice.hpp"
#include "lightcone/frame/received_colour.hpp"
#include "lightcone/frame/request_rules.hpp"
#include "lightcone/frame/sampler.hpp"
#include "lightcone/frame/star_field.hpp"
#include "lightcone/frame/straight_rays.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/huge_pages.hpp"
#include "lightcone/physics/accretion_disk.hpp"
#include "lightcone/portable.hpp"

namespace lightcone {
namespace {

constexpr int kTileSize = 16;
// A tile's pixels are traced in blocks of one ray packet (Tracer::kPacketSize), whose rays
// leave through neighbouring pixels and so mostly meet the same bodies; a block's lit points are
// shaded together, their shadow rays to each light traced as packets too.
constexpr int kBlockWidth = 4, kBlockHeight = 2;
static_assert(kBlockWidth * kBlockHeight == Tracer::kPacketSize);

}  // namespace

LinearRgb radiance_along(const ResolvedScene& scene, const EmissionTable& emission,
                         const Tracer& tracer, const Vec3& u, const Lighting* lighting,
                         const std::array<double, 2>& light_sample) {
  const std::optional<Hit> hit = tracer.trace(u);
  LinearRgb out;
  radiance_of(scene, emission, std::span(&hit, 1), std::span(&u, 1), lighting,
              std::span(&light_sample, 1), std::span(&out, 1));
  return out;
}

void radiance_of(const ResolvedScene& scene, const EmissionTable& emission,
                 std::span<const std::optional<Hit>> hits, std::span<const Vec3> directions,
                 const Lighting* lighting, std::span<const std::array<double, 2>> light_samples,
                 std::span<LinearRgb> out) {
  const RenderSettings& settings = scene.scene->render;
  // An emitter's colour does not depend on D when neither its colour nor its brightness does.
  const bool emitters_see_d =
      settings.doppler != DopplerModel::kOff || settings.searchlight != SearchlightModel::kOff;
  // A sky of one colour seen with D = 1 (at rest in F, or its colour blind to D) is received
  // the same in every direction: once, not per ray.
  const PointEmission* uniform_sky = emission.uniform_sky();
  const Vec3& sky_velocity = scene.sky_velocity;
  const bool sky_sees_d =
      emitters_see_d && (sky_velocity.x != 0 || sky_velocity.y != 0 || sky_velocity.z != 0);
  const std::optional<LinearRgb> sky_everywhere =
      uniform_sky && !sky_sees_d ? std::optional(received_colour(*uniform_sky, 1.0, settings))
                                 : std::nullopt;
  constexpr std::size_t kBatch = Lighting::kBatchSize;
  for (std::size_t first = 0; first < hits.size(); first += kBatch) {
    const std::size_t count = std::min(kBatch, hits.size() - first);
    // The sky and the emitters first; the lit points, if any, are shaded together after.
    std::size_t lit_ray[kBatch], lit_count = 0;
    for (std::size_t r = first; r < first + count; ++r) {
      const std::optional<Hit>& hit = hits[r];
      const Vec3& u = directions[r];
      if (!hit) {
        if (sky_everywhere) {
          out[r] = *sky_everywhere;
          continue;
        }
        const double d = emitters_see_d ? scene.doppler(u, sky_velocity) : 1.0;
        out[r] = received_colour(uniform_sky ? *uniform_sky : emission.sky(scene.sky_direction(u)),
                                 d, settings);
        continue;
      }
      if (scene.bodies[hit->body].object->material.unlit) {
        out[r] = received_colour(emission.surface(hit->body, *hit),
                                 emitters_see_d ? scene.doppler(u, hit->velocity) : 1.0, settings);
      } else if (!lighting) {
        out[r] = {0, 0, 0};
      } else {
        lit_ray[lit_count++] = r;
      }
    }
    if (lit_count == 0) continue;
    Lighting::LitPoint lit[kBatch];
    for (std::size_t k = 0; k < lit_count; ++k) {
      const std::size_t r = lit_ray[k];
      const Hit& hit = *hits[r];
      lit[k] = {&hit, directions[r], scene.doppler(directions[r], hit.velocity),
                emission.surface(hit.body, hit), light_samples[r]};
    }
    LinearRgb shaded[kBatch];
    lighting->received(std::span(lit, lit_count), std::span(shaded, lit_count));
    for (std::size_t k = 0; k < lit_count; ++k) out[lit_ray[k]] = shaded[k];
  }
}

LinearRgb curved_radiance(const ResolvedScene& scene, const EmissionTable& emission,
                          const CurvedRay& ray, const Lighting* lighting,
                          const std::array<double, 2>& light_sample, HoleLegStarts* leg_starts) {
  const RenderSettings& settings = scene.scene->render;
  switch (ray.end) {
    case CurvedRayEnd::kSky:
      return received_colour(emission.sky(ray.sky_direction), ray.shift, settings);
    case CurvedRayEnd::kDisk:
      return received_thermal_colour(emission.disk(),
                                     disk_temperature_ratio(scene.hole->mass, ray.disk_radius),
                                     ray.shift, settings);
    case CurvedRayEnd::kBody: {
      const PointEmission surface = emission.surface(ray.hit.body, ray.hit);
      if (scene.scene->objects[ray.hit.body].material.unlit)
        return received_colour(surface, ray.shift, settings);
      if (!lighting) break;
      const Lighting::HoleSurface at{ray.event, ray.to_camera, ray.local_velocity, leg_starts};
      Lighting::LitPoint point{&ray.hit, {}, ray.shift, surface, light_sample, &at};
      LinearRgb out;
      lighting->received(std::span(&point, 1), std::span(&out, 1));
      return out;
    }
    case CurvedRayEnd::kHorizon:
      break;
  }
  return {0, 0, 0};
}

namespace {

// Everything one observation event needs: the scene seen from it and its tables.
struct Observation {
  explicit Observation(const Scene& scene)
      : resolved(resolve_scene(scene)),
        tracer(resolved),
        emission(resolved),
        curved_bodies(resolved.hole && !resolved.bodies.empty()
                          ? std::make_unique<CurvedBodies>(resolved, tracer)
                          : nullptr),
        lighting(resolved, &tracer, curved_bodies.get()),
        straight_rays(StraightRays::of(resolved)) {}
  ResolvedScene resolved;
  Tracer tracer;
  EmissionTable emission;
  std::unique_ptr<CurvedBodies> curved_bodies;  // near a black hole
  Lighting lighting;
  // Near a black hole, the rays it leaves straight: a packet of them is traced as in flat space.
  std::optional<StraightRays> straight_rays;
};

// Meters a finished tile's pixels [x0, x_end) x [y0, y_end) of a picture `width` pixels wide,
// `subject_samples` of whose `samples` each (kTileSize a row) met the subject (null: none did):
// in a loop of its own, over pixels still in the cache, which runs faster than metering each
// pixel among the render's work.
void meter_tile(ExposureMeter& meter, const float* rgb, int width, int x0, int y0, int x_end,
                int y_end, const int* subject_samples, int samples) {
  for (int y = y0; y < y_end; ++y) {
    const float* row = rgb + 3 * (static_cast<std::size_t>(y) * width + x0);
    const auto pixels = static_cast<std::size_t>(x_end - x0);
    if (subject_samples)
      meter.add_samples(row, pixels, subject_samples + (y - y0) * kTileSize, samples);
    else
      meter.add(row, pixels);
  }
}

}  // namespace

Image render_image(const Scene& scene, const RenderOptions& options, RenderStats* stats) {
  if (const auto refused = render_refused(scene, {.aovs = options.aovs}))
    throw std::invalid_argument(*refused);
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<tbb::global_control> limit;
  if (options.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  options.threads);
  const Camera& cam = scene.camera;
  const int n = cam.samples;
  // With a shutter, sample k of every pixel is seen from the observation event at the middle
  // of the k-th of n equal parts of the shutter (docs/design/motion-blur.md); each has its own
  // resolved scene, so they are rendered one after the other and summed.
  const int observations = cam.shutter > 0 ? n : 1;
  const PixelWindow window = options.crop.value_or(PixelWindow{0, 0, cam.width, cam.height});
  const int stride = options.lattice;
  if (stride < 1) throw std::invalid_argument("RenderOptions::lattice must be at least 1");
  // The image's pixel (a, b) is the window's pixel (lattice_pixel(a), lattice_pixel(b)).
  const int window_width = window.x1 - window.x0, window_height = window.y1 - window.y0;
  const int width = lattice_size(window_width, stride),
            height = lattice_size(window_height, stride);
  Image image;
  image.width = width;
  image.height = height;
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  assign_zeros_on_huge_pages(image.rgb, pixels * 3);
  std::vector<double> sum(observations > 1 ? pixels * 3 : 0, 0.0);
  const int tiles_x = (width + kTileSize - 1) / kTileSize;
  const int tiles_y = (height + kTileSize - 1) / kTileSize;
  const std::size_t tiles = static_cast<std::size_t>(tiles_x) * tiles_y;
  const std::size_t total = tiles * observations;
  // The output variables' channels, one after another from aov_start.
  const std::size_t aov_start = image.channels.size();
  for (const Aov aov : options.aovs)
    for (const std::string& name : aov_channel_names(aov))
      image.channels.push_back({name, std::vector<float>(pixels)});
  const std::size_t aov_channels = image.channels.size() - aov_start;
  std::atomic<std::size_t> done{0};
  std::atomic<bool> skipped{false};
  std::atomic<std::uint64_t> image_orders{0};
  const bool light_samples =
      std::any_of(scene.lights.begin(), scene.lights.end(),
                  [](const Light& l) { return std::holds_alternative<SphereLight>(l.kind); });

  // The stars: deposited over the traced picture where its samples saw the sky (the fraction of
  // each pixel's samples that did), from each observation in turn.
  const bool with_stars =
      scene.sky.stars && scene.sky.stars->stars && !scene.sky.stars->stars->empty();
  // With a shutter they are summed apart, as the observations' radiance is; else added at once.
  std::vector<float> sky_coverage(with_stars ? pixels : 0),
      star_rgb(with_stars && observations > 1 ? pixels * 3 : 0);
  // The automatic exposure's subject: the share of each pixel's samples that met a body moving
  // relative to the camera (summed over the observations). Where a pixel is final when its tile
  // is done (one observation, no stars), the tiles fill the exposure's meters as they write
  // their pixels, and the picture is not read again; otherwise the subject is kept per pixel.
  const bool metered_in_pass = scene.render.auto_exposure && observations == 1 && !with_stars;
  const bool with_subject = (scene.render.auto_exposure && !metered_in_pass) || options.subject;
  std::vector<float> subject(with_subject ? pixels : 0, 0.0f);
  PerThread<ExposureMeter> meters;
  // Near a hole, each tile's lit points start their lights' legs from the tile's last ones.
  PerThread<HoleLegStarts> thread_leg_starts;

  double setup_seconds = 0, stars_seconds = 0;
  for (int o = 0; o < observations; ++o) {
    Scene moved;
    if (observations > 1) {
      moved = scene;
      moved.camera.world_line = observation_after(cam, cam.shutter * (o + 0.5) / n);
    }
    const auto setup_start = std::chrono::steady_clock::now();
    const Observation seen(observations > 1 ? moved : scene);
    setup_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count();
    const ResolvedScene& resolved = seen.resolved;
    const int first = observations > 1 ? o : 0, count = observations > 1 ? 1 : n;
    // The output variables come from the first observation's ray through each pixel's centre.
    const bool with_aovs = o == 0 && !options.aovs.empty();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tiles, 1), [&](const auto& range) {
      HoleLegStarts& leg_starts = thread_leg_starts.local();
      for (std::size_t tile = range.begin(); tile != range.end(); ++tile) {
        leg_starts.begin_tile(o * tiles + tile + 1);
        if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
          skipped = true;
          continue;
        }
        // Pixel (a, b) of the image is pixel (i, j) of the camera's; its samples depend on
        // (i, j) alone, so a crop or a lattice renders exactly the pixels of the whole image.
        const int x0 = static_cast<int>(tile % tiles_x) * kTileSize;
        const int y0 = static_cast<int>(tile / tiles_x) * kTileSize;
        const int x_end = std::min(x0 + kTileSize, width);
        const int y_end = std::min(y0 + kTileSize, height);
        std::uint64_t tile_orders = 0;  // the image orders of its curved rays, summed
        std::vector<float> aov_pixel(with_aovs ? aov_channels : 0);  // a pixel's, in order
        // The samples of each of the tile's pixels that met the subject, for its meter.
        // (zeroed when the tile's first sample meets the subject: most tiles' never do)
        int tile_subject[kTileSize * kTileSize];
        bool tile_met_subject = false;
        // A block's samplers, rays, hits and colours, made once a tile: made per block, their
        // 2.9 KB were zeroed for every 8 pixels. Constructed in place: a sampler built aside and
        // copied in was a store-forwarding stall per pixel (a twentieth of a black-hole render).
        std::optional<PixelSampler> samplers[Tracer::kPacketSize];
        Vec3 directions[Tracer::kPacketSize];
        std::optional<Hit> hits[Tracer::kPacketSize];
        LinearRgb colours[Tracer::kPacketSize];
        CurvedRay curved[Tracer::kPacketSize];
        for (int by = y0; by < y_end; by += kBlockHeight)
          for (int bx = x0; bx < x_end; bx += kBlockWidth) {
            // The block's pixels in the window, and their sums over the samples.
            int pixel_a[Tracer::kPacketSize], pixel_b[Tracer::kPacketSize];
            int pixel_i[Tracer::kPacketSize], pixel_j[Tracer::kPacketSize];
            std::size_t lanes = 0;
            for (int b = by; b < std::min(by + kBlockHeight, y_end); ++b)
              for (int a = bx; a < std::min(bx + kBlockWidth, x_end); ++a) {
                const int i = window.x0 + lattice_pixel(a, window_width, stride);
                const int j = window.y0 + lattice_pixel(b, window_height, stride);
                samplers[lanes].emplace(i, j, n, options.seed, light_samples);
                pixel_a[lanes] = a;
                pixel_b[lanes] = b;
                pixel_i[lanes] = i;
                pixel_j[lanes++] = j;
              }
            double sums[Tracer::kPacketSize][3] = {};
            int sky_samples[Tracer::kPacketSize] = {}, subject_samples[Tracer::kPacketSize] = {};
            std::array<double, 2> light[Tracer::kPacketSize];
            for (int k = first; k < first + count; ++k) {
              for (std::size_t l = 0; l < lanes; ++l) {
                const PixelSample ps = (*samplers[l])(k);
                directions[l] =
                    look_direction(resolved.camera, pixel_i[l] + ps.x, pixel_j[l] + ps.y);
                light[l] = ps.light;
              }
              const bool straight = seen.straight_rays &&
                                    std::all_of(directions, directions + lanes, [&](const Vec3& u) {
                                      return seen.straight_rays->straight(u);
                                    });
              if (resolved.hole && !straight) {
                follow_curved_rays(*resolved.hole, std::span(directions, lanes),
                                   seen.curved_bodies.get(), std::span(curved, lanes));
                for (std::size_t l = 0; l < lanes; ++l) {
                  const CurvedRay& ray = curved[l];
                  colours[l] = curved_radiance(resolved, seen.emission, ray, &seen.lighting,
                                               light[l], &leg_starts);
                  tile_orders += ray.order;
                  sky_samples[l] += ray.end == CurvedRayEnd::kSky;
                  subject_samples[l] += ray.end == CurvedRayEnd::kBody &&
                                        resolved.bodies[ray.hit.body].moves_relative_to_camera();
                }
              } else {
                seen.tracer.trace(std::span(directions, lanes), std::span(hits, lanes));
                radiance_of(resolved, seen.emission, std::span(hits, lanes),
                            std::span(directions, lanes), &seen.lighting, std::span(light, lanes),
                            std::span(colours, lanes));
                for (std::size_t l = 0; l < lanes; ++l) {
                  sky_samples[l] += !hits[l];
                  subject_samples[l] +=
                      hits[l] && resolved.bodies[hits[l]->body].moves_relative_to_camera();
                }
              }
              for (std::size_t l = 0; l < lanes; ++l) {
                sums[l][0] += colours[l].r;
                sums[l][1] += colours[l].g;
                sums[l][2] += colours[l].b;
              }
            }
            for (std::size_t l = 0; l < lanes; ++l) {
              const int i = pixel_i[l], j = pixel_j[l];
              const std::size_t at = static_cast<std::size_t>(pixel_b[l]) * width + pixel_a[l];
              for (int c = 0; c < 3; ++c) {
                if (observations > 1)
                  sum[3 * at + c] += sums[l][c];
                else
                  image.rgb[3 * at + c] = static_cast<float>(sums[l][c] / n);
              }
              if (with_stars) sky_coverage[at] = static_cast<float>(sky_samples[l]) / count;
              if (with_subject) subject[at] += static_cast<float>(subject_samples[l]) / n;
              if (with_aovs) {
                const Vec3 centre = look_direction(resolved.camera, i + 0.5, j + 0.5);
                aov_values(resolved, seen.tracer, centre, options.aovs, aov_pixel.data(),
                           seen.curved_bodies.get());
                for (std::size_t c = 0; c < aov_channels; ++c)
                  image.channels[aov_start + c].values[at] = aov_pixel[c];
              }
            }
            // The block's samples that met the subject, for the tile's meter.
            if (metered_in_pass) {
              int met = 0;
              for (std::size_t l = 0; l < lanes; ++l) met |= subject_samples[l];
              if (met != 0) {
                if (!tile_met_subject)
                  std::fill(std::begin(tile_subject), std::end(tile_subject), 0);
                tile_met_subject = true;
                for (std::size_t l = 0; l < lanes; ++l)
                  tile_subject[(pixel_b[l] - y0) * kTileSize + pixel_a[l] - x0] =
                      subject_samples[l];
              }
            }
          }
        if (metered_in_pass)
          meter_tile(meters.local(), image.rgb.data(), width, x0, y0, x_end, y_end,
                     tile_met_subject ? tile_subject : nullptr, n);
        if (tile_orders) image_orders += tile_orders;
        const std::size_t now = ++done;
        if (options.progress) options.progress(now, total);
      }
    });
    if (with_stars) {
      const auto stars_start = std::chrono::steady_clock::now();
      const StarPhotometry photometry = star_photometry(resolved);
      const std::vector<StarImage> stars = star_images(resolved, photometry);
      deposit_stars(stars, resolved.camera, window.x0, window.y0, window_width, window_height,
                    sky_coverage, 1.0 / observations, observations > 1 ? star_rgb : image.rgb,
                    stride);
      stars_seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - stars_start).count();
    }
  }
  if (observations > 1)
    for (std::size_t v = 0; v < sum.size(); ++v) image.rgb[v] = static_cast<float>(sum[v] / n);
  for (std::size_t v = 0; v < star_rgb.size(); ++v) image.rgb[v] += star_rgb[v];

  const double ev = !scene.render.auto_exposure ? scene.render.exposure
                    : metered_in_pass           ? meters.combined().ev(scene.render.tonemap)
                                      : auto_exposure(image, scene.render.tonemap, subject);
  const std::size_t non_finite = options.defer_exposure ? 0 : expose(image, ev);
  if (options.subject) *options.subject = std::move(subject);

  if (stats) {
    stats->exposure = ev;
    stats->setup_seconds = setup_seconds;
    stats->stars_seconds = stars_seconds;
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->rays = static_cast<std::uint64_t>(width) * height * n;
    stats->cancelled = skipped;
    stats->mean_image_order = stats->rays ? static_cast<double>(image_orders) / stats->rays : 0;
  }
  if (const auto refused = picture_refused(scene, non_finite, ev))
    throw std::runtime_error(*refused);
  return image;
}

}  // namespace lightcone

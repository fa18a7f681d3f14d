// The offline renderer: one or more camera rays per pixel, tiles in parallel on TBB.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/lighting.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/scene/scene.hpp"
#include "lightcone/trace/aov.hpp"
#include "lightcone/trace/tracer.hpp"

namespace lightcone {

// A window of pixels [x0, x1) x [y0, y1) of the camera's image.
struct PixelWindow {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct RenderOptions {
  int threads = 0;         // 0: all cores
  std::uint64_t seed = 0;  // of the sample pattern (render_image is deterministic for each)
  // Called from worker threads (must be thread-safe) after each finished tile.
  std::function<void(std::size_t done, std::size_t total)> progress;
  // Render only this window (pbrt's crop window): the image is the window's size and equals
  // that region of the whole render pixel for pixel (with a fixed exposure; "auto" looks at
  // the window only).
  std::optional<PixelWindow> crop;
  // Above 1: render only the window's lattice of that stride (frame/pixel_lattice.hpp, one
  // pixel of each lattice x lattice block): the image is the lattice's size and equals those
  // pixels of the window's render exactly (with a fixed exposure; "auto" looks at them only).
  int lattice = 1;
  // When set, receives each pixel's share of samples that met a body moving relative to the
  // camera (the automatic exposure's subject weights), whatever the exposure.
  std::vector<float>* subject = nullptr;
  // When set (from any thread, e.g. a signal handler), tiles not yet started are skipped and
  // stay black; RenderStats::cancelled says so.
  const std::atomic<bool>* cancel = nullptr;
  // Output variables to add to the image as named channels (Image::channels), each from the
  // ray through the pixel's centre.
  std::vector<Aov> aovs;
  // When set, the picture is left at EV 0 and RenderStats::exposure holds the EV to apply, for
  // a caller that only shows it: expose_and_tone_map (tone_map.hpp) then exposes and maps it in
  // one pass, and the caller refuses it (request_rules' picture_refused) as render_image would.
  bool defer_exposure = false;
};

struct RenderStats {
  double seconds = 0;
  double setup_seconds = 0;  // of those, resolving the scene and building its tables and BVHs
  double stars_seconds = 0;  // and finding the stars' images and depositing them
  std::uint64_t rays = 0;    // camera rays traced
  double exposure = 0;       // EV applied
  bool cancelled = false;    // some tiles were skipped (RenderOptions::cancel)
  // Near a black hole: the mean image order of the camera rays (0 for flat scenes).
  double mean_image_order = 0;
};

// Linear sRGB radiance arriving along look direction u (unit, in the camera's frame F). Lit
// surfaces need `lighting` (without it they are black); `light_sample` picks points on sphere
// lights.
LinearRgb radiance_along(const ResolvedScene& scene, const EmissionTable& emission,
                         const Tracer& tracer, const Vec3& u, const Lighting* lighting = nullptr,
                         const std::array<double, 2>& light_sample = {0.5, 0.5});

// The same for many rays whose nearest hits are known (out[i] along directions[i], hits[i] its
// nearest hit, light_samples[i] its sample; all of one size), their lit points shaded together
// (Lighting's batches).
void radiance_of(const ResolvedScene& scene, const EmissionTable& emission,
                 std::span<const std::optional<Hit>> hits, std::span<const Vec3> directions,
                 const Lighting* lighting, std::span<const std::array<double, 2>> light_samples,
                 std::span<LinearRgb> out);

// The radiance arriving along a curved camera ray near the scene's black hole: the sky, the
// disk and emitting bodies seen with the ray's shift g, through the same colour laws as every
// emitter; lit bodies as `lighting` shades them (black without it), light_sample picking points
// on sphere lights, leg_starts (where given) starting the lights' legs from the last ones.
LinearRgb curved_radiance(const ResolvedScene& scene, const EmissionTable& emission,
                          const CurvedRay& ray, const Lighting* lighting = nullptr,
                          const std::array<double, 2>& light_sample = {0.5, 0.5},
                          HoleLegStarts* leg_starts = nullptr);

// Renders the scene: linear radiance times 2^exposure (or the automatic exposure), one RGB
// triple per pixel. `stats->exposure` reports the EV used.
Image render_image(const Scene& scene, const RenderOptions& options, RenderStats* stats = nullptr);

}  // namespace lightcone

// The offline renderer: one or more camera rays per pixel, tiles in parallel on TBB.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include "lightcone/render/resolved_scene.hpp"
#include "lightcone/render/tracer.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct RenderOptions {
  int threads = 0;  // 0: all cores
  // Called from worker threads (must be thread-safe) after each finished tile.
  std::function<void(std::size_t done, std::size_t total)> progress;
};

struct RenderStats {
  double seconds = 0;
  std::uint64_t rays = 0;  // camera rays traced
};

// Radiance arriving along look direction u (unit, in the camera's frame F), times 2^exposure.
Rgb radiance_along(const ResolvedScene& scene, const Tracer& tracer, const Vec3& u);

// Renders the scene: linear radiance times 2^exposure, one RGB triple per pixel.
Image render_image(const Scene& scene, const RenderOptions& options, RenderStats* stats = nullptr);

}  // namespace lightcone

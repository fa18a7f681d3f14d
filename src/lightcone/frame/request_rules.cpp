#include "lightcone/frame/request_rules.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lightcone {
namespace {

std::string source_of(const Scene& scene) {
  return scene.source.empty() ? std::string("the scene") : scene.source;
}

std::string refusal(const Scene& scene, const std::string& field, const std::string& why) {
  return fmt::format("{}: {}: {}", source_of(scene), field, why);
}

// Near a black hole: locate measures from W's time at the camera, which is not defined inside
// the horizon.
std::optional<std::string> locate_inside_horizon_refused(const Scene& scene) {
  if (!camera_inside_horizon(scene.camera.motion)) return std::nullopt;
  return refusal(scene, "camera",
                 "locate does not answer for a camera inside the black hole's horizon yet");
}

}  // namespace

std::optional<std::string> scene_refused(const Scene& scene) {
  const Camera& c = scene.camera;
  for (const auto& [field, value] :
       {std::pair{"camera.width", c.width}, {"camera.height", c.height}})
    if (!(value >= 1 && value <= kMaxCameraSide))
      return refusal(scene, field,
                     fmt::format("must be an integer from 1 to {}, got {}", kMaxCameraSide, value));
  if (std::int64_t{c.width} * c.height > kMaxCameraPixels)
    return refusal(scene, "camera.width",
                   fmt::format("{} x {} pixels is more than the limit of {} (2^27)", c.width,
                               c.height, kMaxCameraPixels));
  if (!(c.samples >= 1 && c.samples <= kMaxCameraSamples))
    return refusal(
        scene, "camera.samples",
        fmt::format("must be an integer from 1 to {}, got {}", kMaxCameraSamples, c.samples));
  if (!scene.black_hole) return std::nullopt;
  if (!scene.render.relativity || !scene.render.light_delay)
    return refusal(scene, "black_hole",
                   "render.relativity and render.light_delay must stay on: curved spacetime has "
                   "no classical picture");
  if (!scene.lights.empty() && scene.render.light_source_delay != LightSourceDelay::kSurface)
    return refusal(scene, "black_hole",
                   "render.light_source_delay must stay \"surface\" near a black hole: each light "
                   "is met where its light left for the surface, along the curved ray");
  return std::nullopt;
}

std::optional<std::string> renderer_refused(std::string_view name) {
  if (name == "trace" || name == "raster") return std::nullopt;
  return fmt::format(
      "renderer '{}': must be trace (the ray tracer) or raster (the real-time "
      "renderer)",
      name);
}

std::optional<std::string> render_refused(const Scene& scene, const RenderRequest& request) {
  if (auto refused = scene_refused(scene)) return refused;
  if (scene.black_hole && camera_inside_horizon(scene.camera.motion))
    for (const Aov aov : request.aovs)
      if (aov_needs_world_time(aov))
        return refusal(scene, "camera",
                       fmt::format("the output variable {} is measured from W's time at the "
                                   "camera, which is not defined inside the black hole's "
                                   "horizon (from there: doppler, object, normal, image_order)",
                                   aov_name(aov)));
  return std::nullopt;
}

std::optional<std::string> locate_refused(const Scene& scene, const LocateQuery& query) {
  if (auto refused = scene_refused(scene)) return refused;
  if (!scene.black_hole) return std::nullopt;
  if (auto refused = locate_inside_horizon_refused(scene)) return refused;
  if (query.kind == LocateQuery::Kind::WorldPoint) {
    const BlackHole& hole = *scene.black_hole;
    // In units of M, as the kernels measure (the scene's units' squares overflow or underflow
    // at the masses the kernels take, 1e-300 to 1e300).
    const double r_in_m = length((query.value - hole.position) / hole.mass);
    const double r = r_in_m * hole.mass, horizon = 2 * hole.mass;
    if (!(r_in_m > 2))
      return refusal(
          scene, "black_hole",
          fmt::format("no light leaves the world point ({}, {}, {}): it is {} from the hole's "
                      "centre, {} its horizon r = 2M = {}",
                      query.value.x, query.value.y, query.value.z, r, r_in_m == 2 ? "on" : "inside",
                      horizon));
  }
  return std::nullopt;
}

std::optional<std::string> probe_request_refused(std::span<const double> pixel, bool object_named) {
  if (object_named) return "locate: pixel takes no object: it finds what is seen";
  if (pixel.size() != 2)
    return fmt::format("locate: pixel must be two numbers x, y, got {}", pixel.size());
  return std::nullopt;
}

std::optional<std::string> probe_refused(const Scene& scene, double x, double y) {
  if (auto refused = scene_refused(scene)) return refused;
  const Camera& c = scene.camera;
  if (!(x >= 0 && x < c.width && y >= 0 && y < c.height))
    return refusal(scene, "pixel",
                   fmt::format("({}, {}) is not in the {} x {} picture: x must be from 0 to under "
                               "{} and y from 0 to under {}",
                               x, y, c.width, c.height, c.width, c.height));
  return scene.black_hole ? locate_inside_horizon_refused(scene) : std::nullopt;
}

std::optional<std::string> picture_refused(const Scene& scene, std::size_t non_finite,
                                           double exposure) {
  if (non_finite == 0) return std::nullopt;
  return fmt::format(
      "{}: the render has {} non-finite value{} (NaN or infinity): its radiance times 2^{} is "
      "beyond a float's range (is render.exposure, sky.stars.exposure or an emitter's luminance "
      "too large?); no picture is given",
      source_of(scene), non_finite, non_finite == 1 ? "" : "s", exposure);
}

}  // namespace lightcone

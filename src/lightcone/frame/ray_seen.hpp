// What the ray through a pixel's centre saw, and the output variables' values from it: one
// definition of each variable for both renderers (the ray tracer's trace/aov.hpp, the raster
// renderer's raster/surface_variables.cpp), which differ only in how they find what was seen.
#pragma once

#include <optional>
#include <span>

#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/output_variable.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/surface_hit.hpp"

namespace lightcone {

struct RaySeen {
  double doppler = 1;
  int order = 0;
  bool surface = false;  // it met a body or the disk
  float object = kObjectSky;
  // On a surface: the event met (W), its distance in the camera's frame and the surface's
  // normal (W's axes, facing the incoming ray).
  Vec4 event;
  double distance = 0;
  Vec3 normal;
};

// A body's surface normal with W's axes (its rest frame's), from the shape's own.
Vec3 body_normal(const ResolvedBody& body, const Vec3& shape_normal);

// What the straight ray of look direction u (flat spacetime) meets: the body of `hit` (the
// ray's first, as the tracer finds it), or the sky.
RaySeen seen_on_straight_ray(const ResolvedScene& scene, const Vec3& u,
                             const std::optional<Hit>& hit);

// What the curved ray of look direction u near a black hole (scene.hole) meets: a body of
// `bodies` when given, the disk, the shadow or the sky.
RaySeen seen_along_curved_ray(const ResolvedScene& scene, const Vec3& u,
                              const CurvedBodies* bodies = nullptr);
// The same from the ray already followed (follow_curved_ray).
RaySeen seen_on_curved_ray(const ResolvedScene& scene, const Vec3& u, const CurvedRay& ray);

// The values of each of `aovs` for a ray of look direction u, one after another in `out` (as
// many as each one's channels, aov_channel_names).
void write_aov_values(const ResolvedScene& scene, const Vec3& u, const RaySeen& seen,
                      std::span<const Aov> aovs, float* out);

}  // namespace lightcone

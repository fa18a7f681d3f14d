// Shadows near a black hole for the raster renderer's lit bodies (lit per vertex by Lighting,
// raster/hole_bodies.hpp), the chords of their paths met through the ray tracer's Embree scenes:
// faster on meshes than the raster renderer's own DirectBodySegments (frame/body_segments.hpp).
#pragma once

#include <memory>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/shadow_query.hpp"

namespace lightcone {

// The scene must outlive the query. Null where the scene has no black hole or no bodies.
std::unique_ptr<CurvedShadowQuery> curved_body_shadows(const ResolvedScene& scene);

}  // namespace lightcone

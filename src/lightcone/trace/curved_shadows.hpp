// Shadows near a black hole for another renderer: the ray tracer's own curved shadow paths
// (CurvedBodies::occluded) over the frame's bodies, for the raster renderer's lit bodies, which
// are lit per vertex by Lighting (raster/hole_bodies.hpp).
#pragma once

#include <memory>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/shadow_query.hpp"

namespace lightcone {

// The scene must outlive the query. Null where the scene has no black hole or no bodies.
std::unique_ptr<CurvedShadowQuery> curved_body_shadows(const ResolvedScene& scene);

}  // namespace lightcone

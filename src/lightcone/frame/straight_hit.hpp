// The first body a straight camera ray meets in flat spacetime, found without Embree: what the
// ray tracer's Tracer::trace finds, for the doors that have no Embree (the web page) and for
// single rays (locate --pixel), where building the tracer's hierarchy would cost more than the
// ray.
#pragma once

#include <optional>

#include "lightcone/frame/body_segments.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/surface_hit.hpp"

namespace lightcone {

// The first hit of the camera ray of look direction u (unit, in F) on the scene's bodies (none:
// it meets the sky): each body whose bounds the ray crosses met exactly, by `segments` (a
// DirectBodySegments of the scene) or, spinning, on its turning shape
// (spinning_intersection.hpp); the hit completed as a camera ray's (its texture coordinates,
// normal, clock and velocity).
std::optional<Hit> first_straight_hit(const ResolvedScene& scene, const BodySegments& segments,
                                      const Vec3& u);

}  // namespace lightcone

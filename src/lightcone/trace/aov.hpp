// Output variables beside the colour, for research use (`lightcone render --aov`, `--map`): per
// pixel, what the ray through the pixel's centre meets.
#pragma once

#include <span>

#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/output_variable.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/trace/tracer.hpp"

namespace lightcone {

// The values of each of `aovs` along the look direction u, one after another in `out` (as many
// as each one's channels, aov_channel_names), from one ray: near a black hole the curved ray,
// meeting `bodies` when given.
void aov_values(const ResolvedScene& scene, const Tracer& tracer, const Vec3& u,
                std::span<const Aov> aovs, float* out, const CurvedBodies* bodies = nullptr);

}  // namespace lightcone

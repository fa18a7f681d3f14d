// Output variables beside the colour, for research use (`lightcone render --aov`, `--map`): per
// pixel, what the ray through the pixel's centre meets.
#pragma once

#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/output_variable.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/trace/tracer.hpp"

namespace lightcone {

// The values of `aov` along the look direction u (as many as its channels); near a black hole
// along the curved ray, meeting `bodies` when given.
void aov_values(const ResolvedScene& scene, const Tracer& tracer, const Vec3& u, Aov aov,
                float* out, const CurvedBodies* bodies = nullptr);

}  // namespace lightcone

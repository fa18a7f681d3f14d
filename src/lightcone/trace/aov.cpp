#include "lightcone/trace/aov.hpp"

#include "lightcone/frame/ray_seen.hpp"

namespace lightcone {

void aov_values(const ResolvedScene& scene, const Tracer& tracer, const Vec3& u,
                std::span<const Aov> aovs, float* out, const CurvedBodies* bodies) {
  const RaySeen seen = scene.hole ? seen_along_curved_ray(scene, u, bodies)
                                  : seen_on_straight_ray(scene, u, tracer.trace(u));
  write_aov_values(scene, u, seen, aovs, out);
}

}  // namespace lightcone

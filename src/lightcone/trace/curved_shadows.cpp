#include "lightcone/trace/curved_shadows.hpp"

#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/trace/tracer.hpp"

namespace lightcone {

std::unique_ptr<CurvedShadowQuery> curved_body_shadows(const ResolvedScene& scene) {
  if (!scene.hole || scene.bodies.empty()) return nullptr;
  return curved_body_shadows_met_by(scene, std::make_unique<Tracer>(scene));
}

}  // namespace lightcone

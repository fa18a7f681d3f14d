#include "lightcone/trace/curved_shadows.hpp"

#include "lightcone/trace/curved_bodies.hpp"
#include "lightcone/trace/tracer.hpp"

namespace lightcone {

namespace {

// The bodies' tracer and the paths that meet them, owned together.
class TracedCurvedShadows final : public CurvedShadowQuery {
 public:
  explicit TracedCurvedShadows(const ResolvedScene& scene)
      : tracer_(scene), bodies_(scene, tracer_) {}
  bool occluded(const CurvedShadowRay& ray) const override { return bodies_.occluded(ray); }

 private:
  Tracer tracer_;
  CurvedBodies bodies_;
};

}  // namespace

std::unique_ptr<CurvedShadowQuery> curved_body_shadows(const ResolvedScene& scene) {
  if (!scene.hole || scene.bodies.empty()) return nullptr;
  return std::make_unique<TracedCurvedShadows>(scene);
}

}  // namespace lightcone

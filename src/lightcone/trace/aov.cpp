#include "lightcone/trace/aov.hpp"

#include <limits>

#include "lightcone/frame/curved_ray.hpp"

namespace lightcone {

void aov_values(const ResolvedScene& scene, const Tracer& tracer, const Vec3& u, Aov aov,
                float* out, const CurvedBodies* bodies) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  if (scene.hole) {
    const CurvedRay ray = follow_curved_ray(*scene.hole, u, bodies);
    out[0] = aov == Aov::kDoppler             ? static_cast<float>(ray.shift)
             : aov == Aov::kImageOrder        ? static_cast<float>(ray.order)
             : ray.end == CurvedRayEnd::kBody ? static_cast<float>(ray.hit.body)
                                              : -1.0f;
    return;
  }
  const auto hit = tracer.trace(u);
  if (!hit) {
    switch (aov) {
      case Aov::kDoppler:
        out[0] = static_cast<float>(scene.doppler(u, scene.sky_velocity));
        return;
      case Aov::kEmissionTime:
        out[0] = -kInf;
        return;
      case Aov::kDistance:
      case Aov::kDepth:
        out[0] = kInf;
        return;
      case Aov::kObject:
        out[0] = -1;
        return;
      case Aov::kImageOrder:  // flat space: every image is the primary
        out[0] = 0;
        return;
      case Aov::kNormal:
        out[0] = out[1] = out[2] = 0;
        return;
    }
  }
  const ResolvedBody& body = scene.bodies[hit->body];
  switch (aov) {
    case Aov::kDoppler:
      out[0] = static_cast<float>(scene.doppler(u, hit->velocity));
      return;
    case Aov::kEmissionTime:
      out[0] =
          static_cast<float>(scene.trace_to_world(Vec4{scene.ray_time * hit->s, u * hit->s}).t /
                             scene.scene->speed_of_light);
      return;
    case Aov::kDistance:
      out[0] = static_cast<float>(hit->s);
      return;
    case Aov::kObject:
      out[0] = static_cast<float>(hit->body);
      return;
    case Aov::kImageOrder:
      out[0] = 0;
      return;
    case Aov::kDepth:
      out[0] = static_cast<float>(hit->s * dot(u, scene.camera.forward));
      return;
    case Aov::kNormal: {
      const Object& o = *body.object;
      const Vec3 n = normalize(o.rotation * component_div(hit->shape_normal, o.scale));
      out[0] = static_cast<float>(n.x);
      out[1] = static_cast<float>(n.y);
      out[2] = static_cast<float>(n.z);
      return;
    }
  }
}

}  // namespace lightcone

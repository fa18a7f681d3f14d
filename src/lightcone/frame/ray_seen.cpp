#include "lightcone/frame/ray_seen.hpp"

#include <limits>

namespace lightcone {

void write_aov_values(const ResolvedScene& scene, const Vec3& u, const RaySeen& seen,
                      std::span<const Aov> aovs, float* out) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (const Aov aov : aovs) {
    switch (aov) {
      case Aov::kDoppler:
        *out++ = static_cast<float>(seen.doppler);
        break;
      case Aov::kImageOrder:
        *out++ = static_cast<float>(seen.order);
        break;
      case Aov::kObject:
        *out++ = seen.object;
        break;
      case Aov::kEmissionTime:
        *out++ =
            seen.surface ? static_cast<float>(seen.event.t / scene.scene->speed_of_light) : -kInf;
        break;
      case Aov::kDistance:
        *out++ = seen.surface ? static_cast<float>(seen.distance) : kInf;
        break;
      case Aov::kDepth:
        *out++ =
            seen.surface ? static_cast<float>(seen.distance * dot(u, scene.camera.forward)) : kInf;
        break;
      case Aov::kNormal:
        *out++ = static_cast<float>(seen.normal.x);
        *out++ = static_cast<float>(seen.normal.y);
        *out++ = static_cast<float>(seen.normal.z);
        break;
    }
  }
}

}  // namespace lightcone

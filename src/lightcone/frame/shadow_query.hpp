// What the lighting code asks a renderer that casts shadows: whether a body blocks a light path.
#pragma once

#include <span>

#include "lightcone/physics/vec.hpp"

namespace lightcone {

// The spacetime segment origin + sigma direction, sigma in (t_near, t_far), with events and
// direction in the world frame W: its events lie within W-times
// [ResolvedScene::shadow_time_min, shadow_time_max]. A ray of light `light` whose ShadowLight is
// labelled carries its label (ShadowLight::label); light -1 names none.
struct ShadowRay {
  Vec4 origin, direction;
  double t_near = 0, t_far = 0;
  int light = -1;
  double label = 0;
};

class ShadowQuery {
 public:
  virtual ~ShadowQuery() = default;
  // Whether a body blocks each ray (blocked[i] for rays[i], of the same size); bodies are met
  // where they are at each event. Rays asked together may be traced together, which is faster
  // where they are alike (from neighbouring points of a picture to one light).
  virtual void occluded(std::span<const ShadowRay> rays, std::span<bool> blocked) const = 0;
  bool occluded(const ShadowRay& ray) const {
    bool blocked = false;
    occluded(std::span(&ray, 1), std::span(&blocked, 1));
    return blocked;
  }
};

}  // namespace lightcone

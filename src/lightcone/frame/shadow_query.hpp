// What the lighting code asks a renderer that casts shadows: whether a body blocks a light path.
#pragma once

#include "lightcone/physics/vec.hpp"

namespace lightcone {

class ShadowQuery {
 public:
  virtual ~ShadowQuery() = default;
  // Whether a body blocks the spacetime segment origin + sigma direction, sigma in
  // (t_near, t_far), with events and direction in the world frame W (a shadow ray: its events
  // must lie within W-times [ResolvedScene::shadow_time_min, shadow_time_max]). Bodies are met
  // where they are at each event.
  virtual bool occluded(const Vec4& origin, const Vec4& direction, double t_near,
                        double t_far) const = 0;
};

}  // namespace lightcone

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

// Near a black hole: the direct null geodesic from a lit surface event back to a light
// (physics/hole_light_leg.hpp's HoleLegPath), in the plane of the hole (at `centre`, mass M), the
// surface (along e1 from the hole) and the light (toward e2); a body blocks it if the path meets
// one between swept angles sweep_near and sweep_far from the surface. A radial path (impact 0,
// the light on the line through the hole and the surface) sweeps no angle: a body blocks it
// between radii radius_near and radius_far (in units of M; infinity for a plane wave).
struct CurvedShadowRay {
  Vec4 origin;  // the surface event, in W
  Vec3 e1, e2;
  double impact = 0;     // in units of M
  bool outward = false;  // r grows at the surface along the path
  double sweep_near = 0, sweep_far = 0;
  double radius_near = 0, radius_far = 0;
};

class CurvedShadowQuery {
 public:
  virtual ~CurvedShadowQuery() = default;
  virtual bool occluded(const CurvedShadowRay& ray) const = 0;
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

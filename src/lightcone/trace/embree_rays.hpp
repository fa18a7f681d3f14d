// Single rays and 8-wide packets as Embree takes them, and hits of the tracer's own callbacks
// written where Embree reads them.
#pragma once

#include <embree3/rtcore.h>

#include <algorithm>

#include "lightcone/frame/shape_intersection.hpp"
#include "lightcone/physics/vec.hpp"

namespace lightcone {

// A ray as Embree traces it, in single precision, with no hit yet (the parameter range clamped
// to what a float holds).
inline RTCRayHit embree_ray(const Vec3& origin, const Vec3& direction, double tnear, double tfar,
                            float time = 0) {
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(origin.x);
  rh.ray.org_y = static_cast<float>(origin.y);
  rh.ray.org_z = static_cast<float>(origin.z);
  rh.ray.dir_x = static_cast<float>(direction.x);
  rh.ray.dir_y = static_cast<float>(direction.y);
  rh.ray.dir_z = static_cast<float>(direction.z);
  rh.ray.tnear = static_cast<float>(tnear);
  rh.ray.tfar = static_cast<float>(std::min(tfar, 3.0e38));
  rh.ray.time = time;
  rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// The ray through a mesh's BVH.
inline RTCRayHit mesh_ray(const ShapeRay& ray, double tnear, double tfar) {
  return embree_ray(ray.origin, ray.direction, tnear, tfar);
}

// Lane i of an 8-wide packet set from a single ray (and its empty hit), and a lane's result read
// back: the two layouts hold the same fields.
inline void put_lane(RTCRay8& packet, unsigned i, const RTCRay& ray) {
  packet.org_x[i] = ray.org_x;
  packet.org_y[i] = ray.org_y;
  packet.org_z[i] = ray.org_z;
  packet.tnear[i] = ray.tnear;
  packet.dir_x[i] = ray.dir_x;
  packet.dir_y[i] = ray.dir_y;
  packet.dir_z[i] = ray.dir_z;
  packet.time[i] = ray.time;
  packet.tfar[i] = ray.tfar;
  packet.mask[i] = ray.mask;
  packet.id[i] = ray.id;
  packet.flags[i] = ray.flags;
}

inline void put_lane(RTCRayHit8& packet, unsigned i, const RTCRayHit& rh) {
  put_lane(packet.ray, i, rh.ray);
  packet.hit.geomID[i] = rh.hit.geomID;
  packet.hit.instID[0][i] = rh.hit.instID[0];
}

inline void take_lane(const RTCRayHit8& packet, unsigned i, RTCRayHit& rh) {
  rh.ray.tfar = packet.ray.tfar[i];
  rh.hit.geomID = packet.hit.geomID[i];
  rh.hit.primID = packet.hit.primID[i];
  rh.hit.u = packet.hit.u[i];
  rh.hit.v = packet.hit.v[i];
  rh.hit.instID[0] = packet.hit.instID[0][i];
}

// A hit of this code's own into lane i of the hits Embree passes through: geomID holds the
// body, primID the triangle of a mesh body.
inline void record_hit(RTCHitN* hits, unsigned n, unsigned i, unsigned body, unsigned prim, float u,
                       float v) {
  RTCHitN_geomID(hits, n, i) = body;
  RTCHitN_primID(hits, n, i) = prim;
  RTCHitN_u(hits, n, i) = u;
  RTCHitN_v(hits, n, i) = v;
  RTCHitN_instID(hits, n, i, 0) = RTC_INVALID_GEOMETRY_ID;
}

}  // namespace lightcone

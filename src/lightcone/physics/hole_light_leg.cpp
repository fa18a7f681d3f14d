#include "lightcone/physics/hole_light_leg.hpp"

#include <cmath>
#include <limits>

#include "lightcone/physics/lorentz.hpp"

namespace lightcone {
namespace {

// The plane through the hole, the receiver (e1) and a second point, the angle psi between them
// about the hole, and the way a ray of image order k sweeps round from e1: toward the point for
// even k, away from it for odd k (e2).
struct LegPlane {
  Vec3 e1, e2;
  double psi = 0;
};
LegPlane leg_plane(const Vec3& receiver, const Vec3& other, int order) {
  LegPlane p;
  p.e1 = normalize(receiver);
  const double along = dot(other, p.e1);
  const Vec3 across = other - p.e1 * along;
  const double across_length = length(across);
  p.e2 = across_length > 0 ? across / across_length : any_perpendicular(p.e1);
  if (order % 2 != 0) p.e2 = p.e2 * -1.0;
  p.psi = std::atan2(across_length, along);
  return p;
}

// A photon of unit static-frame energy travelling along n, as the observer moving with w
// measures it: its energy, and its direction of travel.
struct Measured {
  double energy = 1;
  Vec3 direction;
};
Measured measured(const Vec3& n, const Vec3& w) {
  if (dot(w, w) == 0) return {1, n};
  const Vec4 k = boost(w) * Vec4{1, n};
  return {k.t, k.x / k.t};
}

// The side a receiver at rest against its static observer faces (its normal `lit_side`), in the
// leg's plane; none for a moving receiver, whose light is turned by aberration.
std::optional<FacingSide> facing_side(const LegPlane& plane, const Vec3& w_r,
                                      const Vec3* lit_side) {
  if (!lit_side || dot(w_r, w_r) != 0) return std::nullopt;
  return FacingSide{dot(*lit_side, plane.e1), dot(*lit_side, plane.e2)};
}

HoleLegPath leg_path(const LegPlane& plane, const RayBetween& ray) {
  // Back from the receiver (end a) the path leaves toward the emitter: r grows along it where
  // that direction points outward.
  return {plane.e1, plane.e2, ray.impact, ray.cos_a > 0, ray.sweep};
}

}  // namespace

std::optional<HoleLeg> hole_light_leg(double mass, const Vec3& emitter, const Vec3& w_e,
                                      const Vec3& receiver, const Vec3& w_r, int order,
                                      RayBetweenStart* warm_start, const Vec3* lit_side,
                                      bool timed) {
  const double r_e = length(emitter), r_r = length(receiver);
  const LegPlane plane = leg_plane(receiver, emitter, order);
  if (plane.psi == 0 && r_e == r_r) return std::nullopt;
  const std::optional<FacingSide> facing = facing_side(plane, w_r, lit_side);
  const std::optional<RayBetween> ray =
      ray_between(mass, r_r, r_e, plane.psi, order, warm_start, facing ? &*facing : nullptr, timed);
  if (!ray || !(ray->spread_b_to_a > 0)) return std::nullopt;
  // In the static frames: the receiver sees the light arrive from the direction in which the
  // path leaves it; the emitter, at angle `sweep` round from e1 toward e2, sends it back round
  // (toward decreasing angle).
  const Vec3& e1 = plane.e1;
  const Vec3& e2 = plane.e2;
  const Vec3 travel_at_receiver = (e1 * ray->cos_a + e2 * ray->sin_a) * -1.0;
  const double c = std::cos(ray->sweep), s = std::sin(ray->sweep);
  const Vec3 out_e = e1 * c + e2 * s, across_e = e1 * -s + e2 * c;
  const Vec3 travel_at_emitter = out_e * ray->cos_b - across_e * ray->sin_b;
  // Energies per unit conserved energy: 1 / sqrt(f) for the static observers.
  const double static_r = 1 / std::sqrt(1 - 2 * mass / r_r);
  const double static_e = 1 / std::sqrt(1 - 2 * mass / r_e);
  const Measured at_r = measured(travel_at_receiver, w_r);
  const Measured at_e = measured(travel_at_emitter, w_e);
  HoleLeg out;
  out.leg.doppler = (static_r * at_r.energy) / (static_e * at_e.energy);
  out.leg.distance = static_r * at_r.energy / static_e * std::sqrt(ray->spread_b_to_a);
  out.leg.direction = at_r.direction;
  out.leg.emitted_direction = at_e.direction;
  out.time = ray->time;
  out.path = leg_path(plane, *ray);
  return out;
}

std::optional<HolePlaneWave> hole_plane_wave(double mass, const Vec3& receiver, const Vec3& w_r,
                                             const Vec3& propagation, int order,
                                             RayBetweenStart* warm_start, const Vec3* lit_side) {
  const double r_r = length(receiver);
  // The wave comes from far away along -propagation.
  const LegPlane plane = leg_plane(receiver, propagation * -1.0, order);
  const std::optional<FacingSide> facing = facing_side(plane, w_r, lit_side);
  const std::optional<RayBetween> ray =
      ray_between(mass, r_r, std::numeric_limits<double>::infinity(), plane.psi, order, warm_start,
                  facing ? &*facing : nullptr);
  if (!ray || !(ray->focusing > 0) || !std::isfinite(ray->focusing)) return std::nullopt;
  const Vec3 travel = (plane.e1 * ray->cos_a + plane.e2 * ray->sin_a) * -1.0;
  const Measured at_r = measured(travel, w_r);
  HolePlaneWave out;
  out.doppler = at_r.energy / std::sqrt(1 - 2 * mass / r_r);
  out.focusing = ray->focusing;
  out.direction = at_r.direction;
  out.path = leg_path(plane, *ray);
  return out;
}

}  // namespace lightcone

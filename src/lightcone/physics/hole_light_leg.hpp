// Light from a lamp to a lit surface near one Schwarzschild black hole (PHYSICS.md, "Curved
// spacetime"; docs/design/black-hole.md, "Lights"): a null geodesic between them, directly or
// round the far side (schwarzschild_lens.hpp, ray_between), seen by the emitter and the
// receiver, each moving with
// its velocity relative to the static observer where it is. The same quantities as a flat leg
// (light_path.hpp), so that the flat irradiance laws hold unchanged: D becomes the shift g =
// (p . u_receiver) / (p . u_emitter), and the distance an effective one that carries the lens's
// focusing. G = c = 1, M the gravitational radius, positions relative to the hole.
#pragma once

#include <optional>

#include "lightcone/physics/light_path.hpp"
#include "lightcone/physics/schwarzschild_lens.hpp"
#include "lightcone/physics/vec.hpp"

namespace lightcone {

// The path of such a light back from the receiver, for a shadow test: in the plane of the hole
// and the receiver (along e1 from the hole), sweeping from e1 toward e2 (toward the emitter for
// the direct ray, away from it round the far side), with impact parameter b, r growing at the
// receiver along it (outward) or not, and sweeping `sweep` to the emitter (for a plane wave,
// to the direction it comes from).
struct HoleLegPath {
  Vec3 e1, e2;
  double impact = 0;
  bool outward = false;
  double sweep = 0;
};

struct HoleLeg {
  // doppler: g = nu_receiver / nu_emitter. distance: r_eff with D^4 I cos / r_eff^2 the
  // irradiance, r_eff = (nu_receiver / nu_static,e) sqrt(dA_receiver / dOmega_static,e): the
  // photon's energies against the emitter's static observer, and the bundle's area at the
  // receiver per unit solid angle its static observer sends (the receiver-frame distance in flat
  // space). direction and emitted_direction in the receiver's and the emitter's rest frames.
  ReceivedLeg leg;
  double time = 0;  // the coordinate time the light takes (NaN where not `timed`)
  HoleLegPath path;
};

// Light from a point at `emitter` (r > 2M) moving with velocity w_e against its static
// observer, to one at `receiver` (r > 2M) moving with w_r, along the ray of image order
// `order` (0 direct, 1 round the far side). None where that ray carries no light: the two
// points coincide, or the receiver lies on a caustic (the two points exactly in line through
// the hole), where a point's light is focused without bound. `warm_start`, where given, starts
// the ray's solve (ray_between) from an earlier leg's between ends nearby and is then set to
// this leg's; the leg is the same whatever it holds. `lit_side`, where given, is the normal of
// a receiver at rest against its static observer that takes no light on its back: none then
// where the light arrives from behind it (found before the ray is solved to the last bits).
// Without `timed`, its `time` is NaN, not taken (a lamp at rest lights every event alike).
std::optional<HoleLeg> hole_light_leg(double mass, const Vec3& emitter, const Vec3& w_e,
                                      const Vec3& receiver, const Vec3& w_r, int order = 0,
                                      RayBetweenStart* warm_start = nullptr,
                                      const Vec3* lit_side = nullptr, bool timed = true);

// A plane wave: light that far away travels along the unit `propagation` (in W), received at
// `receiver` (r > 2M) moving with w_r. doppler is nu_receiver / nu far away (in W), direction
// the propagation direction in the receiver's frame, and focusing the ratio of the areas across
// the rays far away and at the receiver (1 in flat space): the irradiance there is D^2 E
// focusing cos, E the wave's irradiance far away, D this doppler times the wave's own there.
// `warm_start` and `lit_side` as for hole_light_leg.
struct HolePlaneWave {
  double doppler = 1, focusing = 1;
  Vec3 direction;
  HoleLegPath path;
};
std::optional<HolePlaneWave> hole_plane_wave(double mass, const Vec3& receiver, const Vec3& w_r,
                                             const Vec3& propagation, int order = 0,
                                             RayBetweenStart* warm_start = nullptr,
                                             const Vec3* lit_side = nullptr);

}  // namespace lightcone

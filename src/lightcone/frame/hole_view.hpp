// A scene's black hole seen from one observation event (docs/design/black-hole.md): what the
// curved-ray walker (frame/curved_ray.hpp) and the colour tables need, once per frame.
//
// The camera's rest frame F is the boost, by the camera's velocity, of the orthonormal frame of
// the static observer at its event, whose axes are W's (its radial axis is the unit vector from
// the hole to the camera). Far away the static observers are W itself, so the sky's rest frame
// is reached from W as in flat space.
//
// Lengths and times near the hole are kept in units of its mass M (G = c = 1 leave no other
// length), so that the kernels see every scene that differs only in scale alike, whatever M is
// (docs/design/black-hole.md, "Scale"): a position relative to the hole, or a W time, divided by
// `scale` is one here, and what is handed back to W is multiplied by it.
#pragma once

#include <optional>

#include "lightcone/color/doppler_table.hpp"
#include "lightcone/physics/hole_world_line.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct HoleView {
  static constexpr double mass = 1;  // in its own units
  double scale = 1;                  // M in W's units
  Vec3 centre;                       // in W
  double camera_radius = 0;          // Schwarzschild r of the camera, > 2 unless it is falling
  Vec3 outward;                      // unit, from the hole toward the camera
  double camera_lapse = 1;           // sqrt(1 - 2M / r) at the camera
  double camera_rapidity = 0;        // of the camera relative to the static observer there
  // A camera on a radial fall: the tracer finds its rays in its own frame
  // (physics/radial_observer.hpp), at and inside the horizon too, where there is no static
  // observer (camera_lapse 0, no rapidity; trace_to_static, which the raster renderer reads
  // outside, is unset).
  std::optional<RadialObserver> falling;
  // The range of ln(camera_photon_energy) over the rays that can bring the camera light.
  double camera_log_energy_lo = 0, camera_log_energy_hi = 0;
  Mat4 trace_to_static;               // F to the static observer's orthonormal frame (Lorentz)
  Mat4 world_to_sky;                  // W (far away) to the sky's rest frame (Lorentz)
  Mat3 to_pattern;                    // the sky's rest frame to its pattern coordinates
  double sky_rapidity = 0;            // of the sky relative to W
  std::optional<AccretionDisk> disk;  // its radii in units of M
};

std::optional<HoleView> hole_view(const Scene& scene);

// An event of W relative to the hole, in units of M, and back.
Vec4 in_hole_units(const HoleView& hole, const Vec4& world);
Vec4 in_world(const HoleView& hole, const Vec4& near);

// The world-line of an object's origin about the hole, or of a straight coordinate line
// position + velocity (t - time) (a light's), in units of M.
HoleWorldLine hole_world_line(const HoleView& hole, const Object& object);
HoleWorldLine hole_world_line(const HoleView& hole, const WorldLine& line);

// The energy the camera measures for a photon it receives along look direction u (unit, in its
// rest frame F), in units of the photon's conserved energy (what a static observer far away
// measures): 1 / sqrt(f) at the static observer, over -t for the static-frame event (t, x) that
// the backward direction (-1, u) becomes (`in_static`, for a caller that has it already).
double camera_photon_energy(const HoleView& hole, const Vec4& in_static);
// (A falling camera: its radial_observer ray's energy; 0 for light of no positive energy.)
double camera_photon_energy(const HoleView& hole, const Vec3& u);

// How far light that reaches the camera along look direction u (unit, in its rest frame F) has
// travelled, in the camera's frame: its coordinate time of flight `flight` (W's, in W's units)
// times the camera's Doppler factor against the static observer where it is (the photon's
// energy at the camera over the static observer's), as flat space takes a ray's length from W
// into F (s_F = s_W gamma (1 + beta . d_W)). The output variable distance and locate's.
double camera_frame_distance(const HoleView& hole, const Vec3& u, double flight);

// The energy the sky's rest frame measures for a photon that arrives from W's direction `far`
// (unit, pointing away from the hole), in the same units: its flat Doppler factor far away, -t
// for the sky-frame event (t, x) that (-1, far) becomes (`in_sky`).
double sky_photon_energy(const Vec4& in_sky);
double sky_photon_energy(const HoleView& hole, const Vec3& far);

// The range of ln g, g = nu_camera / nu_emitter, with which the camera can see the sky, over
// every direction: the camera's Doppler factor relative to its static observer (within
// +-camera_rapidity), the blueshift 1 / sqrt(1 - 2M/r) of light falling to it, and the sky's
// own Doppler factor far away (within +-sky_rapidity). Exact bounds, not attained in general.
struct LogShiftRange {
  double lo = 0, hi = 0;
};
LogShiftRange sky_log_shift_range(const HoleView& hole);

// The same for the disk's gas: a ring at r, on its circular geodesic, is seen from far away with
// ln g in -(-ln sqrt(f(r)) +- atanh(v(r))), v its speed relative to the static observer there
// (both fall with r), shifted by the camera's terms.
LogShiftRange disk_log_shift_range(const HoleView& hole);

// The same for an object (at rest, on a straight coordinate line or on a geodesic): a static
// emitter at r is seen from far away with g = sqrt(f(r)), and its motion, at a local speed up
// to its world-line's peak, moves ln g by its rapidity at most.
LogShiftRange body_log_shift_range(const HoleView& hole, const Object& object);

// How deep in the hole's well and how fast a light's or an object's points get: the least
// (1/2) ln f (f = 1 - 2M/r) over their path and the largest rapidity against the static
// observers where they are (a fall's stops at 2M (1 + 1e-6), where its light is shifted beyond
// any display). They bound the shift of light between a light and a surface it lights:
// g = sqrt(f_e / f_r) gamma_r (1 - w_r . n_r) / (gamma_e (1 - w_e . n_e)).
struct HoleDepth {
  double log_lapse = 0;  // <= 0
  double rapidity = 0;
};
HoleDepth object_depth(const HoleView& hole, const Object& object);
HoleDepth light_depth(const HoleView& hole, const Light& light);

}  // namespace lightcone

// The camera rays near a black hole, tabulated once per frame for the raster renderer
// (docs/design/black-hole.md, "The raster renderer"). In the static observer's frame a camera
// ray's path depends only on the angle alpha between its direction and the outward radial
// direction (its plane is fixed by the pixel), so a few hundred rays, each followed by the exact
// kernel (physics/schwarzschild.hpp: photon_orbit, prepare_sweep, radius_after_angle, the very
// functions frame/curved_ray.cpp calls), stand for the whole image. The shader
// (shaders/black_hole.glsl) interpolates between them; the lookups below are its C++ mirror, on
// the same single-precision nodes, for the tests that bound its error against the kernel.
//
// Rows. The escape side (alpha < alpha_c, the shadow's edge) and the capture side (alpha >
// alpha_c) each get `rows` rays, uniform in x = ln(delta / e), where delta is the angle from
// alpha_c and e the angle from the side's far end (alpha = 0 or pi, a radial ray): the nodes
// crowd logarithmically toward the shadow's edge, where the swept angle diverges like -ln delta
// (so that it is almost linear in x there), and toward the radial rays, where the impact
// parameter b -> 0 (so that the path's scale 1/b changes by a fixed ratio from row to row).
//
// Per row: the total angle swept (to infinity or the horizon) and, for a disk, the path u = M/r
// against the swept angle on two legs, each at `nodes` equally spaced angles with the exact
// derivative du/dphi from the orbit equation (cubic Hermite between them): the in-leg from the
// camera, over [0, L_in], and the out-leg measured back from infinity (escaping rays), over
// [0, L_out]. A ray that stays outside r_stop = (3M + inner) / 2 has its whole path on each leg;
// for one that passes inside, the legs end at r_stop, and the rest of its path (near the photon
// sphere, where near-critical rays wind) lies in the disk's hole.
//
// Lookups. Between rows: cubic (Lagrange, four rows) in x, for the total angle and for u (at
// the swept angle from the camera on the in-legs; past half the total angle on the escape side,
// at the angle still to sweep on the out-legs, so that the rows are compared at like points of
// their paths). Measured against follow_curved_ray (tests/test_raster_black_hole.cpp): on
// scenes/black-hole.json at 1920 x 1080 the sky's picture is displaced by under 0.001 pixels and
// the disk's by under 0.03 (docs/design/black-hole.md, "The raster renderer").
#pragma once

#include <vector>

#include "lightcone/frame/hole_view.hpp"

namespace lightcone {

// From inside the horizon (a falling camera at r0 <= 2M, where there is no static observer):
// every ray that escapes (b < b_c) moves outward, through r = R = 2.5M, and meets nothing below
// R (the disk lies beyond 6M). So the tables are those of a static observer at R, which that
// ray passes looking outward at sin(alpha) = b sqrt(1 - 2M/R) / R, after sweeping the angle
// phi_in(b) from r0 to R, tabulated at kInnerNodes values of b uniform over [0, b_c]. The rays
// with b > b_c turn below the photon sphere and fall back: the shadow.

struct HoleRayTables {
  static constexpr int kDefaultRows = 256;  // per side
  static constexpr int kDefaultNodes = 16;  // per leg
  static constexpr int kTemperatureNodes = 1024;
  static constexpr int kInnerNodes = 1024;
  static constexpr double kInnerRadius = 2.5;  // R, in units of M
  // (One texture holds both as rows of the same width.)
  static_assert(kInnerNodes == kTemperatureNodes);

  double mass = 1;
  double camera_radius = 0;
  double critical_alpha = 0;  // alpha_c: rays at smaller alpha escape, at larger fall in
  // Per side (0: escape, 1: capture): its width in alpha, and the rows' x = x_first + i x_step.
  double side_width[2] = {0, 0};
  double x_first[2] = {0, 0}, x_step[2] = {1, 1};
  int rows = 0;            // per side
  int nodes = 0;           // per leg; 0 without a disk
  double stop_radius = 0;  // r_stop
  // RGBA texels, rows 0 .. rows - 1 the escape side's, then the capture side's; `width` texels a
  // row: (phi_total, L_in, L_out, 1 for a path that is one leg, else 0), then the in-leg's nodes
  // (u, du/dphi) in pairs, texel j holding nodes j and j + 1 (n - 1 texels), then the out-leg's
  // (u, du/dpsi), psi the angle still to sweep to infinity.
  int width = 1;
  std::vector<float> texels;
  // The square of the disk's temperature ratio, tau^2 = sqrt(F / F_peak) (disk_temperature_ratio),
  // at kTemperatureNodes radii uniform in ln r over [inner, outer]: smooth at the ISCO, where tau
  // itself rises like sqrt(r - 6M).
  std::vector<float> temperature;
  double log_inner = 0, log_step = 1;
  // From inside the horizon: the camera's radius r0 (then camera_radius is R), and phi_in at
  // b = b_c j / (kInnerNodes - 1); empty outside.
  double inside_radius = 0;
  std::vector<float> inner_angle;
};

// Whether the camera is inside the horizon (a fall at r0 <= 2M), where the tables are R's.
bool tables_from_inside(const HoleView& hole);

HoleRayTables hole_ray_tables(const HoleView& hole, int rows = HoleRayTables::kDefaultRows,
                              int nodes = HoleRayTables::kDefaultNodes);

// Where a ray at alpha (given by its sine and cosine, in the static frame) falls among the rows:
// its side and its fractional row p, below 0 past the first row (nearer the edge).
struct HoleRowPosition {
  int side = 0;  // 0: escapes, 1: falls in
  double p = 0;
};
HoleRowPosition hole_row_position(const HoleRayTables& tables, double sin_alpha, double cos_alpha);

// The weights of rows first .. first + 3 at p: cubic (Lagrange) between them, linear through the
// first two before the first row.
struct HoleRowWeights {
  int first = 0;
  double w[4] = {0, 0, 0, 0};
};
HoleRowWeights hole_row_weights(const HoleRayTables& tables, double p);

// The total angle swept: cubic between the rows in x, and past the first row extrapolated
// linearly in x (the angle's asymptote is -ln(delta)).
double tabulated_total_angle(const HoleRayTables& tables, const HoleRowPosition& at);

// The radius after sweeping phi (< the total angle): u = M/r on the rows' in-legs at phi, or,
// past half the total angle on the escape side, on their out-legs at the angle still to sweep,
// interpolated between the rows as the total angle is (clamped to the first row before it);
// infinity for u <= 0, r_stop where the rows say the path is inside it.
double tabulated_radius(const HoleRayTables& tables, const HoleRowPosition& at, double phi);

// tau = disk_temperature_ratio, from the table (the square root of its linear interpolation).
double tabulated_temperature_ratio(const HoleRayTables& tables, double r);

// From inside the horizon: phi_in(b) for 0 <= b < b_c, linear between the nodes.
double tabulated_inner_angle(const HoleRayTables& tables, double impact);

}  // namespace lightcone

// The raster renderer's black hole (docs/design/black-hole.md, "The raster renderer"): the
// frame's tables of camera rays (hole_tables.hpp) as float textures, and the uniforms of the sky
// pass's black-hole variant (shaders/black_hole.glsl), which follows each pixel's ray round the
// hole to the sky, the accretion disk or the horizon.
#pragma once

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/hole_view.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/hole_tables.hpp"

namespace lightcone {

// Needs a current OpenGL 3.3 context.
class BlackHolePass {
 public:
  // The texture units its two textures are bound to.
  static constexpr int kRaysUnit = 5, kTemperatureUnit = 6;

  BlackHolePass();
  ~BlackHolePass();
  BlackHolePass(const BlackHolePass&) = delete;
  BlackHolePass& operator=(const BlackHolePass&) = delete;

  // Tabulates the rays for this frame (the kernel, in double precision, on the CPU) and uploads
  // the tables.
  void prepare(const HoleView& hole);
  const HoleRayTables& tables() const { return tables_; }

  // Sets the hole's uniforms on `program` (in use) and binds its textures. `disk_row` is the
  // colour row of the disk's hottest ring against ln s (disk_row_colour), `disk_floor` its floor.
  void set_uniforms(GLuint program, const HoleView& hole, double disk_floor, int disk_row,
                    const RenderSettings& settings) const;

 private:
  HoleRayTables tables_;
  GLuint rays_ = 0, temperature_ = 0;
};

// The disk's row: the hottest ring's colour seen with factor s, before any searchlight factor
// (received_thermal_colour at tau = 1, spectral, searchlight off); black below the floor.
LinearRgb disk_row_colour(const ThermalEmission& disk, double s);

// The range of ln s the disk's row is read at: s = tau g (spectral) or tau (the others), tau in
// [floor, 1] and g within disk_log_shift_range.
struct LogRange {
  double lo = 0, hi = 0;
};
LogRange disk_row_range(const HoleView& hole, const ThermalEmission& disk);

}  // namespace lightcone

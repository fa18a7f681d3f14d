#include "lightcone/raster/black_hole_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "lightcone/frame/received_colour.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {

BlackHolePass::BlackHolePass() {
  glGenTextures(1, &rays_);
  glGenTextures(1, &temperature_);
  for (const GLuint texture : {rays_, temperature_}) {
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  check_gl("creating the black hole's textures");
}

BlackHolePass::~BlackHolePass() {
  glDeleteTextures(1, &rays_);
  glDeleteTextures(1, &temperature_);
}

void BlackHolePass::prepare(const HoleView& hole) {
  tables_ = hole_ray_tables(hole);
  glActiveTexture(GL_TEXTURE0 + kRaysUnit);
  glBindTexture(GL_TEXTURE_2D, rays_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, tables_.width, 2 * tables_.rows, 0, GL_RGBA, GL_FLOAT,
               tables_.texels.data());
  glActiveTexture(GL_TEXTURE0 + kTemperatureUnit);
  glBindTexture(GL_TEXTURE_2D, temperature_);
  // Row 0 the disk's temperatures, row 1 the angles swept below R (from inside the horizon).
  const std::size_t width =
      std::max({tables_.temperature.size(), tables_.inner_angle.size(), std::size_t{2}});
  std::vector<float> rows(2 * width, 0.0f);
  std::copy(tables_.temperature.begin(), tables_.temperature.end(), rows.begin());
  std::copy(tables_.inner_angle.begin(), tables_.inner_angle.end(),
            rows.begin() + static_cast<std::ptrdiff_t>(width));
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, static_cast<GLsizei>(width), 2, 0, GL_RED, GL_FLOAT,
               rows.data());
  glActiveTexture(GL_TEXTURE0);
  check_gl("uploading the black hole's tables");
}

void BlackHolePass::set_uniforms(GLuint p, const HoleView& hole, double disk_floor, int disk_row,
                                 const RenderSettings& settings) const {
  const HoleRayTables& t = tables_;
  glActiveTexture(GL_TEXTURE0 + kRaysUnit);
  glBindTexture(GL_TEXTURE_2D, rays_);
  glActiveTexture(GL_TEXTURE0 + kTemperatureUnit);
  glBindTexture(GL_TEXTURE_2D, temperature_);
  glActiveTexture(GL_TEXTURE0);
  glUniform1i(uniform(p, "hole_rays"), kRaysUnit);
  glUniform1i(uniform(p, "hole_temperature"), kTemperatureUnit);
  set_mat4(p, "hole_trace_to_static", hole.trace_to_static);
  // From inside the horizon: the falling camera's own frame, and the tables' radius R.
  const bool inside = t.inside_radius > 0;
  glUniform1i(uniform(p, "hole_inside"), inside ? 1 : 0);
  glUniform4f(uniform(p, "hole_falling"), static_cast<float>(inside ? hole.falling->energy : 1),
              static_cast<float>(inside ? hole.falling->radial_velocity : 0),
              static_cast<float>(t.inside_radius),
              static_cast<float>(critical_impact_parameter(hole.mass)));
  glUniform1i(uniform(p, "hole_inner_nodes"), static_cast<GLint>(t.inner_angle.size()));
  set_mat4(p, "hole_world_to_sky", hole.world_to_sky);
  set_mat3(p, "hole_to_pattern", hole.to_pattern);
  set_vec3(p, "hole_outward", hole.outward);
  glUniform1f(uniform(p, "hole_camera_lapse"),
              static_cast<float>(std::sqrt(1 - 2 * hole.mass / t.camera_radius)));
  glUniform1f(uniform(p, "hole_camera_radius"), static_cast<float>(t.camera_radius));
  glUniform1f(uniform(p, "hole_mass"), static_cast<float>(hole.mass));
  glUniform1f(uniform(p, "hole_critical_alpha"), static_cast<float>(t.critical_alpha));
  glUniform2f(uniform(p, "hole_side_width"), static_cast<float>(t.side_width[0]),
              static_cast<float>(t.side_width[1]));
  glUniform2f(uniform(p, "hole_x_first"), static_cast<float>(t.x_first[0]),
              static_cast<float>(t.x_first[1]));
  glUniform2f(uniform(p, "hole_x_step"), static_cast<float>(t.x_step[0]),
              static_cast<float>(t.x_step[1]));
  glUniform1i(uniform(p, "hole_rows"), t.rows);
  glUniform1i(uniform(p, "hole_nodes"), t.nodes);
  glUniform1f(uniform(p, "hole_stop_radius"), static_cast<float>(t.stop_radius));
  const AccretionDisk none;
  const AccretionDisk& d = hole.disk ? *hole.disk : none;
  set_vec3(p, "disk_normal", d.normal);
  glUniform2f(uniform(p, "disk_radii"), static_cast<float>(d.inner), static_cast<float>(d.outer));
  glUniform2f(uniform(p, "disk_temperature_grid"), static_cast<float>(t.log_inner),
              static_cast<float>(t.log_step));
  glUniform1i(uniform(p, "disk_row"), disk_row);
  glUniform1f(uniform(p, "disk_floor"), static_cast<float>(disk_floor));
  glUniform1i(uniform(p, "disk_searchlight"),
              settings.searchlight == SearchlightModel::kPhysical    ? 0
              : settings.searchlight == SearchlightModel::kChang1996 ? 1
                                                                     : 2);
}

LinearRgb disk_row_colour(const ThermalEmission& disk, double s) {
  RenderSettings plain;
  plain.doppler = DopplerModel::kSpectral;
  plain.searchlight = SearchlightModel::kOff;
  return received_thermal_colour(disk, 1, s, plain);
}

LogRange disk_row_range(const HoleView& hole, const ThermalEmission& disk) {
  const LogShiftRange g = disk_log_shift_range(hole);
  return {std::log(disk.floor) + std::min(g.lo, 0.0), std::max(g.hi, 0.0)};
}

}  // namespace lightcone

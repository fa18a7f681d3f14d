#include "lightcone/raster/body_patterns.hpp"

#include <variant>

namespace lightcone {

void set_pattern_uniforms(GLuint p, const Object& object, int pattern) {
  const Material& m = object.material;
  glUniform1i(uniform(p, "pattern"), pattern);
  const auto* checker = std::get_if<Checker>(&m.pattern);
  glUniform1f(uniform(p, "checker_size"), checker ? static_cast<float>(checker->size) : 1.0f);
  const auto* blink = std::get_if<Blink>(&m.pattern);
  const auto* clock = std::get_if<Clock>(&m.pattern);
  glUniform1f(uniform(p, "pattern_period"), static_cast<float>(blink   ? blink->period
                                                               : clock ? clock->period
                                                                       : 1.0));
  glUniform1f(uniform(p, "blink_duty"), blink ? static_cast<float>(blink->duty) : 0.0f);
  const Shape& shape = object.shape;
  const auto* box = std::get_if<Box>(&shape);
  const auto* plane = std::get_if<Plane>(&shape);
  glUniform1i(uniform(p, "shape_kind"), box                                     ? 1
                                        : plane                                 ? 2
                                        : std::holds_alternative<Sphere>(shape) ? 3
                                                                                : 0);
  set_vec3(p, "box_size",
           box     ? box->size
           : plane ? Vec3{plane->size_x, 0, plane->size_z}
                   : Vec3{1, 1, 1});
}

}  // namespace lightcone

#include "lightcone/raster/hole_bodies.hpp"

#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>
#include <variant>

#include "lightcone/frame/locate.hpp"
#include "lightcone/raster/adaptive_split.hpp"
#include "lightcone/raster/body_patterns.hpp"

namespace lightcone {

namespace {

struct HoleSeeing {
  struct Corner {
    Vec3 p;
    bool seen = false;
    ApparentPoint at;
    // The emission point along the line from the hole toward the camera, and across it.
    double along = 0, across_x = 0, across_y = 0;
    double emission_time = 0;
    float log_shift = 0, proper_time = 0;
  };
  const ResolvedScene& scene;
  const HoleView& hole;
  const Object& object;
  const HoleWorldLine& line;
  int order = 0;
  const TessellationLimits& limits;
  Vec3 across_x, across_y;  // unit, perpendicular to the axis and each other
  std::vector<float>& out;

  // Each edge's midpoint, solved once for both triangles that share the edge.
  mutable std::map<std::array<double, 6>, Corner> middles;

  Corner corner(const Vec3& p, std::optional<double> emission_time_guess = {}) const {
    Corner c;
    c.p = p;
    const Vec3 rest = object.rotation * component_mul(object.scale, p);
    const auto image = hole_body_point_image(hole, scene.scene->camera.world_line, line, rest,
                                             order, emission_time_guess);
    if (!image) return c;
    c.seen = true;
    c.emission_time = image->emission_time;
    const double lag = scene.scene->camera.world_line.time - image->emission_time;
    c.at = {image->direction * lag, project_direction(scene.camera, image->direction), p};
    const Vec3 from_hole = image->emission_position - hole.centre;
    c.along = dot(from_hole, hole.outward);
    c.across_x = dot(from_hole, across_x);
    c.across_y = dot(from_hole, across_y);
    c.log_shift = static_cast<float>(std::log(image->shift));
    c.proper_time = static_cast<float>(image->proper_time);
    return c;
  }

  Corner middle(const Corner& a, const Corner& b, const Vec3& p) const {
    const bool ordered = std::tie(a.p.x, a.p.y, a.p.z) < std::tie(b.p.x, b.p.y, b.p.z);
    const Vec3 &u = ordered ? a.p : b.p, &v = ordered ? b.p : a.p;
    const auto [it, added] = middles.try_emplace({u.x, u.y, u.z, v.x, v.y, v.z});
    if (added) {
      // The ends' emission times bracket the midpoint's closely.
      std::optional<double> guess;
      if (a.seen && b.seen)
        guess = (a.emission_time + b.emission_time) / 2;
      else if (a.seen || b.seen)
        guess = a.seen ? a.emission_time : b.emission_time;
      it->second = corner(p, guess);
    }
    return it->second;
  }

  bool needs_split(const Corner& a, const Corner& b, const Corner& middle) const {
    // Follow the edge of what has an image down to the finest level.
    if (!a.seen || !b.seen || !middle.seen) return a.seen || b.seen || middle.seen;
    return edge_error_pixels(scene.camera, a.at, b.at, middle.at) > limits.max_error_pixels;
  }

  // Whether the triangle's emission points, seen along the axis, enclose it (or touch it) where
  // the images of this order form a ring: behind the hole for every order, in front of it (the
  // light turned by a whole turn) for orders 1 and up.
  bool winds_round_axis(const Corner& a, const Corner& b, const Corner& c) const {
    if (order == 0 && a.along + b.along + c.along > 0) return false;
    const auto side = [](const Corner& u, const Corner& v) {
      return u.across_x * v.across_y - u.across_y * v.across_x;
    };
    const double ab = side(a, b), bc = side(b, c), ca = side(c, a);
    return (ab >= 0 && bc >= 0 && ca >= 0) || (ab <= 0 && bc <= 0 && ca <= 0);
  }

  void emit(const Corner& a, const Corner& b, const Corner& c) const {
    if (!a.seen || !b.seen || !c.seen || winds_round_axis(a, b, c)) return;
    for (const Corner* k : {&a, &b, &c})
      out.insert(
          out.end(),
          {static_cast<float>(k->at.position.x), static_cast<float>(k->at.position.y),
           static_cast<float>(k->at.position.z), static_cast<float>(k->p.x),
           static_cast<float>(k->p.y), static_cast<float>(k->p.z), k->log_shift, k->proper_time});
  }
};

}  // namespace

void tessellate_hole_image(const ResolvedScene& scene, const Object& object,
                           const HoleWorldLine& line, const RestMesh& mesh, int order,
                           const TessellationLimits& limits, std::vector<float>& out) {
  const HoleView& hole = *scene.hole;
  const Vec3 across_x = any_perpendicular(hole.outward);
  HoleSeeing seeing{
      scene, hole, object, line, order, limits, across_x, cross(hole.outward, across_x), out};
  const AdaptiveSplit split(seeing, mesh, limits.max_level);
  std::vector<HoleSeeing::Corner> corners;
  corners.reserve(mesh.positions.size());
  // The body's points are seen at nearly one time: each starts from the last one's.
  std::optional<double> guess;
  for (const Vec3& p : mesh.positions) {
    corners.push_back(seeing.corner(p, guess));
    if (corners.back().seen) guess = corners.back().emission_time;
  }
  for (const auto& [i, j, k] : mesh.triangles) split.triangle(corners[i], corners[j], corners[k]);
}

HoleBodiesPass::HoleBodiesPass(GLuint program) : program_(program) {
  glGenVertexArrays(1, &vertex_array_);
  glGenBuffers(1, &vertex_buffer_);
  glBindVertexArray(vertex_array_);
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  constexpr GLsizei stride = kHoleVertexFloats * sizeof(float);
  for (const auto& [location, size, first] : {std::array<int, 3>{0, 3, 0}, {1, 3, 3}, {2, 2, 6}}) {
    glEnableVertexAttribArray(static_cast<GLuint>(location));
    glVertexAttribPointer(static_cast<GLuint>(location), size, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(first * sizeof(float)));
  }
  glBindVertexArray(0);
  check_gl("creating the pass of bodies near the black hole");
}

HoleBodiesPass::~HoleBodiesPass() {
  glDeleteBuffers(1, &vertex_buffer_);
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteProgram(program_);
}

std::size_t HoleBodiesPass::prepare(const ResolvedScene& scene, const std::vector<Body>& bodies,
                                    const TessellationLimits& limits) {
  const BlackHole& hole = *scene.scene->black_hole;
  std::vector<std::vector<float>> parts(bodies.size() * kRasterHoleOrders);
  tbb::parallel_for(std::size_t{0}, parts.size(), [&](std::size_t k) {
    const Body& body = bodies[k / kRasterHoleOrders];
    const Object& object = *scene.bodies[body.index].object;
    tessellate_hole_image(scene, object, hole_world_line(object, hole), *body.mesh,
                          static_cast<int>(k % kRasterHoleOrders), limits, parts[k]);
  });
  draws_.clear();
  std::size_t total = 0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    Draw d;
    d.body = bodies[k / kRasterHoleOrders];
    d.first_vertex = static_cast<GLint>(total / kHoleVertexFloats);
    d.vertex_count = static_cast<GLsizei>(parts[k].size() / kHoleVertexFloats);
    total += parts[k].size();
    if (d.vertex_count > 0) draws_.push_back(d);
  }
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(total * sizeof(float)), nullptr,
               GL_STATIC_DRAW);
  std::size_t offset = 0;
  for (const std::vector<float>& part : parts) {
    if (!part.empty())
      glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(offset * sizeof(float)),
                      static_cast<GLsizeiptr>(part.size() * sizeof(float)), part.data());
    offset += part.size();
  }
  check_gl("uploading the bodies near the black hole");
  return total / kHoleVertexFloats / 3;
}

void HoleBodiesPass::draw(const ResolvedScene& scene) const {
  const GLuint p = program_;
  glBindVertexArray(vertex_array_);
  // Depth: the light's coordinate time of flight, on the flat bodies' log scale.
  glUniform2f(uniform(p, "depth_range"), std::log(1e-6f), std::log(1e12f));
  for (const Draw& d : draws_) {
    glUniform1i(uniform(p, "colour_row"), d.body.first_row);
    set_pattern_uniforms(p, *scene.bodies[d.body.index].object, d.body.pattern);
    glDrawArrays(GL_TRIANGLES, d.first_vertex, d.vertex_count);
  }
  check_gl("drawing the bodies near the black hole");
}

}  // namespace lightcone

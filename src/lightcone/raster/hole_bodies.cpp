#include "lightcone/raster/hole_bodies.hpp"

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <tuple>
#include <variant>

#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/shading.hpp"
#include "lightcone/frame/surface_coordinates.hpp"
#include "lightcone/portable.hpp"
#include "lightcone/raster/adaptive_split.hpp"
#include "lightcone/raster/body_patterns.hpp"
#include "lightcone/raster/shader_build.hpp"
#include "lightcone/raster/shader_sources.hpp"

namespace lightcone {

namespace {

constexpr float kLitColourTolerance = 1.0f / 128;
// Where a vertex holds its ln g (kHoleVertexFloats: after its apparent position and shape
// point; attribute 2's first float).
constexpr int kLogShiftFloat = 6;

struct HoleSeeing {
  struct Corner {
    Vec3 p;
    bool seen = false;
    ApparentPoint at;
    // The emission point along the line from the hole toward the camera, and across it.
    double along = 0, across_x = 0, across_y = 0;
    // The emission event, the shift g and the body's clock then; for a lit body also, in the
    // static observer's frame there, the light's direction toward the camera and the body's
    // velocity.
    Vec4 event;
    double shift = 1;
    float proper_time = 0;
    Vec3 to_camera, local_velocity;
    double swept = 0;  // hole_swept_angle
  };
  const ResolvedScene& scene;
  const HoleView& hole;
  const Object& object;
  const HoleWorldLine& line;
  int order = 0;
  const TessellationLimits& limits;
  Vec3 across_x, across_y;  // unit, perpendicular to the axis and each other
  std::vector<float>& out;
  const HoleLitBody* lit = nullptr;
  bool round = false;               // a sphere: its normal is its point's direction
  bool closed = false;              // a sphere or a box: its outward normals face the camera
  Vec3 face_normal;                 // of the untessellated triangle being split (shape coordinates)
  std::array<double, 8> face_uv{};  // and its texture coordinates' map (triangle_uv_map)

  // A lit corner's two colours, per corner, normal (a box's edge joins two faces) and texture
  // coordinates (a mesh's faces may meet at a seam of its texture).
  using Colours = std::array<float, 6>;
  mutable std::map<std::array<double, 8>, Colours> colours;

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
    const double lag = scene.scene->camera.world_line.time - image->emission_time;
    c.at = {image->direction * lag, project_direction(scene.camera, image->direction)};
    const Vec3 from_hole = image->emission_position - hole.centre;
    c.along = dot(from_hole, hole.outward);
    c.across_x = dot(from_hole, across_x);
    c.across_y = dot(from_hole, across_y);
    c.proper_time = static_cast<float>(image->proper_time);
    c.event = {image->emission_time, image->emission_position};
    c.to_camera = image->to_camera;
    c.local_velocity = image->local_velocity;
    c.shift = image->shift;
    c.swept = hole_swept_angle(from_hole, hole.outward, order);
    return c;
  }

  // The outward normal at corner c (shape coordinates), and whether the surface there faces the
  // way its light leaves for the camera.
  Vec3 normal_at(const Corner& c) const { return round ? normalize(c.p) : face_normal; }
  bool faces_camera(const Corner& c) const {
    return dot(object.rotation * component_div(normal_at(c), object.scale), c.to_camera) >= 0;
  }

  // What the lit surface at corner c sends to the camera, for each of its material's fixed
  // colours: the ray tracer's Lighting at that point (without shadows, as the raster renderer
  // draws everywhere), the normal facing the camera as the tracer's faces the ray.
  const Colours& colours_at(const Corner& c) const {
    const Vec3 n = normal_at(c);
    const std::array<double, 2> uv = lit->texture_albedo ? uv_at(c) : std::array<double, 2>{};
    const auto [it, added] =
        colours.try_emplace({c.p.x, c.p.y, c.p.z, n.x, n.y, n.z, uv[0], uv[1]});
    if (!added) return it->second;
    Hit hit;
    hit.body = static_cast<int>(lit->body);
    hit.shape_point = c.p;
    hit.uv = uv;
    // A closed shape is seen from outside (the tracer's normal faces the ray, outward but for
    // grazing rays); a plane or a mesh from either side.
    hit.shape_normal = closed || faces_camera(c) ? n : n * -1.0;
    const Lighting::HoleSurface at{c.event, c.to_camera, c.local_velocity, lit->leg_starts};
    std::array<Lighting::LitPoint, 2> points;
    const PointEmission texel =
        lit->texture_albedo ? lit->texture_albedo->surface(lit->object, hit) : PointEmission{};
    for (int k = 0; k < 2; ++k)
      points[k] = {&hit,       {}, c.shift, lit->texture_albedo ? texel : *lit->albedo[k],
                   {0.5, 0.5}, &at};
    std::array<LinearRgb, 2> received;
    lit->lighting->received(points, received);
    for (int k = 0; k < 2; ++k) {
      it->second[3 * k] = static_cast<float>(received[k].r);
      it->second[3 * k + 1] = static_cast<float>(received[k].g);
      it->second[3 * k + 2] = static_cast<float>(received[k].b);
    }
    return it->second;
  }

  // The texture coordinates at corner c, as the tracer gives a point met there (on a box, of
  // the face being split; on a mesh, its face's map).
  std::array<double, 2> uv_at(const Corner& c) const {
    if (const auto* box = std::get_if<Box>(&object.shape)) {
      int axis = 0;
      for (int i = 1; i < 3; ++i)
        if (std::abs(face_normal[i]) > std::abs(face_normal[axis])) axis = i;
      return box_uv(*box, c.p, axis);
    }
    if (round) return sphere_uv(c.p);
    if (const auto* plane = std::get_if<Plane>(&object.shape)) return plane_uv(*plane, c.p);
    return face_uv_at(c.p);
  }
  // The face's texture coordinates at shape point p (zero but on a mesh with them).
  std::array<double, 2> face_uv_at(const Vec3& p) const {
    const std::array<double, 8>& m = face_uv;
    return {m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3],
            m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7]};
  }

  Corner middle(const Corner& a, const Corner& b, const Vec3& p) const {
    const bool ordered = std::tie(a.p.x, a.p.y, a.p.z) < std::tie(b.p.x, b.p.y, b.p.z);
    const Vec3 &u = ordered ? a.p : b.p, &v = ordered ? b.p : a.p;
    const auto [it, added] = middles.try_emplace({u.x, u.y, u.z, v.x, v.y, v.z});
    if (added) {
      // The ends' emission times bracket the midpoint's closely.
      std::optional<double> guess;
      if (a.seen && b.seen)
        guess = (a.event.t + b.event.t) / 2;
      else if (a.seen || b.seen)
        guess = a.seen ? a.event.t : b.event.t;
      it->second = corner(p, guess);
    }
    return it->second;
  }

  bool needs_split(const Corner& a, const Corner& b, const Corner& middle) const {
    // Follow the edge of what has an image down to the finest level.
    if (!a.seen || !b.seen || !middle.seen) return a.seen || b.seen || middle.seen;
    if (edge_error_pixels(scene.camera, a.at, b.at, middle.at) > limits.max_error_pixels)
      return true;
    // A lit edge longer than a pixel is also split until the colours drawn along it
    // (interpolated between its ends) lie within kLitColourTolerance of the brightest there;
    // not where it turns from the camera (a closed body's far side is hidden, and an outline
    // is drawn to its half pixel already).
    if (!lit || std::hypot(a.at.image.x - b.at.image.x, a.at.image.y - b.at.image.y) <= 1)
      return false;
    const bool facing = faces_camera(a);
    if (faces_camera(b) != facing || faces_camera(middle) != facing || (closed && !facing))
      return false;
    const Colours &ca = colours_at(a), &cb = colours_at(b), &cm = colours_at(middle);
    float error = 0, brightest = 0;
    for (int i = 0; i < 6; ++i) {
      error = std::max(error, std::abs(cm[i] - 0.5f * (ca[i] + cb[i])));
      brightest = std::max({brightest, ca[i], cb[i], cm[i]});
    }
    return error > kLitColourTolerance * brightest;
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
    for (const Corner* k : {&a, &b, &c}) {
      out.insert(out.end(),
                 {static_cast<float>(k->at.position.x), static_cast<float>(k->at.position.y),
                  static_cast<float>(k->at.position.z), static_cast<float>(k->p.x),
                  static_cast<float>(k->p.y), static_cast<float>(k->p.z),
                  static_cast<float>(std::log(k->shift)), k->proper_time});
      static const Colours kNone{};
      const Colours& lit_colours = lit ? colours_at(*k) : kNone;
      out.insert(out.end(), lit_colours.begin(), lit_colours.end());
      const std::array<double, 2> uv = face_uv_at(k->p);
      out.insert(out.end(), {static_cast<float>(uv[0]), static_cast<float>(uv[1]),
                             static_cast<float>(k->swept)});
    }
  }
};

}  // namespace

double hole_swept_angle(const Vec3& from_hole, const Vec3& outward, int order) {
  // (atan2 of the sine and cosine: well conditioned at 0 and pi, where acos is not.)
  const double theta = std::atan2(length(cross(from_hole, outward)), dot(from_hole, outward));
  return order == 0 ? theta : 2 * std::numbers::pi - theta;
}

void tessellate_hole_image(const ResolvedScene& scene, const Object& object,
                           const HoleWorldLine& line, const RestMesh& mesh, int order,
                           const TessellationLimits& limits, std::vector<float>& out,
                           const HoleLitBody* lit) {
  const HoleView& hole = *scene.hole;
  const Vec3 across_x = any_perpendicular(hole.outward);
  const bool closed =
      std::holds_alternative<Sphere>(object.shape) || std::holds_alternative<Box>(object.shape);
  HoleSeeing seeing{scene,
                    hole,
                    object,
                    line,
                    order,
                    limits,
                    across_x,
                    cross(hole.outward, across_x),
                    out,
                    lit,
                    mesh.sphere_radius > 0,
                    closed,
                    {},
                    {},
                    {},
                    {}};
  std::vector<AdaptiveSplit<HoleSeeing, RestMesh>::Node> nodes;
  const AdaptiveSplit split(seeing, mesh, limits.max_level, nodes);
  std::vector<HoleSeeing::Corner> corners;
  corners.reserve(mesh.positions.size());
  // The body's points are seen at nearly one time: each starts from the last one's.
  std::optional<double> guess;
  for (const Vec3& p : mesh.positions) {
    corners.push_back(seeing.corner(p, guess));
    if (corners.back().seen) guess = corners.back().event.t;
  }
  for (const auto& [i, j, k] : mesh.triangles) {
    const Vec3 &a = mesh.positions[i], &b = mesh.positions[j], &c = mesh.positions[k];
    const Vec3 n = cross(b - a, c - a);
    seeing.face_normal = length(n) > 0 ? normalize(n) : Vec3{0, 1, 0};
    if (!mesh.uvs.empty())
      seeing.face_uv = triangle_uv_map({a, b, c}, {mesh.uvs[i], mesh.uvs[j], mesh.uvs[k]});
    split.triangle(corners[i], corners[j], corners[k]);
  }
}

HoleBodiesPass::HoleBodiesPass() {
  glGenVertexArrays(1, &vertex_array_);
  glGenBuffers(1, &vertex_buffer_);
  glBindVertexArray(vertex_array_);
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  constexpr GLsizei stride = kHoleVertexFloats * sizeof(float);
  for (const auto& [location, size, first] : {std::array<int, 3>{0, 3, 0},
                                              {1, 3, 3},
                                              {2, 2, kLogShiftFloat},
                                              {3, 3, 8},
                                              {4, 3, 11},
                                              {5, 2, 14},
                                              {6, 1, 16}}) {
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
  for (const auto& programs : programs_)
    for (GLuint p : programs)
      if (p) glDeleteProgram(p);
}

GLuint HoleBodiesPass::program(bool disk, bool surface_variables) {
  GLuint& p = programs_[disk ? 1 : 0][surface_variables ? 1 : 0];
  if (p) return p;
  const std::string defines = std::string(disk ? "#define LIGHTCONE_DISK_HIDES_BODIES 1\n" : "") +
                              (surface_variables ? "#define LIGHTCONE_SURFACE_VARIABLES 1\n" : "");
  return p = link_program(vertex_shader(shader_sources::hole_body_vert, false, defines),
                          fragment_shader(shader_sources::hole_body_frag,
                                          std::string(shader_sources::patterns_glsl) +
                                              (disk ? shader_sources::black_hole_glsl : ""),
                                          defines.c_str()));
}

std::vector<std::vector<float>> hole_body_vertices(const ResolvedScene& scene,
                                                   const std::vector<HoleBodiesPass::Body>& bodies,
                                                   const EmissionTable& emission,
                                                   const Lighting& lighting,
                                                   const TessellationLimits& limits) {
  const HoleView& hole = *scene.hole;
  std::vector<std::vector<float>> parts(bodies.size() * kRasterHoleOrders);
  parallel_for(std::size_t{0}, parts.size(), [&](std::size_t k) {
    const HoleBodiesPass::Body& body = bodies[k / kRasterHoleOrders];
    const Object& object = *scene.bodies[body.index].object;
    // Each image's legs start afresh, so that its colours do not depend on the threads' order.
    HoleLegStarts leg_starts;
    leg_starts.begin_tile(1);
    HoleLitBody lit{
        &lighting,
        body.index,
        {&emission.object_colour(body.index, 0), &emission.object_colour(body.index, 0)}};
    lit.leg_starts = &leg_starts;
    Rgb colours[2];
    if (pattern_colours(object.material, colours) == 2)
      lit.albedo[1] = &emission.object_colour(body.index, 1);
    if (std::holds_alternative<Texture>(object.material.pattern)) {
      lit.texture_albedo = &emission;
      lit.object = static_cast<std::size_t>(&object - scene.scene->objects.data());
    }
    tessellate_hole_image(scene, object, hole_world_line(hole, object), *body.mesh,
                          static_cast<int>(k % kRasterHoleOrders), limits, parts[k],
                          body.lit ? &lit : nullptr);
  });
  return parts;
}

std::size_t HoleBodiesPass::prepare(const ResolvedScene& scene, const std::vector<Body>& bodies,
                                    const EmissionTable& emission, const Lighting& lighting,
                                    const TessellationLimits& limits) {
  const std::vector<std::vector<float>> parts =
      hole_body_vertices(scene, bodies, emission, lighting, limits);
  draws_.clear();
  log_shift_range_.reset();
  for (const std::vector<float>& part : parts)
    for (std::size_t v = kLogShiftFloat; v < part.size(); v += kHoleVertexFloats) {
      const double ln_g = part[v];
      log_shift_range_ = log_shift_range_ ? LogShiftRange{std::min(log_shift_range_->lo, ln_g),
                                                          std::max(log_shift_range_->hi, ln_g)}
                                          : LogShiftRange{ln_g, ln_g};
    }
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

void HoleBodiesPass::draw(const ResolvedScene& scene, GLuint p) const {
  glBindVertexArray(vertex_array_);
  // Depth: the light's coordinate time of flight, on the flat bodies' log scale.
  glUniform2f(uniform(p, "depth_range"), std::log(kDepthNear), std::log(kDepthFar));
  glUniform1i(uniform(p, "texture_image"), 3);
  for (const Draw& d : draws_) {
    if (d.body.texture) {
      glActiveTexture(GL_TEXTURE3);
      glBindTexture(GL_TEXTURE_2D, d.body.texture);
      glActiveTexture(GL_TEXTURE0);
    }
    glUniform1i(uniform(p, "colour_row"), d.body.first_row);
    glUniform1f(uniform(p, "body_index"), static_cast<float>(d.body.index));
    glUniform1i(uniform(p, "lit"), d.body.lit ? 1 : 0);
    glUniform1f(uniform(p, "subject_alpha"),
                scene.bodies[d.body.index].moves_relative_to_camera() ? 2.0f : 1.0f);
    set_pattern_uniforms(p, *scene.bodies[d.body.index].object, d.body.pattern);
    glDrawArrays(GL_TRIANGLES, d.first_vertex, d.vertex_count);
  }
  check_gl("drawing the bodies near the black hole");
}

}  // namespace lightcone

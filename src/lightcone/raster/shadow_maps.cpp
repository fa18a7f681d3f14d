#include "lightcone/raster/shadow_maps.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "lightcone/physics/lorentz.hpp"
#include "lightcone/raster/shader_build.hpp"

namespace lightcone {
namespace {

// The cube's faces: each looks along `forward` with `right` and `up` as its image axes, 90
// degrees across (lighting.glsl's shadow_lookup picks the face and reads it the same way).
struct Face {
  Vec3 forward, right, up;
};
constexpr Face kFaces[6] = {
    {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
    {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
};

// Where a world-line is at W-time t.
Vec3 position_at(const WorldLine& line, double t) {
  return line.position + line.velocity * (t - line.time);
}

void append(std::vector<double>& key, const Vec3& v) {
  key.insert(key.end(), {v.x, v.y, v.z});
}

}  // namespace

RasterShadowCast raster_shadow_cast(const Object& object, const Light& light,
                                    const RenderSettings& settings) {
  // Resolved scenes hold no other motion; a body or light beyond its tangent is not cast.
  if (object.motion.geodesic || !object.motion.inertial() || !light.motion.inertial())
    return RasterShadowCast::kNone;
  if (object.spin) return RasterShadowCast::kExact;  // its shape turns along the ray
  const Vec3 relative = object.world_line.velocity - light.world_line.velocity;
  const bool at_rest = !settings.relativity || dot(relative, relative) <= 1e-24;
  const bool from_a_point = std::holds_alternative<PointLight>(light.kind) ||
                            std::holds_alternative<SpotLight>(light.kind);
  return at_rest && from_a_point ? RasterShadowCast::kMap : RasterShadowCast::kExact;
}

ShadowMaps::ShadowMaps() {
  program_ = link_program(vertex_shader(shader_sources::shadow_vert),
                          fragment_shader(shader_sources::shadow_frag));
  glGenTextures(1, &texture_);
  glGenFramebuffers(1, &framebuffer_);
  glGenVertexArrays(1, &vertex_array_);
  glGenBuffers(1, &vertex_buffer_);
  glBindVertexArray(vertex_array_);
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glBindVertexArray(0);
  check_gl("creating the shadow maps");
}

ShadowMaps::~ShadowMaps() {
  glDeleteBuffers(1, &vertex_buffer_);
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteTextures(1, &texture_);
  glDeleteProgram(program_);
}

void ShadowMaps::prepare(const ResolvedScene& scene, std::size_t lights) {
  const Scene& s = *scene.scene;
  const bool relativity = s.render.relativity;
  std::vector<double> key = {relativity ? 1.0 : 0.0, relativity ? 0.0 : scene.observation_event.t,
                             static_cast<double>(lights), static_cast<double>(s.objects.size())};
  for (std::size_t l = 0; l < lights; ++l) {
    const Light& light = s.lights[l];
    key.insert(key.end(), {static_cast<double>(light.kind.index()), light.world_line.time,
                           light.motion.inertial() ? 1.0 : 0.0});
    append(key, light.world_line.position);
    append(key, light.world_line.velocity);
  }
  for (const Object& o : s.objects) {
    key.insert(key.end(),
               {o.world_line.time,
                static_cast<double>(reinterpret_cast<std::uintptr_t>(shape_identity(o.shape)))});
    append(key, o.world_line.position);
    append(key, o.world_line.velocity);
    append(key, o.scale);
    for (const auto& row : o.rotation.m) key.insert(key.end(), row.begin(), row.end());
  }
  // The observation event moves the maps' origins (their contents stay).
  const Vec4& observation = scene.observation_event;
  if (key != key_) {
    build(scene, lights);
    key_ = std::move(key);
  }
  for (std::size_t l = 0; l < lights; ++l) {
    const WorldLine& line = s.lights[l].world_line;
    views_[l].origin = Vec4{0, position_at(line, observation.t) - observation.x};
  }
}

void ShadowMaps::build(const ResolvedScene& scene, std::size_t lights) {
  const Scene& s = *scene.scene;
  const double t = scene.observation_event.t;
  views_.assign(lights, {});
  int layers = 0;
  for (std::size_t l = 0; l < lights; ++l)
    for (const Object& o : s.objects)
      if (views_[l].layer < 0 &&
          raster_shadow_cast(o, s.lights[l], s.render) == RasterShadowCast::kMap) {
        views_[l].layer = layers;
        layers += 6;
      }
  if (layers == 0) return;
  face_size_ = layers > 6 * 8 ? 256 : 512;

  // Every casting shape's untessellated triangles, once (straight edges stay straight in R),
  // and the radius about its origin.
  std::vector<float> vertices;
  struct ShapeRange {
    GLint first = 0;
    GLsizei count = 0;
    double radius = 0;
  };
  std::map<const void*, ShapeRange> shapes;
  std::vector<const ShapeRange*> body_shape(s.objects.size());
  for (std::size_t b = 0; b < s.objects.size(); ++b) {
    const Object& o = s.objects[b];
    bool casts = false;  // into any light's maps
    for (std::size_t l = 0; l < lights && !casts; ++l)
      casts = raster_shadow_cast(o, s.lights[l], s.render) == RasterShadowCast::kMap;
    if (!casts) continue;
    const void* shape_key = shape_identity(o.shape);
    auto [it, added] = shapes.emplace(shape_key, ShapeRange{});
    if (added) {
      // A sphere is drawn as its bounding box, and met exactly per texel (shadow.frag).
      const auto* sphere = std::get_if<Sphere>(&o.shape);
      const RestMesh mesh =
          sphere ? rest_mesh(Box{Vec3{2, 2, 2} * sphere->radius}) : rest_mesh(o.shape);
      it->second.first = static_cast<GLint>(vertices.size() / 3);
      for (const Vec3& p : mesh.positions)
        it->second.radius = std::max(it->second.radius, length(p));
      for (const auto& triangle : mesh.triangles)
        for (const std::uint32_t i : triangle) {
          const Vec3& p = mesh.positions[i];
          vertices.insert(vertices.end(), {static_cast<float>(p.x), static_cast<float>(p.y),
                                           static_cast<float>(p.z)});
        }
      it->second.count = static_cast<GLsizei>(vertices.size() / 3) - it->second.first;
    }
    body_shape[b] = &it->second;
  }

  GLint framebuffer = 0, viewport[4];
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  glGetIntegerv(GL_VIEWPORT, viewport);
  glBindTexture(GL_TEXTURE_2D_ARRAY, texture_);
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT32F, face_size_, face_size_, layers, 0,
               GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  glBindVertexArray(vertex_array_);
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
               vertices.data(), GL_STATIC_DRAW);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  const GLenum none = GL_NONE;
  glDrawBuffers(1, &none);
  glReadBuffer(GL_NONE);
  glViewport(0, 0, face_size_, face_size_);
  glUseProgram(program_);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);

  for (std::size_t l = 0; l < lights; ++l) {
    ShadowMapView& view = views_[l];
    if (view.layer < 0) continue;
    const Light& light = s.lights[l];
    // Events at the camera's time, carried into R (the light's rest frame; in the classical
    // picture, W itself at that instant).
    const Mat4 to_light_frame =
        s.render.relativity ? boost(light.world_line.velocity) : Mat4::identity();
    const Vec4 light_event{t, position_at(light.world_line, t)};
    struct Caster {
      std::size_t body;
      Vec3 offset;
    };
    std::vector<Caster> casters;
    double far = 1e-6;
    for (std::size_t b = 0; b < s.objects.size(); ++b) {
      const Object& o = s.objects[b];
      if (raster_shadow_cast(o, light, s.render) != RasterShadowCast::kMap) continue;
      const Vec4 body_event{t, position_at(o.world_line, t)};
      const Vec3 offset = (to_light_frame * (body_event - light_event)).x;
      casters.push_back({b, offset});
      const Vec3& k = o.scale;
      far = std::max(
          far, length(offset) +
                   body_shape[b]->radius * std::max({std::abs(k.x), std::abs(k.y), std::abs(k.z)}));
    }
    view.far = 1.01 * far;
    glUniform1f(uniform(program_, "far_distance"), static_cast<float>(view.far));
    for (int f = 0; f < 6; ++f) {
      glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, texture_, 0, view.layer + f);
      glClear(GL_DEPTH_BUFFER_BIT);
      set_vec3(program_, "face_forward", kFaces[f].forward);
      set_vec3(program_, "face_right", kFaces[f].right);
      set_vec3(program_, "face_up", kFaces[f].up);
      for (const Caster& c : casters) {
        const Object& o = s.objects[c.body];
        const Mat3 shape_to_light = o.rotation * Mat3::diagonal(o.scale);
        set_mat3(program_, "shape_to_light", shape_to_light);
        set_mat3(program_, "light_to_shape",
                 Mat3::diagonal({1 / o.scale.x, 1 / o.scale.y, 1 / o.scale.z}) *
                     o.rotation.transposed());
        const auto* sphere = std::get_if<Sphere>(&o.shape);
        glUniform1f(uniform(program_, "sphere_radius"),
                    sphere ? static_cast<float>(sphere->radius) : 0.0f);
        set_vec3(program_, "body_offset", c.offset);
        glDrawArrays(GL_TRIANGLES, body_shape[c.body]->first, body_shape[c.body]->count);
      }
    }
  }
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(framebuffer));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  check_gl("drawing the shadow maps");
}

void ShadowMaps::bind(int unit) const {
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  glBindTexture(GL_TEXTURE_2D_ARRAY, texture_);
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace lightcone

#include "lightcone/raster/shadow_casters.hpp"

#include <algorithm>
#include <string>

#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/shadow_maps.hpp"

namespace lightcone {
namespace {

// Both textures are rows of this many RGBA texels (lighting.glsl's kCasterTexelsPerRow).
constexpr int kTexelsPerRow = 2048;
// A caster's texels in the table (lighting.glsl's exactly_shadowed): its kind and size, the
// three rows of its map, its offset and (a mesh) its root node; for a spinning body also the
// rows of rest_from_shape and of shape_of_rest, its axis and rate, its clock's row, and the
// radius of its ball and its clock's origin.
constexpr int kCasterTexels = 14;

// Uploads `texels` RGBA floats as rows of kTexelsPerRow texels.
void upload_rows(GLuint texture, int unit, std::vector<float>& texels, const char* what) {
  const std::size_t count = std::max<std::size_t>(texels.size() / 4, 1);
  const std::size_t rows = (count + kTexelsPerRow - 1) / kTexelsPerRow;
  GLint largest = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
  // A texel's index must also stay exact as a float (2^24).
  if (rows > static_cast<std::size_t>(largest) || count > (std::size_t{1} << 24))
    throw GlUnavailable(std::string("the ") + what + " need " + std::to_string(rows) +
                        " rows of a texture, more than this GL driver allows (" +
                        std::to_string(largest) + ")");
  texels.resize(4 * rows * kTexelsPerRow, 0.0f);
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kTexelsPerRow, static_cast<GLsizei>(rows), 0, GL_RGBA,
               GL_FLOAT, texels.data());
  glActiveTexture(GL_TEXTURE0);
}

void push(std::vector<float>& out, const Vec3& v, double w) {
  out.insert(out.end(), {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z),
                         static_cast<float>(w)});
}

}  // namespace

std::vector<ExactCaster> exact_casters(const ResolvedScene& scene, std::size_t lights) {
  const Scene& s = *scene.scene;
  std::vector<ExactCaster> out;
  for (std::size_t b = 0; b < s.objects.size(); ++b) {
    const Object& o = s.objects[b];
    bool exact = false;
    for (std::size_t l = 0; l < lights && !exact; ++l)
      exact = raster_shadow_cast(o, s.lights[l], s.render) == RasterShadowCast::kExact;
    if (!exact) continue;
    ExactCaster c;
    if (const auto* box = std::get_if<Box>(&o.shape)) {
      c.kind = 1;
      c.size = box->size;
    } else if (const auto* plane = std::get_if<Plane>(&o.shape)) {
      c.kind = 2;
      c.size = {plane->size_x, 0, plane->size_z};
    } else if (const auto* sphere = std::get_if<Sphere>(&o.shape)) {
      c.kind = 3;
      c.size = {sphere->radius, 0, 0};
    } else {
      c.kind = 4;
      c.mesh = std::get<MeshShape>(o.shape).mesh;
      if (c.mesh->triangles.empty()) continue;  // casts nothing
    }
    // The tracer's map from W events to shape coordinates, for events relative to the
    // observation event.
    const WorldShapeMap& map = scene.world_maps[b];
    for (int r = 0; r < 3; ++r)
      c.rows[static_cast<std::size_t>(r)] = {
          map.time_column[r], {map.spatial.m[r][0], map.spatial.m[r][1], map.spatial.m[r][2]}};
    c.offset = map.shape_point(scene.observation_event);
    if (scene.bodies[b].spin >= 0) {
      const ResolvedSpin& spin = scene.spins[static_cast<std::size_t>(scene.bodies[b].spin)];
      if (!spin.round) {
        c.spin = &spin;
        const Vec4& row = spin.shadow_proper_time_row;
        c.tau_origin = spin.shadow_proper_time_origin + row.t * scene.observation_event.t +
                       dot(row.x, scene.observation_event.x);
      }
    }
    out.push_back(std::move(c));
  }
  return out;
}

ShadowCasters::ShadowCasters() {
  glGenTextures(1, &table_texture_);
  glGenTextures(1, &mesh_texture_);
}

ShadowCasters::~ShadowCasters() {
  glDeleteTextures(1, &mesh_texture_);
  glDeleteTextures(1, &table_texture_);
}

void ShadowCasters::prepare(const ResolvedScene& scene, std::size_t lights) {
  const std::vector<ExactCaster> casters = exact_casters(scene, lights);
  count_ = static_cast<int>(casters.size());
  any_spinning_ = std::any_of(casters.begin(), casters.end(),
                              [](const ExactCaster& c) { return c.spin != nullptr; });

  // The meshes' hierarchies: made again only when the set of meshes cast changes.
  std::map<std::shared_ptr<const Mesh>, int> roots;
  for (const ExactCaster& c : casters)
    if (c.mesh) roots.emplace(c.mesh, 0);
  any_mesh_ = !roots.empty();
  bool same = roots.size() == mesh_roots_.size() &&
              std::equal(roots.begin(), roots.end(), mesh_roots_.begin(),
                         [](const auto& a, const auto& b) { return a.first == b.first; });
  if (!same && any_mesh_) {
    // Per mesh: its nodes (two texels each: lower and leaf count, upper and second child or
    // first triangle), then its triangles (three texels each, a corner a texel).
    std::vector<float> texels;
    for (auto& [mesh, root] : roots) {
      const MeshBvh bvh = build_mesh_bvh(*mesh);
      root = static_cast<int>(texels.size() / 4);
      const int triangles = root + 2 * static_cast<int>(bvh.nodes.size());
      for (const MeshBvh::Node& n : bvh.nodes) {
        push(texels, n.lower, n.count);
        push(texels, n.upper, n.count ? triangles + 3 * n.first : root + 2 * n.second);
      }
      for (const std::uint32_t t : bvh.order)
        for (const std::uint32_t v : mesh->triangles[t]) push(texels, mesh->positions[v], 0);
    }
    upload_rows(mesh_texture_, kCasterMeshUnit, texels, "shadows of meshes");
  }
  if (!same) mesh_roots_ = std::move(roots);

  table_.clear();
  for (const ExactCaster& c : casters) {
    push(table_, c.size, c.kind + (c.spin ? 8 : 0));
    for (const Vec4& row : c.rows) push(table_, row.x, row.t);
    push(table_, c.offset, c.mesh ? mesh_roots_.at(c.mesh) : 0);
    if (!c.spin) {
      table_.resize(table_.size() + 4 * (kCasterTexels - 5), 0.0f);
      continue;
    }
    for (const Mat3* m : {&c.spin->rest_from_shape, &c.spin->shape_of_rest})
      for (const auto& row : m->m) push(table_, {row[0], row[1], row[2]}, 0);
    push(table_, c.spin->axis, c.spin->rate);
    push(table_, c.spin->shadow_proper_time_row.x, c.spin->shadow_proper_time_row.t);
    push(table_, {c.spin->radius, c.tau_origin, 0}, 0);
  }
  upload_rows(table_texture_, kCasterTableUnit, table_, "shadow casters");
  check_gl("preparing the shadow casters");
}

void ShadowCasters::bind(GLuint program, int table_unit, int mesh_unit) const {
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + table_unit));
  glBindTexture(GL_TEXTURE_2D, table_texture_);
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + mesh_unit));
  glBindTexture(GL_TEXTURE_2D, mesh_texture_);
  glActiveTexture(GL_TEXTURE0);
  glUniform1i(uniform(program, "caster_count"), count_);
  glUniform1i(uniform(program, "caster_table"), table_unit);
  glUniform1i(uniform(program, "caster_meshes"), mesh_unit);
}

}  // namespace lightcone

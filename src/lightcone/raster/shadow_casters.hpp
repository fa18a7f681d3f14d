// The bodies whose shadows the raster renderer meets exactly along each shadow ray, as the
// tracer does: each body's shape in its own rest frame, where it stands still, against the
// shadow ray carried there by the tracer's own map from W events (ResolvedScene::world_maps).
// Any number of them, read from a table texture (lighting.glsl's exactly_shadowed); a mesh's
// triangles in a bounding-volume hierarchy of their own, kept while the mesh is in the scene
// (docs/design/raster.md, "Shadows").
#pragma once

#include <array>
#include <map>
#include <memory>
#include <vector>

#include "lightcone/frame/mesh_bvh.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/raster/gl.hpp"

namespace lightcone {

// One exactly cast body: a shape kind (box 1, plane 2, sphere 3, mesh 4), the map from W events
// relative to the observation event to its shape coordinates (frozen at the angle its origin
// shows, for a spinning body), rows[r] . (t, x, y, z) + offset[r], its size (box sides; plane
// sides in x and z; sphere radius in x) and, for a mesh, its mesh. A spinning body (other than a
// round sphere, which is the same at every angle) also has its spin (ResolvedSpin) and its clock
// at W events relative to the observation event, tau_origin + shadow_proper_time_row . (t, x).
struct ExactCaster {
  int kind = 0;
  std::array<Vec4, 3> rows;
  Vec3 offset, size;
  std::shared_ptr<const Mesh> mesh;
  const ResolvedSpin* spin = nullptr;
  double tau_origin = 0;
};

// Of the scene's bodies, those cast exactly for any of its first `lights` lights
// (raster_shadow_cast), in the scene's order.
std::vector<ExactCaster> exact_casters(const ResolvedScene& scene, std::size_t lights);

// The texture units the body programs read the casters' tables from (units 0 to 11 hold the
// other tables).
inline constexpr int kCasterTableUnit = 12, kCasterMeshUnit = 13;

// The casters' tables on the GPU. Needs a current OpenGL 3.3 context.
class ShadowCasters {
 public:
  ShadowCasters();
  ~ShadowCasters();
  ShadowCasters(const ShadowCasters&) = delete;
  ShadowCasters& operator=(const ShadowCasters&) = delete;

  // The frame's casters: the table made again each frame (it holds the observation event), the
  // meshes' hierarchies when the set of meshes cast changes.
  void prepare(const ResolvedScene& scene, std::size_t lights);
  int count() const { return count_; }
  bool any_mesh() const { return any_mesh_; }
  bool any_spinning() const { return any_spinning_; }
  // Binds the table to unit `table_unit` and the meshes' hierarchies to `mesh_unit`, and sets
  // lighting.glsl's caster uniforms on `program` (in use).
  void bind(GLuint program, int table_unit, int mesh_unit) const;

 private:
  GLuint table_texture_ = 0, mesh_texture_ = 0;
  int count_ = 0;
  bool any_mesh_ = false, any_spinning_ = false;
  std::vector<float> table_;
  // Each mesh's root node as a texel index of the mesh texture (the meshes held, so that no
  // other mesh can take a freed one's address).
  std::map<std::shared_ptr<const Mesh>, int> mesh_roots_;
};

}  // namespace lightcone

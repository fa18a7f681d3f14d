// Retarded shadows for the raster renderer. For each point or spot light, a cube of
// distance maps of the bodies at rest relative to it, in its rest frame R. There those bodies
// and the light stand still, so the backward null ray from a lit surface event to the light's
// emission event (the tracer's shadow ray) runs along the straight segment from the light's
// fixed position to the surface's position in R, whatever the event's time: the map answers
// the tracer's question exactly, to its resolution. In the classical picture the bodies stand
// where they are at the camera's time and the map is of that instant (docs/design/raster.md,
// "Shadows"). Other bodies are met exactly along each shadow ray (raster_shadow_cast,
// raster/shadow_casters.hpp).
#pragma once

#include <map>
#include <vector>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/tessellation.hpp"

namespace lightcone {

// How the raster renderer casts body `object`'s shadow of light `light`, both of a resolved
// scene (accelerated and keyframed bodies and lights on their tangent world-lines, as the tracer
// draws them: ResolvedScene::scene):
// - kMap: in the light's maps (point and spot lights). The body stands still relative to the
//   light: inertial, not spinning, at the light's velocity (in the classical picture every
//   inertial, unspinning body does, at the camera's time);
// - kExact: by meeting its shape exactly along each shadow ray, carried into its rest frame as
//   the tracer does (raster/shadow_casters.hpp; a spinning body along the curve the ray traces
//   through its turning shape): every other body, lit by any light;
// - kNone: bodies on geodesics near a black hole (shadowed per vertex along the curved shadow
//   paths instead: raster/hole_bodies.hpp), and bodies or lights not on their tangent
//   world-lines (not of a resolved scene).
enum class RasterShadowCast { kMap, kExact, kNone };
RasterShadowCast raster_shadow_cast(const Object& object, const Light& light,
                                    const RenderSettings& settings);

// What the lit body programs read of one light's maps (lighting.glsl's shadow uniforms).
struct ShadowMapView {
  int layer = -1;  // the first of its six layers, or -1 for none
  Vec4 origin;     // its position at the camera's time, relative to the observation event (W)
  double far = 1;  // distances are stored over this
};

// Needs a current OpenGL 3.3 context.
class ShadowMaps {
 public:
  ShadowMaps();
  ~ShadowMaps();
  ShadowMaps(const ShadowMaps&) = delete;
  ShadowMaps& operator=(const ShadowMaps&) = delete;

  // The maps of the scene's lights (the first `lights` of them), made again only when a light,
  // a body or the relativity setting changed (the viewer's frames differ in the camera alone).
  void prepare(const ResolvedScene& scene, std::size_t lights);
  const ShadowMapView& view(std::size_t light) const { return views_[light]; }
  // Binds the maps' texture array to texture unit `unit`.
  void bind(int unit) const;
  // Each face's side in texels: 512, or 256 where more than eight lights cast (memory).
  int face_size() const { return face_size_; }

 private:
  void build(const ResolvedScene& scene, std::size_t lights);
  GLuint program_ = 0, texture_ = 0, framebuffer_ = 0, vertex_array_ = 0, vertex_buffer_ = 0;
  std::vector<ShadowMapView> views_;
  std::vector<double> key_;  // what the maps were made from
  int face_size_ = 512;
};

}  // namespace lightcone

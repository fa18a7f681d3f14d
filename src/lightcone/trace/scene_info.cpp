#include "lightcone/trace/scene_info.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/trace/tracer.hpp"

namespace lightcone {
namespace {

BodyInfo body(const std::string& name, const char* kind, const Vec3& v) {
  return {name, kind, v, length(v), lorentz_gamma(v)};
}

// Embree's BVH over triangles, roughly, per triangle.
constexpr std::uint64_t kBvhBytesPerTriangle = 64;

}  // namespace

SceneInfo scene_info(const Scene& scene) {
  SceneInfo info;
  info.width = scene.camera.width;
  info.height = scene.camera.height;
  info.samples = scene.camera.samples;
  // Times in the scene's units; velocities (as seen: accelerating bodies where the camera sees
  // them) in units of c.
  const double c = scene.speed_of_light;
  info.observation_time = scene.camera.world_line.time / c;
  const ResolvedScene resolved = resolve_scene(scene);
  info.bodies.push_back(body("camera", "camera", scene.camera.world_line.velocity));
  for (const Object& o : resolved.scene->objects)
    info.bodies.push_back(body(o.name, "object", o.world_line.velocity));
  for (const Light& l : resolved.scene->lights)
    info.bodies.push_back(body(l.name, "light", l.world_line.velocity));
  info.bodies.push_back(body("sky", "sky", scene.sky.velocity));

  bool first = true;
  for (const bool lit : {false, true}) {
    const LogDopplerRange r = visible_log_doppler(resolved, lit);
    if (r.empty) continue;
    info.doppler_min = first ? std::exp(r.lo) : std::min(info.doppler_min, std::exp(r.lo));
    info.doppler_max = first ? std::exp(r.hi) : std::max(info.doppler_max, std::exp(r.hi));
    first = false;
  }

  // Emission times of what a grid of rays meets.
  const Tracer tracer(resolved);
  constexpr int kRays = 48;
  for (int j = 0; j < kRays; ++j)
    for (int i = 0; i < kRays; ++i) {
      const Vec3 u = look_direction(resolved.camera, (i + 0.5) * info.width / kRays,
                                    (j + 0.5) * info.height / kRays);
      const auto hit = tracer.trace(u);
      if (!hit) continue;
      const double t = resolved.trace_to_world(Vec4{resolved.ray_time * hit->s, u * hit->s}).t / c;
      info.emission_time_min = std::min(info.emission_time_min.value_or(t), t);
      info.emission_time_max = std::max(info.emission_time_max.value_or(t), t);
    }

  std::set<const Mesh*> meshes;
  std::set<const Image*> images;
  for (const Object& o : scene.objects) {
    if (const auto* m = std::get_if<MeshShape>(&o.shape)) meshes.insert(m->mesh.get());
    if (const auto* t = std::get_if<Texture>(&o.material.pattern)) images.insert(t->image.get());
  }
  if (const auto* s = std::get_if<SkyImage>(&scene.sky.pattern)) images.insert(s->image.get());
  for (const Mesh* m : meshes) {
    info.triangles += m->triangles.size();
    info.memory_bytes += m->positions.size() * sizeof(Vec3) + m->uvs.size() * 8 +
                         m->triangles.size() * (12 + kBvhBytesPerTriangle);
  }
  for (const Image* image : images) info.memory_bytes += image->rgb.size() * sizeof(float);
  // The image being rendered, its tone-mapped copy and the 8-bit output.
  info.memory_bytes += static_cast<std::uint64_t>(info.width) * info.height * (12 + 12 + 3);
  return info;
}

}  // namespace lightcone

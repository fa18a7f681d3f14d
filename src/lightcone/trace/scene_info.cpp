#include "lightcone/trace/scene_info.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/aberration.hpp"
#include "lightcone/physics/accretion_disk.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/schwarzschild.hpp"
#include "lightcone/trace/tracer.hpp"

namespace lightcone {
namespace {

BodyInfo body(const std::string& name, const char* kind, const Vec3& v) {
  return {name, kind, v, length(v), lorentz_gamma(v)};
}

// Embree's BVH over triangles, roughly, per triangle.
constexpr std::uint64_t kBvhBytesPerTriangle = 64;

constexpr double kDegrees = 180 / 3.14159265358979323846;

// The grid of camera rays sampled for the shifts and emission times: kRays x kRays.
constexpr int kRays = 48;

// Widens [lo, hi] (unset while `any` is false) to hold x.
void include(double x, bool& any, double& lo, double& hi) {
  lo = any ? std::min(lo, x) : x;
  hi = any ? std::max(hi, x) : x;
  any = true;
}

void add_emission_time(SceneInfo& info, double t) {
  info.emission_time_min = std::min(info.emission_time_min.value_or(t), t);
  info.emission_time_max = std::max(info.emission_time_max.value_or(t), t);
}

// The hole, and what the image shows near it: the shift g of every image of the sky, the disk
// and the bodies a grid of the camera's curved rays meets (each hit solved on the true path, so
// g is exact there), and of every image in view of each body's origin (locate's, as if
// unoccluded: a small body between the grid's rays is not missed); the emission times of the
// bodies met.
HoleInfo hole_info(const Scene& scene, const ResolvedScene& resolved, const Tracer& tracer,
                   SceneInfo& info) {
  const HoleView& hole = *resolved.hole;
  const double m = hole.mass;
  HoleInfo h;
  // In W's units; the view's lengths are in units of the mass.
  h.mass = hole.scale;
  h.horizon = 2 * hole.scale;
  h.photon_sphere = photon_sphere_radius(hole.scale);
  h.isco = isco_radius(hole.scale);
  h.camera_radius = hole.camera_radius * hole.scale;
  // Inside the horizon there is no static observer (NaN: printed as none).
  h.shadow_static_degrees = hole.camera_radius > 2 * m
                                ? static_shadow_angle(m, hole.camera_radius) * kDegrees
                                : std::numeric_limits<double>::quiet_NaN();
  h.shadow_degrees =
      (hole.falling ? shadow_angle(*hole.falling)
                    : shadow_angle_for_camera(hole, scene.camera.world_line.velocity)) *
      kDegrees;
  const std::unique_ptr<const CurvedBodies> bodies =
      resolved.bodies.empty() ? nullptr : std::make_unique<CurvedBodies>(resolved, tracer);
  const double c = scene.speed_of_light;
  double orders = 0;
  for (int j = 0; j < kRays; ++j)
    for (int i = 0; i < kRays; ++i) {
      const Vec3 u = look_direction(resolved.camera, (i + 0.5) * resolved.camera.width / kRays,
                                    (j + 0.5) * resolved.camera.height / kRays);
      const CurvedRay ray = follow_curved_ray(hole, u, bodies.get());
      orders += ray.order;
      if (ray.end == CurvedRayEnd::kHorizon) continue;
      include(ray.shift, h.any_light, h.shift_min, h.shift_max);
      if (ray.end != CurvedRayEnd::kBody) continue;
      add_emission_time(info, ray.event.t / c);
    }
  h.mean_image_order = orders / (kRays * kRays);
  if (hole.camera_radius > 2 * m)  // locate's images need a camera outside the horizon
    for (const ResolvedBody& b : resolved.bodies)
      for (const LocateImage& image :
           locate(scene, resolved, {LocateQuery::Kind::ObjectPoint, b.object->name, {}}).images)
        if (image.in_view) include(image.shift, h.any_light, h.shift_min, h.shift_max);
  return h;
}

}  // namespace

double shadow_angle_for_camera(const HoleView& hole, const Vec3& beta) {
  // The shadow's edge for the static observer: the cone of half-angle alpha about the hole's
  // direction a. Aberration maps it to a circle; three of its points fix that circle.
  const double alpha = static_shadow_angle(hole.mass, hole.camera_radius);
  const Vec3 a = hole.outward * -1.0;
  const Vec3 e =
      std::abs(a.x) < 0.9 ? normalize(cross(a, {1, 0, 0})) : normalize(cross(a, {0, 1, 0}));
  const Vec3 f = cross(a, e);
  Vec3 q[3];
  for (int k = 0; k < 3; ++k) {
    const double theta = 2.0943951023931954923 * k;
    const Vec3 p =
        a * std::cos(alpha) + (e * std::cos(theta) + f * std::sin(theta)) * std::sin(alpha);
    q[k] = aberrate_into_moving_frame(p, beta);
  }
  const Vec3 axis = aberrate_into_moving_frame(a, beta);
  const Vec3 normal = cross(q[1] - q[0], q[2] - q[0]);
  // A shadow too small for the three points to fix a plane in double precision is centred on
  // its axis's image to rounding.
  Vec3 centre = length(normal) > 1e-200 ? normalize(normal) : axis;
  // The shadow holds the image of its axis.
  if (dot(centre, axis) < dot(centre, q[0])) centre = centre * -1.0;
  return std::acos(std::clamp(dot(centre, q[0]), -1.0, 1.0));
}

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
    // On a geodesic near a hole: the velocity the static observer where it is measures, at
    // the camera's time (its coordinate velocity goes to 0 at the horizon).
    info.bodies.push_back(body(
        o.name, "object",
        o.motion.geodesic && scene.black_hole
            ? hole_world_line(o, *scene.black_hole).at(scene.camera.world_line.time).local_velocity
            : o.world_line.velocity));
  for (const Light& l : resolved.scene->lights)
    info.bodies.push_back(body(l.name, "light", l.world_line.velocity));
  info.bodies.push_back(body("sky", "sky", scene.sky.velocity));

  const Tracer tracer(resolved);
  if (resolved.hole) {
    info.hole = hole_info(scene, resolved, tracer, info);
    if (info.hole->any_light) {
      info.doppler_min = info.hole->shift_min;
      info.doppler_max = info.hole->shift_max;
    }
  } else {
    bool any = false;
    for (const bool lit : {false, true}) {
      const LogDopplerRange r = visible_log_doppler(resolved, lit);
      if (r.empty) continue;
      include(std::exp(r.lo), any, info.doppler_min, info.doppler_max);
      include(std::exp(r.hi), any, info.doppler_min, info.doppler_max);
    }
    // Emission times of what a grid of rays meets.
    for (int j = 0; j < kRays; ++j)
      for (int i = 0; i < kRays; ++i) {
        const Vec3 u = look_direction(resolved.camera, (i + 0.5) * info.width / kRays,
                                      (j + 0.5) * info.height / kRays);
        const auto hit = tracer.trace(u);
        if (!hit) continue;
        add_emission_time(
            info, resolved.trace_to_world(Vec4{resolved.ray_time * hit->s, u * hit->s}).t / c);
      }
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

namespace {

nlohmann::ordered_json to_json(const Vec3& v) {
  return nlohmann::ordered_json::array({v.x, v.y, v.z});
}

}  // namespace

std::string scene_info_json(const SceneInfo& info, const Scene& scene) {
  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  for (const BodyInfo& b : info.bodies)
    bodies.push_back({{"name", b.name},
                      {"kind", b.kind},
                      {"velocity", to_json(b.velocity)},
                      {"speed", b.speed},
                      {"gamma", b.gamma}});
  nlohmann::ordered_json out = {
      {"image", {{"width", info.width}, {"height", info.height}, {"samples", info.samples}}},
      {"bodies", bodies},
      {"doppler", {info.doppler_min, info.doppler_max}},
      {"observation_time", info.observation_time},
      {"emission_time", nullptr},
      {"triangles", info.triangles},
      {"memory_bytes", info.memory_bytes}};
  if (info.emission_time_min)
    out["emission_time"] = {*info.emission_time_min, *info.emission_time_max};
  if (const auto& stars = scene.sky.stars)
    out["stars"] = {{"catalogue", stars->catalogue},
                    {"count", stars->stars ? stars->stars->size() : 0},
                    {"magnitude_limit", stars->magnitude_limit},
                    {"exposure", stars->exposure}};
  if (const auto& h = info.hole)
    out["black_hole"] = {{"mass", h->mass},
                         {"horizon", h->horizon},
                         {"photon_sphere", h->photon_sphere},
                         {"isco", h->isco},
                         {"camera_radius", h->camera_radius},
                         {"shadow_degrees", h->shadow_degrees},
                         {"shadow_static_degrees", h->shadow_static_degrees},
                         {"shift", {h->shift_min, h->shift_max}},
                         {"mean_image_order", h->mean_image_order}};
  return out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace lightcone

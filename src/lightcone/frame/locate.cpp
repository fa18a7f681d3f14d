#include "lightcone/frame/locate.hpp"

#include <stdexcept>

#include "lightcone/frame/resolved_scene.hpp"

namespace lightcone {
namespace {

void set_pixel(const CameraBasis& camera, LocateResult& result) {
  const ImagePoint p = project_direction(camera, result.direction);
  result.pixel_x = p.x;
  result.pixel_y = p.y;
  result.in_view =
      p.in_front && p.x >= 0 && p.x <= camera.width && p.y >= 0 && p.y <= camera.height;
}

// The look direction in F of a ray that, carried into the sky's frame, looks along d.
Vec3 direction_from_sky(const ResolvedScene& r, const Vec3& d_pattern) {
  // Solve sky_time_column * ray_time + sky_spatial * u  =  lambda d  for u (unit).
  const Mat3 inv = r.sky_spatial.inverse();
  const Vec3 a = inv * d_pattern;                       // lambda part
  const Vec3 b = inv * r.sky_time_column * r.ray_time;  // fixed part: u = lambda a - b
  // |lambda a - b| = 1, lambda > 0.
  const double aa = dot(a, a), ab = dot(a, b), bb = dot(b, b);
  const double lambda = (ab + std::sqrt(ab * ab - aa * (bb - 1.0))) / aa;
  return normalize(a * lambda - b);
}

}  // namespace

LocateResult locate(const Scene& scene, const LocateQuery& query) {
  const ResolvedScene r = resolve_scene(scene);
  LocateResult result;
  if (query.kind == LocateQuery::Kind::SkyDirection) {
    result.direction =
        direction_from_sky(r, scene.sky.rotation.transposed() * normalize(query.value));
    result.doppler = r.doppler(result.direction, r.sky_velocity);
    set_pixel(r.camera, result);
    return result;
  }

  AffineMap4 world_to_rest;
  Vec3 rest_point;
  double object_proper_time = 0;
  if (query.kind == LocateQuery::Kind::WorldPoint) {
    world_to_rest = body_frame_map(scene.render, WorldLine{});
    rest_point = query.value;
  } else {
    const Object* object = nullptr;
    for (const Object& o : r.scene->objects)
      if (o.name == query.object) object = &o;
    if (!object) throw std::invalid_argument("no object named '" + query.object + "'");
    world_to_rest = body_frame_map(scene.render, object->world_line);
    object_proper_time = object->world_line.proper_time;
    rest_point = object->rotation * component_mul(object->scale, query.value);
  }
  const AffineMap4 trace_to_rest{
      world_to_rest.linear * r.trace_to_world.linear,
      world_to_rest.linear * r.trace_to_world.offset + world_to_rest.offset};
  const TraceWorldLine line = trace_world_line(trace_to_rest, rest_point);
  const RayEvent event = meet_world_line(r.ray_time, line);
  result.direction = normalize(event.position);
  result.doppler = r.doppler(result.direction, line.velocity);
  result.distance = event.s;
  const Vec4 emission{r.ray_time * event.s, event.position};
  const Vec4 world = r.trace_to_world(emission);
  result.emission_time = world.t;
  if (query.kind == LocateQuery::Kind::ObjectPoint)
    result.emission_proper_time = trace_to_rest(emission).t + object_proper_time;
  result.emission_position = world.x;
  set_pixel(r.camera, result);
  return result;
}

}  // namespace lightcone

#include "lightcone/frame/locate.hpp"

#include <cmath>
#include <stdexcept>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/aberration.hpp"
#include "lightcone/physics/schwarzschild_lens.hpp"
#include "lightcone/physics/world_line.hpp"

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

// Near a black hole: the images of a point at rest in W or of a direction far away, each on its
// exact ray (lens_image), carried into the camera's frame by the flat aberration law.
LocateResult locate_near_hole(const Scene& scene, const ResolvedScene& r,
                              const LocateQuery& query) {
  if (query.kind == LocateQuery::Kind::ObjectPoint)
    throw std::invalid_argument("objects near a black hole are not drawn yet");
  const HoleView& hole = *r.hole;
  const Vec3& e1 = hole.outward;
  Vec3 toward;  // from the hole toward the point, or the direction far away
  double r_e = std::numeric_limits<double>::infinity();
  if (query.kind == LocateQuery::Kind::WorldPoint) {
    const Vec3 rel = query.value - hole.centre;
    r_e = length(rel);
    if (!(r_e > 2 * hole.mass))
      throw std::invalid_argument("the point is inside the black hole's horizon");
    toward = rel / r_e;
  } else {
    toward = aberrate_out_of_moving_frame(scene.sky.rotation * normalize(query.value),
                                          scene.sky.velocity);
  }
  const double psi = std::acos(std::clamp(dot(e1, toward), -1.0, 1.0));
  // Exactly in line with the hole every image is a ring; its point toward any side stands for it.
  const Vec3 side = toward - e1 * dot(e1, toward);
  const Vec3 t = length(side) > 0
                     ? normalize(side)
                     : normalize(cross(e1, std::abs(e1.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
  const Vec3 beta = scene.camera.world_line.velocity;
  LocateResult result;
  for (int order = 0; order <= 2; ++order) {
    const auto image = lens_image(hole.mass, hole.camera_radius, r_e, psi, order);
    if (!image) continue;
    const Vec3 d = e1 * image->cos_alpha + t * ((order % 2 == 0 ? 1 : -1) * image->sin_alpha);
    LocateImage out;
    out.order = order;
    out.direction = aberrate_into_moving_frame(d, beta);
    const double camera_energy = camera_photon_energy(hole, out.direction);
    if (query.kind == LocateQuery::Kind::WorldPoint) {
      out.emission_time = scene.camera.world_line.time - image->time;
      out.shift = camera_energy * std::sqrt(1 - 2 * hole.mass / r_e);  // a static emitter
    } else {
      out.shift = camera_energy / sky_photon_energy(hole, toward);
    }
    LocateResult one;
    one.direction = out.direction;
    set_pixel(r.camera, one);
    out.pixel_x = one.pixel_x, out.pixel_y = one.pixel_y, out.in_view = one.in_view;
    result.images.push_back(out);
  }
  if (result.images.empty()) return result;
  const LocateImage& primary = result.images.front();
  result.direction = primary.direction;
  result.pixel_x = primary.pixel_x, result.pixel_y = primary.pixel_y;
  result.in_view = primary.in_view;
  result.doppler = primary.shift;
  result.emission_time = primary.emission_time;
  if (query.kind == LocateQuery::Kind::WorldPoint) result.emission_position = query.value;
  return result;
}

}  // namespace

LocateResult locate(const Scene& scene, const LocateQuery& query) {
  const ResolvedScene r = resolve_scene(scene);
  if (r.hole) return locate_near_hole(scene, r, query);
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
  const Spin* spin = nullptr;
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
    if (object->spin) spin = &*object->spin;
    rest_point = object->rotation * component_mul(object->scale, query.value);
  }
  const AffineMap4 trace_to_rest{
      world_to_rest.linear * r.trace_to_world.linear,
      world_to_rest.linear * r.trace_to_world.offset + world_to_rest.offset};
  if (spin) {
    // The point's own world-line in the rest frame of the body's centre: turning, its angle at
    // the centre's time t' is rate (tau + t').
    const RotatingPointWorldLine point(
        spin->axis, spin->rate,
        Mat3::rotation(spin->axis, spin->rate * object_proper_time) * rest_point);
    const Vec4 observation = trace_to_rest.offset;  // the F origin in the rest frame
    const Mat4 to_trace = inverse(trace_to_rest.linear);
    const AffineMap4 rest_to_trace{to_trace, -1.0 * (to_trace * observation)};
    const Vec3 f_velocity =
        scene.render.relativity ? velocity_of(trace_to_rest.linear * Vec4{1, {}}) : Vec3{};
    const WorldLinePoint p = r.ray_time == -1 ? point.retarded(observation)
                                              : simultaneous_point(point, observation, f_velocity);
    const Vec4 emission = rest_to_trace(p.event);
    result.direction = normalize(emission.x);
    result.doppler =
        r.doppler(result.direction, velocity_of(rest_to_trace.linear * p.four_velocity));
    result.distance = length(emission.x);
    const Vec4 world = r.trace_to_world(emission);
    result.emission_time = world.t;
    result.emission_position = world.x;
    result.emission_proper_time = p.event.t + object_proper_time;
    set_pixel(r.camera, result);
    return result;
  }
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

#include "lightcone/frame/locate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/aberration.hpp"
#include "lightcone/physics/emission_root.hpp"
#include "lightcone/physics/hole_world_line.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/schwarzschild.hpp"
#include "lightcone/physics/schwarzschild_lens.hpp"
#include "lightcone/physics/world_line.hpp"

namespace lightcone {
namespace {

// A sky direction of any nonzero length, made unit: scaled by its largest component first, so
// that components near the limits of double precision square safely.
Vec3 unit_direction(const Vec3& v) {
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return normalize(v / largest);
}

void set_pixel(const CameraBasis& camera, LocateResult& result) {
  const ImagePoint p = project_direction(camera, result.direction);
  result.pixel_x = p.x;
  result.pixel_y = p.y;
  result.in_view =
      p.in_front && p.x >= 0 && p.x <= camera.width && p.y >= 0 && p.y <= camera.height;
}

// One image's ray from the camera toward a point at radius r_e in direction `toward` from the
// hole: its look direction in the camera's static frame, or none.
struct HoleImageRay {
  RayBetween lens;
  Vec3 static_direction;
  Vec3 at_point_radial, at_point_along;  // at the point: the backward ray's unit vectors
  bool outward_at_point = false;         // the backward ray moves outward there
};

std::optional<HoleImageRay> hole_image_ray(const HoleView& hole, double r_e, const Vec3& toward,
                                           int order) {
  const Vec3& e1 = hole.outward;
  const double psi = std::acos(std::clamp(dot(e1, toward), -1.0, 1.0));
  // Exactly in line with the hole every image is a ring; its point toward any side stands for it.
  const Vec3 side = toward - e1 * dot(e1, toward);
  const Vec3 t = length(side) > 0 ? normalize(side) : any_perpendicular(e1);
  const auto lens = ray_between(hole.mass, hole.camera_radius, r_e, psi, order);
  if (!lens) return std::nullopt;
  HoleImageRay ray;
  ray.lens = *lens;
  // The backward ray sweeps from e1 toward the point (even orders) or the other way round.
  const Vec3 turn = order % 2 == 0 ? t : t * -1.0;
  ray.static_direction = e1 * lens->cos_a + turn * lens->sin_a;
  const double c = std::cos(lens->sweep), s = std::sin(lens->sweep);
  ray.at_point_radial = e1 * c + turn * s;
  ray.at_point_along = turn * c - e1 * s;
  // There the ray leaves toward the camera along cos_b; the backward ray goes the other way.
  if (std::isfinite(r_e)) ray.outward_at_point = lens->cos_b < 0;
  return ray;
}

// The direction in which the photon of one image leaves the point at radius r toward the camera
// on `ray`, in the static observer's frame there (W's axes): opposite to the backward ray.
Vec3 photon_direction_at_point(const HoleView& hole, const HoleImageRay& ray, double r) {
  const double f = 1 - 2 * hole.mass / r, b = ray.lens.impact;
  const double radial = std::sqrt(std::max(0.0, 1 - b * b * f / (r * r)));
  const Vec3 backward = ray.at_point_radial * ((ray.outward_at_point ? 1 : -1) * radial) +
                        ray.at_point_along * (b * std::sqrt(f) / r);
  return backward * -1.0;
}

// The energy a body moving with velocity w against the static observer at radius r measures for
// a photon of unit energy at infinity travelling along n (photon_direction_at_point) there: in
// that observer's frame the photon has energy 1 / sqrt(f), so gamma_w (1 - n . w) / sqrt(f).
double emitter_photon_energy(const HoleView& hole, const Vec3& n, double r, const Vec3& w) {
  return lorentz_gamma(w) * (1 - dot(n, w)) / std::sqrt(1 - 2 * hole.mass / r);
}

// Where the point at rest_point from a body's origin is at coordinate time t: relative to the
// hole, with the static observer's velocity of the body there and its clock. Its rest-frame
// offset is contracted along the coordinate velocity (W-simultaneous).
struct PointState {
  Vec3 position, local_velocity;
  double proper_time = 0;
};
PointState body_point_at(const HoleWorldLine& line, const Vec3& rest_point, double t) {
  const HoleWorldLineState s = line.at(t);
  return PointState{s.position + contracted_offset(rest_point, s.velocity), s.local_velocity,
                    s.proper_time};
}

}  // namespace

std::optional<HolePointImage> hole_body_point_image(const HoleView& hole, const WorldLine& camera,
                                                    const HoleWorldLine& line,
                                                    const Vec3& rest_point, int order,
                                                    std::optional<double> emission_time_guess) {
  // Solved in units of the hole's mass, as `line` is; the answers' times and position are W's.
  const double m = hole.scale, now = camera.time / m;
  const Vec3 rest = rest_point / m;
  PointState point;
  double r_e = 0;
  const auto ray_at = [&](double t) {
    point = body_point_at(line, rest, t);
    r_e = length(point.position);
    return r_e > 2 * hole.mass ? hole_image_ray(hole, r_e, point.position / r_e, order)
                               : std::nullopt;
  };
  // late(t) > 0 where light from the point at t arrives after the camera's time; infinite where
  // the point is within the horizon (its light never arrives), NaN where it has no image of this
  // order.
  const auto late = [&](double t) {
    const auto at = ray_at(t);
    if (!at)
      return r_e <= 2 * hole.mass ? std::numeric_limits<double>::infinity()
                                  : std::numeric_limits<double>::quiet_NaN();
    return t + at->lens.time - now;
  };
  double t_e = now;
  std::optional<HoleImageRay> ray;
  if (line.still()) {
    // One place, one ray: its time of flight is the delay.
    ray = ray_at(now);
    if (!ray) return std::nullopt;
    t_e = now - ray->lens.time;
    point = body_point_at(line, rest, t_e);  // (its clock then)
  } else {
    // From the guess (or the camera's time); a part of a body that has fallen within the
    // horizon by the camera's time is still seen from before it crossed.
    const double start =
        emission_time_guess && *emission_time_guess / m < now ? *emission_time_guess / m : now;
    const auto root = emission_time_root(late, now, start, late(start));
    if (!root) return std::nullopt;
    t_e = *root;
    ray = ray_at(t_e);
    if (!ray) return std::nullopt;
  }
  HolePointImage out;
  out.direction = aberrate_into_moving_frame(ray->static_direction, camera.velocity);
  out.emission_time = t_e * m;
  out.emission_position = hole.centre + point.position * m;
  out.proper_time = point.proper_time * m;
  out.to_camera = photon_direction_at_point(hole, *ray, r_e);
  out.local_velocity = point.local_velocity;
  out.shift = camera_photon_energy(hole, out.direction) /
              emitter_photon_energy(hole, out.to_camera, r_e, point.local_velocity);
  return out;
}

HoleSkyImage hole_sky_image_seen(const HoleView& hole, const Vec3& toward, const Vec3& direction,
                                 double solid_angle_ratio) {
  HoleSkyImage image;
  image.direction = direction;
  image.shift = camera_photon_energy(hole, image.direction) / sky_photon_energy(hole, toward);
  // Solid angles go as the inverse square of the photon's energy in each frame: the static
  // observer's 1 / sqrt(f) against the camera's, W's 1 far away against the sky's.
  image.magnification =
      solid_angle_ratio / (hole.camera_lapse * hole.camera_lapse * image.shift * image.shift);
  return image;
}

std::optional<HoleSkyImage> hole_sky_image(const HoleView& hole, const Scene& scene,
                                           const Vec3& sky_direction, int order) {
  const Vec3 toward = aberrate_out_of_moving_frame(sky_direction, scene.sky.velocity);
  const auto ray = hole_image_ray(hole, std::numeric_limits<double>::infinity(), toward, order);
  if (!ray) return std::nullopt;
  // `focusing` is the plane wave's dA_far / dA_camera: the bundle's solid angle at the camera
  // over that far away is f times it.
  const double f = hole.camera_lapse * hole.camera_lapse;
  return hole_sky_image_seen(
      hole, toward,
      aberrate_into_moving_frame(ray->static_direction, scene.camera.world_line.velocity),
      f * ray->lens.focusing);
}

namespace {

// Near a black hole: the images of a point at rest in W, of a direction far away, or of a point
// of a body (at rest, on a line or on a geodesic), each on its exact ray (ray_between), carried
// into the camera's frame by the flat aberration law. A body's point is met where the light's
// time of flight for its position at t_e brings it to the camera at the camera's time:
// t_cam - t_e - T_k(x(t_e)) = 0, strictly decreasing in t_e for a body slower than light,
// bracketed and solved with TOMS 748.
LocateResult locate_near_hole(const Scene& scene, const ResolvedScene& r,
                              const LocateQuery& query) {
  const HoleView& hole = *r.hole;
  const double now = scene.camera.world_line.time;
  const Vec3 beta = scene.camera.world_line.velocity;
  const Object* object = nullptr;
  if (query.kind == LocateQuery::Kind::ObjectPoint) {
    for (const Object& o : r.scene->objects)
      if (o.name == query.object) object = &o;
    if (!object) throw std::invalid_argument("no object named '" + query.object + "'");
  }
  std::optional<HoleWorldLine> line;
  Vec3 rest_point;
  if (object) {
    line = hole_world_line(hole, *object);
    rest_point = object->rotation * component_mul(object->scale, query.value);
  }
  LocateResult result;
  for (int order = 0; order <= 2; ++order) {
    LocateImage out;
    out.order = order;
    std::optional<HoleImageRay> ray;
    double r_e = std::numeric_limits<double>::infinity();
    if (query.kind == LocateQuery::Kind::SkyDirection) {
      const auto image = hole_sky_image(hole, scene, unit_direction(query.value), order);
      if (!image) continue;
      out.direction = image->direction;
      out.shift = image->shift;
    } else if (object) {
      const auto image =
          hole_body_point_image(hole, scene.camera.world_line, *line, rest_point, order);
      if (!image) continue;
      out.direction = image->direction;
      out.emission_time = image->emission_time;
      out.emission_position = image->emission_position;
      out.emission_proper_time = image->proper_time;
      out.shift = image->shift;
    } else {
      const Vec3 from_hole = (query.value - hole.centre) / hole.scale;
      r_e = std::hypot(from_hole.x, from_hole.y, from_hole.z);
      if (!(r_e > 2 * hole.mass)) continue;
      ray = hole_image_ray(hole, r_e, from_hole / r_e, order);
      if (!ray) continue;
      out.direction = aberrate_into_moving_frame(ray->static_direction, beta);
      out.emission_time = now - ray->lens.time * hole.scale;
      out.emission_position = query.value;
      out.shift = camera_photon_energy(hole, out.direction) /
                  emitter_photon_energy(hole, photon_direction_at_point(hole, *ray, r_e), r_e, {});
    }
    if (out.emission_time)
      out.distance = camera_frame_distance(hole, out.direction, now - *out.emission_time);
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
  result.emission_position = primary.emission_position;
  result.emission_proper_time = primary.emission_proper_time;
  result.distance = primary.distance;
  return result;
}

}  // namespace

LocateResult locate(const Scene& scene, const LocateQuery& query) {
  return locate(scene, resolve_scene(scene), query);
}

std::vector<BodyOutOfView> bodies_out_of_view(const Scene& scene) {
  std::vector<BodyOutOfView> out;
  if (scene.black_hole) return out;
  const ResolvedScene r = resolve_scene(scene);
  const CameraBasis& camera = r.camera;
  const double ax = camera.tan_half_fov * camera.aspect, ay = camera.tan_half_fov;
  // The view's four sides, by their inward unit normals.
  const Vec3 sides[4] = {
      normalize(camera.forward * ax + camera.right), normalize(camera.forward * ax - camera.right),
      normalize(camera.forward * ay + camera.up), normalize(camera.forward * ay - camera.up)};
  for (const Object& o : scene.objects) {
    const bool moving = !o.motion.inertial() || o.world_line.velocity != Vec3{};
    if (!moving) continue;  // placed where it is seen
    const LocateResult seen = locate(scene, r, {LocateQuery::Kind::ObjectPoint, o.name, {}});
    const double distance = seen.distance.value_or(0);
    const double radius = origin_radius(o.shape, o.scale);
    if (!(distance > radius)) continue;       // the camera may be within it
    const double margin = radius / distance;  // the sine of the angle the ball subtends
    const bool outside = std::any_of(std::begin(sides), std::end(sides), [&](const Vec3& n) {
      return dot(seen.direction, n) < -margin;
    });
    if (outside) out.push_back({o.name, seen, dot(seen.direction, camera.forward) < 0});
  }
  return out;
}

LocateResult locate(const Scene& scene, const ResolvedScene& r, const LocateQuery& query) {
  if (r.hole) return locate_near_hole(scene, r, query);
  LocateResult result;
  if (query.kind == LocateQuery::Kind::SkyDirection) {
    result.direction =
        r.look_direction_from_sky(scene.sky.rotation.transposed() * unit_direction(query.value));
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

#include "lightcone/render/resolved_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lightcone/physics/retarded_time.hpp"

namespace lightcone {
namespace {

AffineMap4 compose(const AffineMap4& outer, const AffineMap4& inner) {
  return {outer.linear * inner.linear, outer.linear * inner.offset + outer.offset};
}

AffineMap4 invert(const AffineMap4& map) {
  const Mat4 inv = inverse(map.linear);
  return {inv, -1.0 * (inv * map.offset)};
}

Vec3 time_column(const Mat4& m) {
  return {m.m[1][0], m.m[2][0], m.m[3][0]};
}

void expand(Bounds3& b, const Vec3& p, double r) {
  for (int i = 0; i < 3; ++i) {
    b.lower[i] = std::min(b.lower[i], p[i] - r);
    b.upper[i] = std::max(b.upper[i], p[i] + r);
  }
}

Bounds3 empty_bounds() {
  const double inf = std::numeric_limits<double>::infinity();
  return {{inf, inf, inf}, {-inf, -inf, -inf}};
}

// Every event where a ray can meet the body lies within `radius` of the centre's position at
// the same F-time. On the past light cone that F-time is -s with |s - tau_centre| <=
// radius / (1 - |beta|), since s - |X(-s)| changes at a rate of at least 1 - |beta|.
Bounds3 trace_bounds(double ray_time, const TraceWorldLine& centre, double radius) {
  Bounds3 b = empty_bounds();
  if (ray_time == 0) {
    expand(b, centre.position_at_zero, radius);
    return b;
  }
  const double tau = retarded_delay(centre.position_at_zero, centre.velocity);
  const double spread = radius / (1.0 - length(centre.velocity));
  for (double s : {std::max(0.0, tau - spread), tau + spread})
    expand(b, centre.position_at_zero - centre.velocity * s, radius);
  return b;
}

}  // namespace

AffineMap4 body_frame_map(const RenderSettings& settings, const WorldLine& line) {
  const Vec4 origin{line.time, line.position};
  if (settings.relativity) return rest_frame_map(origin, line.velocity);
  const Mat4 g = galilean(line.velocity);
  return {g, -1.0 * (g * origin)};
}

TraceWorldLine trace_world_line(const AffineMap4& trace_to_body, const Vec3& rest_point) {
  const AffineMap4 body_to_trace = invert(trace_to_body);
  const Vec4 at_rest_origin = body_to_trace(Vec4{0, rest_point});
  const Vec4 tangent = body_to_trace.linear * Vec4{1, {}};
  const Vec3 velocity = velocity_of(tangent);
  return {at_rest_origin.x - velocity * at_rest_origin.t, velocity};
}

RayEvent meet_world_line(double ray_time, const TraceWorldLine& line) {
  if (ray_time == 0) return {length(line.position_at_zero), line.position_at_zero};
  const double tau = retarded_delay(line.position_at_zero, line.velocity);
  return {tau, line.position_at_zero - line.velocity * tau};
}

Bounds3 shape_bounds(const Shape& shape) {
  struct Visitor {
    Bounds3 operator()(const Sphere& s) const {
      return {{-s.radius, -s.radius, -s.radius}, {s.radius, s.radius, s.radius}};
    }
    Bounds3 operator()(const Box& b) const { return {b.size * -0.5, b.size * 0.5}; }
    Bounds3 operator()(const Plane& p) const {
      return {{-p.size_x / 2, 0, -p.size_z / 2}, {p.size_x / 2, 0, p.size_z / 2}};
    }
    Bounds3 operator()(const MeshShape& m) const {
      Bounds3 b = empty_bounds();
      for (const Vec3& p : m.mesh->positions) expand(b, p, 0);
      return b;
    }
  };
  return std::visit(Visitor{}, shape);
}

ResolvedScene resolve_scene(const Scene& scene) {
  ResolvedScene r;
  r.scene = &scene;
  r.camera = camera_basis(scene.camera);
  const RenderSettings& settings = scene.render;
  r.ray_time = (settings.relativity && settings.light_delay) ? -1.0 : 0.0;
  const WorldLine& cam = scene.camera.world_line;
  r.observation_event = {cam.time, cam.position};
  // Classical: F is W shifted to the observation event (the camera's motion is irrelevant).
  WorldLine camera_line = cam;
  if (!settings.relativity) camera_line.velocity = {};
  r.world_to_trace = body_frame_map(settings, camera_line);
  r.trace_to_world = invert(r.world_to_trace);

  r.bodies.reserve(scene.objects.size());
  for (const Object& object : scene.objects) {
    const AffineMap4 trace_to_body =
        compose(body_frame_map(settings, object.world_line), r.trace_to_world);
    // shape coordinates p = S^-1 R^-1 x_rest
    const Mat3 to_shape =
        Mat3::diagonal(component_div({1, 1, 1}, object.scale)) * object.rotation.transposed();
    ResolvedBody body;
    body.object = &object;
    body.shape_origin = to_shape * trace_to_body.offset.x;
    body.ray_offset = to_shape * time_column(trace_to_body.linear) * r.ray_time;
    body.spatial = to_shape * trace_to_body.linear.spatial();

    const Bounds3 local = shape_bounds(object.shape);
    const Vec3 centre = (local.lower + local.upper) * 0.5;
    const double radius = length(component_mul(object.scale, (local.upper - local.lower) * 0.5));
    const Vec3 rest_centre = object.rotation * component_mul(object.scale, centre);
    body.trace_bounds =
        trace_bounds(r.ray_time, trace_world_line(trace_to_body, rest_centre), radius);
    r.bodies.push_back(body);
  }

  WorldLine sky_line;
  sky_line.velocity = scene.sky.velocity;
  const AffineMap4 trace_to_sky = compose(body_frame_map(settings, sky_line), r.trace_to_world);
  const Mat3 to_pattern = scene.sky.rotation.transposed();
  r.sky_time_column = to_pattern * time_column(trace_to_sky.linear);
  r.sky_spatial = to_pattern * trace_to_sky.linear.spatial();
  return r;
}

}  // namespace lightcone

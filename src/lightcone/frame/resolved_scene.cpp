#include "lightcone/frame/resolved_scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "lightcone/physics/doppler.hpp"
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

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Conservative bounds in F of the events where a ray can meet a body that lies within the ball
// (rest_centre, radius) of its rest frame. In F the body lies within the ball of that radius
// about its centre c(t) (contracted, in any frame). On the backward null ray an event at F-time
// t is at distance -t from the camera, so the body is met at times t with t + |c(t)| in
// [-radius, radius]: from where the centre crosses the past light cone of the event
// (-radius, 0) to where it crosses that of (radius, 0) (retarded_delay, closed form). On the
// simultaneity hyperplane the body is the (contracted) ball around its centre.
Capsule trace_capsule(double ray_time, const AffineMap4& trace_to_body, const Vec3& rest_centre,
                      double radius) {
  const TraceWorldLine centre = trace_world_line(trace_to_body, rest_centre);
  if (ray_time == 0) return {centre.position_at_zero, centre.position_at_zero, radius};
  Vec3 ends[2];
  for (int k = 0; k < 2; ++k) {
    const double apex = k == 0 ? -radius : radius;
    const Vec3 at_apex = centre.position_at_zero + centre.velocity * apex;
    const double t = apex - retarded_delay(at_apex, centre.velocity);
    ends[k] = centre.position_at_zero + centre.velocity * t;
  }
  return {ends[0], ends[1], radius};
}

Bounds3 capsule_bounds(const Capsule& capsule) {
  Bounds3 b = empty_bounds();
  expand(b, capsule.from, capsule.radius);
  expand(b, capsule.to, capsule.radius);
  return b;
}

// Radius of the ball around the shape's bounds centre that holds the scaled shape.
double scaled_radius(const Shape& shape, const Vec3& scale, const Vec3& centre) {
  if (const auto* sphere = std::get_if<Sphere>(&shape))
    return sphere->radius * std::max({std::abs(scale.x), std::abs(scale.y), std::abs(scale.z)});
  if (const auto* mesh = std::get_if<MeshShape>(&shape)) {
    double r2 = 0;
    for (const Vec3& p : mesh->mesh->positions) {
      const Vec3 q = component_mul(scale, p - centre);
      r2 = std::max(r2, dot(q, q));
    }
    return std::sqrt(r2);
  }
  const Bounds3 local = shape_bounds(shape);
  return length(component_mul(scale, (local.upper - local.lower) * 0.5));
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

WorldLinePoint observed_point(const Scene& scene, const TimelikeWorldLine& line) {
  const RenderSettings& settings = scene.render;
  const WorldLine& cam = scene.camera.world_line;
  const Vec4 observation{cam.time, cam.position};
  if (settings.relativity && settings.light_delay) return line.retarded(observation);
  return simultaneous_point(line, observation, settings.relativity ? cam.velocity : Vec3{});
}

std::shared_ptr<const Scene> tangent_scene(const Scene& scene) {
  const auto moves = [](const auto& body) { return !body.motion.inertial(); };
  if (std::none_of(scene.objects.begin(), scene.objects.end(), moves) &&
      std::none_of(scene.lights.begin(), scene.lights.end(), moves))
    return nullptr;
  auto out = std::make_shared<Scene>(scene);
  // The body's orientation at that event: its rotation in the axes its world-line carries.
  for (Object& o : out->objects)
    if (const auto line = body_world_line(o.world_line, o.motion)) {
      const WorldLinePoint seen = observed_point(scene, *line);
      const Mat3 carried = line->carried_rotation(seen.proper_time);
      o.rotation = carried * o.rotation;
      if (o.spin) o.spin->axis = carried * o.spin->axis;
      o.world_line = tangent_line(seen);
      o.motion = {};
    }
  for (Light& l : out->lights)
    if (const auto line = body_world_line(l.world_line, l.motion)) {
      const WorldLinePoint seen = observed_point(scene, *line);
      if (auto* spot = std::get_if<SpotLight>(&l.kind))
        spot->direction = line->carried_rotation(seen.proper_time) * spot->direction;
      l.world_line = tangent_line(seen);
      l.motion = {};
    }
  return out;
}

std::vector<std::string> tangent_warnings(const Scene& scene) {
  std::vector<std::string> warnings;
  const std::shared_ptr<const Scene> tangent = tangent_scene(scene);
  if (!tangent) return warnings;
  const auto warn = [&](const std::string& what, double a, double r, const char* size) {
    if (a * r > kTangentErrorLimit)
      warnings.push_back(fmt::format(
          "{} accelerates at up to {:.3g} with {} {:.3g}: the tangent approximation's error "
          "(a R = {:.3g}) exceeds {} (docs/design/accelerated-bodies.md)",
          what, a, size, r, a * r, kTangentErrorLimit));
  };
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& o = scene.objects[i];
    const auto line = body_world_line(o.world_line, o.motion);
    if (!line) continue;
    warn(fmt::format("object \"{}\"", o.name), line->max_proper_acceleration(),
         origin_radius(o.shape, o.scale), "radius R");
  }
  // A light lights surfaces from events up to its distance from them away from the one the
  // camera sees.
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    const auto line = body_world_line(l.world_line, l.motion);
    if (!line) continue;
    const Vec3 at = tangent->lights[i].world_line.position;
    double reach = 0;
    for (const Object& o : tangent->objects)
      if (!o.material.unlit) reach = std::max(reach, length(o.world_line.position - at));
    warn(fmt::format("light \"{}\"", l.name), line->max_proper_acceleration(), reach,
         "lit bodies at distance R up to");
  }
  return warnings;
}

SkyToLook ResolvedScene::sky_to_look() const {
  const Mat3 inverse = sky_spatial.inverse();
  return {inverse, inverse * sky_time_column * ray_time};
}

ResolvedScene resolve_scene(const Scene& true_scene) {
  ResolvedScene r;
  r.tangent_scene = tangent_scene(true_scene);
  const Scene& scene = r.tangent_scene ? *r.tangent_scene : true_scene;
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
  const bool with_world_maps = !scene.lights.empty() || scene.black_hole.has_value();
  if (with_world_maps) r.world_maps.reserve(scene.objects.size());
  // Each body's centre world-line in W and bounding radius, for its shadow bounds below.
  std::vector<std::pair<TraceWorldLine, double>> world_centres;
  if (with_world_maps) world_centres.reserve(scene.objects.size());
  // A shape's bounds and the radius of the ball about their centre that holds it scaled, once
  // for all the bodies of one mesh and scale: a swarm of one mesh would otherwise go through its
  // vertices once a body.
  struct ShapeExtent {
    Bounds3 local;
    double scaled_radius = 0;
  };
  std::map<std::tuple<const Mesh*, double, double, double>, ShapeExtent> mesh_extents;
  ShapeExtent other_extent;
  const auto extent_of = [&](const Object& object) -> const ShapeExtent& {
    const auto compute = [&](ShapeExtent& e) {
      e.local = shape_bounds(object.shape);
      e.scaled_radius =
          scaled_radius(object.shape, object.scale, (e.local.lower + e.local.upper) * 0.5);
    };
    const auto* mesh = std::get_if<MeshShape>(&object.shape);
    if (!mesh) {
      compute(other_extent);
      return other_extent;
    }
    const auto key =
        std::make_tuple(mesh->mesh.get(), object.scale.x, object.scale.y, object.scale.z);
    auto it = mesh_extents.find(key);
    if (it == mesh_extents.end()) {
      it = mesh_extents.emplace(key, ShapeExtent{}).first;
      compute(it->second);
    }
    return it->second;
  };
  for (const Object& object : scene.objects) {
    const AffineMap4 world_to_body = body_frame_map(settings, object.world_line);
    const AffineMap4 trace_to_body = compose(world_to_body, r.trace_to_world);
    // shape coordinates p = S^-1 R^-1 x_rest; a spinning body's at the angle its origin shows
    Mat3 to_shape =
        Mat3::diagonal(component_div({1, 1, 1}, object.scale)) * object.rotation.transposed();
    ResolvedBody body;
    body.object = &object;
    if (object.spin) {
      ResolvedSpin spin;
      spin.rest_of_shape = object.rotation * Mat3::diagonal(object.scale);
      spin.shape_of_rest = to_shape;
      spin.axis = object.spin->axis;
      spin.rate = object.spin->rate;
      const double radius = origin_radius(object.shape, object.scale);
      spin.radius = radius * (1 + 1e-9);
      spin.rim_speed = std::abs(spin.rate) * radius;
      const Vec3& k = object.scale;
      spin.round = std::holds_alternative<Sphere>(object.shape) && k.x == k.y && k.y == k.z;
      const RayEvent origin_seen = meet_world_line(r.ray_time, trace_world_line(trace_to_body, {}));
      const double seen_time =
          trace_to_body(Vec4{r.ray_time * origin_seen.s, origin_seen.position}).t +
          object.world_line.proper_time;
      spin.frozen_angle = spin.rate * seen_time;
      const Mat3 frozen = Mat3::rotation(spin.axis, spin.frozen_angle);
      spin.rest_from_shape = frozen * spin.rest_of_shape;
      to_shape = to_shape * frozen.transposed();
      spin.shadow_proper_time_origin = object.world_line.proper_time + world_to_body.offset.t;
      spin.shadow_proper_time_row = {world_to_body.linear.m[0][0],
                                     {world_to_body.linear.m[0][1], world_to_body.linear.m[0][2],
                                      world_to_body.linear.m[0][3]}};
      spin.trace_from_rest = inverse(trace_to_body.linear);
      body.spin = static_cast<int>(r.spins.size());
      r.spins.push_back(spin);
    }
    body.shape_origin = to_shape * trace_to_body.offset.x;
    body.time_column = to_shape * time_column(trace_to_body.linear);
    body.ray_offset = body.time_column * r.ray_time;
    body.spatial = to_shape * trace_to_body.linear.spatial();
    if (with_world_maps)
      r.world_maps.push_back({to_shape * world_to_body.offset.x,
                              to_shape * time_column(world_to_body.linear),
                              to_shape * world_to_body.linear.spatial(),
                              {}});

    const ShapeExtent& extent = extent_of(object);
    const Vec3 centre = (extent.local.lower + extent.local.upper) * 0.5;
    // Slightly enlarged so that rounding in the maps cannot cut off a grazing hit; a spinning
    // body sweeps the ball about its origin.
    const double radius =
        body.spin >= 0 ? r.spins[body.spin].radius : extent.scaled_radius * (1 + 1e-9);
    const Vec3 rest_centre =
        body.spin >= 0 ? Vec3{} : object.rotation * component_mul(object.scale, centre);
    body.trace_capsule = trace_capsule(r.ray_time, trace_to_body, rest_centre, radius);
    body.trace_bounds = capsule_bounds(body.trace_capsule);
    body.velocity = trace_world_line(trace_to_body, rest_centre).velocity;
    body.proper_time_origin = object.world_line.proper_time + trace_to_body.offset.t;
    body.proper_time_row = {
        trace_to_body.linear.m[0][0],
        {trace_to_body.linear.m[0][1], trace_to_body.linear.m[0][2], trace_to_body.linear.m[0][3]}};
    body.rest_centre = rest_centre;
    body.radius = radius;
    r.bodies.push_back(body);
    if (with_world_maps)
      world_centres.emplace_back(trace_world_line(world_to_body, rest_centre), radius);
  }

  WorldLine sky_line;
  sky_line.velocity = scene.sky.velocity;
  const AffineMap4 trace_to_sky = compose(body_frame_map(settings, sky_line), r.trace_to_world);
  const Mat3 to_pattern = scene.sky.rotation.transposed();
  r.sky_time_column = to_pattern * time_column(trace_to_sky.linear);
  r.sky_spatial = to_pattern * trace_to_sky.linear.spatial();
  r.sky_velocity = trace_world_line(trace_to_sky, {}).velocity;
  r.hole = hole_view(scene);

  // Shadow rays run between surface events (on camera rays, so inside the union of the trace
  // bounds, at F-times down to -s_far) and light events, which are at most the light's delay
  // tau earlier; |P(t) - x| <= dist(P(0), box) + |w| s_far bounds the distance, and
  // tau <= distance / (1 - |w|). Directional lights are followed for twice the scene's reach.
  Bounds3 visible = empty_bounds();
  double s_far = 0;
  for (const ResolvedBody& body : r.bodies)
    for (int i = 0; i < 8; ++i) {
      s_far = std::max(s_far, length(corner(body.trace_bounds, i)));
      expand(visible, corner(body.trace_bounds, i), 0);
    }
  auto farthest = [&](const Vec3& from) {
    double d = 0;
    for (int i = 0; i < 8 && !r.bodies.empty(); ++i)
      d = std::max(d, length(corner(visible, i) - from));
    return d;
  };
  struct LightLine {
    TraceWorldLine line;  // in F
    double extent;        // radius of a sphere light
  };
  std::vector<LightLine> light_lines;  // lights at finite distance
  double light_reach = 0;
  for (const Light& light : scene.lights) {
    if (std::holds_alternative<DirectionalLight>(light.kind)) {
      light_reach = std::max(light_reach, 2 * (s_far + farthest({})));
      continue;
    }
    const TraceWorldLine line =
        trace_world_line(compose(body_frame_map(settings, light.world_line), r.trace_to_world), {});
    const double extent = std::holds_alternative<SphereLight>(light.kind)
                              ? std::get<SphereLight>(light.kind).radius
                              : 0;
    const double speed = length(line.velocity);
    const double to_surfaces =
        (farthest(line.position_at_zero) + extent + speed * s_far) / (1 - speed);
    const double to_camera =
        retarded_delay(line.position_at_zero, line.velocity) + extent / (1 - speed);
    light_reach = std::max({light_reach, to_surfaces, to_camera});
    light_lines.push_back({line, extent});
  }
  // The same window in W: events with F-times in [t_min, 0] within a ball of radius reach_f
  // around the F origin (surfaces, lights and the segments between them) have W-times
  // t_obs + a t_F + b.x_F.
  const double t_min = -(s_far + light_reach) * (1 + 1e-9) - 1e-9;
  double reach_f = s_far - t_min;
  for (const LightLine& l : light_lines)
    reach_f = std::max(
        reach_f, length(l.line.position_at_zero) + length(l.line.velocity) * -t_min + l.extent);
  const Mat4& to_world = r.trace_to_world.linear;
  const double a = to_world.m[0][0];
  const double b = length(Vec3{to_world.m[0][1], to_world.m[0][2], to_world.m[0][3]});
  r.shadow_time_min = r.observation_event.t + a * t_min - b * reach_f;
  r.shadow_time_max = r.observation_event.t + b * reach_f;
  for (std::size_t i = 0; i < r.world_maps.size(); ++i) {
    const auto& [centre, radius] = world_centres[i];
    Bounds3& bounds = r.world_maps[i].shadow_bounds;
    bounds = empty_bounds();
    for (double t : {r.shadow_time_min, r.shadow_time_max})
      expand(bounds, centre.position_at_zero + centre.velocity * t, radius);
  }

  // Each light's shadow rays and the range of their labels: the emission events lie within the
  // shadow window; a directional light's label is that of the surface event, which lies on a
  // camera ray within the visible box, at an F-time in [ray_time s_far, 0].
  const double label_slack = 1e-9 * (1 + r.shadow_time_max - r.shadow_time_min);
  for (const Light& light : scene.lights) {
    ShadowLight shadow;
    const Vec3 velocity = settings.relativity ? light.world_line.velocity : Vec3{};
    if (const auto* sun = std::get_if<DirectionalLight>(&light.kind)) {
      const Vec4 k = boost(-velocity) * Vec4{1.0, normalize(sun->direction)};
      shadow.labelled = true;
      shadow.direction = k.x * (1 / k.t);
      shadow.label_min = kInfinity;
      shadow.label_max = -kInfinity;
      for (int i = 0; i < 16 && !r.bodies.empty(); ++i) {
        const double label = shadow.label(
            r.trace_to_world(Vec4{i < 8 ? r.ray_time * s_far : 0, corner(visible, i % 8)}));
        shadow.label_min = std::min(shadow.label_min, label);
        shadow.label_max = std::max(shadow.label_max, label);
      }
    } else {
      shadow.labelled = lit_from_retarded_event(settings);
      shadow.line = trace_world_line(body_frame_map(settings, light.world_line), {});
      if (const auto* sphere = std::get_if<SphereLight>(&light.kind))
        shadow.extent = sphere->radius;
      shadow.label_min = r.shadow_time_min;
      shadow.label_max = r.shadow_time_max;
    }
    shadow.label_min -= label_slack;
    shadow.label_max += label_slack;
    r.shadow_lights.push_back(shadow);
  }
  return r;
}

bool lit_from_retarded_event(const RenderSettings& settings) {
  return settings.relativity && settings.light_source_delay == LightSourceDelay::kSurface;
}

// In W the body lies within the ball of radius R about its centre c(t) (contracted, in any
// frame), and a light's emission points within its radius e of its centre P(sigma). Light from
// the emission event at label sigma reaches a point x at t = sigma + |x - e|, so it meets the
// body at times t with t - sigma - |c(t) - P(sigma)| in [-K, K], K = R + e: from where the centre
// crosses the future light cone of the event (sigma - K, P(sigma)) to where it crosses that of
// (sigma + K, P(sigma)). In the body's rest frame, where the centre C is still, that crossing of
// the cone of an event (T, Q) is at T + |C - Q|: affine in sigma plus the norm of an affine
// function. A directional light's wave of phase sigma meets the body at times t with
// t - n.c(t) in [sigma - R, sigma + R], affine in sigma.
LabelledBounds labelled_bounds(const ResolvedScene& scene, const ResolvedBody& body,
                               const ShadowLight& light) {
  const AffineMap4 world_to_body = body_frame_map(scene.scene->render, body.object->world_line);
  LabelledBounds b;
  b.half = body.radius;
  if (light.directional()) {
    const TraceWorldLine centre = trace_world_line(world_to_body, body.rest_centre);
    const double rate = 1 / (1 - dot(light.direction, centre.velocity));
    const double phase = dot(light.direction, centre.position_at_zero);
    b.early_t0 = (phase - body.radius) * rate;
    b.late_t0 = (phase + body.radius) * rate;
    b.t1 = rate;
    b.x0 = centre.position_at_zero;
    b.v = centre.velocity;
    return b;
  }
  const double reach = body.radius + light.extent;
  const Vec4 e0 = world_to_body(Vec4{0, light.line.position_at_zero});
  const Vec4 e1 = world_to_body.linear * Vec4{1, light.line.velocity};
  const Vec4 later = world_to_body.linear * Vec4{reach, {}};  // (reach, 0) in body coordinates
  b.early_t0 = e0.t - later.t;
  b.late_t0 = e0.t + later.t;
  b.t1 = e1.t;
  b.early_a = body.rest_centre - e0.x + later.x;
  b.late_a = body.rest_centre - e0.x - later.x;
  b.b = -1.0 * e1.x;
  const AffineMap4 body_to_world = invert(world_to_body);
  b.x0 = body_to_world(Vec4{0, body.rest_centre}).x;
  b.v = time_column(body_to_world.linear);
  return b;
}

Bounds3 LabelledBounds::at(double label, double early, double late) const {
  const double first = early_t0 + t1 * label + length(early_a + b * label) - early;
  const double last = late_t0 + t1 * label + length(late_a + b * label) + late;
  Bounds3 box = empty_bounds();
  for (const double t : {first, last}) expand(box, x0 + v * t, half);
  return box;
}

namespace {

// The most the chord of D(sigma) = |a + b sigma| between lo and hi lies above it. D is a
// hyperbola, sqrt(p^2 + |b|^2 (sigma - c)^2) with p its least value (at sigma = c); the chord of
// slope m lies farthest above it where D' = m, at sigma - c = m p / (|b| sqrt(|b|^2 - m^2)). The
// result is enlarged by rounding's reach (1e-9 of D).
double norm_chord_gap(const Vec3& a, const Vec3& b, double lo, double hi) {
  const double speed2 = dot(b, b);
  if (speed2 == 0 || !(hi > lo)) return 0;
  const double at_lo = length(a + b * lo), at_hi = length(a + b * hi);
  const double slope = (at_hi - at_lo) / (hi - lo);
  const double room = speed2 - slope * slope;
  const double rounding = 1e-9 * (at_lo + at_hi);
  if (!(room > 0)) return rounding;
  const double vertex = -dot(a, b) / speed2, least = length(a + b * vertex);
  const double s =
      std::clamp(vertex + slope * least / (std::sqrt(speed2) * std::sqrt(room)), lo, hi);
  return std::max(0.0, at_lo + slope * (s - lo) - length(a + b * s)) + rounding;
}

}  // namespace

double LabelledBounds::chord_gap(double lo, double hi) const {
  return std::max(norm_chord_gap(early_a, b, lo, hi), norm_chord_gap(late_a, b, lo, hi));
}

Bounds3 label_step_bounds(const LabelledBounds& bounds, const ShadowLight& light, unsigned steps,
                          unsigned step) {
  const double width = (light.label_max - light.label_min) / (steps - 1);
  const double label = light.label_min + step * width;
  double gap = 0;
  if (step > 0) gap = bounds.chord_gap(label - width, label);
  if (step + 1 < steps) gap = std::max(gap, bounds.chord_gap(label, label + width));
  return bounds.at(label, gap, 0);
}

double ResolvedScene::doppler(const Vec3& u, const Vec3& velocity) const {
  if (!scene->render.relativity) return 1.0;
  // An emitter at rest in F: the law gives (k.U)/(k.U) = 1 exactly, without its square root
  // and division (the sky and the bodies at rest, most of a picture's rays).
  if (velocity.x == 0 && velocity.y == 0 && velocity.z == 0) return 1.0;
  return doppler_factor(-u, velocity, {});
}

}  // namespace lightcone

// The per-frame resolved view of a scene: everything the tracer needs, expressed in the trace
// frame F for one observation event. The true-state Scene stays untouched.
//
// F has its origin at the observation event. With relativity on, F is the camera's rest frame
// (W boosted by the camera velocity); with relativity off, F is W shifted to the observation
// event and bodies map to their own frames by Galilean transformations. Every camera ray is
// the family of events s (ray_time, u), s >= 0, with u the look direction in F:
//   ray_time = -1: the backward null ray (light delay on), s = light travel time in F;
//   ray_time =  0: the camera's simultaneity hyperplane (light delay off, or classical).
// Each body maps such an event affinely into its shape's own coordinates, where it is static,
// so a ray meets it as an ordinary straight ray (shape_origin + s (time_column * ray_time +
// spatial * u)). The parameter s is common to all bodies, so hits are ordered by it.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/hole_view.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct Bounds3 {
  Vec3 lower, upper;
};

// Bounds that hold nothing: any point extends them.
inline Bounds3 empty_bounds() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {{inf, inf, inf}, {-inf, -inf, -inf}};
}
// Extends b to hold the ball of radius r about p (the point itself for r = 0).
inline void expand(Bounds3& b, const Vec3& p, double r = 0) {
  for (int i = 0; i < 3; ++i) {
    b.lower[i] = std::min(b.lower[i], p[i] - r);
    b.upper[i] = std::max(b.upper[i], p[i] + r);
  }
}

// Corner i (bit 0: x, bit 1: y, bit 2: z upper) of a box.
inline Vec3 corner(const Bounds3& b, int i) {
  return {(i & 1) ? b.upper.x : b.lower.x, (i & 2) ? b.upper.y : b.lower.y,
          (i & 4) ? b.upper.z : b.lower.z};
}

// The points within `radius` of the segment from `from` to `to`.
struct Capsule {
  Vec3 from, to;
  double radius = 0;
};

// A spinning body's rotation, for the exact intersection of rays with it: the ray is carried
// into its rest frame (rest_from_shape of its shape coordinates, which are those of the shape
// frozen at the angle `frozen_angle` its origin shows the camera), where at proper time tau
// the shape is turned by rate tau about axis: a shape point p sits at R(rate tau) rest_of_shape p.
struct ResolvedSpin {
  Mat3 rest_from_shape;  // R(frozen_angle) rotation scale
  Mat3 rest_of_shape;    // rotation scale
  Mat3 shape_of_rest;    // its inverse
  Vec3 axis;
  double rate = 0;          // radians per unit of proper time
  double frozen_angle = 0;  // rate times the proper time at which the camera sees the origin
  double radius = 0;        // of the ball about the origin that holds the shape (padded)
  // A sphere scaled alike on every axis: the same ball at every angle, so a ray meets it where
  // the straight ray does.
  bool round = false;
  // |rate| times the shape's own radius about the origin (not padded): the fastest point's
  // speed relative to the centre, below 1.
  double rim_speed = 0;
  // The proper time at the W event (t, x): shadow_proper_time_origin + row . (t, x).
  double shadow_proper_time_origin = 0;
  Vec4 shadow_proper_time_row;
  Mat4 trace_from_rest;  // the linear part: velocities of points from the rest frame to F
};

// The rapidity of a spinning body's rim relative to its centre: the most any of its points'
// Doppler factors differ from its centre's, in ln D. From the rim speed itself, not from the
// padded radius: a rim within 1e-9 of the speed of light would round up to 1 there, and the
// colour tables refuse an infinite range of ln D.
inline double spin_rapidity(const ResolvedSpin& spin) {
  return std::atanh(spin.rim_speed);
}

struct ResolvedBody {
  const Object* object = nullptr;
  int spin = -1;  // index into ResolvedScene::spins, or -1
  // Shape coordinates of the F event (t, x): shape_origin + time_column t + spatial x. A camera
  // ray s (ray_time, u) maps to shape_origin + s (ray_offset + spatial u).
  Vec3 shape_origin;
  Vec3 time_column;
  Vec3 ray_offset;  // time_column * ray_time
  Mat3 spatial;
  // Conservative bounds in F of every point where a camera ray can meet the body: a capsule
  // (the ball that holds it, along its centre's path while camera rays can meet it), and the
  // capsule's box.
  Capsule trace_capsule;
  Bounds3 trace_bounds;
  Vec3 velocity;  // in F, for the Doppler factor
  // The body's own clock at the F event (t, x): proper_time_origin + proper_time_row . (t, x)
  // (its rest-frame time; every point of a rigid body keeps the clock of its origin).
  double proper_time_origin = 0;
  Vec4 proper_time_row;
  // The ball that holds the body in its rest frame (about its origin for a spinning body).
  Vec3 rest_centre;
  double radius = 0;

  // Whether the body moves relative to the camera (or spins): a subject of the automatic
  // exposure (frame/tone_map.hpp), whose light carries the effects. A body on a geodesic near a
  // black hole (an orbit, a fall) moves, which its world-line's velocity here does not hold.
  bool moves_relative_to_camera() const {
    return spin >= 0 || dot(velocity, velocity) > 0 || object->motion.geodesic.has_value();
  }
  Vec3 shape_direction(const Vec3& u) const { return ray_offset + spatial * u; }
  Vec3 shape_point(const Vec4& event) const {
    return shape_origin + time_column * event.t + spatial * event.x;
  }
  Vec3 shape_vector(const Vec4& direction) const {
    return time_column * direction.t + spatial * direction.x;
  }
  double proper_time(const Vec4& event) const {
    return proper_time_origin + proper_time_row.t * event.t + dot(proper_time_row.x, event.x);
  }
};

// A body seen from the world frame W, where shadow rays are traced (scenes usually keep most
// bodies at rest there, so their bounds need no sweep) and, near a black hole, curved rays
// followed: shape coordinates of the W event (t, x) are origin + time_column t + spatial x, and
// shadow_bounds holds every point the body occupies at W-times in
// [ResolvedScene::shadow_time_min, ResolvedScene::shadow_time_max].
struct WorldShapeMap {
  Vec3 origin;
  Vec3 time_column;
  Mat3 spatial;
  Bounds3 shadow_bounds;

  Vec3 shape_point(const Vec4& world_event) const {
    return origin + time_column * world_event.t + spatial * world_event.x;
  }
  Vec3 shape_vector(const Vec4& world_direction) const {
    return time_column * world_direction.t + spatial * world_direction.x;
  }
};

// A body or point at rest in its own frame, seen from F: where it is at F-time 0 and how it
// moves. Used for bounds and by `locate`.
struct TraceWorldLine {
  Vec3 position_at_zero;
  Vec3 velocity;
};

// How the tracer bounds one light's shadow rays (docs/design/tracer.md). A shadow ray that runs
// along a light cone keeps one number all along it, its label: the W-time of its emission event
// for a point, spot or sphere light seen from the surface's own past light cone
// (LightSourceDelay::kSurface), or its wave's phase t - n.x for a directional light (n its
// direction of propagation in W). The events where rays with labels in an interval can meet a
// body are compact (LabelledBounds), so these rays need no bounds swept over the whole shadow
// window.
struct ShadowLight {
  bool labelled = false;  // false: emission from a fixed event, not along a light cone
  Vec3 direction;         // directional: n (unit); zero for the others
  TraceWorldLine line;    // point, spot, sphere: the centre's world-line in W
  double extent = 0;      // the radius of a sphere light
  double label_min = 0, label_max = 0;  // every shadow ray's label lies within

  bool directional() const { return direction.x != 0 || direction.y != 0 || direction.z != 0; }
  // The label of a shadow ray from its event at the light's end (any of its events for a
  // directional light).
  double label(const Vec4& light_end) const { return light_end.t - dot(direction, light_end.x); }
};

// Bounds of the events where a light's labelled shadow rays with label sigma can meet a body:
// the box around the body's centre x0 + v t, widened by `half`, at its times t (rest-frame
// time; W-time for a directional light) from early(sigma) to late(sigma), each of the form
// t0 + t1 sigma + |a + b sigma|.
struct LabelledBounds {
  double early_t0 = 0, late_t0 = 0, t1 = 0;
  Vec3 early_a, late_a, b;
  Vec3 x0, v;
  double half = 0;

  // The box for label sigma, its time interval widened by `early` and `late` at its two ends.
  Bounds3 at(double label, double early, double late) const;
  // The most the chords of the two norms between labels lo and hi lie above them (norms of
  // affine functions are convex): the margin that keeps boxes interpolated linearly between the
  // two labels conservative.
  double chord_gap(double lo, double hi) const;
};

// Body bounds for `steps` evenly spaced labels from light.label_min to light.label_max, for a
// structure that interpolates boxes linearly between them: the box at step `step` (its label's
// events, lowered at their early end by the chord gaps of the intervals on either side) and the
// one at the next step, interpolated, hold the events of every label between.
Bounds3 label_step_bounds(const LabelledBounds& bounds, const ShadowLight& light, unsigned steps,
                          unsigned step);

// Whether lit surfaces see a light at the event on their own past light cone (else at a fixed
// event: the camera's light cone, or its time).
bool lit_from_retarded_event(const RenderSettings& settings);

// The look direction u whose ray looks along d in the sky's pattern coordinates: the unit u
// with sky_time_column * ray_time + sky_spatial * u = lambda d, lambda > 0, which is
// u = lambda a - b with a = sky_spatial^-1 d, b = sky_spatial^-1 sky_time_column ray_time and
// |lambda a - b| = 1.
struct SkyToLook {
  Mat3 inverse;  // sky_spatial^-1
  Vec3 fixed;    // b
  Vec3 operator()(const Vec3& d) const {
    const Vec3 a = inverse * d;
    const double aa = dot(a, a), ab = dot(a, fixed), bb = dot(fixed, fixed);
    const double lambda = (ab + std::sqrt(ab * ab - aa * (bb - 1.0))) / aa;
    return normalize(a * lambda - fixed);
  }
};

struct ResolvedScene {
  // The scene the renderers read: the true-state scene, or, when bodies or lights move
  // non-inertially, tangent_scene (owned here): the same scene with each of them on the
  // inertial world-line tangent to its own where the observation sees it (tangent_scene()).
  const Scene* scene = nullptr;
  std::shared_ptr<const Scene> tangent_scene;
  CameraBasis camera;
  double ray_time = -1;
  Vec4 observation_event;  // in W
  AffineMap4 world_to_trace;
  AffineMap4 trace_to_world;
  std::vector<ResolvedBody> bodies;
  // bodies[i] seen from W, for scenes with lights or a black hole (empty otherwise: a scene of
  // many unlit bodies does not carry them).
  std::vector<WorldShapeMap> world_maps;
  std::vector<ResolvedSpin> spins;
  // Look direction in the sky's pattern coordinates of the ray event (ray_time, u):
  // normalize(sky_time_column * ray_time + sky_spatial * u).
  Vec3 sky_time_column;
  Mat3 sky_spatial;
  Vec3 sky_velocity;  // in F
  // Shadow rays (segments between surface events and light events, in W) stay within W-times
  // [shadow_time_min, shadow_time_max]; see resolve_scene.
  double shadow_time_min = 0, shadow_time_max = 0;
  std::vector<ShadowLight> shadow_lights;  // one per light of the scene
  // The scene's black hole seen from the observation event: camera rays are then curved
  // (frame/curved_ray.hpp) and the sky's fields above are not used.
  std::optional<HoleView> hole;

  // Doppler factor nu_camera / nu_emitter for light arriving along look direction u from an
  // emitter moving with `velocity` in F (1 for the classical picture).
  double doppler(const Vec3& u, const Vec3& velocity) const;

  Vec3 sky_direction(const Vec3& u) const {
    return normalize(sky_time_column * ray_time + sky_spatial * u);
  }
  // Its inverse: the look direction whose ray looks along `pattern_direction` (unit) in the
  // sky's pattern coordinates (for many directions, sky_to_look() once).
  Vec3 look_direction_from_sky(const Vec3& pattern_direction) const {
    return sky_to_look()(pattern_direction);
  }
  SkyToLook sky_to_look() const;
};

ResolvedScene resolve_scene(const Scene& scene);

// The event of a world-line the observation sees, as the tracer's rays meet it: on the
// camera's past light cone (light delay on), else simultaneous with the observation in the
// camera's rest frame, or at its world time in the classical picture.
WorldLinePoint observed_point(const Scene& scene, const TimelikeWorldLine& line);

// The scene with every object and light that moves non-inertially put on the inertial
// world-line tangent to its origin's at observed_point (docs/design/accelerated-bodies.md);
// null when all move inertially.
std::shared_ptr<const Scene> tangent_scene(const Scene& scene);

// One warning per body whose tangent approximation errs by more than kTangentErrorLimit: its
// largest proper acceleration a times its bounding radius R bounds the relative error of the
// Doppler factor (a R) and twice that of the position in units of R (a R^2 / 2).
constexpr double kTangentErrorLimit = 0.01;
std::vector<std::string> tangent_warnings(const Scene& scene);

// The map from W events to the rest frame of a body with world-line `line` (origin at the
// event (line.time, line.position)), Lorentz or Galilean as the settings say.
AffineMap4 body_frame_map(const RenderSettings& settings, const WorldLine& line);

// The world-line in F of a point at rest at `rest_point` in a body's frame, where
// `trace_to_body` maps F events to the body frame.
TraceWorldLine trace_world_line(const AffineMap4& trace_to_body, const Vec3& rest_point);

// Where a ray event (ray_time, direction) meets a world-line: the ray parameter s >= 0 of the
// event on the ray that lies on the world-line (ray_time -1: retarded, closed form; 0:
// simultaneous in F), and the event's position in F.
struct RayEvent {
  double s = 0;
  Vec3 position;
};
RayEvent meet_world_line(double ray_time, const TraceWorldLine& line);

// The bounds of the events where `light`'s labelled shadow rays can meet `body`.
LabelledBounds labelled_bounds(const ResolvedScene& scene, const ResolvedBody& body,
                               const ShadowLight& light);

// Half extents of a shape's axis-aligned bounds and their centre, in shape coordinates.
Bounds3 shape_bounds(const Shape& shape);

}  // namespace lightcone

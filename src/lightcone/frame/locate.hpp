// Where a point appears: the inverse of the renderer for one point, ignoring occlusion.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/vec.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct LocateQuery {
  enum class Kind { ObjectPoint, WorldPoint, SkyDirection };
  Kind kind = Kind::WorldPoint;
  std::string object;  // for ObjectPoint
  Vec3 value;  // point in the object's shape coordinates / point at rest in W / direction (any
               // nonzero length)
};

// One image of the point near a black hole (orders 0, 1, 2: the primary, the one round the far
// side, the next round the near side).
struct LocateImage {
  int order = 0;
  double pixel_x = 0, pixel_y = 0;
  bool in_view = false;
  Vec3 direction;                       // look direction, camera rest frame
  std::optional<double> emission_time;  // W (Schwarzschild coordinate) time; none at infinity
  std::optional<Vec3> emission_position;
  std::optional<double> emission_proper_time;  // an object's clock (its origin's) then
  // The light's coordinate time of flight in the camera's frame (camera_frame_distance): the
  // output variable distance of the pixel; none at infinity.
  std::optional<double> distance;
  double shift = 1;  // g = nu_camera / nu_emitter
};

struct LocateResult {
  double pixel_x = 0, pixel_y = 0;  // image point (pixel (i, j) has its centre at i+.5, j+.5)
  Vec3 direction;                   // apparent look direction, camera rest frame
  // The emission event in W; absent for a direction at infinity.
  std::optional<double> emission_time;
  std::optional<Vec3> emission_position;
  std::optional<double> distance;  // light travel distance in the camera frame
  // The object's own clock when it emitted the light (for an object's point).
  std::optional<double> emission_proper_time;
  bool in_view = false;
  double doppler = 1;  // D = nu_camera / nu_emitter for light from the located point
  // Near a black hole: every image of orders 0 to 2 that exists, the first of which the fields
  // above describe (a point at rest in W, a direction far away, or a point of an object).
  std::vector<LocateImage> images;
};

// Throws std::invalid_argument when the named object does not exist.
LocateResult locate(const Scene& scene, const LocateQuery& query);
// The same with the scene resolved beforehand (resolve_scene(scene)).
LocateResult locate(const Scene& scene, const ResolvedScene& resolved, const LocateQuery& query);

// A moving body the camera does not see (flat spacetime): its origin is seen outside the view
// by more than the angle its radius about the origin subtends at the distance its light
// travelled, so none of it can be in view. For check's and info's warnings: a moving body
// placed by `position` is seen where it was when its light left, which can be far from there
// (a body at rest in W is seen where it is, so it is the user's framing, and not warned of).
struct BodyOutOfView {
  std::string name;
  LocateResult seen;    // where its origin is seen
  bool behind = false;  // in the half of the sky behind the camera
};
// Every such body; none near a black hole (whose images can be anywhere).
std::vector<BodyOutOfView> bodies_out_of_view(const Scene& scene);

// Near a black hole (the camera outside the horizon): the image of order k (0, 1, 2, ...) of a
// point of a body, `rest_point` its offset from the body's origin in the body's rest frame
// (W's axes: rotation and scale applied), on the body's world-line `line` (in units of the
// hole's mass: hole_world_line(hole, object), hole_view.hpp): the emission event
// at which light from where the point then is reaches the camera at its time along that
// order's exact ray, t_cam - t_e - T_k(x(t_e)) = 0 (strictly decreasing in t_e; bracketed and
// solved with TOMS 748), with its look direction in the camera's frame, shift and clock. None
// where the point is within the horizon or has no image of that order. locate's --object answers
// and the raster renderer's vertices near a hole both come from here; the renderer's
// `emission_time_guess` (its neighbours', a W time) starts the bracket near the root.
struct HoleView;
struct HolePointImage {
  Vec3 direction;            // look direction, camera rest frame
  double emission_time = 0;  // W
  Vec3 emission_position;    // W
  double proper_time = 0;    // the body's clock (its origin's) then
  double shift = 1;          // g = nu_camera / nu_emitter
  // In the static observer's frame at the emission event: the direction the light leaves in
  // toward the camera, and the body's velocity.
  Vec3 to_camera, local_velocity;
};
std::optional<HolePointImage> hole_body_point_image(const HoleView& hole, const WorldLine& camera,
                                                    const HoleWorldLine& line,
                                                    const Vec3& rest_point, int order,
                                                    std::optional<double> emission_time_guess = {});

// Near a black hole (the camera outside the horizon, not falling): the image of order k of a
// direction far away, `sky_direction` in the sky's rest frame (unit, pointing away from the
// hole), on its exact ray, carried into the camera's frame by the flat aberration law: its look
// direction, its shift g and the ratio of a small bundle's solid angle at the camera to that in
// the sky's frame (the lens's and both frames' aberration together: 1 / g^2 without a lens).
// None where that order does not exist. locate --direction and the stars both use it.
struct HoleSkyImage {
  Vec3 direction;  // look direction, camera rest frame
  double shift = 1;
  double magnification = 1;
};
std::optional<HoleSkyImage> hole_sky_image(const HoleView& hole, const Scene& scene,
                                           const Vec3& sky_direction, int order);
// The same from what a lens solve gives: `toward`, W's direction far away (the sky's direction
// carried out of its frame), the image's look direction (the static observer's at the camera
// carried into the camera's frame by the flat aberration law), and the ratio of a bundle's solid
// angle in the static observer's frame to that far away (FarImageTable's).
HoleSkyImage hole_sky_image_seen(const HoleView& hole, const Vec3& toward, const Vec3& direction,
                                 double solid_angle_ratio);

}  // namespace lightcone

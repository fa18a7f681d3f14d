#include "lightcone/scene/reframe.hpp"

#include <stdexcept>

#include "lightcone/physics/lorentz.hpp"

namespace lightcone {
namespace {

Vec3 velocity_in_frame(const Vec3& velocity, const Vec3& frame_beta) {
  const double g = lorentz_gamma(velocity);
  return velocity_of(boost(frame_beta) * Vec4{g, velocity * g});
}

WorldLine reframe_line(const WorldLine& line, const Vec3& frame_beta) {
  const Vec4 event = boost(frame_beta) * Vec4{line.time, line.position};
  return {event.t, event.x, velocity_in_frame(line.velocity, frame_beta), line.proper_time};
}

}  // namespace

Mat3 wigner_rotation(const Vec3& velocity, const Vec3& frame_beta) {
  const Vec3 moved = velocity_in_frame(velocity, frame_beta);
  return (boost(velocity) * boost(-frame_beta) * boost(-moved)).spatial();
}

// A body's phases of acceleration, written in the new frame (its start event moves with the
// world-line); keyframes, world times and positions on a cubic in W's time, are no cubic in
// another frame's.
template <class Body>
void reframe_motion(Body& body, const Vec3& frame_beta) {
  if (!body.motion.keyframes.empty())
    throw std::invalid_argument("a keyframed world-line cannot be described in another frame");
  if (body.motion.phases.empty()) return;
  const AcceleratedWorldLine line(body.world_line.time, body.world_line.position,
                                  body.world_line.velocity, body.motion.phases);
  body.motion.phases = line.described_in(boost(frame_beta)).phases;
}

Scene describe_in_frame(const Scene& scene, const Vec3& beta) {
  Scene out = scene;
  for (Object& o : out.objects) {
    reframe_motion(o, beta);
    const Mat3 turn = wigner_rotation(o.world_line.velocity, beta).transposed();
    o.rotation = turn * o.rotation;
    if (o.spin) o.spin->axis = turn * o.spin->axis;
    o.world_line = reframe_line(o.world_line, beta);
  }
  for (Light& light : out.lights) {
    reframe_motion(light, beta);
    const Mat3 turn = wigner_rotation(light.world_line.velocity, beta).transposed();
    if (auto* spot = std::get_if<SpotLight>(&light.kind)) spot->direction = turn * spot->direction;
    if (auto* sun = std::get_if<DirectionalLight>(&light.kind))
      sun->direction = turn * sun->direction;
    light.world_line = reframe_line(light.world_line, beta);
  }
  Camera& cam = out.camera;
  const Mat3 camera_turn = wigner_rotation(cam.world_line.velocity, beta).transposed();
  cam.forward = camera_turn * cam.forward;
  cam.up = camera_turn * cam.up;
  cam.world_line = reframe_line(cam.world_line, beta);
  if (!cam.motion.keyframes.empty())
    throw std::invalid_argument("a keyframed world-line cannot be described in another frame");
  if (!cam.motion.phases.empty()) {
    const AcceleratedWorldLine line(cam.motion.start.time, cam.motion.start.position,
                                    cam.motion.start.velocity, cam.motion.phases);
    cam.motion.phases = line.described_in(boost(beta)).phases;
  }
  cam.motion.start = reframe_line(cam.motion.start, beta);
  out.sky.rotation = wigner_rotation(scene.sky.velocity, beta).transposed() * scene.sky.rotation;
  out.sky.velocity = velocity_in_frame(scene.sky.velocity, beta);
  return out;
}

}  // namespace lightcone

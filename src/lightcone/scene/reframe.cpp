#include "lightcone/scene/reframe.hpp"

#include "lightcone/physics/lorentz.hpp"

namespace lightcone {
namespace {

Vec3 velocity_in_frame(const Vec3& velocity, const Vec3& frame_beta) {
  const double g = lorentz_gamma(velocity);
  return velocity_of(boost(frame_beta) * Vec4{g, velocity * g});
}

WorldLine reframe_line(const WorldLine& line, const Vec3& frame_beta) {
  const Vec4 event = boost(frame_beta) * Vec4{line.time, line.position};
  return {event.t, event.x, velocity_in_frame(line.velocity, frame_beta)};
}

}  // namespace

Mat3 wigner_rotation(const Vec3& velocity, const Vec3& frame_beta) {
  const Vec3 moved = velocity_in_frame(velocity, frame_beta);
  return (boost(velocity) * boost(-frame_beta) * boost(-moved)).spatial();
}

Scene describe_in_frame(const Scene& scene, const Vec3& beta) {
  Scene out = scene;
  for (Object& o : out.objects) {
    o.rotation = wigner_rotation(o.world_line.velocity, beta).transposed() * o.rotation;
    o.world_line = reframe_line(o.world_line, beta);
  }
  for (Light& light : out.lights) {
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
  out.sky.rotation = wigner_rotation(scene.sky.velocity, beta).transposed() * scene.sky.rotation;
  out.sky.velocity = velocity_in_frame(scene.sky.velocity, beta);
  return out;
}

}  // namespace lightcone

// Re-describing a scene from another inertial frame: the same physical events, bodies and
// camera, written in the coordinates of a frame W' that moves with beta relative to W.
// Used to check the principle of relativity (the image must not change).
#pragma once

#include "lightcone/scene/scene.hpp"

namespace lightcone {

// Every world-line's reference event and velocity are transformed; every rest-frame
// orientation (object rotations, camera forward/up, sky rotation) is corrected by the Wigner
// rotation between the pure boost from W and the pure boost from W' of the body's velocity
// (lights' spot axes and directions included).
Scene describe_in_frame(const Scene& scene, const Vec3& beta);

// The Wigner rotation W with (rest coordinates via the pure boost from W) =
// W (rest coordinates via the pure boost from W'), for a body with velocity `velocity` in W,
// where W' moves with `frame_beta` relative to W.
Mat3 wigner_rotation(const Vec3& velocity, const Vec3& frame_beta);

}  // namespace lightcone

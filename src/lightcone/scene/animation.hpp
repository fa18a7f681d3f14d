// The moments of an animation: frame i of a scene seen at the camera's proper time
// tau_0 + i / fps, or at its world time t_0 + i / fps (in the scene's units of time), as
// `lightcone animate` and the Python module's animate draw them.
#pragma once

#include <optional>
#include <string>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

enum class AnimationClock { kCamera, kWorld };

// Why the scene cannot be animated (a camera that moves near a black hole without a geodesic
// motion: a velocity alone is not a free path there), or nothing.
std::optional<std::string> animation_refused(const Scene& scene);

// Why frames [first, last] cannot be rendered as a part of the animation of frames
// [whole_first, whole_last] (a job array's task given the whole animation, whose automatic
// exposure is smoothed over its frames alone): the whole must hold the part. Or nothing.
std::optional<std::string> animation_part_refused(long long first, long long last,
                                                  long long whole_first, long long whole_last);

// Sets `frame` to frame i's scene: the camera's clock set as camera.proper_time would set it.
// Near a black hole a camera without a geodesic motion is a static one: it stays where it is,
// and its clock runs at sqrt(1 - 2M/r) of W's time. Returns why frame i cannot be drawn (the
// camera at the speed of light by then, a body too fast relative to it, a falling camera past
// where it is drawn), starting "frame i: ", or nothing. The scene must not be refused by
// animation_refused.
std::optional<std::string> animation_frame(const Scene& scene, long long i, double fps,
                                           AnimationClock clock, Scene& frame);

}  // namespace lightcone

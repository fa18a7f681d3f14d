// locate's answer as JSON: what `lightcone locate` prints and the Python module returns.
#pragma once

#include <string>

#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/pixel_probe.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// Whether every number of the answer is finite (a point so far away that its light path
// overflows double precision has none to give).
bool locate_result_is_finite(const LocateResult& r);

// The fields of docs/guide.md's "locate": pixel (null out of view), direction, the emission
// event (times in the scene's units), distance, in_view, doppler; near a black hole every image
// (none, and direction and doppler null, where no light from the point reaches the camera).
// One line, the fields in that order.
std::string locate_json(const LocateResult& r, const Scene& scene);

// The fields of docs/guide.md's "What is seen at a pixel" (`locate --pixel`): pixel, direction,
// meets ("object", "sky", "disk" or "shadow") and what it met (object and point, sky, disk),
// the emission event (times in the scene's units), distance, doppler (g near a black hole) and
// near a black hole the image order. One line, the fields in that order; null where a field
// does not apply.
std::string probe_json(const PixelProbe& p, const Scene& scene);

}  // namespace lightcone

// `lightcone locate --pixel` and the Python module's locate(pixel=...): what the camera sees
// through a point of its picture, on the ray tracer's exact ray (frame/pixel_probe.hpp).
#pragma once

#include "lightcone/frame/pixel_probe.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The probe of image point (x, y) of `scene`, which request_rules' probe_refused lets through.
PixelProbe probe_pixel(const Scene& scene, double x, double y);

}  // namespace lightcone

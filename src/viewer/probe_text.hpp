// The readouts of probes (frame/pixel_probe.hpp) as the viewer's panel and the web page show
// them: what a probe met and its numbers, and the ruler between two.
#pragma once

#include <string>
#include <vector>

#include "lightcone/frame/pixel_probe.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The readout of one probe of `scene` (without its number): what it met, then its numbers.
std::vector<std::string> probe_readout(const PixelProbe& probe, const Scene& scene);
// The ruler between two probes: the angle between their look directions (degrees), and where
// both met a surface, the difference of their emission times (the second's less the first's).
// (Times in units of the scene's speed_of_light, as locate prints them.)
std::string probe_ruler(const PixelProbe& first, const PixelProbe& second, double speed_of_light);

// The readouts of up to two probes of `scene`: each probe's lines, numbered from 1 (its further
// lines indented), then with two the ruler's.
std::vector<std::string> probe_lines(const std::vector<PixelProbe>& probes, const Scene& scene);

}  // namespace lightcone

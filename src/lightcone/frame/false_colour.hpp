// A picture of one output variable (`lightcone render --map NAME`): its values through a
// perceptually uniform colour map, with a labelled scale bar in a band along its bottom.
#pragma once

#include <span>
#include <string>

#include "lightcone/color/cie.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The colour map at t in [0, 1], linear sRGB: a ramp in OKLab (Ottosson, "A perceptual color
// space for image processing", 2020) whose lightness rises evenly from 0.30 to 0.92 while the
// hue turns from blue through green to yellow (chroma 0.12, reduced where sRGB cannot show it),
// so that equal steps of the value look like equal steps.
LinearRgb colour_map(double t);

// The legend's height: the bottom band of a map, where the map is dimmed beneath the bar.
inline constexpr int kLegendHeight = 44;

// The display image (values in [0, 1]) of a width x height channel, the same size: finite values
// mapped linearly from their minimum to their maximum, the others (the sky's distance, -inf
// emission times) grey; where `sky` (a value a pixel) is 1, hatched with dark stripes, so that a
// surface with the sky's value stands apart from it. In the bottom kLegendHeight pixels, over the
// dimmed map: `label` (the quantity and its unit), beside the bar of the map on its left, and
// the values at the bar's ticks beneath it.
Image false_colour(const NamedChannel& channel, int width, int height, const std::string& label,
                   std::span<const float> sky = {});

}  // namespace lightcone

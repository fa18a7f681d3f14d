// A picture of one output variable (`lightcone render --map NAME`): its values through a
// perceptually uniform colour map, with a labelled scale bar beneath.
#pragma once

#include <string>

#include "lightcone/color/cie.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The colour map at t in [0, 1], linear sRGB: a ramp in OKLab (Ottosson, "A perceptual color
// space for image processing", 2020) whose lightness rises evenly from 0.30 to 0.92 while the
// hue turns from blue through green to yellow (chroma 0.12, reduced where sRGB cannot show it),
// so that equal steps of the value look like equal steps.
LinearRgb colour_map(double t);

// The display image (values in [0, 1]) of a width x height channel: finite values mapped
// linearly from their minimum to their maximum, the others (the sky's distance, -inf emission
// times) grey; below it a bar of the map labelled with five values and `label`.
Image false_colour(const NamedChannel& channel, int width, int height, const std::string& label);

}  // namespace lightcone

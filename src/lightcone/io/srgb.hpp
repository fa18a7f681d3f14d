// The sRGB transfer function of 8- and 16-bit images, read and written (image_file.cpp; in the
// browser build, the page's images, which the browser decodes).
#pragma once

#include <array>

namespace lightcone {

// sRGB opto-electronic transfer function for a linear value in [0, 1].
double srgb_encode(double linear);
// Its inverse.
double srgb_decode(double encoded);
// srgb_decode of each 8-bit code, as float.
const std::array<float, 256>& srgb_8bit_decoded();

}  // namespace lightcone

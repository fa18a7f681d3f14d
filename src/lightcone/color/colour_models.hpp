// The simpler Doppler colour models of the seeds, kept beside the spectral one for teaching:
// "rgb3" (seed 000: three spectral lines) and "hue" (seed 003: a hue rotation). Both act on a
// linear RGB colour already known at rest.
#pragma once

#include "lightcone/color/cie.hpp"

namespace lightcone {

// Seed 000's line wavelengths (nm) for red, green and blue.
inline constexpr double kRgb3Wavelengths[3] = {626.0, 534.0, 465.0};

// Line powers (in the 1/cie_y_integral() normalisation) that reproduce `rgb` exactly at D = 1.
LinearRgb rgb3_line_powers(const LinearRgb& rgb);

// The colour of those three lines received with Doppler factor d: each line moves to
// lambda / d and its power is multiplied by `power_factor` (d^4 for the physical searchlight);
// lines outside 360-830 nm contribute nothing.
LinearRgb rgb3_shift(const LinearRgb& rgb, double d, double power_factor);

struct Hsv {
  double h = 0, s = 0, v = 0;  // h in degrees
};
Hsv hsv_from_rgb(const LinearRgb& rgb);
LinearRgb rgb_from_hsv(const Hsv& hsv);

// Seed 003's shader with the exact shift: H += 512 log2(d) degrees (512 per doubling of
// frequency). Outside [0, 300] the value fades linearly to black over 60 degrees (H clamped
// to 0 or 300), or, with `loop`, H wraps around 360 and nothing fades. S and V are kept.
LinearRgb hue_shift(const LinearRgb& rgb, double d, bool loop);

}  // namespace lightcone

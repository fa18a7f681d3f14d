// From linear radiance to what a display shows: automatic exposure and tone curves.
#pragma once

#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The automatic exposure rule: the EV that brings the 95th percentile of pixel luminance
// (Y of linear sRGB) to 0.8, so that a few highlights (a searchlit sun) may clip while the
// rest of the picture is readable. 0 for an image without light.
double auto_exposure(const Image& linear);

// Scales a rendered image by 2^EV, EV the settings' exposure or (auto_exposure on) the automatic
// one; returns the EV applied. Both renderers' pictures end here.
double apply_exposure(Image& linear, const RenderSettings& settings);

// Display-referred linear values in [0, 1] (the PNG then applies the sRGB curve):
//   clamp:    min(max(L, 0), 1) per channel;
//   reinhard: L / (1 + Y) on the luminance Y, so hue is kept while highlights compress;
//   filmic:   the ACES filmic fit of Narkowicz (2015) per channel,
//             x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14).
Image tone_map(const Image& linear, ToneMap curve);

}  // namespace lightcone

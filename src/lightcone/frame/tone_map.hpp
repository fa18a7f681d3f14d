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
//   filmic:   filmic_on_luminance.
Image tone_map(const Image& linear, ToneMap curve);

// The ACES filmic fit of Narkowicz (2015), y (2.51 y + 0.03) / (y (2.43 y + 0.59) + 0.14), at
// most 1 (the fit itself tends to 1.033).
double filmic_curve(double y);

// The filmic curve on a pixel's luminance Y, so that its hue and saturation are kept: the
// colour is scaled by min(f(Y) / Y, f(M) / M), f the filmic curve and M the largest channel.
// The second bound keeps a saturated colour from clipping long before a grey of its luminance
// would: its largest channel reaches 1 only where f does (M about 7.2). Per channel, the curve
// would turn a bright red toward orange and a blue toward cyan, a false Doppler shift.
void filmic_on_luminance(float* rgb);

}  // namespace lightcone

// From linear radiance to what a display shows: automatic exposure and tone curves.
#pragma once

#include <span>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The luminance (Y of linear sRGB) that `curve` shows as 0.9 of white.
double display_white(ToneMap curve);

// The automatic exposure rule: the EV that shows the upper quartile of the subject's luminance
// as 0.5, unless that would take the brightest 2 % of the whole picture past
// display_white(curve); then the EV that brings them there. `subject` weighs each pixel (the
// share of its samples that met a body moving relative to the camera); without it, or with
// less than 0.1 % of the picture's worth, the subject is the whole picture. 0 for an image
// without light. Both quantiles are read from histograms of 1/256 of an octave (an
// ExposureMeter, exposure_meter.hpp), within 0.003 EV of the pixels' own values, in one
// parallel pass; a renderer that fills the meter as it draws gets the same EV without it.
double auto_exposure(const Image& linear, ToneMap curve, std::span<const float> subject = {});

// The factor an exposure of `ev` scales radiance by, 2^EV, in single precision.
float exposure_scale(double ev);

// Scales a rendered image by 2^EV (nothing to scale at EV 0) and returns how many of its
// values are then not finite: counted in the same pass, so that a renderer's check of its
// picture (request_rules' picture_refused) does not read it again.
std::size_t expose(Image& linear, double ev);

// expose() at the settings' exposure or (auto_exposure on) the automatic one: the EV applied
// and the values then not finite. Both renderers' pictures end here or in expose().
struct AppliedExposure {
  double ev = 0;
  std::size_t non_finite = 0;
};
AppliedExposure apply_exposure(Image& linear, const RenderSettings& settings,
                               std::span<const float> subject = {});

// Display-referred linear values in [0, 1] (the PNG then applies the sRGB curve):
//   clamp:    min(max(L, 0), 1) per channel;
//   reinhard: L / (1 + Y) on the luminance Y, so hue is kept while highlights compress;
//   filmic:   filmic_on_luminance.
// The picture only: the linear image's output variables (channels) are not carried. The
// second form maps the picture in place, without a new one to fill.
Image tone_map(const Image& linear, ToneMap curve);
Image tone_map(Image&& linear, ToneMap curve);
// expose() then tone_map() in one pass over the picture, in place, for a picture only a display
// will show (a renderer's left at EV 0 by RenderOptions::defer_exposure): the same values as the
// two passes, and `non_finite` what expose() would return.
Image expose_and_tone_map(Image&& linear, double ev, ToneMap curve, std::size_t& non_finite);

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

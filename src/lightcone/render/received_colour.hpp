// The colour a camera receives from a rest-frame emission seen with Doppler factor D, under the
// scene's Doppler colour model and searchlight model.
#pragma once

#include "lightcone/color/wavelengths.hpp"
#include "lightcone/render/emission.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The factor on spectral radiance (D^5 physical, D for Chang et al. 1996, 1 off).
double spectral_searchlight(double d, SearchlightModel model);
// The factor on radiance integrated over wavelength (D^4 physical, D, 1).
double integrated_searchlight(double d, SearchlightModel model);

// Linear sRGB received. For the spectral model the estimate is the rest colour plus a hero-
// wavelength Monte Carlo estimate of what the shift changes,
//   integral of [s(D) L_E(D lambda) - L_E(lambda)] cmf(lambda) dlambda / integral of y-bar,
// which has the same expectation as estimating the shifted spectrum directly but no noise and
// no RGB-to-spectrum fitting error at D = 1 (the rest colour is exact), and little near it.
LinearRgb received_colour(const PointEmission& emission, double d, const RenderSettings& settings,
                          const SampledWavelengths& wavelengths);

}  // namespace lightcone

// The colour a camera receives from a rest-frame emission seen with Doppler factor D, under the
// scene's Doppler colour model and searchlight model.
#pragma once

#include "lightcone/frame/emission.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The factor on spectral radiance (D^5 physical, D for Chang et al. 1996, 1 off).
double spectral_searchlight(double d, SearchlightModel model);
// The factor on radiance integrated over wavelength (D^4 physical, D, 1).
double integrated_searchlight(double d, SearchlightModel model);

// Linear sRGB received. For the spectral model: the emission's tabulated colour at D (the
// deterministic quadrature of L_E(D lambda) against the CIE observer) times the spectral
// searchlight factor; at D = 1 exactly, the rest colour with no spectral work.
LinearRgb received_colour(const PointEmission& emission, double d, const RenderSettings& settings);

}  // namespace lightcone

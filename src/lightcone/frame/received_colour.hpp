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

// The colour received from a blackbody at tau times the temperature of `thermal`'s hottest part,
// seen with factor d. Planck's law scales: B_lambda(lambda; tau T) = tau^5 B_lambda(tau lambda; T),
// so its colour at rest is tau^5 times the hottest part's seen with factor tau, and seen with d
// it is tau^5 times the hottest part's seen with tau d, times the searchlight factor of d (with
// the physical law, exactly a blackbody at tau d T). The other colour models shift its colour at
// rest. Black below the table's floor.
LinearRgb received_thermal_colour(const ThermalEmission& thermal, double tau, double d,
                                  const RenderSettings& settings);

}  // namespace lightcone

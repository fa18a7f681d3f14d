// The colour a camera receives from a rest-frame emission seen with Doppler factor D, under the
// scene's Doppler colour model and searchlight model.
#pragma once

#include "lightcone/frame/emission.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The factor on spectral radiance (D^5 physical, D for Chang et al. 1996, 1 off).
inline double spectral_searchlight(double d, SearchlightModel model) {
  switch (model) {
    case SearchlightModel::kPhysical:
      return d * d * d * d * d;
    case SearchlightModel::kChang1996:
      return d;
    case SearchlightModel::kOff:
      break;
  }
  return 1.0;
}
// The factor on radiance integrated over wavelength (D^4 physical, D, 1).
inline double integrated_searchlight(double d, SearchlightModel model) {
  switch (model) {
    case SearchlightModel::kPhysical:
      return d * d * d * d;
    case SearchlightModel::kChang1996:
      return d;
    case SearchlightModel::kOff:
      break;
  }
  return 1.0;
}

// received_colour under the models that shift the rest colour's RGB (rgb3, hue).
LinearRgb received_shifted_rgb(const PointEmission& emission, double d,
                               const RenderSettings& settings);

// Linear sRGB received. For the spectral model: the emission's tabulated colour at D (the
// deterministic quadrature of L_E(D lambda) against the CIE observer) times the spectral
// searchlight factor; at D = 1 exactly, the rest colour with no spectral work. (Inline: it is
// looked up once per camera ray, where a call's own cost was a tenth of the spectral model's.)
inline LinearRgb received_colour(const PointEmission& emission, double d,
                                 const RenderSettings& settings) {
  const auto scaled = [](const LinearRgb& c, double k) -> LinearRgb {
    return {c.r * k, c.g * k, c.b * k};
  };
  switch (settings.doppler) {
    case DopplerModel::kSpectral:
      if (d == 1 || emission.table_count == 0) return emission.rest_rgb;
      return scaled(emission.rgb_seen_with_doppler(d),
                    spectral_searchlight(d, settings.searchlight));
    case DopplerModel::kOff:
      return scaled(emission.rest_rgb, integrated_searchlight(d, settings.searchlight));
    case DopplerModel::kRgb3:
    case DopplerModel::kHue:
      break;
  }
  return received_shifted_rgb(emission, d, settings);
}

// The colour received from a blackbody at tau times the temperature of `thermal`'s hottest part,
// seen with factor d. Planck's law scales: B_lambda(lambda; tau T) = tau^5 B_lambda(tau lambda; T),
// so its colour at rest is tau^5 times the hottest part's seen with factor tau, and seen with d
// it is tau^5 times the hottest part's seen with tau d, times the searchlight factor of d (with
// the physical law, exactly a blackbody at tau d T). The other colour models shift its colour at
// rest. Black below the table's floor.
LinearRgb received_thermal_colour(const ThermalEmission& thermal, double tau, double d,
                                  const RenderSettings& settings);

}  // namespace lightcone

#include "lightcone/frame/received_colour.hpp"

#include "lightcone/color/colour_models.hpp"

namespace lightcone {
namespace {

LinearRgb scaled(const LinearRgb& c, double k) {
  return {c.r * k, c.g * k, c.b * k};
}

}  // namespace

double spectral_searchlight(double d, SearchlightModel model) {
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

double integrated_searchlight(double d, SearchlightModel model) {
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

LinearRgb received_colour(const PointEmission& e, double d, const RenderSettings& settings) {
  switch (settings.doppler) {
    case DopplerModel::kOff:
      return scaled(e.rest_rgb, integrated_searchlight(d, settings.searchlight));
    case DopplerModel::kRgb3:
      return rgb3_shift(e.rest_rgb, d, integrated_searchlight(d, settings.searchlight));
    case DopplerModel::kHue:
      return scaled(hue_shift(e.rest_rgb, d, settings.hue_loop),
                    integrated_searchlight(d, settings.searchlight));
    case DopplerModel::kSpectral:
      break;
  }
  if (d == 1 || e.table_count == 0) return e.rest_rgb;
  return scaled(e.rgb_seen_with_doppler(d), spectral_searchlight(d, settings.searchlight));
}

LinearRgb received_thermal_colour(const ThermalEmission& thermal, double tau, double d,
                                  const RenderSettings& settings) {
  const bool spectral = settings.doppler == DopplerModel::kSpectral;
  const double s = spectral ? tau * d : tau;
  if (!(s >= thermal.floor)) return {0, 0, 0};
  const double tau5 = tau * tau * tau * tau * tau;
  const Xyz seen = thermal.peak.seen_with_doppler(s);
  const LinearRgb colour = linear_srgb_from_xyz({tau5 * seen.x, tau5 * seen.y, tau5 * seen.z});
  if (spectral) return scaled(colour, spectral_searchlight(d, settings.searchlight));
  PointEmission at_rest;
  at_rest.rest_rgb = colour;
  return received_colour(at_rest, d, settings);
}

}  // namespace lightcone

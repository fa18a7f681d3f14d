#include "lightcone/frame/received_colour.hpp"

#include "lightcone/color/colour_models.hpp"

namespace lightcone {
namespace {

LinearRgb scaled(const LinearRgb& c, double k) {
  return {c.r * k, c.g * k, c.b * k};
}

}  // namespace

LinearRgb received_shifted_rgb(const PointEmission& e, double d, const RenderSettings& settings) {
  const double searchlight = integrated_searchlight(d, settings.searchlight);
  if (settings.doppler == DopplerModel::kRgb3) return rgb3_shift(e.rest_rgb, d, searchlight);
  return scaled(hue_shift(e.rest_rgb, d, settings.hue_loop), searchlight);
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

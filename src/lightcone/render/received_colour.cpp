#include "lightcone/render/received_colour.hpp"

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

LinearRgb received_colour(const PointEmission& e, double d, const RenderSettings& settings,
                          const SampledWavelengths& wavelengths) {
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
  const double factor = spectral_searchlight(d, settings.searchlight);
  std::array<double, kHeroWavelengths> change;
  for (int i = 0; i < kHeroWavelengths; ++i) {
    const double lambda = wavelengths.lambda[i];
    change[i] = factor * e.fast_spectral_radiance(d * lambda) - e.fast_spectral_radiance(lambda);
  }
  const LinearRgb delta = linear_srgb_from_xyz(xyz_from_samples(wavelengths, change));
  return {e.rest_rgb.r + delta.r, e.rest_rgb.g + delta.g, e.rest_rgb.b + delta.b};
}

}  // namespace lightcone

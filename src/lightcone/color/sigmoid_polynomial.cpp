#include "lightcone/color/sigmoid_polynomial.hpp"

#include <cmath>

#include "lightcone/color/spectrum.hpp"

namespace lightcone {
namespace {

// BlackbodySpectrum::with_luminance normalises with xyz_from_spectrum(), the 1 nm quadrature
// that the fit and the tests use, so the reference illuminant's Y is 1 to rounding.
const BlackbodySpectrum& illuminant() {
  static const BlackbodySpectrum illuminant =
      BlackbodySpectrum::with_luminance(kReferenceIlluminantTemperature, 1.0);
  return illuminant;
}

}  // namespace

double reference_illuminant(double lambda_nm) {
  return illuminant()(lambda_nm);
}

LinearRgb reference_white() {
  static const LinearRgb white =
      linear_srgb_from_xyz(xyz_from_spectrum([](double l) { return reference_illuminant(l); }));
  return white;
}

}  // namespace lightcone

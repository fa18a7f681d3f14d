// RGB to spectrum: linear sRGB colours upsampled to spectra defined at every wavelength, by the
// sigmoid-quadratic model of Jakob & Hanika (EGSR 2019) with a coefficient table fitted by the
// project's own optimiser at build time (tools/rgb2spec_gen.cpp, tools/rgb2spec_fit.cpp).
// Design notes: docs/design/spectral.md, "RGB to spectrum (Jakob-Hanika)".
//
// Outside the visible range (see sigmoid_polynomial.hpp and docs/design/spectral.md, "What an
// RGB colour means outside the visible range"): reflectances are flat beyond 360 and 830 nm
// (the model is evaluated at the clamped wavelength); RGB emitters follow the 6504 K blackbody
// reference illuminant there.
#pragma once

#include <limits>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/sigmoid_polynomial.hpp"

namespace lightcone {

// The coefficients of the reflectance that the linear sRGB colour `rgb` means: the one whose
// colour under the reference illuminant (a 6504 K blackbody with Y = 1), white-balanced to that
// illuminant, is rgb; i.e. its colour under the illuminant is (r w.r, g w.g, b w.b) with
// w = reference_white(). So (1, 1, 1) is the flat reflectance 1 and every grey is flat.
// Components are clamped to [0, 1] (NaN counts as 0). The table is looked up with trilinear
// interpolation of the coefficients; black (all components 0) gives c2 = -infinity, i.e. 0 at
// every wavelength. The few colours that no reflectance of this form reaches (the brightest
// saturated ones, near the limit of what a reflectance in [0, 1] can give) get the nearest fit
// in CIELAB.
SigmoidPolynomial rgb_to_sigmoid(const LinearRgb& rgb);

// A reflectance (albedo) spectrum in [0, 1] from a linear sRGB colour in [0, 1]^3.
struct RgbAlbedoSpectrum {
  SigmoidPolynomial sigmoid{0, 0, -std::numeric_limits<double>::infinity()};  // black unless set
  static RgbAlbedoSpectrum from_rgb(const LinearRgb& rgb) { return {rgb_to_sigmoid(rgb)}; }
  double operator()(double lambda_nm) const { return sigmoid(lambda_nm); }
};

// An emitter of any non-negative linear sRGB radiance (negative components count as 0):
//   L(lambda) = scale * s(lambda) * reference_illuminant(lambda),
// where s is the reflectance rgb_to_sigmoid(rgb / (scale w)) (per channel, w =
// reference_white()) and scale = 2 max(r / w.r, g / w.g, b / w.b), so that s is fitted to a
// colour whose largest component is 1/2 (well inside what a reflectance reaches) and at rest
// (D = 1) the integrated colour is exactly rgb (not white-balanced: an emitter's RGB is its
// radiance). Black gives 0 at every wavelength. Outside 360-830 nm s is flat and L falls off as
// the blackbody does. Components must be finite.
struct RgbIlluminantSpectrum {
  double scale = 0;
  SigmoidPolynomial sigmoid;
  static RgbIlluminantSpectrum from_rgb(const LinearRgb& rgb);
  double operator()(double lambda_nm) const {
    return scale > 0 ? scale * sigmoid(lambda_nm) * reference_illuminant(lambda_nm) : 0.0;
  }
};

namespace detail {
// The coefficient table built into the library (kRgbToSpectrumTableFloats floats, layout in
// sigmoid_polynomial.hpp). For tests.
const float* rgb_to_spectrum_table();
}  // namespace detail

}  // namespace lightcone

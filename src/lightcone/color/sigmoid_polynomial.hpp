// The sigmoid-quadratic spectrum model of Jakob & Hanika, "A Low-Dimensional Function Space for
// Efficient Spectral Upsampling" (EGSR 2019), the reference illuminant RGB colours are fitted
// under, and the layout of the RGB-to-coefficients table. This part depends on no table, so the
// table generator (tools/rgb2spec_gen.cpp) can link it; the table-backed API is in
// rgb_spectrum.hpp.
#pragma once

#include <cmath>
#include <cstddef>

#include "lightcone/color/cie.hpp"

namespace lightcone {

// ---------------------------------------------------------------------------------------------
// What an RGB colour means outside the visible range (see docs/design/spectral.md): the model
// is evaluated with lambda clamped to [kCieMinWavelength, kCieMaxWavelength] = [360, 830] nm.
// A reflectance fitted to an RGB colour therefore extends flat beyond the visible range: it
// holds its 360 nm value into the ultraviolet and its 830 nm value into the infrared (a red
// stays red-reflecting into the infrared and dark into the ultraviolet; but the values at 360
// and 830 nm, where the eye is nearly blind, are whatever the fit gives: a bright or pale red
// turns up again at 360 nm). RGB emitters are this reflectance times the reference illuminant,
// a blackbody defined at every wavelength, so they fall off outside the visible range as the
// blackbody does.
// ---------------------------------------------------------------------------------------------

// The polynomial's variable is a normalised wavelength, not nanometres (for conditioning):
//   u = (clamp(lambda, 360, 830) - 595) / 235, which maps [360, 830] nm onto [-1, 1].
inline constexpr double kSigmoidCentreWavelength = 595.0;  // nm
inline constexpr double kSigmoidHalfWidth = 235.0;         // nm
inline double sigmoid_normalised_wavelength(double lambda_nm) {
  // Comparisons rather than fmin/fmax, which are library calls on this hot path.
  const double clamped = lambda_nm < kCieMinWavelength   ? kCieMinWavelength
                         : lambda_nm > kCieMaxWavelength ? kCieMaxWavelength
                                                         : lambda_nm;
  return (clamped - kSigmoidCentreWavelength) / kSigmoidHalfWidth;
}

// S(x) = 1/2 + x / (2 sqrt(1 + x^2)), a smooth map of the real line onto (0, 1); S(-inf) = 0
// and S(+inf) = 1. Written as (r + x) / (2 r), r = sqrt(1 + x^2), and for x < 0 as
// 1 / (2 r (r - x)) so that small values keep their relative precision.
// Both forms and the limits are computed and one is selected, without branches, so that loops
// over wavelengths vectorise (the values are those of the branches).
inline double sigmoid(double x) {
  const double r = std::sqrt(1 + x * x);
  const double value = x >= 0 ? (r + x) / (2 * r) : 1 / (2 * r * (r - x));
  // Past 1e150 (and at +-inf) x * x overflows: the limits.
  return std::fabs(x) > 1e150 ? (x > 0 ? 1.0 : 0.0) : value;
}

// s(lambda) = S(c0 u^2 + c1 u + c2), u = sigmoid_normalised_wavelength(lambda) (clamped: see
// the policy above). Values lie in [0, 1].
struct SigmoidPolynomial {
  double c0 = 0, c1 = 0, c2 = 0;
  double operator()(double lambda_nm) const {
    const double u = sigmoid_normalised_wavelength(lambda_nm);
    return sigmoid((c0 * u + c1) * u + c2);
  }
};

// The illuminant RGB colours are fitted under: a blackbody at 6504 K (planck_radiance) scaled
// so that its CIE Y is 1 (BlackbodySpectrum::with_luminance(6504, 1), Y by xyz_from_spectrum(),
// the 1 nm table's quadrature). Defined and
// positive at every wavelength, unlike tabulated D65; its chromaticity is near, but not at,
// D65's, so a flat reflectance 1 has a linear sRGB colour slightly different from (1, 1, 1).
inline constexpr double kReferenceIlluminantTemperature = 6504.0;  // K
double reference_illuminant(double lambda_nm);

// The reference illuminant's white: the linear sRGB colour of a flat reflectance 1 under it
// (about (1.043, 0.984, 1.036), not (1, 1, 1)). RGB reflectances are white-balanced to it: the
// reflectance meant by rgb has the colour (r w.r, g w.g, b w.b) under the reference illuminant,
// so that (1, 1, 1) is the flat reflectance 1 and every grey is flat (rgb_spectrum.hpp).
LinearRgb reference_white();

// The RGB-to-coefficients table, Jakob-Hanika layout: 3 tables, one per largest component
// l = 0 (r), 1 (g), 2 (b), each res x res x res cells indexed by
//   k (the largest component z = rgb[l], on the nonlinear scale axis below),
//   j (y = rgb[(l + 2) % 3] / z on the uniform grid j / (res - 1)),
//   i (x = rgb[(l + 1) % 3] / z on the uniform grid i / (res - 1)),
// each cell holding c0, c1, c2 (float), i.e. floats at
//   (((l * res + k) * res + j) * res + i) * 3 + c.
inline constexpr int kRgbToSpectrumRes = 64;
inline constexpr int kRgbToSpectrumTableFloats =
    3 * kRgbToSpectrumRes * kRgbToSpectrumRes * kRgbToSpectrumRes * 3;

// Where cell (l, k, j, i)'s c0 is in a table of `res` nodes per axis.
constexpr std::size_t rgb_to_spectrum_cell(int l, int k, int j, int i, int res) {
  return ((static_cast<std::size_t>(l * res + k) * res + j) * res + i) * 3;
}

// The scale axis node k of a table with `res` nodes: smoothstep(smoothstep(k / (res - 1))),
// denser near 0 (dark colours) and 1 (bright, near the limit of what a reflectance can reach),
// as Jakob and Hanika space it. smoothstep(t) = t^2 (3 - 2 t).
inline double rgb_to_spectrum_scale_node(int k, int res) {
  const auto smoothstep = [](double t) { return t * t * (3 - 2 * t); };
  return smoothstep(smoothstep(static_cast<double>(k) / (res - 1)));
}

// The emitter nodes (rgb_spectrum.hpp, RgbEmitterSpectrum): for each ordered pair of a largest
// channel l and a middle channel m (the third channel is zero), kRgbToSpectrumRes reflectances
// fitted exactly (to the 1 nm quadrature, under the reference illuminant) to the white-balanced
// colours 0.5 e_l + 0.5 (i / (res - 1)) e_m, i = 0 .. res - 1. Along one case the colours are
// linear in i, so blending two neighbouring nodes' spectra gives exactly the colour in between.
// Layout: doubles at ((case * res) + i) * 3 + c, case = rgb_emitter_case(l, m).
inline constexpr int kRgbEmitterCases = 6;
inline constexpr int kRgbEmitterNodeDoubles = kRgbEmitterCases * kRgbToSpectrumRes * 3;
inline constexpr int rgb_emitter_case(int largest, int middle) {
  return 2 * largest + (middle == (largest + 1) % 3 ? 0 : 1);
}
// The white-balanced reflectance colour of node i of a case.
inline LinearRgb rgb_emitter_node_colour(int largest, int middle, int i) {
  double c[3] = {0, 0, 0};
  c[largest] = 0.5;
  c[middle] = 0.5 * static_cast<double>(i) / (kRgbToSpectrumRes - 1);
  return {c[0], c[1], c[2]};
}

}  // namespace lightcone

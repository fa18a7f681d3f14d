// RGB to spectrum: linear sRGB colours upsampled to spectra defined at every wavelength, by the
// sigmoid-quadratic model of Jakob & Hanika ("A Low-Dimensional Function Space for Efficient
// Spectral Upsampling", 2019) with a coefficient table fitted by the
// project's own optimiser at build time (tools/rgb2spec_gen.cpp, tools/rgb2spec_fit.cpp).
// Design notes: docs/design/spectral.md, "RGB to spectrum (Jakob-Hanika)".
//
// Outside the visible range (see sigmoid_polynomial.hpp and docs/design/spectral.md, "What an
// RGB colour means outside the visible range"): reflectances are flat beyond 360 and 830 nm
// (the model is evaluated at the clamped wavelength); RGB emitters follow the 6504 K blackbody
// reference illuminant there (RgbEmitterSpectrum).
#pragma once

#include <array>
#include <limits>
#include <span>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/sigmoid_polynomial.hpp"
#include "lightcone/color/spectrum.hpp"

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

// The RGB white: the spectrum whose linear sRGB colour is exactly (1, 1, 1) (by the 1 nm
// quadrature). It is the reference illuminant (the 6504 K blackbody of Y = 1) times
// 1 + sum_k g_k exp(-((lambda - mu_k) / 30 nm)^2 / 2) with mu = 450, 540, 610 nm and the three
// g_k (a few per cent) solved for that colour, so outside about 360-700 nm it is the blackbody.
double rgb_white_spectrum(double lambda_nm);
// The factor 1 + sum_k g_k exp(...) itself: rgb_white_spectrum = reference_illuminant * it.
double rgb_white_factor(double lambda_nm);

// Every RGB emitter below (the RGB white, the emitter nodes N_i and their sums) is the reference
// illuminant times finite factors, so at and below this wavelength (nm) it is exactly 0.
inline double rgb_emitter_zero_wavelength() {
  return planck_zero_wavelength(kReferenceIlluminantTemperature);
}

// An emitter of any non-negative linear sRGB radiance (negative components and NaN count as 0;
// components must be finite). Policy (docs/design/spectral.md, "What an RGB colour means"):
//   L(lambda) = grey * rgb_white_spectrum(lambda)
//             + scale * [(1 - blend) N_node(lambda) + blend N_node+1(lambda)],
// where grey = min(r, g, b) and the chromatic remainder q = rgb - grey (one channel zero) is
// carried by two neighbouring emitter nodes of one case (sigmoid_polynomial.hpp): N_i is the
// node's Jakob-Hanika reflectance times the reference illuminant. With c = q / reference_white()
// (per channel), l its largest and m its middle channel, scale = 2 c_l and the node position
// (i + blend) / (res - 1) = c_m / c_l. The colour at rest is exactly rgb: greys are exactly
// grey * the RGB white (the blackbody outside the visible range, at every Doppler factor), and
// saturated colours (one channel zero) keep the Jakob-Hanika shape.
struct RgbEmitterSpectrum {
  double grey = 0;
  double scale = 0;
  int node_case = 0;  // rgb_emitter_case(l, m)
  int node = 0;       // in [0, kRgbToSpectrumRes - 2]
  double blend = 0;   // in [0, 1]
  static RgbEmitterSpectrum from_rgb(const LinearRgb& rgb);
  double operator()(double lambda_nm) const;
  double constant_below() const { return rgb_emitter_zero_wavelength(); }
};

// Node i of an emitter case: its reflectance (flat outside 360-830 nm, like every
// Jakob-Hanika reflectance); N_i(lambda) = rgb_emitter_node(case, i)(lambda) *
// reference_illuminant(lambda).
SigmoidPolynomial rgb_emitter_node(int node_case, int i);

// The cells of the coefficient table rgb_to_sigmoid may read for a blend of some colours: table
// l, rows j0..j1 and columns i0..i1 (each cell (j, i) reads columns j..j + 1, i..i + 1).
struct RgbToSpectrumCells {
  int l = 0, j0 = 0, j1 = 0, i0 = 0, i1 = 0;
};
// Every cell rgb_to_sigmoid reads for any blend of `colours` with weights >= 0, not all zero (a
// bilinear texture lookup blends four texels), one rectangle for each table that may hold such
// a blend, widened by a cell each way for a lookup in single precision; returns how many of
// `out` it filled. The web page fits those columns before it draws a lit texture.
int rgb_to_spectrum_cells_of_blends(std::span<const LinearRgb> colours,
                                    std::array<RgbToSpectrumCells, 3>& out);

namespace detail {
// The coefficient table (kRgbToSpectrumTableFloats floats, layout in sigmoid_polynomial.hpp)
// with at least the columns (j, i), (j, i + 1), (j + 1, i) and (j + 1, i + 1) of table l in
// place. The native library embeds the whole table, fitted at build time; the web page fits a
// column the first time it is asked for (web/page_tables.cpp), with the same fit, rather than
// download 9 MB.
const float* rgb_to_spectrum_table(int l, int j, int i);
// The emitter nodes built into the library (kRgbEmitterNodeDoubles doubles).
const double* rgb_emitter_nodes();
}  // namespace detail

}  // namespace lightcone

// Spectra defined at every wavelength (not clipped to the visible range), so that Doppler
// shifts can bring ultraviolet and infrared into view.
#pragma once

#include <vector>

namespace lightcone {

// Planck's law: spectral radiance of a blackbody at temperature T (K), per unit wavelength,
// in W sr^-1 m^-2 nm^-1, at wavelength lambda (nm). Exact for every lambda > 0.
double planck_radiance(double lambda_nm, double temperature_k);

// The longest wavelength (nm) at and below which planck_radiance(lambda, T) is exactly 0 in
// double precision: there its deep Wien tail kC1 lambda^-5 exp(-kC2 / (lambda T)) is below half
// the smallest subnormal, at every shorter wavelength too (infinity for T <= 0, where it is 0
// everywhere). Not an approximation: what planck_radiance computes is 0 there.
double planck_zero_wavelength(double temperature_k);

// A blackbody scaled so that its CIE Y (with the 1/cie_y_integral() normalisation) equals
// `luminance` at rest.
struct BlackbodySpectrum {
  double temperature_k = 6504;
  double scale = 1;  // multiplies planck_radiance
  static BlackbodySpectrum with_luminance(double temperature_k, double luminance);
  double operator()(double lambda_nm) const;
  // At and below this wavelength (nm) the spectrum is constant: 0 (planck_zero_wavelength).
  double constant_below() const { return planck_zero_wavelength(temperature_k); }
};

// Piecewise-linear in wavelength; outside the table the end values are held (the table is
// expected to cover the ultraviolet and infrared it matters for).
struct TabulatedSpectrum {
  std::vector<double> wavelengths_nm;  // strictly increasing, > 0
  std::vector<double> values;
  double operator()(double lambda_nm) const;
  // At and below this wavelength (nm) the spectrum is constant: its first value, held.
  double constant_below() const;
};

}  // namespace lightcone

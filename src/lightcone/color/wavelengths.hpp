// Wavelength sampling for the spectral renderer: hero wavelengths (Wilkie, Nawaz, Droske,
// Weidlich and Hanika, "Hero Wavelength Spectral Sampling", EGSR 2014). Each camera sample
// carries kHeroWavelengths wavelengths spread evenly over the visible range [360, 830] nm (where
// the CIE 1931 colour matching functions are defined) and turns the spectral radiances found at
// them into a Monte Carlo estimate of CIE XYZ.
#pragma once

#include <array>

#include "lightcone/color/cie.hpp"

namespace lightcone {

inline constexpr int kHeroWavelengths = 4;
inline constexpr double kSampledMinWavelength = kCieMinWavelength;  // nm
inline constexpr double kSampledMaxWavelength = kCieMaxWavelength;  // nm

struct SampledWavelengths {
  std::array<double, kHeroWavelengths> lambda;  // nm, the camera-frame (received) wavelengths
  std::array<double, kHeroWavelengths> pdf;     // per nm, of each lambda on its own
};

// From one number u in [0, 1): lambda_i = 360 + frac(u + i / 4) * 470 nm, i = 0..3, each with
// pdf 1/470 per nm. u outside [0, 1) is first reduced to frac(u). The set of four is periodic in
// u with period 1/4 (u + 1/4 gives the same wavelengths, rotated by one), so u in [0, 1/4)
// already reaches every set.
SampledWavelengths sample_wavelengths(double u);

// The Monte Carlo estimate, from one sample's four wavelengths and the spectral radiances L_i
// received at them, of (integral over [360, 830] nm of L(lambda) cmf(lambda) dlambda) divided by
// cie_y_integral(): (1/4) sum_i L_i cmf(lambda_i) / pdf_i / cie_y_integral(). Averaged over
// samples it converges to xyz_from_spectrum(L) (up to the 1 nm sum against the integral).
Xyz xyz_from_samples(const SampledWavelengths& wavelengths,
                     const std::array<double, kHeroWavelengths>& radiance);

// The u for sample `sample_index` of the `sample_count` samples of one pixel, with `jitter` in
// [0, 1) drawn per sample: (sample_index + jitter) / (kHeroWavelengths * sample_count), which
// stratifies the period [0, 1/4) of sample_wavelengths(), so the pixel's 4 * sample_count
// wavelengths are stratified over [360, 830) nm with one per stratum of 470 / (4 sample_count) nm.
// (Stratifying the whole of [0, 1) instead, u = (k + jitter) / n, would repeat strata: with
// n = 4 every sample would fall in the same one.) sample_index wraps modulo sample_count;
// sample_count < 1 is treated as 1.
double stratified_wavelength_u(int sample_index, int sample_count, double jitter);

}  // namespace lightcone

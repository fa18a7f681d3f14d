#include "lightcone/color/wavelengths.hpp"

#include <algorithm>
#include <cmath>

namespace lightcone {
namespace {

static_assert(kHeroWavelengths == 4, "stratified_wavelength_u divides by it exactly");

constexpr double kRange = kSampledMaxWavelength - kSampledMinWavelength;  // 470 nm
const double kBelowMax = std::nextafter(kSampledMaxWavelength, 0.0);

// v - floor(v) in [0, 1); the guard catches v - floor(v) rounding up to 1 for tiny negative v.
double frac(double v) {
  const double f = v - std::floor(v);
  return f < 1.0 ? f : 0.0;
}

}  // namespace

SampledWavelengths sample_wavelengths(double u) {
  const double u0 = frac(u);
  SampledWavelengths s;
  for (int i = 0; i < kHeroWavelengths; ++i) {
    const double lambda =
        kSampledMinWavelength + frac(u0 + static_cast<double>(i) / kHeroWavelengths) * kRange;
    s.lambda[i] = std::min(lambda, kBelowMax);  // frac just below 1 may round up to 830
    s.pdf[i] = 1.0 / kRange;
  }
  return s;
}

Xyz xyz_from_samples(const SampledWavelengths& wavelengths,
                     const std::array<double, kHeroWavelengths>& radiance) {
  Xyz sum;
  for (int i = 0; i < kHeroWavelengths; ++i) {
    if (!(wavelengths.pdf[i] > 0)) continue;
    const Xyz c = cie_cmf(wavelengths.lambda[i]);
    const double w = radiance[i] / wavelengths.pdf[i];
    sum.x += w * c.x;
    sum.y += w * c.y;
    sum.z += w * c.z;
  }
  const double n = 1.0 / (kHeroWavelengths * cie_y_integral());
  return {sum.x * n, sum.y * n, sum.z * n};
}

double stratified_wavelength_u(int sample_index, int sample_count, double jitter) {
  const int count = sample_count < 1 ? 1 : sample_count;
  // frac((k + jitter) / n) / 4: below 1/4 even where (k + jitter) / n rounds up (dividing by 4
  // is exact), and sample indices past the count wrap around.
  return frac((sample_index + jitter) / count) / kHeroWavelengths;
}

}  // namespace lightcone

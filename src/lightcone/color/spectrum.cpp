#include "lightcone/color/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "lightcone/color/cie.hpp"

namespace lightcone {
namespace {

// Exact SI values (CODATA 2018, the 2019 SI redefinition).
constexpr double kPlanck = 6.62607015e-34;     // J s
constexpr double kSpeedOfLight = 299792458.0;  // m / s
constexpr double kBoltzmann = 1.380649e-23;    // J / K

// Radiation constants with wavelengths in nm:
//   B(lambda, T) = kC1 / lambda^5 / (exp(kC2 / (lambda T)) - 1)   [W sr^-1 m^-2 nm^-1]
// kC1 = 2 h c^2 (W m^2 sr^-1) * 1e45 nm^5 / m^5 * 1e-9 m / nm;  kC2 = h c / k * 1e9 nm / m.
constexpr double kC1 = 2.0 * kPlanck * kSpeedOfLight * kSpeedOfLight * 1e36;
constexpr double kC2 = kPlanck * kSpeedOfLight / kBoltzmann * 1e9;  // nm K

}  // namespace

double planck_radiance(double lambda_nm, double temperature_k) {
  // Zero for non-positive (or NaN) arguments: no radiation at T <= 0.
  if (!(lambda_nm > 0) || !(temperature_k > 0)) return 0;
  const double x = kC2 / (lambda_nm * temperature_k);  // h nu / k T; +inf if lambda T underflows
  double b;
  if (x < 1) {
    // Rayleigh-Jeans side, written without lambda^5 (which may overflow while x underflows):
    // B = (kC1 / kC2) T / lambda^4 * x / expm1(x), and x / expm1(x) -> 1 as x -> 0. T / lambda^4
    // first, so that a huge T over an infinite lambda^4 gives 0, not inf / inf.
    const double lambda2 = lambda_nm * lambda_nm;
    const double ratio = x > 0 ? x / std::expm1(x) : 1.0;
    b = temperature_k / lambda2 / lambda2 * (kC1 / kC2) * ratio;
  } else if (x > 700) {
    // Deep Wien side: exp(x) would overflow and lambda^5 may underflow; in logarithms the
    // result underflows cleanly to 0 (or is a correct tiny number).
    b = std::exp(std::log(kC1) - 5.0 * std::log(lambda_nm) - x);
  } else {
    // For x >= 1, exp(-x) / (1 - exp(-x)) has no cancellation and costs one exp, about half
    // of expm1 (this runs several times per camera sample in the spectral renderer).
    const double lambda2 = lambda_nm * lambda_nm;
    const double e = std::exp(-x);
    b = kC1 / (lambda2 * lambda2 * lambda_nm) * (e / (1.0 - e));
  }
  // Only absurd temperatures (T above about 1e280 K, or 1e60 K at lambda below 1e-50 nm) have a
  // radiance beyond the largest double: saturate there instead of returning inf.
  return std::min(b, std::numeric_limits<double>::max());
}

double planck_zero_wavelength(double temperature_k) {
  if (!(temperature_k > 0)) return std::numeric_limits<double>::infinity();
  // planck_radiance's deep Wien branch (x = kC2 / (lambda T) > 700) is exp(y), y = ln kC1 -
  // 5 ln lambda - x, and std::exp gives exactly 0 below y = -745.13. With lambda = kC2 / (x T),
  // y = -746 (a margin far above the rounding of y) is x - 5 ln x = K: the fixed point of
  // x = K + 5 ln x, a contraction (slope 5 / x < 0.01). y grows with lambda wherever x > 5, so
  // every shorter wavelength gives 0 as well; the branch needs x > 700.
  const double k = 746 + std::log(kC1) - 5 * std::log(kC2 / temperature_k);
  double x = std::max(k, 701.0);
  for (int i = 0; i < 30; ++i) x = std::max(k + 5 * std::log(x), 701.0);
  return kC2 / (x * temperature_k);
}

BlackbodySpectrum BlackbodySpectrum::with_luminance(double temperature_k, double luminance) {
  BlackbodySpectrum s;
  s.temperature_k = temperature_k;
  s.scale = 1;
  const double y = xyz_from_spectrum(s).y;
  // A blackbody too cold to have any visible radiance in double precision (below about 23 K)
  // cannot be scaled to a luminance: it stays black.
  s.scale = y > 0 ? luminance / y : 0.0;
  return s;
}

double BlackbodySpectrum::operator()(double lambda_nm) const {
  return scale * planck_radiance(lambda_nm, temperature_k);
}

double TabulatedSpectrum::constant_below() const {
  return wavelengths_nm.empty() || values.empty() ? std::numeric_limits<double>::infinity()
                                                  : wavelengths_nm.front();
}

double TabulatedSpectrum::operator()(double lambda_nm) const {
  const std::size_t n = std::min(wavelengths_nm.size(), values.size());
  if (n == 0) return 0;
  if (!(lambda_nm > wavelengths_nm.front())) return values.front();  // also NaN
  if (lambda_nm >= wavelengths_nm[n - 1]) return values[n - 1];
  // First knot strictly greater than lambda: wavelengths_nm[hi - 1] <= lambda < [hi].
  const auto it = std::upper_bound(wavelengths_nm.begin(), wavelengths_nm.begin() + n, lambda_nm);
  const std::size_t hi = static_cast<std::size_t>(it - wavelengths_nm.begin());
  const std::size_t lo = hi - 1;
  const double t = (lambda_nm - wavelengths_nm[lo]) / (wavelengths_nm[hi] - wavelengths_nm[lo]);
  return values[lo] + t * (values[hi] - values[lo]);
}

}  // namespace lightcone

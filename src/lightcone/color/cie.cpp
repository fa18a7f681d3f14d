#include "lightcone/color/cie.hpp"

#include <array>
#include <cmath>

#include "lightcone/color/cie_data.hpp"

namespace lightcone {
namespace {

static_assert(cie_data::kRowCount == kCieTableSize);
static_assert(cie_data::kFirstWavelengthNm == static_cast<int>(kCieMinWavelength));
static_assert(kCieMinWavelength + (kCieTableSize - 1) == kCieMaxWavelength);

using detail::kXyzFromSrgb;

// The printed matrix of the standard, to its four places.
static_assert(kXyzFromSrgb[0][0] > 0.41235 && kXyzFromSrgb[0][0] < 0.41245);
static_assert(kXyzFromSrgb[1][1] > 0.71515 && kXyzFromSrgb[1][1] < 0.71525);
static_assert(kXyzFromSrgb[2][2] > 0.95045 && kXyzFromSrgb[2][2] < 0.95055);

double y_sum() {
  double sum = 0;
  for (int i = 0; i < cie_data::kRowCount; ++i) sum += cie_data::kXyzBar1931[i][1];
  return sum;
}

}  // namespace

Xyz cie_cmf(double lambda_nm) {
  // The negated comparison also sends NaN to zero.
  if (!(lambda_nm >= kCieMinWavelength && lambda_nm <= kCieMaxWavelength)) return {};
  const double offset = lambda_nm - kCieMinWavelength;
  int i = static_cast<int>(offset);
  if (i > kCieTableSize - 2) i = kCieTableSize - 2;  // lambda = 830 exactly
  const double t = offset - i;
  const double* a = cie_data::kXyzBar1931[i];
  const double* b = cie_data::kXyzBar1931[i + 1];
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

double cie_y_integral() {
  static const double integral = y_sum();
  return integral;
}

Xyz xyz_from_linear_srgb(const LinearRgb& c) {
  const detail::Matrix3& m = kXyzFromSrgb;
  return {m[0][0] * c.r + m[0][1] * c.g + m[0][2] * c.b,
          m[1][0] * c.r + m[1][1] * c.g + m[1][2] * c.b,
          m[2][0] * c.r + m[2][1] * c.g + m[2][2] * c.b};
}

}  // namespace lightcone

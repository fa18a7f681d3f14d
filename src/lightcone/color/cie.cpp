#include "lightcone/color/cie.hpp"

#include <array>
#include <cmath>

#include "lightcone/color/cie_data.hpp"

namespace lightcone {
namespace {

static_assert(cie_data::kRowCount == kCieTableSize);
static_assert(cie_data::kFirstWavelengthNm == static_cast<int>(kCieMinWavelength));
static_assert(kCieMinWavelength + (kCieTableSize - 1) == kCieMaxWavelength);

using Matrix3 = std::array<std::array<double, 3>, 3>;

constexpr Matrix3 inverse3(const Matrix3& a) {
  const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  const double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  const double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  const double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
  const double k = 1.0 / det;
  Matrix3 r{};
  r[0][0] = c00 * k;
  r[1][0] = c01 * k;
  r[2][0] = c02 * k;
  r[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) * k;
  r[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * k;
  r[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) * k;
  r[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * k;
  r[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * k;
  r[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * k;
  return r;
}

// RGB -> XYZ from the chromaticities of IEC 61966-2-1 (= ITU-R BT.709 primaries, D65 white):
// column j is primary j's XYZ (x/y, 1, (1-x-y)/y) scaled so that R = G = B = 1 gives the white
// point with Y = 1.
constexpr Matrix3 derive_xyz_from_srgb() {
  constexpr double px[3] = {0.64, 0.30, 0.15};
  constexpr double py[3] = {0.33, 0.60, 0.06};
  Matrix3 p{};
  for (int j = 0; j < 3; ++j) {
    p[0][j] = px[j] / py[j];
    p[1][j] = 1.0;
    p[2][j] = (1.0 - px[j] - py[j]) / py[j];
  }
  const double white[3] = {kD65WhiteX / kD65WhiteY, 1.0,
                           (1.0 - kD65WhiteX - kD65WhiteY) / kD65WhiteY};
  const Matrix3 p_inv = inverse3(p);
  double s[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s[i] += p_inv[i][j] * white[j];
  Matrix3 m{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = p[i][j] * s[j];
  return m;
}

constexpr Matrix3 kXyzFromSrgb = derive_xyz_from_srgb();
constexpr Matrix3 kSrgbFromXyz = inverse3(kXyzFromSrgb);

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

LinearRgb linear_srgb_from_xyz(const Xyz& c) {
  const Matrix3& m = kSrgbFromXyz;
  return {m[0][0] * c.x + m[0][1] * c.y + m[0][2] * c.z,
          m[1][0] * c.x + m[1][1] * c.y + m[1][2] * c.z,
          m[2][0] * c.x + m[2][1] * c.y + m[2][2] * c.z};
}

Xyz xyz_from_linear_srgb(const LinearRgb& c) {
  const Matrix3& m = kXyzFromSrgb;
  return {m[0][0] * c.r + m[0][1] * c.g + m[0][2] * c.b,
          m[1][0] * c.r + m[1][1] * c.g + m[1][2] * c.b,
          m[2][0] * c.r + m[2][1] * c.g + m[2][2] * c.b};
}

}  // namespace lightcone

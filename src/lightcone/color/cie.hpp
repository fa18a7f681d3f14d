// CIE 1931 2-degree colour matching functions (1 nm data, 360-830 nm) and the conversions
// between CIE XYZ and linear sRGB (Rec. 709 primaries, D65 white).
#pragma once

#include <array>

#include "lightcone/color/cie_data.hpp"

namespace lightcone {

inline constexpr double kCieMinWavelength = 360.0;  // nm
inline constexpr double kCieMaxWavelength = 830.0;  // nm
inline constexpr int kCieTableSize = 471;           // 1 nm rows, 360 to 830 nm inclusive

struct Xyz {
  double x = 0, y = 0, z = 0;
};

// x-bar, y-bar, z-bar at lambda (nm): linear interpolation of the 1 nm table, zero outside
// [360, 830].
Xyz cie_cmf(double lambda_nm);

// The integral of y-bar over [360, 830] nm (in nm), as the 1 nm table's sum. Dividing an
// integral of L(lambda) cmf(lambda) by it makes a constant spectrum L = 1 have Y = 1.
double cie_y_integral();

// CIE XYZ of a spectrum s(lambda) (any callable double -> double, lambda in nm) with the 1 nm
// table: sum over lambda = 360, 361, ..., 830 of s(lambda) cmf(lambda), divided by
// cie_y_integral(). A constant spectrum 1 has Y = 1 and chromaticity close to x = y = 1/3.
template <class Spectrum>
Xyz xyz_from_spectrum(const Spectrum& spectrum) {
  Xyz sum;
  for (int i = 0; i < kCieTableSize; ++i) {
    const double s = spectrum(kCieMinWavelength + i);
    // The table's row: what cie_cmf gives at a whole nanometre, without its call.
    const double* c = cie_data::kXyzBar1931[i];
    sum.x += s * c[0];
    sum.y += s * c[1];
    sum.z += s * c[2];
  }
  const double n = 1.0 / cie_y_integral();
  return {sum.x * n, sum.y * n, sum.z * n};
}

// The same sum over a spectrum already sampled at the table's wavelengths: samples[i] at
// 360 + i nm.
inline Xyz xyz_from_samples(const double* samples) {
  return xyz_from_spectrum(
      [samples](double lambda) { return samples[static_cast<int>(lambda - kCieMinWavelength)]; });
}

// Linear sRGB <-> XYZ (IEC 61966-2-1 matrices, D65 white; Y of white (1,1,1) is 1).
// The matrices are derived (at compile time) from the standard's chromaticities: primaries
// R (0.64, 0.33), G (0.30, 0.60), B (0.15, 0.06) and white D65 (0.3127, 0.3290); rounded to
// four places they are the standard's printed matrix (X = 0.4124 R + 0.3576 G + 0.1805 B, ...).
inline constexpr double kD65WhiteX = 0.3127;
inline constexpr double kD65WhiteY = 0.3290;

struct LinearRgb {
  double r = 0, g = 0, b = 0;
};
namespace detail {
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

inline constexpr Matrix3 kXyzFromSrgb = derive_xyz_from_srgb();
inline constexpr Matrix3 kSrgbFromXyz = inverse3(kXyzFromSrgb);

}  // namespace detail

// Inline: the renderer converts once per camera ray.
inline LinearRgb linear_srgb_from_xyz(const Xyz& c) {
  constexpr const detail::Matrix3& m = detail::kSrgbFromXyz;
  return {m[0][0] * c.x + m[0][1] * c.y + m[0][2] * c.z,
          m[1][0] * c.x + m[1][1] * c.y + m[1][2] * c.z,
          m[2][0] * c.x + m[2][1] * c.y + m[2][2] * c.z};
}
Xyz xyz_from_linear_srgb(const LinearRgb& rgb);

}  // namespace lightcone

// CIE 1931 2-degree colour matching functions (1 nm data, 360-830 nm) and the conversions
// between CIE XYZ and linear sRGB (Rec. 709 primaries, D65 white).
#pragma once

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
    const double lambda = kCieMinWavelength + i;
    const double s = spectrum(lambda);
    const Xyz c = cie_cmf(lambda);
    sum.x += s * c.x;
    sum.y += s * c.y;
    sum.z += s * c.z;
  }
  const double n = 1.0 / cie_y_integral();
  return {sum.x * n, sum.y * n, sum.z * n};
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
LinearRgb linear_srgb_from_xyz(const Xyz& xyz);
Xyz xyz_from_linear_srgb(const LinearRgb& rgb);

}  // namespace lightcone

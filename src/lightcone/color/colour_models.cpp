#include "lightcone/color/colour_models.hpp"

#include <algorithm>
#include <cmath>

#include "lightcone/physics/vec.hpp"

namespace lightcone {
namespace {

Xyz line_xyz(double lambda_nm) {
  const Xyz c = cie_cmf(lambda_nm);
  const double n = 1.0 / cie_y_integral();
  return {c.x * n, c.y * n, c.z * n};
}

// Columns: the normalised XYZ of a unit-power line at each of the three wavelengths.
const Mat3& line_matrix_inverse() {
  static const Mat3 inverse = [] {
    Mat3 m;
    for (int j = 0; j < 3; ++j) {
      const Xyz c = line_xyz(kRgb3Wavelengths[j]);
      m.m[0][j] = c.x;
      m.m[1][j] = c.y;
      m.m[2][j] = c.z;
    }
    return m.inverse();
  }();
  return inverse;
}

}  // namespace

LinearRgb rgb3_line_powers(const LinearRgb& rgb) {
  const Xyz xyz = xyz_from_linear_srgb(rgb);
  const Vec3 p = line_matrix_inverse() * Vec3{xyz.x, xyz.y, xyz.z};
  return {p.x, p.y, p.z};
}

LinearRgb rgb3_shift(const LinearRgb& rgb, double d, double power_factor) {
  const LinearRgb p = rgb3_line_powers(rgb);
  const double powers[3] = {p.r, p.g, p.b};
  Xyz sum;
  for (int i = 0; i < 3; ++i) {
    const Xyz c = line_xyz(kRgb3Wavelengths[i] / d);  // zero outside 360-830 nm
    sum.x += powers[i] * power_factor * c.x;
    sum.y += powers[i] * power_factor * c.y;
    sum.z += powers[i] * power_factor * c.z;
  }
  return linear_srgb_from_xyz(sum);
}

Hsv hsv_from_rgb(const LinearRgb& c) {
  const double hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b});
  Hsv out;
  out.v = hi;
  const double delta = hi - lo;
  if (hi <= 0 || delta <= 0) return out;  // grey: hue 0, saturation 0
  out.s = delta / hi;
  double h;
  if (c.r == hi)
    h = (c.g - c.b) / delta;
  else if (c.g == hi)
    h = 2 + (c.b - c.r) / delta;
  else
    h = 4 + (c.r - c.g) / delta;
  h *= 60;
  out.h = h < 0 ? h + 360 : h;
  return out;
}

LinearRgb rgb_from_hsv(const Hsv& c) {
  if (c.s == 0) return {c.v, c.v, c.v};
  const double h = c.h / 60;
  const double sector = std::floor(h);
  const double f = h - sector;
  const double p = c.v * (1 - c.s), q = c.v * (1 - c.s * f), t = c.v * (1 - c.s * (1 - f));
  switch (static_cast<int>(sector)) {
    case 0:
      return {c.v, t, p};
    case 1:
      return {q, c.v, p};
    case 2:
      return {p, c.v, t};
    case 3:
      return {p, q, c.v};
    case 4:
      return {t, p, c.v};
    default:
      return {c.v, p, q};
  }
}

LinearRgb hue_shift(const LinearRgb& rgb, double d, bool loop) {
  Hsv c = hsv_from_rgb(rgb);
  c.h += 512.0 * std::log2(d);
  if (loop) {
    c.h = std::fmod(c.h, 360.0);
    if (c.h < 0) c.h += 360.0;
  } else if (c.h > 300) {
    c.v *= 1 - (std::min(c.h, 360.0) - 300) / 60;
    c.h = 300;
  } else if (c.h < 0) {
    c.v *= (std::max(c.h, -60.0) + 60) / 60;
    c.h = 0;
  }
  return rgb_from_hsv(c);
}

}  // namespace lightcone

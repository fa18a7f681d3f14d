#include "lightcone/color/rgb_spectrum.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>

namespace lightcone {

namespace {

constexpr int kRes = kRgbToSpectrumRes;

const std::array<double, kRes>& scale_nodes() {
  static const std::array<double, kRes> nodes = [] {
    std::array<double, kRes> z{};
    for (int k = 0; k < kRes; ++k) z[k] = rgb_to_spectrum_scale_node(k, kRes);
    return z;
  }();
  return nodes;
}

double clamp01(double v) {
  return v > 0 ? (v < 1 ? v : 1.0) : 0.0;
}  // NaN -> 0

// Cell index and fraction of a coordinate t in [0, 1] on the uniform grid of kRes nodes.
void uniform_cell(double t, int& index, double& fraction) {
  const double f = t * (kRes - 1);
  index = std::min(static_cast<int>(f), kRes - 2);
  fraction = f - index;
}

}  // namespace

SigmoidPolynomial rgb_to_sigmoid(const LinearRgb& rgb) {
  const double c[3] = {clamp01(rgb.r), clamp01(rgb.g), clamp01(rgb.b)};
  // The table whose component is largest (ties go to the earlier one; both tables hold the
  // colour there).
  int l = 0;
  if (c[1] > c[l]) l = 1;
  if (c[2] > c[l]) l = 2;
  const double z = c[l];
  if (z <= 0) return {0, 0, -std::numeric_limits<double>::infinity()};

  int xi, yi;
  double dx, dy;
  uniform_cell(c[(l + 1) % 3] / z, xi, dx);
  uniform_cell(c[(l + 2) % 3] / z, yi, dy);
  const std::array<double, kRes>& nodes = scale_nodes();
  // The last node at or below z, at most kRes - 2 (nodes[0] = 0 < z).
  const int zi = std::min(
      static_cast<int>(std::upper_bound(nodes.begin(), nodes.end(), z) - nodes.begin()) - 1,
      kRes - 2);
  const double dz = (z - nodes[zi]) / (nodes[zi + 1] - nodes[zi]);

  const float* table = detail::rgb_to_spectrum_table();
  const auto cell = [&](int k, int j, int i) {
    return table + ((static_cast<std::size_t>(l * kRes + k) * kRes + j) * kRes + i) * 3;
  };
  double out[3] = {0, 0, 0};
  for (int a = 0; a < 2; ++a) {
    const double wz = a ? dz : 1 - dz;
    for (int b = 0; b < 2; ++b) {
      const double wy = b ? dy : 1 - dy;
      for (int e = 0; e < 2; ++e) {
        const double w = wz * wy * (e ? dx : 1 - dx);
        const float* p = cell(zi + a, yi + b, xi + e);
        for (int n = 0; n < 3; ++n) out[n] += w * p[n];
      }
    }
  }
  return {out[0], out[1], out[2]};
}

RgbIlluminantSpectrum RgbIlluminantSpectrum::from_rgb(const LinearRgb& rgb) {
  // The white-balanced reflectance colour whose radiance under the illuminant is rgb.
  const LinearRgb w = reference_white();
  const auto non_negative = [](double v) { return v > 0 ? v : 0.0; };  // NaN -> 0
  const LinearRgb c{non_negative(rgb.r) / w.r, non_negative(rgb.g) / w.g,
                    non_negative(rgb.b) / w.b};
  const double m = std::max({c.r, c.g, c.b});
  RgbIlluminantSpectrum s;
  if (!(m > 0)) return s;  // black
  s.scale = 2 * m;
  s.sigmoid = rgb_to_sigmoid({c.r / s.scale, c.g / s.scale, c.b / s.scale});
  return s;
}

}  // namespace lightcone

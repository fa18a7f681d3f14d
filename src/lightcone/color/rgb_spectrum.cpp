#include "lightcone/color/rgb_spectrum.hpp"

#include <algorithm>
#include <array>
#include <cmath>
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

  const float* table = detail::rgb_to_spectrum_table(l, yi, xi);
  const auto cell = [&](int k, int j, int i) {
    return table + rgb_to_spectrum_cell(l, k, j, i, kRes);
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

int rgb_to_spectrum_cells_of_blends(std::span<const LinearRgb> colours,
                                    std::array<RgbToSpectrumCells, 3>& out) {
  // A blend's ratio c_m / c_l is a weighted mediant of the colours' own ratios (weights w c_l),
  // so it lies between their least and greatest, but for colours with c_l = 0 < c_m, which only
  // raise it; where l holds the blend (c_l largest) it is at most 1.
  const auto cell = [](double t) {
    int index;
    double fraction;
    uniform_cell(std::min(t, 1.0), index, fraction);
    return index;
  };
  int filled = 0;
  for (int l = 0; l < 3; ++l) {
    const int m[2] = {(l + 1) % 3, (l + 2) % 3};
    double lo[2] = {1, 1}, hi[2] = {0, 0};
    bool any = false;
    bool exceeded[2] = {true, true};  // c_m above c_l in every colour, and so in every blend
    for (const LinearRgb& rgb : colours) {
      const double c[3] = {clamp01(rgb.r), clamp01(rgb.g), clamp01(rgb.b)};
      for (int k = 0; k < 2; ++k) {
        if (c[l] >= c[m[k]]) exceeded[k] = false;
        if (c[l] > 0) {
          const double r = c[m[k]] / c[l];
          lo[k] = std::min(lo[k], r);
          hi[k] = std::max(hi[k], r);
        } else if (c[m[k]] > 0) {
          hi[k] = 1;
        }
      }
      any = any || c[l] > 0;
    }
    // No blend has c_l > 0, or some channel exceeds c_l in every colour (and so in every blend).
    if (!any || exceeded[0] || exceeded[1]) continue;
    const auto widened = [](int index, int step) { return std::clamp(index + step, 0, kRes - 2); };
    out[static_cast<std::size_t>(filled++)] = {l, widened(cell(lo[1]), -1), widened(cell(hi[1]), 1),
                                               widened(cell(lo[0]), -1), widened(cell(hi[0]), 1)};
  }
  return filled;
}

namespace {

constexpr double kWhiteBandCentres[3] = {450, 540, 610};  // nm
constexpr double kWhiteBandWidth = 30;                    // nm

double white_band(int k, double lambda_nm) {
  const double t = (lambda_nm - kWhiteBandCentres[k]) / kWhiteBandWidth;
  return std::exp(-0.5 * t * t);
}

// The band weights g that make the RGB white's colour (1, 1, 1): the colour is linear in g,
// w + A g with column k of A the colour of reference_illuminant * band k.
std::array<double, 3> white_band_weights() {
  double a[3][3];
  for (int k = 0; k < 3; ++k) {
    const LinearRgb c = linear_srgb_from_xyz(
        xyz_from_spectrum([k](double l) { return reference_illuminant(l) * white_band(k, l); }));
    a[0][k] = c.r, a[1][k] = c.g, a[2][k] = c.b;
  }
  const LinearRgb w = reference_white();
  const double rhs[3] = {1 - w.r, 1 - w.g, 1 - w.b};
  // Cramer's rule: A is well conditioned (three separated bands).
  const auto det = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = det(a);
  std::array<double, 3> g{};
  for (int k = 0; k < 3; ++k) {
    double m[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m[r][c] = c == k ? rhs[r] : a[r][c];
    g[k] = det(m) / d;
  }
  return g;
}

}  // namespace

double rgb_white_factor(double lambda_nm) {
  static const std::array<double, 3> g = white_band_weights();
  double factor = 1;
  for (int k = 0; k < 3; ++k) factor += g[k] * white_band(k, lambda_nm);
  return factor;
}

double rgb_white_spectrum(double lambda_nm) {
  return reference_illuminant(lambda_nm) * rgb_white_factor(lambda_nm);
}

SigmoidPolynomial rgb_emitter_node(int node_case, int i) {
  const double* c = detail::rgb_emitter_nodes() + (node_case * kRes + i) * 3;
  return {c[0], c[1], c[2]};
}

RgbEmitterSpectrum RgbEmitterSpectrum::from_rgb(const LinearRgb& rgb) {
  const auto non_negative = [](double v) { return v > 0 ? v : 0.0; };  // NaN -> 0
  const double r = non_negative(rgb.r), g = non_negative(rgb.g), b = non_negative(rgb.b);
  RgbEmitterSpectrum s;
  s.grey = std::min({r, g, b});
  // The chromatic remainder, white-balanced to the nodes' reference illuminant.
  const LinearRgb w = reference_white();
  const double c[3] = {(r - s.grey) / w.r, (g - s.grey) / w.g, (b - s.grey) / w.b};
  int l = 0;
  if (c[1] > c[l]) l = 1;
  if (c[2] > c[l]) l = 2;
  if (!(c[l] > 0)) return s;  // a grey (or black)
  const int m1 = (l + 1) % 3, m2 = (l + 2) % 3;
  const int m = c[m2] > c[m1] ? m2 : m1;
  s.scale = 2 * c[l];
  s.node_case = rgb_emitter_case(l, m);
  const double position = std::min(c[m] / c[l], 1.0) * (kRes - 1);
  s.node = std::min(static_cast<int>(position), kRes - 2);
  s.blend = position - s.node;
  return s;
}

double RgbEmitterSpectrum::operator()(double lambda_nm) const {
  double value = grey > 0 ? grey * rgb_white_spectrum(lambda_nm) : 0.0;
  if (scale > 0) {
    const double a = rgb_emitter_node(node_case, node)(lambda_nm);
    const double b = rgb_emitter_node(node_case, node + 1)(lambda_nm);
    value += scale * ((1 - blend) * a + blend * b) * reference_illuminant(lambda_nm);
  }
  return value;
}

}  // namespace lightcone

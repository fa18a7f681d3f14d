// The colour of a spectrum seen with a Doppler factor D, as a deterministic quadrature
// tabulated against ln D (docs/design/spectral.md, "The spectral estimator"). The renderer
// looks colours up here instead of sampling wavelengths, so a known spectrum renders without
// noise, and its error is relative to what is received, however dim.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/portable.hpp"

namespace lightcone {

// The colour of the spectrum L seen with factor d, before the searchlight factor: the 1 nm
// quadrature of L(d lambda) against the CIE observer (the same sum as xyz_from_spectrum,
// which it equals at d = 1):
//   sum over lambda = 360, 361, ..., 830 nm of L(d lambda) cmf(lambda) / cie_y_integral().
template <class Spectrum>
Xyz xyz_seen_with_doppler(const Spectrum& spectrum, double d) {
  return xyz_from_spectrum([&](double lambda) { return spectrum(d * lambda); });
}

// Nodes k h of ln D, k = first .. last, with h = kStep. A grid covering [lo, hi] in ln D has
// two nodes beyond each end (the cubic stencil). Its tables answer from node 1 to node
// size - 2 and refuse a factor beyond (grid_position), except below a settled grid.
//
// Settled: every table on the grid is constant at node 1 and below, exactly. A table's colour
// seen with D is the quadrature of L_E(D lambda), lambda <= kCieMaxWavelength, times the
// searchlight factor D^k outside it; where D kCieMaxWavelength is at or below a wavelength at
// and below which L_E is constant, so is the quadrature. For a blackbody, and every RGB emitter
// (the 6504 K blackbody times finite factors), that constant is 0: as D -> 0 the visible band
// samples the far Wien tail, exp(-kC2 / (D lambda T)), which is 0 in double precision below
// planck_zero_wavelength(T) (not an approximation). A lookup below a settled grid is node 1's
// value, which is that constant.
struct DopplerGrid {
  static constexpr double kStep = 0.02;
  int first = -2, last = 2;
  bool settled = false;

  // The grid over [lo, hi] (in either order); a range that is not finite is refused
  // (std::invalid_argument).
  static DopplerGrid covering(double lo_log_d, double hi_log_d);
  static DopplerGrid covering(double max_abs_log_d) {
    return covering(-max_abs_log_d, max_abs_log_d);
  }
  // The grid over [lo, hi] (lo <= hi, lo may be -infinity) for tables of spectra constant at
  // and below `constant_below` nm: where lo reaches D = constant_below / kCieMaxWavelength, it
  // stops there, settled. hi must be finite; so must lo, for spectra that are nowhere constant.
  static DopplerGrid reaching(double lo_log_d, double hi_log_d, double constant_below);
  int size() const { return last - first + 1; }
  double log_d(int index) const { return (first + index) * kStep; }
  double d(int index) const { return std::exp(log_d(index)); }
  // The index of the node at D = 1 (when the grid holds it: first <= 0 <= last).
  int rest_index() const { return -first; }
  // The factors its tables answer at: ln D from lowest_log_d() (-infinity where settled) to
  // highest_log_d().
  double lowest_log_d() const {
    return settled ? -std::numeric_limits<double>::infinity() : log_d(1);
  }
  double highest_log_d() const { return log_d(size() - 2); }
};

// Where ln d lies on a grid: the interpolation uses the four nodes first .. first + 3, and d
// lies at `fraction` of the way from node first + 1 to node first + 2.
struct GridPosition {
  int first = 0;
  double fraction = 0;
};
// ln d for the grid, to 1e-12 and several times cheaper than std::log (it runs once per camera
// ray): d = m 2^e, m in [1, 2) split at its top 10 bits into m_k = 1 + k / 1024 and the rest,
// ln m = ln m_k + ln(1 + x) with x = (m - m_k) / m_k < 1/1024, the last by its series to x^4.
namespace detail {
struct GridLogTable {
  double log_node[1024], inverse_node[1024];
  GridLogTable() {
    for (int k = 0; k < 1024; ++k) {
      log_node[k] = std::log1p(k / 1024.0);
      inverse_node[k] = 1 / (1 + k / 1024.0);
    }
  }
};
inline const GridLogTable grid_log_table;
}  // namespace detail

inline double grid_log(double d) {
  if (!(d > 1e-300 && d < 1e300)) return std::log(d);
  const auto bits = lightcone::bit_cast<std::uint64_t>(d);
  const int e = static_cast<int>((bits >> 52) & 0x7ff) - 1023;
  const auto k = static_cast<int>((bits >> 42) & 0x3ff);
  const double m =
      lightcone::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);
  // m_k = 1 + k / 1024 exactly: m's top 10 mantissa bits alone (no conversion on the path).
  const double m_k =
      lightcone::bit_cast<double>((bits & 0x000ffc0000000000ULL) | 0x3ff0000000000000ULL);
  const double x = (m - m_k) * detail::grid_log_table.inverse_node[k];
  const double series = x * (1 - x * (0.5 - x * (1.0 / 3 - x * 0.25)));
  return e * 0.6931471805599453 + detail::grid_log_table.log_node[k] + series;
}

// A factor outside what a grid answers: below a settled grid, node 1 (fraction 0); otherwise
// refused (std::out_of_range): extrapolating the end interval's cubic ran to negative radiance.
GridPosition grid_position_outside(const DopplerGrid& grid, double d);

// d within what the grid answers (lowest_log_d() to highest_log_d(), give or take rounding).
inline GridPosition grid_position(const DopplerGrid& grid, double d) {
  constexpr double kNodesPerUnit = 1 / DopplerGrid::kStep;
  // (grid_log and the caller's own logarithms round: a millionth of a step is let through.)
  constexpr double kRounding = 1e-6;
  const double t = grid_log(d) * kNodesPerUnit - grid.first;
  const double top = grid.size() - 2;
  if (!(t >= 1 - kRounding && t <= top + kRounding)) [[unlikely]]
    return grid_position_outside(grid, d);
  // Truncation is floor for t >= 1; the clamp takes the end intervals up to their ends (held
  // <= size - 3, so first <= size - 4).
  const double held = std::clamp(t, 1.0, top - 1);
  GridPosition p;
  p.first = static_cast<int>(held) - 1;
  p.fraction = t - (p.first + 1);
  return p;
}

// e^x, by its Taylor series (Estrin's scheme) where |x| <= 1/2 (relative error below 3e-10;
// std::exp costs several times more on the hot path), else by std::exp.
inline double exp_near_zero(double x) {
  if (!(std::abs(x) <= 0.5)) return std::exp(x);
  const double x2 = x * x, x4 = x2 * x2;
  const double p01 = 1 + x, p23 = 0.5 + x * (1.0 / 6), p45 = 1.0 / 24 + x * (1.0 / 120),
               p67 = 1.0 / 720 + x * (1.0 / 5040), p89 = 1.0 / 40320 + x * (1.0 / 362880);
  return (p01 + x2 * p23) + x4 * ((p45 + x2 * p67) + x4 * p89);
}

// The weights of Lagrange's cubic through the four nodes of a position (fourth-order
// accurate).
struct GridStencil {
  GridPosition position;
  double weights[4] = {0, 1, 0, 0};
};
GridStencil grid_stencil(const DopplerGrid& grid, double d);

// Runs f(k) for every k in [0, n): one after another, or (a caller's own) in parallel. The
// tables below compute each node on its own, so any order gives the same table.
struct SerialNodes {
  template <class F>
  void operator()(int n, const F& f) const {
    for (int k = 0; k < n; ++k) f(k);
  }
};

// A spectrum sampled for DopplerXyzTable::under: I(d(k) (360 + i)) for every node k of the grid
// and i in [0, kCieTableSize).
template <class Spectrum, class ForEachNode = SerialNodes>
std::vector<double> illuminant_samples(const Spectrum& spectrum, const DopplerGrid& grid,
                                       const ForEachNode& for_each_node = {}) {
  std::vector<double> samples(static_cast<std::size_t>(grid.size()) * kCieTableSize);
  for_each_node(grid.size(), [&](int k) {
    for (int i = 0; i < kCieTableSize; ++i)
      samples[static_cast<std::size_t>(k) * kCieTableSize + i] =
          spectrum(grid.d(k) * (kCieMinWavelength + i));
  });
  return samples;
}

// One spectrum's colour against ln D: xyz_seen_with_doppler at every node, interpolated
// cubically in the logarithms of X, Y and Z so that the relative error stays small across
// many orders of magnitude (a Wien tail is nearly a straight line in ln E against ln D). Where
// a node of the stencil is zero it interpolates the two middle nodes linearly.
class DopplerXyzTable {
 public:
  DopplerXyzTable() = default;
  template <class Spectrum, class ForEachNode = SerialNodes>
  static DopplerXyzTable of(const Spectrum& spectrum, const DopplerGrid& grid,
                            const ForEachNode& for_each_node = {}) {
    std::vector<Xyz> nodes(grid.size());
    for_each_node(grid.size(),
                  [&](int i) { nodes[i] = xyz_seen_with_doppler(spectrum, grid.d(i)); });
    return DopplerXyzTable(grid, std::move(nodes));
  }
  // The same for a spectrum rho(lambda) I(lambda) with I sampled once per grid: `samples`
  // holds I(d(k) (360 + i)) at index k * kCieTableSize + i (illuminant_samples), so that many
  // tables under one illuminant evaluate it once.
  template <class Reflectance, class ForEachNode = SerialNodes>
  static DopplerXyzTable under(const Reflectance& rho, const std::vector<double>& samples,
                               const DopplerGrid& grid, const ForEachNode& for_each_node = {}) {
    std::vector<Xyz> nodes(grid.size());
    for_each_node(grid.size(), [&](int k) {
      const double d = grid.d(k);
      const double* row = &samples[static_cast<std::size_t>(k) * kCieTableSize];
      // The products first, in a loop without a sum, which the compiler can vectorise; then
      // xyz_from_spectrum's sum, in its order.
      std::array<double, kCieTableSize> products;
      for (int i = 0; i < kCieTableSize; ++i)
        products[i] = rho(d * (kCieMinWavelength + i)) * row[i];
      nodes[k] = xyz_from_samples(products.data());
    });
    return DopplerXyzTable(grid, std::move(nodes));
  }
  DopplerXyzTable(const DopplerGrid& grid, std::vector<Xyz> nodes);

  const DopplerGrid& grid() const { return grid_; }
  const Xyz& node(int index) const { return nodes_[index]; }
  // The colour at D = 1, for a grid that holds it.
  const Xyz& at_rest() const { return nodes_[grid_.rest_index()]; }
  Xyz operator()(const GridPosition& p) const {
    const Interval& in = intervals_[p.first + 1];
    if (in.all_values)  // (at a node, the node itself: a settled grid's limit stays exact)
      return p.fraction == 0 ? nodes_[p.first + 1] : xyz_from_linear_srgb(rgb(p));
    const double f = p.fraction;
    double out[3];
    for (int k = 0; k < 3; ++k) {
      const double q = f * (in.c1[k] + f * (in.c2[k] + f * in.c3[k]));
      out[k] = in.mode[k] == Interval::kValues ? in.value[k] + q
               : in.mode[k] == Interval::kLogarithms
                   ? in.value[k] * exp_near_zero(q)
                   : in.value[k] + std::clamp(f, 0.0, 1.0) * in.c1[k];
    }
    return {out[0], out[1], out[2]};
  }
  Xyz operator()(double d) const { return (*this)(grid_position(grid_, d)); }

  // linear_srgb_from_xyz of the colour at p. Where the interval is a cubic in the values (the
  // common case), its coefficients are kept in linear sRGB, taken there once when the table is
  // made (the cubic is linear in them), so that the spectral model's lookup per ray needs no
  // matrix; the XYZ lookup above takes them back.
  LinearRgb rgb(const GridPosition& p) const {
    const Interval& in = intervals_[p.first + 1];
    if (!in.all_values) return linear_srgb_from_xyz((*this)(p));
    const double f = p.fraction;
    double out[3];
    for (int k = 0; k < 3; ++k)
      out[k] = in.value[k] + f * (in.c1[k] + f * (in.c2[k] + f * in.c3[k]));
    return {out[0], out[1], out[2]};
  }

 private:
  DopplerGrid grid_;
  std::vector<Xyz> nodes_;
  // Per interval (from node i to i + 1) and channel, value = E at node i and the cubic
  // q = f (c1 + f (c2 + f c3)) in the fraction f: E = value + q (Lagrange's cubic in the
  // values) where the four nodes of the stencil lie within a factor kValuesRatio of each other,
  // E = value exp(q) (the cubic in ln E) where they are positive, and E = value + f c1
  // (linear, c1 the difference to node i + 1) where one is zero.
  struct Interval {
    enum Mode : unsigned char { kValues, kLogarithms, kLinear };
    double value[3] = {0, 0, 0}, c1[3] = {0, 0, 0}, c2[3] = {0, 0, 0}, c3[3] = {0, 0, 0};
    Mode mode[3] = {kLinear, kLinear, kLinear};
    bool all_values = false;  // then the coefficients are of linear sRGB, not XYZ
  };
  std::vector<Interval> intervals_;
};

// Light of spectrum I reflected by a reflectance rho and seen by a camera: the camera sees the
// reflector with factor d_camera and the reflector sees the light with d_light, so the camera
// receives rho(d_camera lambda) I(d_light d_camera lambda) (before the searchlight factors).
// Its colour by the same 1 nm quadrature.
template <class Reflectance, class Spectrum>
Xyz xyz_of_reflection_seen_with_doppler(const Reflectance& rho, const Spectrum& light,
                                        double d_camera, double d_light) {
  const double d_total = d_camera * d_light;
  return xyz_from_spectrum(
      [&](double lambda) { return rho(d_camera * lambda) * light(d_total * lambda); });
}

// That colour against (ln d_camera, ln d_light) on two grids, interpolated bicubically in the
// logarithms. The camera's grid may be settled: the light is sampled at d_camera d_light lambda,
// so it must be reached for spectra constant below constant_below / (the light grid's largest
// factor), and for the reflectance's own constant part (below kCieMinWavelength).
class ReflectionXyzTable {
 public:
  ReflectionXyzTable() = default;
  // Every node is xyz_of_reflection_seen_with_doppler; since the grids share one step, the
  // light is read at the factors d_camera d_light = e^(k h) of one combined grid, so each
  // spectrum is evaluated once per node and wavelength, not once per pair of nodes.
  template <class Reflectance, class Spectrum, class ForEachNode = SerialNodes>
  static ReflectionXyzTable of(const Reflectance& rho, const Spectrum& light,
                               const DopplerGrid& camera, const DopplerGrid& light_grid,
                               const ForEachNode& for_each_node = {}) {
    const int nc = camera.size(), nl = light_grid.size();
    DopplerGrid total;
    total.first = camera.first + light_grid.first;
    total.last = camera.last + light_grid.last;
    std::vector<double> reflectance(static_cast<std::size_t>(nc) * kCieTableSize);
    std::vector<double> source(static_cast<std::size_t>(total.size()) * kCieTableSize);
    for (int c = 0; c < nc; ++c)
      for (int i = 0; i < kCieTableSize; ++i)
        reflectance[c * kCieTableSize + i] = rho(camera.d(c) * (kCieMinWavelength + i));
    for (int t = 0; t < total.size(); ++t)
      for (int i = 0; i < kCieTableSize; ++i)
        source[t * kCieTableSize + i] = light(total.d(t) * (kCieMinWavelength + i));
    std::vector<Xyz> nodes(static_cast<std::size_t>(nc) * nl);
    for_each_node(nc, [&](int c) {
      for (int l = 0; l < nl; ++l)
        nodes[static_cast<std::size_t>(c) * nl + l] =
            reflected_sum(&reflectance[c * kCieTableSize], &source[(c + l) * kCieTableSize]);
    });
    return ReflectionXyzTable(camera, light_grid, std::move(nodes));
  }
  ReflectionXyzTable(const DopplerGrid& camera, const DopplerGrid& light, std::vector<Xyz> nodes);

  const Xyz& at_rest() const {
    return nodes_[static_cast<std::size_t>(camera_.rest_index()) * light_.size() +
                  light_.rest_index()];
  }
  Xyz operator()(const GridStencil& camera, double d_light) const;

 private:
  // The 1 nm sum of reflectance[i] source[i] cmf(360 + i), normalised as xyz_from_spectrum.
  static Xyz reflected_sum(const double* reflectance, const double* source);
  DopplerGrid camera_, light_;
  std::vector<Xyz> nodes_, logs_;
};

}  // namespace lightcone

// The colour of a spectrum seen with a Doppler factor D, as a deterministic quadrature
// tabulated against ln D (docs/design/spectral.md, "The spectral estimator"). The renderer
// looks colours up here instead of sampling wavelengths, so a known spectrum renders without
// noise, and its error is relative to what is received, however dim.
#pragma once

#include <cmath>
#include <vector>

#include "lightcone/color/cie.hpp"

namespace lightcone {

// The colour of the spectrum L seen with factor d, before the searchlight factor: the 1 nm
// quadrature of L(d lambda) against the CIE observer (the same sum as xyz_from_spectrum,
// which it equals at d = 1):
//   sum over lambda = 360, 361, ..., 830 nm of L(d lambda) cmf(lambda) / cie_y_integral().
template <class Spectrum>
Xyz xyz_seen_with_doppler(const Spectrum& spectrum, double d) {
  return xyz_from_spectrum([&](double lambda) { return spectrum(d * lambda); });
}

// Nodes k h of ln D, k = -half_count .. half_count, with h = kStep. A grid covering
// |ln D| <= r has a node at D = 1 and two nodes beyond r on each side (the cubic stencil).
struct DopplerGrid {
  static constexpr double kStep = 0.02;
  int half_count = 2;

  static DopplerGrid covering(double max_abs_log_d);
  int size() const { return 2 * half_count + 1; }
  double log_d(int index) const { return (index - half_count) * kStep; }
  double d(int index) const { return std::exp(log_d(index)); }
};

// The positions and weights of a cubic (Lagrange, four nodes) interpolation on a grid at ln D.
struct GridStencil {
  int first = 0;  // index of the first of four nodes
  double weights[4] = {0, 1, 0, 0};
  double fraction = 0;  // between nodes first + 1 and first + 2
};
// d must lie within the grid's interior (|ln d| <= kStep * (half_count - 2) plus one step).
GridStencil grid_stencil(const DopplerGrid& grid, double d);

// Interpolates four positive values cubically in their logarithms, so that the relative error
// stays small across many orders of magnitude (a Wien tail is nearly a straight line in ln E
// against ln D). Where a value is zero it interpolates the two middle values linearly.
double log_cubic(const double values[4], const double logs[4], const GridStencil& stencil);

// One spectrum's colour against ln D: xyz_seen_with_doppler at every node.
class DopplerXyzTable {
 public:
  DopplerXyzTable() = default;
  template <class Spectrum>
  static DopplerXyzTable of(const Spectrum& spectrum, const DopplerGrid& grid) {
    std::vector<Xyz> nodes(grid.size());
    for (int i = 0; i < grid.size(); ++i) nodes[i] = xyz_seen_with_doppler(spectrum, grid.d(i));
    return DopplerXyzTable(grid, std::move(nodes));
  }
  DopplerXyzTable(const DopplerGrid& grid, std::vector<Xyz> nodes);

  const DopplerGrid& grid() const { return grid_; }
  const Xyz& node(int index) const { return nodes_[index]; }
  const Xyz& at_rest() const { return nodes_[grid_.half_count]; }
  Xyz operator()(const GridStencil& stencil) const;
  Xyz operator()(double d) const { return (*this)(grid_stencil(grid_, d)); }

 private:
  DopplerGrid grid_;
  std::vector<Xyz> nodes_;
  std::vector<Xyz> logs_;
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
// logarithms.
class ReflectionXyzTable {
 public:
  ReflectionXyzTable() = default;
  // Every node is xyz_of_reflection_seen_with_doppler; since the grids share one step, the
  // light is read at the factors d_camera d_light = e^(k h) of one combined grid, so each
  // spectrum is evaluated once per node and wavelength, not once per pair of nodes.
  template <class Reflectance, class Spectrum>
  static ReflectionXyzTable of(const Reflectance& rho, const Spectrum& light,
                               const DopplerGrid& camera, const DopplerGrid& light_grid) {
    const int nc = camera.size(), nl = light_grid.size();
    DopplerGrid total;
    total.half_count = camera.half_count + light_grid.half_count;
    std::vector<double> reflectance(static_cast<std::size_t>(nc) * kCieTableSize);
    std::vector<double> source(static_cast<std::size_t>(total.size()) * kCieTableSize);
    for (int c = 0; c < nc; ++c)
      for (int i = 0; i < kCieTableSize; ++i)
        reflectance[c * kCieTableSize + i] = rho(camera.d(c) * (kCieMinWavelength + i));
    for (int t = 0; t < total.size(); ++t)
      for (int i = 0; i < kCieTableSize; ++i)
        source[t * kCieTableSize + i] = light(total.d(t) * (kCieMinWavelength + i));
    std::vector<Xyz> nodes(static_cast<std::size_t>(nc) * nl);
    for (int c = 0; c < nc; ++c)
      for (int l = 0; l < nl; ++l)
        nodes[static_cast<std::size_t>(c) * nl + l] =
            reflected_sum(&reflectance[c * kCieTableSize], &source[(c + l) * kCieTableSize]);
    return ReflectionXyzTable(camera, light_grid, std::move(nodes));
  }
  ReflectionXyzTable(const DopplerGrid& camera, const DopplerGrid& light, std::vector<Xyz> nodes);

  const Xyz& at_rest() const {
    return nodes_[static_cast<std::size_t>(camera_.half_count) * light_.size() + light_.half_count];
  }
  Xyz operator()(const GridStencil& camera, double d_light) const;

 private:
  // The 1 nm sum of reflectance[i] source[i] cmf(360 + i), normalised as xyz_from_spectrum.
  static Xyz reflected_sum(const double* reflectance, const double* source);
  DopplerGrid camera_, light_;
  std::vector<Xyz> nodes_, logs_;
};

}  // namespace lightcone

// The project's own fit of the Jakob-Hanika sigmoid-quadratic model to RGB colours, used by the
// table generator (tools/rgb2spec_gen.cpp) at build time and by the tests (to check that the
// table built into the library is what the fit produces now).
//
// Method (after Jakob & Hanika, EGSR 2019; our own implementation): for a target linear sRGB
// colour, find c = (c0, c1, c2) such that the colour of the reflectance
// s(lambda) = S(c0 u^2 + c1 u + c2) under the reference illuminant I (sigmoid_polynomial.hpp),
//   XYZ(c) = sum over lambda = 360, 361, ..., 830 nm of s(lambda) I(lambda) cmf(lambda)
//            / cie_y_integral(),
// matches the target's XYZ. The residual is the difference in CIELAB (white: the XYZ of
// I itself, i.e. of s = 1), so that the error is spread perceptually where a colour cannot be
// reached exactly (bright colours near the limit of what a reflectance in [0, 1] can give).
// It is minimised by Levenberg-Marquardt with the analytic Jacobian
//   dXYZ/dc_n = sum of S'(x(lambda)) u(lambda)^n I cmf / cie_y_integral(),
//   S'(x) = 1 / (2 (1 + x^2)^(3/2)),
// chained with the derivative of the CIELAB transform.
//
// The table holds white-balanced reflectances: the node for the colour rgb is fitted to the
// target rgb * reference_white() (per channel), so that greys come out flat and (1, 1, 1) is the
// flat reflectance 1 (see sigmoid_polynomial.hpp).
//
// The table is filled column by column: for one table l and one (i, j), the fit starts from
// c = 0 at the scale node start_node(res) and walks up the scale axis, each fit warm-started from
// the previous node's solution, then walks down from there in the same way. Columns do not
// depend on each other, so the table is the same whatever the number of threads or their
// scheduling (deterministic).
#pragma once

#include <array>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/sigmoid_polynomial.hpp"

namespace lightcone::rgb2spec {

using Coefficients = std::array<double, 3>;

struct FitResult {
  Coefficients c{};
  double lab_error = 0;  // Euclidean CIELAB distance (Delta E 1976) left at the end
  int iterations = 0;
};

class Fitter {
 public:
  Fitter();  // precomputes the 1 nm quadrature weights I(lambda) cmf(lambda) / cie_y_integral()

  // XYZ of the reflectance with coefficients c under the reference illuminant.
  Xyz xyz(const Coefficients& c) const;

  // Fits the linear sRGB colour `target` (components >= 0), starting from `start`.
  FitResult fit(const LinearRgb& target, const Coefficients& start) const;

  // Fills one column (table l, x index i, y index j, every scale node k) of a table with `res`
  // nodes per axis, in the layout of sigmoid_polynomial.hpp (table has res^3 * 9 floats). Node
  // 0 (black) copies node 1.
  void fit_column(int res, int l, int j, int i, float* table) const;

  // The node the walk along the scale axis starts from.
  static int start_node(int res) { return res / 5; }

 private:
  struct Evaluation {
    std::array<double, 3> residual{};                 // CIELAB(c) - CIELAB(target)
    std::array<std::array<double, 3>, 3> jacobian{};  // d residual_m / d c_n
    double cost = 0;                                  // |residual|^2
  };
  Evaluation evaluate(const Coefficients& c, const std::array<double, 3>& target_lab,
                      bool with_jacobian) const;

  std::vector<double> u_;  // normalised wavelength per sample
  std::vector<double> wx_, wy_, wz_;
  Xyz white_;  // XYZ of s = 1: the CIELAB white
};

// The whole table, 3 * res^3 * 3 floats, computed on `threads` threads (0: all cores).
std::vector<float> generate_table(int res, unsigned threads);

// The emitter nodes (layout in sigmoid_polynomial.hpp), kRgbEmitterNodeDoubles doubles. Each
// case starts at its saturated primary (reached by raising the brightness from a dim one, each
// fit warm-started from the last) and walks the middle channel up. Throws std::runtime_error
// if a node is not fitted to within Delta E 1e-5.
std::vector<double> generate_emitter_nodes();

}  // namespace lightcone::rgb2spec

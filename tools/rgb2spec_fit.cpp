#include "rgb2spec_fit.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

namespace lightcone::rgb2spec {

namespace {

constexpr int kMaxIterations = 100;
constexpr double kTargetCost = 1e-12;  // squared CIELAB distance: Delta E 1e-6

// CIELAB's f(t) and its derivative.
constexpr double kLabDelta = 6.0 / 29.0;
double lab_f(double t) {
  return t > kLabDelta * kLabDelta * kLabDelta ? std::cbrt(t)
                                               : t / (3 * kLabDelta * kLabDelta) + 4.0 / 29.0;
}
double lab_f_prime(double t) {
  if (t > kLabDelta * kLabDelta * kLabDelta) {
    const double c = std::cbrt(t);
    return 1 / (3 * c * c);
  }
  return 1 / (3 * kLabDelta * kLabDelta);
}

std::array<double, 3> lab(const Xyz& xyz, const Xyz& white) {
  const double fx = lab_f(xyz.x / white.x);
  const double fy = lab_f(xyz.y / white.y);
  const double fz = lab_f(xyz.z / white.z);
  return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

// Solves the 3 x 3 system a x = b by Gaussian elimination with partial pivoting; false if
// singular.
bool solve3(std::array<std::array<double, 3>, 3> a, std::array<double, 3> b,
            std::array<double, 3>& x) {
  for (int col = 0; col < 3; ++col) {
    int pivot = col;
    for (int row = col + 1; row < 3; ++row) {
      if (std::fabs(a[row][col]) > std::fabs(a[pivot][col])) pivot = row;
    }
    if (!(std::fabs(a[pivot][col]) > 0)) return false;
    std::swap(a[col], a[pivot]);
    std::swap(b[col], b[pivot]);
    for (int row = col + 1; row < 3; ++row) {
      const double factor = a[row][col] / a[col][col];
      for (int k = col; k < 3; ++k) a[row][k] -= factor * a[col][k];
      b[row] -= factor * b[col];
    }
  }
  for (int row = 2; row >= 0; --row) {
    double sum = b[row];
    for (int k = row + 1; k < 3; ++k) sum -= a[row][k] * x[k];
    x[row] = sum / a[row][row];
  }
  return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
}

}  // namespace

Fitter::Fitter() {
  const double inv_y = 1 / cie_y_integral();
  for (int lambda = static_cast<int>(kCieMinWavelength);
       lambda <= static_cast<int>(kCieMaxWavelength); ++lambda) {
    const Xyz cmf = cie_cmf(lambda);
    const double weight = reference_illuminant(lambda) * inv_y;
    u_.push_back(sigmoid_normalised_wavelength(lambda));
    wx_.push_back(weight * cmf.x);
    wy_.push_back(weight * cmf.y);
    wz_.push_back(weight * cmf.z);
  }
  white_ = xyz({0, 0, 1e300});  // s = 1 everywhere
}

Xyz Fitter::xyz(const Coefficients& c) const {
  Xyz sum;
  for (size_t n = 0; n < u_.size(); ++n) {
    const double s = sigmoid((c[0] * u_[n] + c[1]) * u_[n] + c[2]);
    sum.x += s * wx_[n];
    sum.y += s * wy_[n];
    sum.z += s * wz_[n];
  }
  return sum;
}

Fitter::Evaluation Fitter::evaluate(const Coefficients& c, const std::array<double, 3>& target_lab,
                                    bool with_jacobian) const {
  // XYZ and d XYZ / d c in one pass over the samples. The reductions are vectorised
  // (omp simd, -fopenmp-simd): the summation order is fixed by the compiled code, so a given
  // build gives the same bits on every run.
  double x = 0, y = 0, z = 0;
  double dx0 = 0, dx1 = 0, dx2 = 0, dy0 = 0, dy1 = 0, dy2 = 0, dz0 = 0, dz1 = 0, dz2 = 0;
  const int count = static_cast<int>(u_.size());
  const double* u = u_.data();
  const double* wx = wx_.data();
  const double* wy = wy_.data();
  const double* wz = wz_.data();
  const double c0 = c[0], c1 = c[1], c2 = c[2];
  if (with_jacobian) {
#pragma omp simd reduction(+ : x, y, z, dx0, dx1, dx2, dy0, dy1, dy2, dz0, dz1, dz2)
    for (int n = 0; n < count; ++n) {
      const double arg = (c0 * u[n] + c1) * u[n] + c2;
      const double inv_r = 1 / std::sqrt(1 + arg * arg);
      const double s = 0.5 + 0.5 * arg * inv_r;
      x += s * wx[n];
      y += s * wy[n];
      z += s * wz[n];
      const double d2 = 0.5 * inv_r * inv_r * inv_r;  // S'(arg) = d s / d c2
      const double d1 = d2 * u[n], d0 = d1 * u[n];
      dx0 += d0 * wx[n], dx1 += d1 * wx[n], dx2 += d2 * wx[n];
      dy0 += d0 * wy[n], dy1 += d1 * wy[n], dy2 += d2 * wy[n];
      dz0 += d0 * wz[n], dz1 += d1 * wz[n], dz2 += d2 * wz[n];
    }
  } else {
#pragma omp simd reduction(+ : x, y, z)
    for (int n = 0; n < count; ++n) {
      const double arg = (c0 * u[n] + c1) * u[n] + c2;
      const double s = 0.5 + 0.5 * arg / std::sqrt(1 + arg * arg);
      x += s * wx[n];
      y += s * wy[n];
      z += s * wz[n];
    }
  }
  const double dx[3] = {dx0, dx1, dx2}, dy[3] = {dy0, dy1, dy2}, dz[3] = {dz0, dz1, dz2};
  Evaluation e;
  const std::array<double, 3> current = lab({x, y, z}, white_);
  for (int m = 0; m < 3; ++m) {
    e.residual[m] = current[m] - target_lab[m];
    e.cost += e.residual[m] * e.residual[m];
  }
  if (with_jacobian) {
    const double gx = lab_f_prime(x / white_.x) / white_.x;
    const double gy = lab_f_prime(y / white_.y) / white_.y;
    const double gz = lab_f_prime(z / white_.z) / white_.z;
    for (int n = 0; n < 3; ++n) {
      const double dfx = gx * dx[n], dfy = gy * dy[n], dfz = gz * dz[n];
      e.jacobian[0][n] = 116 * dfy;
      e.jacobian[1][n] = 500 * (dfx - dfy);
      e.jacobian[2][n] = 200 * (dfy - dfz);
    }
  }
  return e;
}

FitResult Fitter::fit(const LinearRgb& target, const Coefficients& start) const {
  const std::array<double, 3> target_lab = lab(xyz_from_linear_srgb(target), white_);
  FitResult result;
  result.c = start;
  Evaluation current = evaluate(result.c, target_lab, true);
  double damping = 1e-4;
  while (result.iterations < kMaxIterations && current.cost > kTargetCost) {
    ++result.iterations;
    // Normal equations (J^T J + damping diag(J^T J)) step = -J^T r.
    std::array<std::array<double, 3>, 3> normal{};
    std::array<double, 3> gradient{};
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        for (int m = 0; m < 3; ++m) normal[a][b] += current.jacobian[m][a] * current.jacobian[m][b];
      }
      for (int m = 0; m < 3; ++m) gradient[a] -= current.jacobian[m][a] * current.residual[m];
    }
    bool improved = false;
    while (damping < 1e12) {
      std::array<std::array<double, 3>, 3> damped = normal;
      for (int a = 0; a < 3; ++a) damped[a][a] += damping * normal[a][a] + 1e-300;
      std::array<double, 3> step{};
      if (solve3(damped, gradient, step)) {
        const Coefficients trial = {result.c[0] + step[0], result.c[1] + step[1],
                                    result.c[2] + step[2]};
        const Evaluation next = evaluate(trial, target_lab, true);
        if (next.cost < current.cost) {
          result.c = trial;
          current = next;
          damping = std::max(damping / 4, 1e-12);
          improved = true;
          break;
        }
      }
      damping *= 4;
    }
    if (!improved) break;  // at a minimum that is not a zero: the colour is out of reach
  }
  result.lab_error = std::sqrt(current.cost);
  return result;
}

void Fitter::fit_column(int res, int l, int j, int i, float* table) const {
  const double x = static_cast<double>(i) / (res - 1);
  const double y = static_cast<double>(j) / (res - 1);
  const LinearRgb white = reference_white();
  const auto solve_node = [&](int k, const Coefficients& start) {
    const double z = rgb_to_spectrum_scale_node(k, res);
    double rgb[3];
    rgb[l] = z;
    rgb[(l + 1) % 3] = x * z;
    rgb[(l + 2) % 3] = y * z;
    // The table's colours are white-balanced reflectances (sigmoid_polynomial.hpp): the
    // target under the reference illuminant is rgb times the illuminant's white.
    const FitResult r = fit({rgb[0] * white.r, rgb[1] * white.g, rgb[2] * white.b}, start);
    float* cell = table + rgb_to_spectrum_cell(l, k, j, i, res);
    for (int n = 0; n < 3; ++n) cell[n] = static_cast<float>(r.c[n]);
    return r.c;
  };
  const int start = start_node(res);
  const Coefficients at_start = solve_node(start, {0, 0, 0});
  Coefficients c = at_start;
  for (int k = start + 1; k < res; ++k) c = solve_node(k, c);
  c = at_start;
  for (int k = start - 1; k >= 1; --k) c = solve_node(k, c);
  // Node 0 is black (z = 0), which only c2 = -infinity reaches exactly; it takes node 1's
  // coefficients instead, so a colour darker than node 1 (max component below ~2e-6 at res 64)
  // gets node 1's spectrum: an absolute error below that node's brightness.
  float* node0 = table + rgb_to_spectrum_cell(l, 0, j, i, res);
  const float* node1 = table + rgb_to_spectrum_cell(l, 1, j, i, res);
  std::copy(node1, node1 + 3, node0);
}

std::vector<float> generate_table(int res, unsigned threads) {
  std::vector<float> table(static_cast<size_t>(3) * res * res * res * 3);
  const Fitter fitter;
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  std::atomic<int> next{0};
  const int columns = 3 * res * res;
  const auto work = [&] {
    for (int column = next++; column < columns; column = next++) {
      const int l = column / (res * res);
      const int j = (column / res) % res;
      const int i = column % res;
      fitter.fit_column(res, l, j, i, table.data());
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  return table;
}

std::vector<double> generate_emitter_nodes() {
  const int res = kRgbToSpectrumRes;
  std::vector<double> nodes(kRgbEmitterNodeDoubles);
  const Fitter fitter;
  const LinearRgb white = reference_white();
  const auto balanced = [&](const LinearRgb& c) {
    return LinearRgb{c.r * white.r, c.g * white.g, c.b * white.b};
  };
  for (int l = 0; l < 3; ++l)
    for (int m : {(l + 1) % 3, (l + 2) % 3}) {
      const int case_index = rgb_emitter_case(l, m);
      Coefficients c{0, 0, 0};
      const LinearRgb primary = rgb_emitter_node_colour(l, m, 0);
      for (int step = 1; step <= 20; ++step) {
        const double t = step / 20.0;
        c = fitter.fit(balanced({primary.r * t, primary.g * t, primary.b * t}), c).c;
      }
      for (int i = 0; i < res; ++i) {
        const FitResult r = fitter.fit(balanced(rgb_emitter_node_colour(l, m, i)), c);
        if (!(r.lab_error < 1e-5))
          throw std::runtime_error("emitter node " + std::to_string(case_index) + "/" +
                                   std::to_string(i) + " not fitted (Delta E " +
                                   std::to_string(r.lab_error) + ")");
        c = r.c;
        for (int n = 0; n < 3; ++n) nodes[(case_index * res + i) * 3 + n] = c[n];
      }
    }
  return nodes;
}

}  // namespace lightcone::rgb2spec

#include "lightcone/color/doppler_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lightcone {
namespace {

double safe_log(double v) {
  return v > 0 ? std::log(v) : -std::numeric_limits<double>::infinity();
}

std::vector<Xyz> logs_of(const std::vector<Xyz>& nodes) {
  std::vector<Xyz> logs(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    logs[i] = {safe_log(nodes[i].x), safe_log(nodes[i].y), safe_log(nodes[i].z)};
  return logs;
}

double component(const Xyz& c, int n) {
  return n == 0 ? c.x : n == 1 ? c.y : c.z;
}

}  // namespace

DopplerGrid DopplerGrid::covering(double max_abs_log_d) {
  DopplerGrid g;
  const double r = std::isfinite(max_abs_log_d) ? std::abs(max_abs_log_d) : 0.0;
  g.half_count = static_cast<int>(std::ceil(r / kStep)) + 2;
  return g;
}

GridStencil grid_stencil(const DopplerGrid& grid, double d) {
  // The grid covers every factor the scene can produce (with two spare nodes); a factor that
  // rounding puts past the last interval is extrapolated by that interval's cubic.
  const double t = std::log(d) / DopplerGrid::kStep + grid.half_count;
  const double floor_t = std::floor(t);
  GridStencil s;
  s.first = std::clamp(static_cast<int>(floor_t) - 1, 0, grid.size() - 4);
  const double f = t - (s.first + 1);
  s.fraction = f;
  // Lagrange's cubic through the four nodes at -1, 0, 1, 2 (fourth-order accurate).
  s.weights[0] = -f * (f - 1) * (f - 2) / 6;
  s.weights[1] = (f + 1) * (f - 1) * (f - 2) / 2;
  s.weights[2] = -(f + 1) * f * (f - 2) / 2;
  s.weights[3] = (f + 1) * f * (f - 1) / 6;
  return s;
}

double log_cubic(const double values[4], const double logs[4], const GridStencil& stencil) {
  if (values[0] > 0 && values[1] > 0 && values[2] > 0 && values[3] > 0) {
    double l = 0;
    for (int k = 0; k < 4; ++k) l += stencil.weights[k] * logs[k];
    return std::exp(l);
  }
  const double f = std::clamp(stencil.fraction, 0.0, 1.0);
  return values[1] + f * (values[2] - values[1]);
}

DopplerXyzTable::DopplerXyzTable(const DopplerGrid& grid, std::vector<Xyz> nodes)
    : grid_(grid), nodes_(std::move(nodes)), logs_(logs_of(nodes_)) {}

Xyz DopplerXyzTable::operator()(const GridStencil& s) const {
  double out[3];
  for (int n = 0; n < 3; ++n) {
    double values[4], logs[4];
    for (int k = 0; k < 4; ++k) {
      values[k] = component(nodes_[s.first + k], n);
      logs[k] = component(logs_[s.first + k], n);
    }
    out[n] = log_cubic(values, logs, s);
  }
  return {out[0], out[1], out[2]};
}

Xyz ReflectionXyzTable::reflected_sum(const double* reflectance, const double* source) {
  return xyz_from_spectrum([&](double lambda) {
    const auto i = static_cast<int>(lambda - kCieMinWavelength);
    return reflectance[i] * source[i];
  });
}

ReflectionXyzTable::ReflectionXyzTable(const DopplerGrid& camera, const DopplerGrid& light,
                                       std::vector<Xyz> nodes)
    : camera_(camera), light_(light), nodes_(std::move(nodes)), logs_(logs_of(nodes_)) {}

Xyz ReflectionXyzTable::operator()(const GridStencil& camera, double d_light) const {
  const GridStencil light = grid_stencil(light_, d_light);
  const std::size_t row = light_.size();
  double out[3];
  for (int n = 0; n < 3; ++n) {
    // Bicubic in the logarithms where all sixteen nodes are positive, else bilinear.
    double log_sum = 0;
    bool positive = true;
    for (int c = 0; c < 4; ++c)
      for (int l = 0; l < 4; ++l) {
        const std::size_t index = (camera.first + c) * row + light.first + l;
        positive = positive && component(nodes_[index], n) > 0;
        log_sum += camera.weights[c] * light.weights[l] * component(logs_[index], n);
      }
    if (positive) {
      out[n] = std::exp(log_sum);
      continue;
    }
    const double fc = std::clamp(camera.fraction, 0.0, 1.0);
    const double fl = std::clamp(light.fraction, 0.0, 1.0);
    const auto at = [&](int c, int l) {
      return component(nodes_[(camera.first + c) * row + light.first + l], n);
    };
    out[n] = (1 - fc) * ((1 - fl) * at(1, 1) + fl * at(1, 2)) +
             fc * ((1 - fl) * at(2, 1) + fl * at(2, 2));
  }
  return {out[0], out[1], out[2]};
}

}  // namespace lightcone

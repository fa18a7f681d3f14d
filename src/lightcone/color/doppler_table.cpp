#include "lightcone/color/doppler_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

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

// Within this ratio across four nodes (an exponential rising by 2^(1/3) a step) the error of
// the cubic in the values is below 7e-5 of the value, the same order as the cubic in the
// logarithms, and it needs no exp.
constexpr double kValuesRatio = 2.0;

double component(const Xyz& c, int n) {
  return n == 0 ? c.x : n == 1 ? c.y : c.z;
}

// A settled grid's promise (DopplerGrid), checked where it costs nothing: the table is constant
// from node 1 down, so nodes 0 and 1 (of every row `stride` apart) are equal.
void check_settled(const DopplerGrid& grid, const std::vector<Xyz>& nodes, std::size_t stride) {
  if (!grid.settled) return;
  for (std::size_t i = 0; i < stride; ++i)
    if (nodes[i].x != nodes[stride + i].x || nodes[i].y != nodes[stride + i].y ||
        nodes[i].z != nodes[stride + i].z)
      throw std::logic_error(
          "a colour table on a settled grid is not constant below it: its spectrum is not "
          "constant where the grid was told it is");
}

}  // namespace

DopplerGrid DopplerGrid::covering(double lo_log_d, double hi_log_d) {
  // (A range of ln D wider than this, a factor of 10^130, is no bound anything rendered needs.)
  constexpr double kWidest = 300;
  if (!(std::abs(lo_log_d) <= kWidest && std::abs(hi_log_d) <= kWidest))
    throw std::invalid_argument("a colour table was asked to cover ln D from " +
                                std::to_string(lo_log_d) + " to " + std::to_string(hi_log_d) +
                                ": a range of Doppler factors must be finite");
  if (lo_log_d > hi_log_d) std::swap(lo_log_d, hi_log_d);
  DopplerGrid g;
  g.first = static_cast<int>(std::floor(lo_log_d / kStep)) - 2;
  g.last = static_cast<int>(std::ceil(hi_log_d / kStep)) + 2;
  return g;
}

DopplerGrid DopplerGrid::reaching(double lo_log_d, double hi_log_d, double constant_below) {
  // The largest D at which the quadrature samples the spectrum only where it is constant (all
  // of it below hi, where it is constant over the whole range).
  const double limit = std::min(std::log(constant_below / kCieMaxWavelength), hi_log_d);
  if (!(lo_log_d > limit) && std::isfinite(limit)) {
    // Node 1 lies a step or more below the limit: a margin far above the rounding of D lambda.
    DopplerGrid g = covering(limit, hi_log_d);
    g.settled = true;
    return g;
  }
  return covering(lo_log_d, hi_log_d);
}

GridPosition grid_position_outside(const DopplerGrid& grid, double d) {
  if (grid.settled && grid_log(d) < grid.log_d(1)) return {0, 0.0};
  std::ostringstream message;
  message << "a colour table covering D from "
          << (grid.settled ? 0.0 : std::exp(grid.lowest_log_d())) << " to "
          << std::exp(grid.highest_log_d()) << " was asked for D = " << d
          << ": the range it was built for missed a factor the picture shows";
  throw std::out_of_range(message.str());
}

GridStencil grid_stencil(const DopplerGrid& grid, double d) {
  GridStencil s;
  s.position = grid_position(grid, d);
  const double f = s.position.fraction;
  const double fm1 = f - 1, fm2 = f - 2, fp1 = f + 1;
  const double a = f * fm1, b = fp1 * fm2;
  s.weights[0] = -(1.0 / 6) * a * fm2;
  s.weights[1] = 0.5 * b * fm1;
  s.weights[2] = -0.5 * b * f;
  s.weights[3] = (1.0 / 6) * a * fp1;
  return s;
}

DopplerXyzTable::DopplerXyzTable(const DopplerGrid& grid, std::vector<Xyz> nodes)
    : grid_(grid), nodes_(std::move(nodes)) {
  check_settled(grid_, nodes_, 1);
  // Lagrange's cubic through (-1, u0), (0, u1), (1, u2), (2, u3), less u1, is
  // f (c1 + f (c2 + f c3)) with these c from the differences d_k = u_k - u1 (u the values
  // or their logarithms).
  const auto cubic = [](double d0, double d2, double d3, double& c1, double& c2, double& c3) {
    c1 = -d0 / 3 + d2 - d3 / 6;
    c2 = (d0 + d2) / 2;
    c3 = (-d0 + d3) / 6 - d2 / 2;
  };
  const int n = static_cast<int>(nodes_.size());
  intervals_.resize(nodes_.size());
  for (int i = 1; i + 2 < n; ++i) {
    Interval& in = intervals_[i];
    in.all_values = true;
    for (int k = 0; k < 3; ++k) {
      double v[4];
      for (int j = 0; j < 4; ++j) v[j] = component(nodes_[i - 1 + j], k);
      const double lo = std::min({v[0], v[1], v[2], v[3]});
      const double hi = std::max({v[0], v[1], v[2], v[3]});
      in.value[k] = v[1];
      if (lo > 0 && hi <= kValuesRatio * lo) {
        in.mode[k] = Interval::kValues;
        cubic(v[0] - v[1], v[2] - v[1], v[3] - v[1], in.c1[k], in.c2[k], in.c3[k]);
      } else if (lo > 0) {
        in.mode[k] = Interval::kLogarithms;
        const double l1 = std::log(v[1]);
        cubic(std::log(v[0]) - l1, std::log(v[2]) - l1, std::log(v[3]) - l1, in.c1[k], in.c2[k],
              in.c3[k]);
      } else {
        in.mode[k] = Interval::kLinear;
        in.c1[k] = v[2] - v[1];
      }
      in.all_values = in.all_values && in.mode[k] == Interval::kValues;
    }
    if (in.all_values)
      for (double* c : {in.value, in.c1, in.c2, in.c3}) {
        const LinearRgb rgb = linear_srgb_from_xyz({c[0], c[1], c[2]});
        c[0] = rgb.r, c[1] = rgb.g, c[2] = rgb.b;
      }
  }
}

Xyz ReflectionXyzTable::reflected_sum(const double* reflectance, const double* source) {
  return xyz_from_spectrum([&](double lambda) {
    const auto i = static_cast<int>(lambda - kCieMinWavelength);
    return reflectance[i] * source[i];
  });
}

ReflectionXyzTable::ReflectionXyzTable(const DopplerGrid& camera, const DopplerGrid& light,
                                       std::vector<Xyz> nodes)
    : camera_(camera), light_(light), nodes_(std::move(nodes)), logs_(logs_of(nodes_)) {
  check_settled(camera_, nodes_, static_cast<std::size_t>(light_.size()));
}

Xyz ReflectionXyzTable::operator()(const GridStencil& camera_stencil, double d_light) const {
  const GridStencil light_stencil = grid_stencil(light_, d_light);
  const GridPosition& camera = camera_stencil.position;
  const GridPosition& light = light_stencil.position;
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
        log_sum +=
            camera_stencil.weights[c] * light_stencil.weights[l] * component(logs_[index], n);
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

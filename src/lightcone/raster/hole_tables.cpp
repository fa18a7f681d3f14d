#include "lightcone/raster/hole_tables.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "lightcone/physics/accretion_disk.hpp"
#include "lightcone/physics/schwarzschild.hpp"
#include "lightcone/portable.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// How close to the shadow's edge and to the radial rays the rows reach: 1e-7 rad (a thousandth
// of a pixel at 1920 x 1080 and 22 degrees; single precision resolves alpha to about 2e-7 there),
// or less on a side narrower than 1e-4 rad.
double reach(double side_width) {
  return std::min(1e-7, 1e-3 * side_width);
}

// du/dphi for u = M/r on the orbit of impact parameter b: (du/dphi)^2 = (M/b)^2 - u^2 (1 - 2u).
double slope(double mass, double impact, double u) {
  const double m_b = mass / impact;
  return std::sqrt(std::max(0.0, m_b * m_b - u * u * (1 - 2 * u)));
}

double u_of(double mass, double r) {
  return std::isinf(r) ? 0.0 : mass / r;
}

// One row: the ray at alpha (sin, cos) followed by the kernel.
void fill_row(const HoleRayTables& t, const AccretionDisk* disk, double sin_alpha, double cos_alpha,
              float* row) {
  const double m = t.mass, r0 = t.camera_radius;
  const double impact = static_impact_parameter(m, r0, sin_alpha);
  const PhotonOrbit orbit = photon_orbit(m, impact);
  const bool outward = cos_alpha > 0;
  const AngleSweep sweep = prepare_sweep(orbit, r0, outward);
  row[0] = static_cast<float>(sweep.angle_total);
  row[1] = row[2] = row[3] = 0;
  if (!disk) return;
  const RayCourse course = ray_course(orbit, r0, outward);
  const bool escapes = course.fate == RayFate::kEscapes;
  const double stop = t.stop_radius;
  // The legs' lengths. A ray that stays outside r_stop is one leg, its whole path; one that
  // passes inside (winding round the photon sphere when near the edge) has a leg from the camera
  // to r_stop and one from r_stop to infinity, and nothing is asked of it in between.
  double l_in = 0, l_out = 0;
  if (escapes && (outward || course.turning_radius >= stop)) {
    l_in = l_out = sweep.angle_total;
  } else if (escapes) {
    if (!outward && r0 > stop) l_in = swept_angle(orbit, r0, stop);
    l_out = swept_angle(orbit, stop, kInf);
  } else if (!outward && r0 > stop) {
    l_in = swept_angle(orbit, r0, stop);
  }
  row[1] = static_cast<float>(l_in);
  row[2] = static_cast<float>(l_out);
  row[3] = escapes && l_in == l_out ? 1.0f : 0.0f;  // one leg, the whole path
  // Each leg's nodes (u, du/dphi), stored in pairs: texel j of a leg holds nodes j and j + 1.
  const int n = t.nodes;
  const bool turns = course.turning_radius > 0;
  std::vector<double> u(n), du(n);
  const auto store = [&](float* leg) {
    for (int j = 0; j + 1 < n; ++j) {
      float* texel = leg + 4 * j;
      texel[0] = static_cast<float>(u[j]);
      texel[1] = static_cast<float>(du[j]);
      texel[2] = static_cast<float>(u[j + 1]);
      texel[3] = static_cast<float>(du[j + 1]);
    }
  };
  for (int j = 0; j < n; ++j) {
    const double phi = l_in * j / (n - 1);
    u[j] = u_of(m, radius_after_angle(sweep, phi));
    // u grows while the ray goes inward: at first unless it starts outward, and the other way
    // after its turning point.
    const bool inward = !outward != (turns && phi > course.angle_to_turn);
    du[j] = (inward ? 1 : -1) * slope(m, impact, u[j]);
  }
  store(row + 4);
  std::fill(u.begin(), u.end(), 0.0);
  std::fill(du.begin(), du.end(), 0.0);
  if (l_out > 0) {
    // The out-leg: the same path swept from infinity (inward there, up to its turning point,
    // and on to the camera for a whole path).
    const AngleSweep from_far = prepare_sweep(orbit, kInf, false);
    const double psi_turn = course.angle_total - course.angle_to_turn;
    for (int j = 0; j < n; ++j) {
      const double psi = l_out * j / (n - 1);
      u[j] = u_of(m, radius_after_angle(from_far, psi));
      du[j] = (turns && psi > psi_turn ? -1 : 1) * slope(m, impact, u[j]);
    }
  }
  store(row + 4 * n);
}

// The logistic function and its complement, e^x / (1 + e^x) and 1 / (1 + e^x).
double logistic(double x) {
  return x >= 0 ? 1 / (1 + std::exp(-x)) : std::exp(x) / (1 + std::exp(x));
}

// Cubic Hermite on one leg of one row (its first texel `leg`): `nodes` nodes (u, du/dphi) over
// [0, length], phi clamped to it.
double hermite(const float* leg, int nodes, double length, double phi) {
  if (!(length > 0)) return leg[0];
  const double p = std::clamp(phi / length, 0.0, 1.0) * (nodes - 1);
  const int j = std::min(static_cast<int>(p), nodes - 2);
  const double s = p - j, h = length / (nodes - 1);
  const float* a = leg + 4 * j;
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * a[0] + (s3 - 2 * s2 + s) * h * a[1] + (3 * s2 - 2 * s3) * a[2] +
         (s3 - s2) * h * a[3];
}

const float* row_texels(const HoleRayTables& t, int side, int row) {
  return &t.texels[4 * static_cast<std::size_t>(t.width) * (side * t.rows + row)];
}

// u = M/r on one row after sweeping phi, with psi = (the pixel's total) - phi still to sweep: the
// in-leg at phi, or (use_out) the out-leg at psi.
double row_u(const HoleRayTables& t, int side, int row, double phi, double psi, bool use_out) {
  const float* r = row_texels(t, side, row);
  const double length = use_out ? r[2] : r[1], at = use_out ? psi : phi;
  const bool whole = r[3] != 0;
  if (use_out ? !(psi > 0) : (whole && phi > length)) return 0;  // escaped
  if (at > length && !whole) return t.mass / t.stop_radius;      // inside r_stop
  // On a whole path, psi past its length is before the camera: its start.
  return hermite(r + 4 * (use_out ? t.nodes : 1), t.nodes, length, at);
}

}  // namespace

HoleRayTables hole_ray_tables(const HoleView& hole, int rows, int nodes) {
  HoleRayTables t;
  t.mass = hole.mass;
  t.camera_radius = hole.camera_radius;
  if (tables_from_inside(hole)) {
    t.inside_radius = hole.camera_radius;
    t.camera_radius = HoleRayTables::kInnerRadius * hole.mass;
    const int n = HoleRayTables::kInnerNodes;
    t.inner_angle.resize(n);
    const double bc = critical_impact_parameter(hole.mass);
    parallel_for(0, n, [&](int j) {
      // (The last node a hair below b_c, where the closed form's pair of roots meets.)
      const double b = bc * std::min(static_cast<double>(j) / (n - 1), 1 - 1e-12);
      t.inner_angle[j] = static_cast<float>(
          swept_angle(photon_orbit(hole.mass, b), t.inside_radius, t.camera_radius));
    });
  }
  t.critical_alpha = kPi - static_shadow_angle(hole.mass, t.camera_radius);
  t.side_width[0] = t.critical_alpha;
  t.side_width[1] = kPi - t.critical_alpha;
  t.rows = std::max(rows, 2);
  const AccretionDisk* disk = hole.disk ? &*hole.disk : nullptr;
  t.nodes = disk ? std::max(nodes, 2) : 0;
  t.width = disk ? 2 * t.nodes - 1 : 1;
  if (disk) t.stop_radius = (3 * hole.mass + disk->inner) / 2;
  for (int side = 0; side < 2; ++side) {
    const double d = t.side_width[side], e = reach(d);
    t.x_first[side] = std::log(e / (d - e));
    t.x_step[side] = (std::log((d - e) / e) - t.x_first[side]) / (t.rows - 1);
  }
  t.texels.resize(4 * static_cast<std::size_t>(t.width) * 2 * t.rows);
  parallel_for(0, 2 * t.rows, [&](int k) {
    const int side = k / t.rows, i = k % t.rows;
    // The row's angle from its side's far end: alpha on the escape side, pi - alpha on the other.
    const double far = t.side_width[side] * logistic(-(t.x_first[side] + i * t.x_step[side]));
    const double cos_far = std::cos(far);
    fill_row(t, disk, std::sin(far), side == 0 ? cos_far : -cos_far,
             &t.texels[4 * static_cast<std::size_t>(t.width) * k]);
  });
  if (disk) {
    const int n = HoleRayTables::kTemperatureNodes;
    t.log_inner = std::log(disk->inner);
    t.log_step = (std::log(disk->outer) - t.log_inner) / (n - 1);
    t.temperature.resize(n);
    for (int j = 0; j < n; ++j) {
      const double tau = disk_temperature_ratio(hole.mass, std::exp(t.log_inner + j * t.log_step));
      t.temperature[j] = static_cast<float>(tau * tau);
    }
  }
  return t;
}

HoleRowPosition hole_row_position(const HoleRayTables& t, double sin_alpha, double cos_alpha) {
  // alpha and pi - alpha, each to its own relative precision; delta (from alpha_c) from whichever
  // of them is the smaller near alpha_c.
  const double alpha = std::atan2(sin_alpha, cos_alpha);
  const double beta = std::atan2(sin_alpha, -cos_alpha);
  HoleRowPosition at;
  double delta = 0;
  if (t.critical_alpha > kPi / 2) {
    at.side = beta > t.side_width[1] ? 0 : 1;
    delta = std::abs(beta - t.side_width[1]);
  } else {
    at.side = alpha < t.critical_alpha ? 0 : 1;
    delta = std::abs(alpha - t.critical_alpha);
  }
  const double far = at.side == 0 ? alpha : beta;
  const double x = std::log(std::max(delta, 1e-30)) - std::log(far);
  at.p = (x - t.x_first[at.side]) / t.x_step[at.side];
  if (!(at.p < t.rows - 1)) at.p = t.rows - 1;  // the radial rays' end (or alpha exactly on it)
  return at;
}

HoleRowWeights hole_row_weights(const HoleRayTables& t, double p) {
  HoleRowWeights w;
  if (p <= 0) {  // linear, extrapolated before the first row
    w.w[0] = 1 - p;
    w.w[1] = p;
    return w;
  }
  // Cubic through four rows (Lagrange), the interval between the middle two where there are.
  w.first = std::clamp(static_cast<int>(std::floor(p)) - 1, 0, t.rows - 4);
  const double s = p - w.first;
  w.w[0] = -(s - 1) * (s - 2) * (s - 3) / 6;
  w.w[1] = s * (s - 2) * (s - 3) / 2;
  w.w[2] = -s * (s - 1) * (s - 3) / 2;
  w.w[3] = s * (s - 1) * (s - 2) / 6;
  return w;
}

double tabulated_total_angle(const HoleRayTables& t, const HoleRowPosition& at) {
  const HoleRowWeights w = hole_row_weights(t, at.p);
  double total = 0;
  for (int k = 0; k < 4; ++k)
    if (w.w[k] != 0) total += w.w[k] * row_texels(t, at.side, w.first + k)[0];
  return total;
}

double tabulated_radius(const HoleRayTables& t, const HoleRowPosition& at, double phi) {
  const double total = tabulated_total_angle(t, at);
  // From the nearer end: the in-legs at phi, the out-legs at the angle still to sweep.
  const bool use_out = at.side == 0 && phi > total / 2;
  const HoleRowWeights w = hole_row_weights(t, std::max(at.p, 0.0));
  double u = 0;
  for (int k = 0; k < 4; ++k)
    if (w.w[k] != 0) u += w.w[k] * row_u(t, at.side, w.first + k, phi, total - phi, use_out);
  return u > 0 ? t.mass / u : kInf;
}

bool tables_from_inside(const HoleView& hole) {
  return hole.falling && !(hole.camera_radius > 2 * hole.mass);
}

double tabulated_inner_angle(const HoleRayTables& t, double impact) {
  const int n = static_cast<int>(t.inner_angle.size());
  const double p = std::clamp(impact / critical_impact_parameter(t.mass) * (n - 1), 0.0, n - 1.0);
  const int j = std::min(static_cast<int>(p), n - 2);
  return t.inner_angle[j] + (t.inner_angle[j + 1] - t.inner_angle[j]) * (p - j);
}

double tabulated_temperature_ratio(const HoleRayTables& t, double r) {
  const int n = static_cast<int>(t.temperature.size());
  const double p = std::clamp((std::log(r) - t.log_inner) / t.log_step, 0.0, n - 1.0);
  const int j = std::min(static_cast<int>(p), n - 2);
  const double q = t.temperature[j] + (t.temperature[j + 1] - t.temperature[j]) * (p - j);
  return std::sqrt(std::max(q, 0.0));
}

}  // namespace lightcone

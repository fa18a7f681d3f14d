#include "lightcone/physics/lorentz.hpp"

#include <algorithm>
#include <cmath>

namespace lightcone {

double lorentz_gamma(const Vec3& beta) {
  return 1.0 / std::sqrt(1.0 - dot(beta, beta));
}

Mat4 Mat4::operator*(const Mat4& o) const {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += m[i][k] * o.m[k][j];
      r.m[i][j] = s;
    }
  return r;
}

Mat3 Mat4::spatial() const {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = m[i + 1][j + 1];
  return r;
}

double rapidity(const Vec3& beta) {
  return std::atanh(std::min(length(beta), 1.0));
}

double relative_rapidity(const Vec3& a, const Vec3& b) {
  const double g = lorentz_gamma(a) * lorentz_gamma(b) * (1 - dot(a, b));
  return g > 1 ? std::acosh(g) : 0.0;
}

Mat4 boost(const Vec3& beta) {
  const double b2 = dot(beta, beta);
  Mat4 r;
  if (b2 == 0) return r;
  const double g = lorentz_gamma(beta);
  // (g - 1)/b^2 written as g^2/(g + 1) avoids cancellation for small beta.
  const double k = g * g / (g + 1.0);
  r.m[0][0] = g;
  for (int i = 0; i < 3; ++i) {
    r.m[0][i + 1] = -g * beta[i];
    r.m[i + 1][0] = -g * beta[i];
    for (int j = 0; j < 3; ++j) r.m[i + 1][j + 1] = (i == j ? 1.0 : 0.0) + k * beta[i] * beta[j];
  }
  return r;
}

Mat4 spatial_rotation(const Mat3& rotation) {
  Mat4 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i + 1][j + 1] = rotation.m[i][j];
  return r;
}

Mat4 galilean(const Vec3& beta) {
  Mat4 r;
  for (int i = 0; i < 3; ++i) r.m[i + 1][0] = -beta[i];
  return r;
}

Mat4 lorentz_inverse(const Mat4& l) {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const double sign = ((i == 0) == (j == 0)) ? 1.0 : -1.0;
      r.m[i][j] = sign * l.m[j][i];
    }
  return r;
}

Mat4 inverse(const Mat4& a) {
  // Gauss-Jordan with partial pivoting; 4x4 so cost is irrelevant.
  std::array<std::array<double, 8>, 4> w{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      w[i][j] = a.m[i][j];
      w[i][j + 4] = (i == j) ? 1.0 : 0.0;
    }
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(w[r][c]) > std::abs(w[p][c])) p = r;
    std::swap(w[c], w[p]);
    const double inv = 1.0 / w[c][c];
    for (double& v : w[c]) v *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double f = w[r][c];
      for (int j = 0; j < 8; ++j) w[r][j] -= f * w[c][j];
    }
  }
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = w[i][j + 4];
  return r;
}

BoostRotation decompose_lorentz(const Mat4& l) {
  // The new frame's origin (x' = 0) moves along the first column of L^-1.
  const Mat4 inv = lorentz_inverse(l);
  const Vec3 beta = Vec3{inv.m[1][0], inv.m[2][0], inv.m[3][0]} / inv.m[0][0];
  const Mat4 rot4 = l * lorentz_inverse(boost(beta));
  return {beta, rot4.spatial()};
}

Vec3 velocity_addition(const Vec3& beta_a, const Vec3& beta_b) {
  // Boost the body's 4-velocity out of frame A back into the original frame.
  const Vec4 u_in_a{lorentz_gamma(beta_b), lorentz_gamma(beta_b) * beta_b};
  return velocity_of(boost(-beta_a) * u_in_a);
}

AffineMap4 rest_frame_map(const Vec4& event, const Vec3& beta) {
  const Mat4 l = boost(beta);
  return {l, -1.0 * (l * event)};
}

Vec3 contracted_offset(const Vec3& rest_offset, const Vec3& beta) {
  const double b2 = dot(beta, beta);
  if (b2 == 0) return rest_offset;
  return rest_offset - beta * ((1 - 1 / lorentz_gamma(beta)) * dot(beta, rest_offset) / b2);
}

Vec3 rest_offset_of(const Vec3& offset, const Vec3& beta) {
  const double b2 = dot(beta, beta);
  if (b2 == 0) return offset;
  return offset + beta * ((lorentz_gamma(beta) - 1) * dot(beta, offset) / b2);
}

}  // namespace lightcone

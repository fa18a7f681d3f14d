#include "lightcone/physics/vec.hpp"

namespace lightcone {

Mat3 Mat3::rotation(const Vec3& axis, double radians) {
  const Vec3 a = normalize(axis);
  const double c = std::cos(radians), s = std::sin(radians), k = 1 - c;
  Mat3 r;
  r.m = {{{c + a.x * a.x * k, a.x * a.y * k - a.z * s, a.x * a.z * k + a.y * s},
          {a.y * a.x * k + a.z * s, c + a.y * a.y * k, a.y * a.z * k - a.x * s},
          {a.z * a.x * k - a.y * s, a.z * a.y * k + a.x * s, c + a.z * a.z * k}}};
  return r;
}

Mat3 Mat3::operator*(const Mat3& o) const {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[i][j] = m[i][0] * o.m[0][j] + m[i][1] * o.m[1][j] + m[i][2] * o.m[2][j];
  return r;
}

Mat3 Mat3::transposed() const {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = m[j][i];
  return r;
}

double Mat3::determinant() const {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Mat3 Mat3::inverse() const {
  const double inv_det = 1.0 / determinant();
  Mat3 r;
  r.m = {{{(m[1][1] * m[2][2] - m[1][2] * m[2][1]) * inv_det,
           (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv_det,
           (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv_det},
          {(m[1][2] * m[2][0] - m[1][0] * m[2][2]) * inv_det,
           (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv_det,
           (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv_det},
          {(m[1][0] * m[2][1] - m[1][1] * m[2][0]) * inv_det,
           (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv_det,
           (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv_det}}};
  return r;
}

}  // namespace lightcone

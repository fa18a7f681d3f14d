// Small value types for 3-vectors, 3x3 matrices and 4-vectors (t, x) in double precision.
#pragma once

#include <array>
#include <cmath>

namespace lightcone {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  constexpr Vec3& operator-=(const Vec3& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  constexpr Vec3& operator*=(double s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
};

constexpr Vec3 operator+(Vec3 a, const Vec3& b) {
  return a += b;
}
constexpr Vec3 operator-(Vec3 a, const Vec3& b) {
  return a -= b;
}
constexpr Vec3 operator*(Vec3 a, double s) {
  return a *= s;
}
constexpr Vec3 operator*(double s, Vec3 a) {
  return a *= s;
}
constexpr Vec3 operator/(const Vec3& a, double s) {
  return {a.x / s, a.y / s, a.z / s};
}
constexpr bool operator==(const Vec3& a, const Vec3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
constexpr double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3& a) {
  return std::sqrt(dot(a, a));
}
inline Vec3 normalize(const Vec3& a) {
  return a / length(a);
}

// A unit vector perpendicular to the unit vector n.
inline Vec3 any_perpendicular(const Vec3& n) {
  const Vec3 other = std::abs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return normalize(cross(n, other));
}
inline Vec3 component_mul(const Vec3& a, const Vec3& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
inline Vec3 component_div(const Vec3& a, const Vec3& b) {
  return {a.x / b.x, a.y / b.y, a.z / b.z};
}

// v turned by `radians` about the unit `axis`, right-handed (Rodrigues; the same as
// Mat3::rotation(axis, radians) * v without building the matrix).
inline Vec3 rotated(const Vec3& axis, double radians, const Vec3& v) {
  const double c = std::cos(radians), s = std::sin(radians);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1 - c));
}

// Row-major 3x3 matrix.
struct Mat3 {
  std::array<std::array<double, 3>, 3> m{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

  static Mat3 identity() { return {}; }
  static Mat3 diagonal(const Vec3& d) {
    Mat3 r;
    r.m = {{{d.x, 0, 0}, {0, d.y, 0}, {0, 0, d.z}}};
    return r;
  }
  // Right-handed rotation by `radians` about `axis` (need not be unit length).
  static Mat3 rotation(const Vec3& axis, double radians);

  Vec3 operator*(const Vec3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  Mat3 operator*(const Mat3& o) const;
  Mat3 transposed() const;
  Mat3 inverse() const;
  double determinant() const;
};

// A 4-vector or event: time component t and spatial part x (c = 1).
struct Vec4 {
  double t = 0;
  Vec3 x;
};

constexpr Vec4 operator+(const Vec4& a, const Vec4& b) {
  return {a.t + b.t, a.x + b.x};
}
constexpr Vec4 operator-(const Vec4& a, const Vec4& b) {
  return {a.t - b.t, a.x - b.x};
}
constexpr Vec4 operator*(double s, const Vec4& a) {
  return {s * a.t, s * a.x};
}
// Minkowski product with signature (+, -, -, -).
constexpr double minkowski_dot(const Vec4& a, const Vec4& b) {
  return a.t * b.t - dot(a.x, b.x);
}

}  // namespace lightcone

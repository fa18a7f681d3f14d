// Linear maps of events: Lorentz boosts, rotations, their composition, and the Galilean map
// used for the classical (non-relativistic) picture.
#pragma once

#include <array>

#include "lightcone/physics/vec.hpp"

namespace lightcone {

// gamma = 1 / sqrt(1 - beta.beta); requires |beta| < 1.
double lorentz_gamma(const Vec3& beta);

// Rapidity atanh(|beta|): the largest |ln D| of any Doppler factor between a body moving with
// beta and a receiver at rest (D ranges over [e^-r, e^r] with the direction).
double rapidity(const Vec3& beta);

// The rapidity of the relative motion of two bodies with velocities a and b in one frame:
// acosh(gamma_a gamma_b (1 - a.b)), the same in every frame.
double relative_rapidity(const Vec3& a, const Vec3& b);

// A 4x4 matrix acting on (t, x, y, z); index 0 is time. Row-major.
struct Mat4 {
  std::array<std::array<double, 4>, 4> m{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};

  static Mat4 identity() { return {}; }
  Vec4 operator*(const Vec4& v) const {
    const double in[4] = {v.t, v.x.x, v.x.y, v.x.z};
    double out[4];
    for (int i = 0; i < 4; ++i)
      out[i] = m[i][0] * in[0] + m[i][1] * in[1] + m[i][2] * in[2] + m[i][3] * in[3];
    return {out[0], {out[1], out[2], out[3]}};
  }
  Mat4 operator*(const Mat4& o) const;
  // The spatial 3x3 block.
  Mat3 spatial() const;
};

// Coordinates of an event in a frame moving with velocity beta relative to the current frame
// (origins coincide). This is PHYSICS.md's boost: x' = x + [(g-1)/b^2 (b.x) - g t] b,
// t' = g (t - b.x).
Mat4 boost(const Vec3& beta);

// A purely spatial rotation acting on the spatial part (time untouched).
Mat4 spatial_rotation(const Mat3& rotation);

// The Galilean map to a frame moving with beta: x' = x - beta t, t' = t.
Mat4 galilean(const Vec3& beta);

// Inverse of a Lorentz matrix: eta L^T eta (exact, no numerical inversion).
Mat4 lorentz_inverse(const Mat4& lorentz);

// Inverse of a Galilean map composed with rotations: general 4x4 inverse.
Mat4 inverse(const Mat4& m);

// A proper orthochronous Lorentz matrix written as rotation * boost(beta): `beta` is the velocity
// of the new frame in the old one, `rotation` the Wigner (Thomas) rotation left over.
struct BoostRotation {
  Vec3 beta;
  Mat3 rotation;
};
BoostRotation decompose_lorentz(const Mat4& lorentz);

// Relativistic composition: velocity, measured in the original frame, of a body that moves with
// `beta_b` in a frame that itself moves with `beta_a` (both pure boosts). Exact formula.
Vec3 velocity_addition(const Vec3& beta_a, const Vec3& beta_b);

// The 4-velocity (gamma, gamma beta) of velocity `beta` (|beta| < 1).
inline Vec4 four_velocity(const Vec3& beta) {
  const double gamma = lorentz_gamma(beta);
  return {gamma, beta * gamma};
}

// Velocity in the current frame of a world-line whose tangent 4-vector is u (u.t > 0).
inline Vec3 velocity_of(const Vec4& u) {
  return u.x / u.t;
}

// Lorentz contraction of a body's extent: where the point at `rest_offset` from its origin (in
// its rest frame, axes parallel to the frame's) lies relative to the origin at one instant of a
// frame in which the body moves with beta: shortened by 1 / gamma along beta, unchanged across.
Vec3 contracted_offset(const Vec3& rest_offset, const Vec3& beta);
// Its inverse: the rest-frame offset of a point seen at `offset` from the origin at one instant.
Vec3 rest_offset_of(const Vec3& offset, const Vec3& beta);

// An affine map of events: e' = linear * e + offset.
struct AffineMap4 {
  Mat4 linear;
  Vec4 offset;
  Vec4 operator()(const Vec4& e) const { return linear * e + offset; }
};

// Coordinates in the rest frame of a body on the inertial world-line through `event` with
// velocity beta (its rest frame is the pure boost; `event` becomes the origin).
AffineMap4 rest_frame_map(const Vec4& event, const Vec3& beta);

}  // namespace lightcone

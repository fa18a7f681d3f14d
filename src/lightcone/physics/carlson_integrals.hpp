// Carlson's symmetric elliptic integrals R_F, R_D, R_J and R_C in double precision (Boost.Math),
// and Carlson's reductions of the integrals of 1 / sqrt(cubic) to them, in the forms the
// Schwarzschild geodesics need (physics/schwarzschild.cpp): a cubic of three real linear factors
// (Carlson 1989, "A table of elliptic integrals: cubic cases"), and one of a linear factor and a
// quadratic without real roots (Carlson 1991, "A table of elliptic integrals: one quadratic
// factor"). Every term of a reduction is positive where the factors are, so nothing cancels,
// and a factor that vanishes at a limit (a turning point) is fine.
#pragma once

#include <cmath>

namespace lightcone::carlson {

// Boost's R_F, R_D, R_J and R_C in double precision, without exceptions (math_policy.hpp): NaN
// for a NaN argument or one outside their domain, 0 (their limit) for an infinite one. R_J is
// Boost's duplication with the small R_C terms of its steps summed as a series (within a few
// ulps of Boost's, without an arctangent or logarithm for each).
double rf(double x, double y, double z);
double rd(double x, double y, double z);
double rj(double x, double y, double z, double p);
// The same given R_F(x, y, z), which R_J's Cauchy principal value for p < 0 takes (DLMF 19.20.14),
// where the caller has it already.
double rj(double x, double y, double z, double p, double rf_xyz);
double rc(double x, double y);

// Up to kMaxBatch of R_F at once, equal to rf's to the bit: run side by side, two to a vector,
// the independent chains of square roots overlap instead of waiting on each other (a few camera
// rays' integrals together).
struct RfArgs {
  double x, y, z;
};
inline constexpr int kMaxBatch = 32;
void rf_batch(const RfArgs* args, double* out, int n);

// Three real linear factors L_i = a_i + b_i t, positive between the limits: their values at one
// limit, and their square roots there.
struct LinearFactors {
  double f1, f2, f3;
};
struct FactorRoots {
  double s1, s2, s3;
};

// int_y^x dt / sqrt(L1 L2 L3) = 2 R_F(U12^2, U13^2, U23^2) (Carlson 1989; DLMF 19.29(i)), with
// U12 = (X1 X2 Y3 + Y1 Y2 X3) / d and so on, X_i, Y_i the factors' square roots at the limits and
// d = |x - y| > 0. cubic_args gives R_F's arguments (symmetric in the two limits), so that several
// integrals can share rf_batch.
inline FactorRoots roots(const LinearFactors& f) {
  return {std::sqrt(f.f1), std::sqrt(f.f2), std::sqrt(f.f3)};
}
inline RfArgs cubic_args(double d, const FactorRoots& x, const FactorRoots& y) {
  const double u12 = (x.s1 * x.s2 * y.s3 + y.s1 * y.s2 * x.s3) / d;
  const double u13 = (x.s1 * x.s3 * y.s2 + y.s1 * y.s3 * x.s2) / d;
  const double u23 = (x.s2 * x.s3 * y.s1 + y.s2 * y.s3 * x.s1) / d;
  return {u12 * u12, u13 * u13, u23 * u23};
}
double cubic_integral(double d, const LinearFactors& x, const LinearFactors& y);

// The cubic integrals of the first, second and third kind between y < x for three real factors
// (Carlson 1989): the factors' values at x and y, d_ij = a_i b_j - a_j b_i, dx = x - y, and what
// they share.
struct RealCubic {
  FactorRoots x, y;      // sqrt(L_i) at x and y
  double u1s, u2s, u3s;  // U_1^2 = U23^2 = ((X1 Y2 Y3 + Y1 X2 X3) / dx)^2, U13^2, U12^2
  double d12, d13, b1;
  double rf;  // R_F(U1^2, U2^2, U3^2)
};
RealCubic real_cubic(double dx, const LinearFactors& fx, const LinearFactors& fy, double d12,
                     double d13, double b1);
// int_y^x dw / sqrt(L1 L2 L3) = 2 R_F.
double first_kind(const RealCubic& c);
// int_y^x sqrt(L1) dw / sqrt(L2 L3) = (2/3) d12 d13 R_D(U3^2, U2^2, U1^2) + 2 X1 Y1 / U1.
double second_kind(const RealCubic& c);

// A pole factor L4 = a4 + b4 w (positive between the limits): its values at x and y and
// d_i4 = a_i b4 - a4 b_i.
struct Pole {
  double b4, l4x, l4y, d14, d24, d34;
};
// int_y^x dw / (L4 sqrt(L1 L2 L3)). `regular`: the pole is at y (L4(y) = 0; only used with
// L4 = w at w = 0, where the integrand is 1/w + O(1)), and what comes back is the finite limit of
// the integral + ln(L4(y)).
double third_kind(const RealCubic& c, const Pole& p, bool regular);

// The same for L1 = z (a1 = 0, b1 = 1) and the quadratic q = (z - c)^2 + n^2 (Carlson 1991:
// f = A^2, g = -2c, h = 1, A^2 = c^2 + n^2), between 0 <= y < x.
struct QuadraticCubic {
  double x1, y1, xi, eta;  // sqrt(z), sqrt(q) at x and y
  double m2, lm2, lp2;     // M^2, L_-^2, L_+^2
  double u;                // U = (X1 eta + Y1 xi) / dx
  double a, c;
  double rf;  // R_F(M^2, L_-^2, L_+^2)
};
QuadraticCubic quadratic_cubic(double x, double y, double c, double n);
// int_y^x dz / sqrt(z q) = 4 R_F(M^2, L_-^2, L_+^2).
double first_kind(const QuadraticCubic& k);
// int_y^x z^(-3/2) q^(-1/2) dz.
double second_kind(const QuadraticCubic& k);
// int_y^x dz / (L4 sqrt(z q)), L4 = a4 + b4 z with values l4x, l4y at the limits; `regular` as
// for three real factors.
double third_kind(const QuadraticCubic& k, double a4, double b4, double l4x, double l4y,
                  bool regular);

}  // namespace lightcone::carlson

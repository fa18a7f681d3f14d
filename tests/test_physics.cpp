// Tests of the pure physics kernels against independent derivations: textbook matrices written
// out element by element, 4-momentum boosts, Einstein's velocity-addition formula, published
// closed forms for the Wigner rotation, and solving the light-cone condition in the body's rest
// frame. Conventions: /work/shared/PHYSICS.md (c = 1, signature +---, look directions point from
// the observer toward the source).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "lightcone/physics/aberration.hpp"
#include "lightcone/physics/emission_root.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/retarded_time.hpp"
#include "lightcone/physics/vec.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// Helpers (deliberately not using the kernels under test).

std::mt19937_64& rng() {
  static std::mt19937_64 engine(20240611);
  return engine;
}

double uniform(double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng());
}

Vec3 random_unit() {
  std::normal_distribution<double> n(0.0, 1.0);
  for (;;) {
    const Vec3 v{n(rng()), n(rng()), n(rng())};
    const double l = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (l > 1e-3) return v / l;
  }
}

// A velocity with a uniformly random direction and |beta| uniform in [0, max_speed].
Vec3 random_beta(double max_speed) {
  return random_unit() * uniform(0.0, max_speed);
}

Vec4 random_event(double scale) {
  return {uniform(-scale, scale),
          {uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale)}};
}

double max_abs_diff(const Mat4& a, const Mat4& b) {
  double m = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m = std::max(m, std::abs(a.m[i][j] - b.m[i][j]));
  return m;
}

double max_abs_diff(const Mat3& a, const Mat3& b) {
  double m = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m = std::max(m, std::abs(a.m[i][j] - b.m[i][j]));
  return m;
}

double max_abs_entry(const Mat4& a) {
  double m = 0;
  for (const auto& row : a.m)
    for (double v : row) m = std::max(m, std::abs(v));
  return m;
}

double dist(const Vec3& a, const Vec3& b) {
  return length(a - b);
}

// Minkowski interval t^2 - |x|^2 written out by hand.
double interval(const Vec4& e) {
  return e.t * e.t - e.x.x * e.x.x - e.x.y * e.x.y - e.x.z * e.x.z;
}

// The textbook boost along the x axis (e.g. Jackson, Classical Electrodynamics, eq. 11.16;
// Taylor & Wheeler), written element by element:
//   t' = gamma (t - beta x),  x' = gamma (x - beta t),  y' = y,  z' = z.
Mat4 textbook_boost_x(double beta) {
  const double g = 1.0 / std::sqrt(1.0 - beta * beta);
  Mat4 r;
  r.m = {{{g, -g * beta, 0, 0}, {-g * beta, g, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
  return r;
}

// Same, along y and z (permuted by hand, not through a rotation).
Mat4 textbook_boost_y(double beta) {
  const double g = 1.0 / std::sqrt(1.0 - beta * beta);
  Mat4 r;
  r.m = {{{g, 0, -g * beta, 0}, {0, 1, 0, 0}, {-g * beta, 0, g, 0}, {0, 0, 0, 1}}};
  return r;
}
Mat4 textbook_boost_z(double beta) {
  const double g = 1.0 / std::sqrt(1.0 - beta * beta);
  Mat4 r;
  r.m = {{{g, 0, 0, -g * beta}, {0, 1, 0, 0}, {0, 0, 1, 0}, {-g * beta, 0, 0, g}}};
  return r;
}

Mat4 transpose4(const Mat4& a) {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[j][i];
  return r;
}

// A boost in an arbitrary direction built independently: rotate the x axis onto beta-hat,
// boost along x, rotate back: B(beta) = R B_x(|beta|) R^T.
Mat4 rotated_textbook_boost(const Vec3& beta) {
  const double b = length(beta);
  const Vec3 n = beta / b;
  const Vec3 x{1, 0, 0};
  const Vec3 axis = cross(x, n);
  Mat3 r3;  // identity when n is already x
  if (length(axis) > 1e-12)
    r3 = Mat3::rotation(axis, std::atan2(length(axis), dot(x, n)));
  else if (dot(x, n) < 0)
    r3 = Mat3::rotation({0, 0, 1}, kPi);
  Mat4 r4;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r4.m[i + 1][j + 1] = r3.m[i][j];
  return r4 * textbook_boost_x(b) * transpose4(r4);
}

// Einstein's velocity addition, written out (e.g. Wikipedia "Velocity-addition formula",
// section "Special relativity", standard form; Moller, The Theory of Relativity, eq. 2.33):
// a body moving with u' in a frame that moves with v relative to the original frame moves with
//   u = [ v + u'/gamma_v + gamma_v/(1 + gamma_v) (v.u') v ] / (1 + v.u')
// in the original frame. Evaluated in long double.
Vec3 einstein_add(const Vec3& v, const Vec3& u_prime) {
  const long double vx = v.x, vy = v.y, vz = v.z;
  const long double ux = u_prime.x, uy = u_prime.y, uz = u_prime.z;
  const long double vv = vx * vx + vy * vy + vz * vz;
  const long double vu = vx * ux + vy * uy + vz * uz;
  const long double g = 1.0L / std::sqrt(1.0L - vv);
  const long double k = g / (1.0L + g) * vu;
  const long double den = 1.0L + vu;
  return {static_cast<double>((vx + ux / g + k * vx) / den),
          static_cast<double>((vy + uy / g + k * vy) / den),
          static_cast<double>((vz + uz / g + k * vz) / den)};
}

double gamma_of(double speed) {
  return 1.0 / std::sqrt(1.0 - speed * speed);
}

// gamma^2 times the double epsilon: the rounding of 1 - beta.beta alone puts a relative error of
// about this size into gamma, so it is the natural accuracy scale of any double kernel that
// takes beta as input.
double gamma2_eps(const Vec3& beta) {
  return std::numeric_limits<double>::epsilon() / (1.0 - dot(beta, beta));
}

// Every test starts from the same seed, so a test's random cases do not depend on which other
// tests ran before it.
class Seeded : public ::testing::Test {
 protected:
  void SetUp() override { rng().seed(20240611); }
};
using Rotation = Seeded;
using Matrix3 = Seeded;
using Boost = Seeded;
using Galilean = Seeded;
using RestFrameMap = Seeded;
using Aberration = Seeded;
using Wigner = Seeded;
using VelocityAddition = Seeded;
using RetardedDelay = Seeded;

// =============================================================================================
// Mat3::rotation

TEST_F(Rotation, RightHandRuleOnTheAxes) {
  // Rotating by +90 degrees about z takes x to y; cyclically about x takes y to z, about y takes
  // z to x (right-hand rule).
  EXPECT_LT(dist(Mat3::rotation({0, 0, 1}, kPi / 2) * Vec3{1, 0, 0}, {0, 1, 0}), 1e-15);
  EXPECT_LT(dist(Mat3::rotation({1, 0, 0}, kPi / 2) * Vec3{0, 1, 0}, {0, 0, 1}), 1e-15);
  EXPECT_LT(dist(Mat3::rotation({0, 1, 0}, kPi / 2) * Vec3{0, 0, 1}, {1, 0, 0}), 1e-15);
  // The axis need not be unit length; a negative angle turns the other way.
  EXPECT_LT(dist(Mat3::rotation({0, 0, 7}, -kPi / 2) * Vec3{1, 0, 0}, {0, -1, 0}), 1e-15);
  // 120 degrees about (1,1,1) permutes the axes: x -> y -> z.
  const Mat3 r = Mat3::rotation({1, 1, 1}, 2 * kPi / 3);
  EXPECT_LT(dist(r * Vec3{1, 0, 0}, {0, 1, 0}), 1e-15);
  EXPECT_LT(dist(r * Vec3{0, 1, 0}, {0, 0, 1}), 1e-15);
}

TEST_F(Rotation, MatchesRodriguesOnRandomVectors) {
  // v_rot = v cos(a) + (n x v) sin(a) + n (n.v)(1 - cos(a)).
  for (int i = 0; i < 200; ++i) {
    const Vec3 n = random_unit();
    const double a = uniform(-kPi, kPi);
    const Vec3 v = random_unit() * uniform(0.1, 10);
    const Vec3 expected =
        v * std::cos(a) + cross(n, v) * std::sin(a) + n * dot(n, v) * (1 - std::cos(a));
    EXPECT_LT(dist(Mat3::rotation(n * uniform(0.01, 100), a) * v, expected), 1e-13);
  }
}

TEST_F(Rotation, OrthonormalWithDeterminantOneAndInverseIsTranspose) {
  for (int i = 0; i < 200; ++i) {
    const Mat3 r = Mat3::rotation(random_unit(), uniform(-kPi, kPi));
    EXPECT_LT(max_abs_diff(r * r.transposed(), Mat3::identity()), 4e-16 * 8);
    EXPECT_NEAR(r.determinant(), 1.0, 4e-16 * 8);
    EXPECT_LT(max_abs_diff(r.inverse(), r.transposed()), 4e-16 * 8);
  }
}

TEST_F(Matrix3, InverseOfGeneralMatrix) {
  Mat3 a;
  a.m = {{{2, -1, 0.5}, {0.25, 3, 1}, {-1, 0.5, 4}}};
  EXPECT_LT(max_abs_diff(a * a.inverse(), Mat3::identity()), 1e-15);
  EXPECT_LT(max_abs_diff(a.inverse() * a, Mat3::identity()), 1e-15);
  // det by the rule of Sarrus, by hand.
  const double det = 2 * 3 * 4 + (-1) * 1 * (-1) + 0.5 * 0.25 * 0.5 - 0.5 * 3 * (-1) -
                     (-1) * 0.25 * 4 - 2 * 1 * 0.5;
  EXPECT_NEAR(a.determinant(), det, 1e-14);
}

// =============================================================================================
// boost()

TEST_F(Boost, MatchesTextbookMatrixAlongEachAxis) {
  for (double b : {-0.9999, -0.6, -1e-8, 1e-8, 0.3, 0.8, 0.99, 0.9999}) {
    const double tol = 1e-15 * gamma_of(b) * gamma_of(b);
    EXPECT_LT(max_abs_diff(boost({b, 0, 0}), textbook_boost_x(b)), tol) << b;
    EXPECT_LT(max_abs_diff(boost({0, b, 0}), textbook_boost_y(b)), tol) << b;
    EXPECT_LT(max_abs_diff(boost({0, 0, b}), textbook_boost_z(b)), tol) << b;
  }
  // A worked case by hand: beta = 0.6 x gives gamma = 1.25, gamma beta = 0.75.
  const Mat4 l = boost({0.6, 0, 0});
  EXPECT_NEAR(l.m[0][0], 1.25, 1e-15);
  EXPECT_NEAR(l.m[0][1], -0.75, 1e-15);
  EXPECT_NEAR(l.m[1][0], -0.75, 1e-15);
  EXPECT_NEAR(l.m[1][1], 1.25, 1e-15);
  EXPECT_EQ(l.m[2][2], 1.0);
  EXPECT_EQ(l.m[3][3], 1.0);
  EXPECT_EQ(l.m[0][2], 0.0);
  // Zero velocity: exactly the identity.
  EXPECT_EQ(max_abs_diff(boost({0, 0, 0}), Mat4::identity()), 0.0);
}

TEST_F(Boost, MatchesRotatedTextbookBoostInAnyDirection) {
  for (int i = 0; i < 300; ++i) {
    const Vec3 beta = random_beta(0.99);
    if (length(beta) < 1e-6) continue;
    const double g = lorentz_gamma(beta);
    EXPECT_LT(max_abs_diff(boost(beta), rotated_textbook_boost(beta)), 1e-14 * g * g);
  }
}

TEST_F(Boost, LorentzGamma) {
  EXPECT_NEAR(lorentz_gamma({0.6, 0, 0}), 1.25, 1e-15);
  EXPECT_NEAR(lorentz_gamma({0, 0.8, 0}), 5.0 / 3.0, 1e-15);
  EXPECT_NEAR(lorentz_gamma({0.48, 0.64, 0}), 5.0 / 3.0, 1e-14);  // |beta| = 0.8
  EXPECT_EQ(lorentz_gamma({0, 0, 0}), 1.0);
}

TEST_F(Boost, PreservesMinkowskiInterval) {
  for (int i = 0; i < 1000; ++i) {
    const Vec3 beta = random_beta(0.999);
    const Vec4 e = random_event(10);
    const Vec4 e2 = boost(beta) * e;
    const double scale = e2.t * e2.t + dot(e2.x, e2.x);
    EXPECT_NEAR(interval(e2), interval(e), 1e-14 * scale);
    EXPECT_NEAR(minkowski_dot(e2, e2), interval(e), 1e-14 * scale);
  }
  // Null, timelike and spacelike stay so: a light ray along y.
  const Vec4 null_event = boost({0.9, 0.1, -0.2}) * Vec4{1, {0, 1, 0}};
  EXPECT_NEAR(interval(null_event), 0.0, 1e-14 * null_event.t * null_event.t);
  EXPECT_GT(null_event.t, 0.0);  // orthochronous
}

TEST_F(Boost, OppositeBoostIsInverse) {
  for (int i = 0; i < 300; ++i) {
    const Vec3 beta = random_beta(0.99);
    EXPECT_LT(max_abs_diff(boost(beta) * boost(-beta), Mat4::identity()), 1e-12);
    EXPECT_LT(max_abs_diff(boost(-beta) * boost(beta), Mat4::identity()), 1e-12);
  }
}

TEST_F(Boost, LorentzInverseEqualsNumericInverse) {
  for (int i = 0; i < 300; ++i) {
    const Vec3 beta = random_beta(0.99);
    const Mat4 b = boost(beta);
    EXPECT_LT(max_abs_diff(lorentz_inverse(b), inverse(b)), 1e-11);
    // A general proper Lorentz matrix: rotation * boost * rotation * boost.
    const Mat4 l = spatial_rotation(Mat3::rotation(random_unit(), uniform(-kPi, kPi))) * b *
                   spatial_rotation(Mat3::rotation(random_unit(), uniform(-kPi, kPi))) *
                   boost(random_beta(0.9));
    const double s = max_abs_entry(l);
    EXPECT_LT(max_abs_diff(lorentz_inverse(l), inverse(l)), 1e-13 * s * s);
    EXPECT_LT(max_abs_diff(l * lorentz_inverse(l), Mat4::identity()), 1e-14 * s * s);
  }
}

TEST_F(Boost, FourVelocityOfTheMovingBodyBecomesAtRest) {
  // u = gamma (1, beta) is the 4-velocity of a body moving with beta; in the frame moving with
  // it, the body is at rest: u' = (1, 0, 0, 0).
  for (int i = 0; i < 300; ++i) {
    const Vec3 beta = random_beta(0.999);
    const double g = 1.0 / std::sqrt(1.0 - dot(beta, beta));
    const Vec4 u = boost(beta) * Vec4{g, beta * g};
    EXPECT_NEAR(u.t, 1.0, 1e-12);
    EXPECT_LT(length(u.x), 1e-12);
  }
}

TEST_F(Boost, TimeDilationAndLengthContraction) {
  // A clock at rest at the origin of W ticks at t = 1: in the frame moving with beta = 0.8 that
  // event is at t' = gamma = 5/3 (dilated) and x' = -gamma beta = -4/3.
  const Vec4 tick = boost({0.8, 0, 0}) * Vec4{1, {0, 0, 0}};
  EXPECT_NEAR(tick.t, 5.0 / 3.0, 1e-15);
  EXPECT_NEAR(tick.x.x, -4.0 / 3.0, 1e-15);
  // A rod of rest length 1 moving with beta = 0.8 along x: its ends, seen at the same W time,
  // are 1/gamma = 0.6 apart. Ends at rest in the moving frame at x' = 0 and x' = 1; in W their
  // world-lines are x = 0.8 t and x = 0.8 t + 0.6.
  const Mat4 to_rod = boost({0.8, 0, 0});
  const Vec4 end0 = to_rod * Vec4{2.0, {1.6, 0, 0}};
  const Vec4 end1 = to_rod * Vec4{2.0, {2.2, 0, 0}};
  EXPECT_NEAR(end1.x.x - end0.x.x, 1.0, 1e-14);
}

// =============================================================================================
// Galilean map and rest_frame_map

TEST_F(Galilean, ShiftsSpaceByBetaTimesTime) {
  for (int i = 0; i < 200; ++i) {
    const Vec3 beta = random_beta(0.99);
    const Vec4 e = random_event(100);
    const Vec4 g = galilean(beta) * e;
    EXPECT_EQ(g.t, e.t);
    EXPECT_LT(dist(g.x, e.x - beta * e.t), 1e-13);
  }
  // Galilean velocities add as vectors; the inverse is the opposite velocity.
  const Vec3 a{0.3, -0.2, 0.5}, b{0.6, 0.1, -0.4};
  EXPECT_LT(max_abs_diff(galilean(a) * galilean(b), galilean(a + b)), 1e-15);
  EXPECT_LT(max_abs_diff(inverse(galilean(a)), galilean(-a)), 1e-15);
}

TEST_F(RestFrameMap, EventToOriginAndWorldLineToSpatialOrigin) {
  for (int i = 0; i < 300; ++i) {
    const Vec3 beta = random_beta(0.999);
    const Vec4 p = random_event(1000);
    const AffineMap4 map = rest_frame_map(p, beta);
    const Vec4 origin = map(p);
    EXPECT_LT(std::abs(origin.t) + length(origin.x), 1e-12 * 1000);
    // Points of the body's world-line p + s (1, beta): at rest at x' = 0, and the rest-frame time
    // elapsed is the proper time s / gamma (time dilation).
    const double g = 1.0 / std::sqrt(1.0 - dot(beta, beta));
    for (double s : {-50.0, 0.5, 3.0, 700.0}) {
      const Vec4 q = map(Vec4{p.t + s, p.x + beta * s});
      const double scale = 1e-13 * g * g * (1000 + std::abs(s));
      EXPECT_LT(length(q.x), scale) << s;
      EXPECT_NEAR(q.t, s / g, scale) << s;
    }
  }
}

// =============================================================================================
// Aberration

// Look direction d in frame F: the photon arrives from d, so the backward null ray from the
// observer is the past-directed null vector k = (-1, d). Boost it into the frame moving with
// beta; the spatial part normalised is the look direction there, and the ratio of time parts is
// the ray-parameter scale.
struct BoostedRay {
  Vec3 direction;
  double scale;
  double null_defect;  // |k'.x| - (-k'.t), zero for a null vector
};
BoostedRay boost_null_ray(const Vec3& d, const Vec3& beta) {
  const Vec4 k{-1.0, d};
  const Vec4 kp = boost(beta) * k;
  const double len = length(kp.x);
  return {kp.x / len, (-kp.t) / (-k.t), len + kp.t};
}

TEST_F(Aberration, MatchesBoostOfNullFourVector) {
  std::vector<double> speeds = {0.999, 0.99, 0.9, 0.5, 1e-6};
  for (int i = 0; i < 3000; ++i) {
    const Vec3 d = random_unit();
    const Vec3 beta = (i < 500) ? random_unit() * speeds[i % speeds.size()] : random_beta(0.999);
    const BoostedRay ref = boost_null_ray(d, beta);
    const Vec3 got = aberrate_into_moving_frame(d, beta);
    EXPECT_LT(dist(got, ref.direction), 1e-13)
        << "beta " << length(beta) << " d.b " << dot(d, beta);
    EXPECT_NEAR(ray_parameter_scale(d, beta), ref.scale, 1e-13 * ref.scale);
    EXPECT_NEAR(ref.null_defect, 0.0, 1e-13 * ref.scale);
    // Unit length to rounding; near d = -beta-hat the kernel's rounding grows as gamma^2 eps
    // (see BackwardConeAccuracy).
    EXPECT_NEAR(length(got), 1.0, std::max(1e-14, 16 * gamma2_eps(beta)));
  }
}

// Reference aberration in long double: the textbook boost of k = (-1, d) written out,
//   k'_t = gamma (k_t - beta.k_x),  k'_x = k_x + [(gamma - 1)/b^2 (beta.k_x) - gamma k_t] beta.
Vec3 aberrate_long_double(const Vec3& d, const Vec3& beta) {
  const long double b[3] = {beta.x, beta.y, beta.z}, k[3] = {d.x, d.y, d.z};
  const long double b2 = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
  const long double bk = b[0] * k[0] + b[1] * k[1] + b[2] * k[2];
  const long double g = 1.0L / std::sqrt(1.0L - b2);
  const long double kt = -1.0L;
  long double out[3], len2 = 0;
  for (int i = 0; i < 3; ++i) {
    out[i] = k[i] + ((g - 1.0L) / b2 * bk - g * kt) * b[i];
    len2 += out[i] * out[i];
  }
  const long double len = std::sqrt(len2);
  return {static_cast<double>(out[0] / len), static_cast<double>(out[1] / len),
          static_cast<double>(out[2] / len)};
}

TEST_F(Aberration, BackwardConeAccuracy) {
  // Looking against the motion (d close to -beta-hat) the image of a small cone is magnified by
  // gamma (1 + b), and the kernel's closed form loses about 8 gamma^2 eps there (measured worst
  // cases: 8e-13 at beta = 0.999, 9e-12 at 0.9999, mostly as a length error of the output).
  // Everywhere else it is within 1e-13 of the long-double boost.
  for (double b : {0.5, 0.9, 0.99, 0.999, 0.9999}) {
    for (int i = 0; i < 2000; ++i) {
      const Vec3 bh = random_unit();
      const Vec3 beta = bh * b;
      const Vec3 d =
          (i % 2 == 0) ? normalize(-bh + random_unit() * std::pow(10.0, -(i % 9))) : random_unit();
      const Vec3 ref = aberrate_long_double(d, beta);
      const Vec3 got = aberrate_into_moving_frame(d, beta);
      const double tol = (1 + dot(bh, d) < 0.1) ? 16 * gamma2_eps(beta) : 1e-13;
      EXPECT_LT(dist(got, ref), tol) << "b " << b << " bh.d " << dot(bh, d);
      EXPECT_NEAR(length(got), 1.0, std::max(4e-16, tol));
    }
  }
}

TEST_F(Aberration, OutOfMovingFrameMatchesInverseBoostAndInverts) {
  for (int i = 0; i < 2000; ++i) {
    const Vec3 d = random_unit();
    const Vec3 beta = random_beta(0.999);
    // Going back to F is the boost by -beta of the moving frame's null vector.
    const BoostedRay ref = boost_null_ray(d, -beta);
    const Vec3 back = aberrate_out_of_moving_frame(d, beta);
    EXPECT_LT(dist(back, ref.direction), 1e-13);
    EXPECT_NEAR(length(back), 1.0, 1e-14);
    EXPECT_LT(dist(aberrate_out_of_moving_frame(aberrate_into_moving_frame(d, beta), beta), d),
              1e-12);
    EXPECT_LT(dist(aberrate_into_moving_frame(aberrate_out_of_moving_frame(d, beta), beta), d),
              1e-12);
    // Scales compose to one: s_F -> s_moving -> s_F.
    const Vec3 dm = aberrate_into_moving_frame(d, beta);
    EXPECT_NEAR(ray_parameter_scale(d, beta) * ray_parameter_scale(dm, -beta), 1.0, 1e-12);
  }
}

TEST_F(Aberration, TextbookAngleFormula) {
  // With theta the angle between d and beta in F, the angle theta' in the moving frame obeys
  //   cos(theta') = (cos(theta) + beta) / (1 + beta cos(theta))
  // (Einstein 1905, par. 7; here for look directions, so the source ahead of the motion moves
  // further ahead), and d' stays in the plane of d and beta on the same side.
  for (double b : {0.1, 0.5, 0.9, 0.999}) {
    for (int i = 0; i < 200; ++i) {
      const Vec3 n = random_unit();
      const Vec3 d = random_unit();
      const double c = dot(d, n);
      const Vec3 dp = aberrate_into_moving_frame(d, n * b);
      EXPECT_NEAR(dot(dp, n), (c + b) / (1 + b * c), 1e-13);
      const Vec3 perp = d - n * c, perp_p = dp - n * dot(dp, n);
      if (length(perp) > 1e-6) {
        EXPECT_NEAR(dot(normalize(perp_p), normalize(perp)), 1.0, 1e-12);
      }
    }
  }
}

TEST_F(Aberration, PerpendicularDirectionTiltsForwardToCosBeta) {
  // d perpendicular to beta in F: k' spatial = d + gamma beta, |k'| = gamma, so
  // d' = d / gamma + beta and d'.bh = |beta| exactly: the source appears tilted toward the
  // direction of motion with cos(theta') = beta.
  for (int i = 0; i < 500; ++i) {
    const Vec3 beta = random_beta(0.9999);
    const double b = length(beta);
    if (b < 1e-6) continue;
    const Vec3 bh = beta / b;
    const Vec3 d = normalize(cross(bh, random_unit()));
    const Vec3 dp = aberrate_into_moving_frame(d, beta);
    EXPECT_NEAR(dot(dp, bh), b, 1e-14);
    EXPECT_LT(dist(dp - bh * dot(dp, bh), d * std::sqrt(1 - b * b)), 1e-14);
  }
  // Worked number used in docs/design/aberration.md: at beta = 0.9 the source at 90 degrees
  // from the motion is seen 25.84 degrees from straight ahead.
  const Vec3 dp = aberrate_into_moving_frame({0, 1, 0}, {0.9, 0, 0});
  EXPECT_NEAR(std::acos(dp.x) * 180 / kPi, 25.841932763, 1e-8);
}

TEST_F(Aberration, SeedSkyFormulaIsWrongByTheDocumentedAmount) {
  // The seed's sky formula x' = normalize(x + (gamma - 1)(vh.x) vh) leaves a perpendicular
  // direction at 90 degrees; the exact direction is at acos(0.9) = 25.84 degrees at beta = 0.9,
  // so the seed is off by 64.16 degrees there (docs/design/aberration.md).
  const Vec3 beta{0.9, 0, 0};
  const double g = 1 / std::sqrt(1 - 0.81);
  const Vec3 d{0, 1, 0};
  const Vec3 seed = normalize(d + Vec3{1, 0, 0} * ((g - 1) * d.x));
  const Vec3 exact = aberrate_into_moving_frame(d, beta);
  const double err_deg = std::acos(dot(seed, exact)) * 180 / kPi;
  EXPECT_NEAR(err_deg, 64.158067237, 1e-8);
  // Largest disagreement at beta = 0.9: the F direction 126.044 degrees from the motion is seen
  // at 48.52 degrees, the seed puts it at 149.08 degrees: 100.56 degrees apart.
  const double th = 126.044 * kPi / 180;
  const Vec3 d2{std::cos(th), std::sin(th), 0};
  const Vec3 seed2 = normalize(d2 + Vec3{1, 0, 0} * ((g - 1) * d2.x));
  EXPECT_NEAR(std::acos(aberrate_into_moving_frame(d2, beta).x) * 180 / kPi, 48.5204, 1e-3);
  EXPECT_NEAR(std::acos(seed2.x) * 180 / kPi, 149.0791, 1e-3);
}

TEST_F(Aberration, ParallelDirectionsUnchanged) {
  for (double b : {1e-9, 0.3, 0.9, 0.9999}) {
    for (int i = 0; i < 50; ++i) {
      const Vec3 n = random_unit();
      const Vec3 beta = n * b;
      const double tol = 16 * gamma2_eps(beta);  // about 8 gamma^2 eps: see BackwardConeAccuracy
      EXPECT_LT(dist(aberrate_into_moving_frame(n, beta), n), 1e-15);
      EXPECT_LT(dist(aberrate_into_moving_frame(-n, beta), -n), tol);
      EXPECT_LT(dist(aberrate_out_of_moving_frame(n, beta), n), tol);
      EXPECT_LT(dist(aberrate_out_of_moving_frame(-n, beta), -n), 1e-15);
      // Ray-parameter scale along the motion is the Doppler factor sqrt((1 + b)/(1 - b)); against
      // it sqrt((1 - b)/(1 + b)). b is taken as |beta| of the rounded input (long double); gamma
      // itself is only good to gamma^2 eps in double.
      const long double bl = std::sqrt((long double)beta.x * beta.x + (long double)beta.y * beta.y +
                                       (long double)beta.z * beta.z);
      const double ahead = static_cast<double>(std::sqrt((1 + bl) / (1 - bl)));
      EXPECT_NEAR(ray_parameter_scale(n, beta), ahead, tol * ahead);
      EXPECT_NEAR(ray_parameter_scale(-n, beta), 1 / ahead, tol / ahead);
    }
  }
}

TEST_F(Aberration, SmallAndZeroVelocity) {
  for (int i = 0; i < 200; ++i) {
    const Vec3 d = random_unit();
    // beta = 0: bit-exact identity.
    const Vec3 same = aberrate_into_moving_frame(d, {0, 0, 0});
    EXPECT_EQ(same.x, d.x);
    EXPECT_EQ(same.y, d.y);
    EXPECT_EQ(same.z, d.z);
    const Vec3 back = aberrate_out_of_moving_frame(d, {0, 0, 0});
    EXPECT_EQ(back.x, d.x);
    EXPECT_EQ(back.y, d.y);
    EXPECT_EQ(back.z, d.z);
    EXPECT_EQ(ray_parameter_scale(d, {0, 0, 0}), 1.0);
    // beta = 1e-12: first-order change |beta_perp| <= 1e-12 (plus rounding of d), so within
    // 1e-12 of d.
    const Vec3 beta = random_unit() * 1e-12;
    EXPECT_LT(dist(aberrate_into_moving_frame(d, beta), d), 1e-12 + 1e-15);
    EXPECT_LT(dist(aberrate_out_of_moving_frame(d, beta), d), 1e-12 + 1e-15);
    // And the change is the classical aberration to first order: d' - d = beta - (beta.d) d.
    const Vec3 change = aberrate_into_moving_frame(d, beta) - d;
    EXPECT_LT(dist(change, beta - d * dot(beta, d)), 1e-15);
  }
}

TEST_F(Aberration, FarVertexOnPastLightConeLandsOnTheSkyDirection) {
  // PHYSICS.md: a mesh vertex very far away and the sky in the same direction land on the same
  // pixel. A vertex at distance R along d, seen at t = 0 from the origin, emitted at t = -R.
  for (int i = 0; i < 200; ++i) {
    const Vec3 d = random_unit();
    const Vec3 beta = random_beta(0.99);
    const double r = 1e7;
    const Vec4 vertex = boost(beta) * Vec4{-r, d * r};
    EXPECT_LT(dist(normalize(vertex.x), aberrate_into_moving_frame(d, beta)), 1e-13);
  }
}

// =============================================================================================
// Composition of boosts and the Wigner rotation

// Wigner rotation angle for two boosts with Lorentz factors g1, g2 and composite factor
// G = g1 g2 (1 + b1.b2) (Wikipedia, "Wigner rotation", section on the rotation angle of two
// general boosts; also Rhodes & Semon, Am. J. Phys. 72, 943 (2004)):
//   cos(theta) = (1 + G + g1 + g2)^2 / ((1 + G)(1 + g1)(1 + g2)) - 1.
// For perpendicular velocities G = g1 g2 and this reduces to
//   cos(theta) = (g1 + g2) / (1 + g1 g2)
// (O'Donnell & Visser, Eur. J. Phys. 32, 1033 (2011), section 3.2.1; equivalently
// tan(theta) = g1 g2 b1 b2 / (g1 + g2)).
double wigner_cos(const Vec3& b1, const Vec3& b2) {
  const double g1 = gamma_of(length(b1)), g2 = gamma_of(length(b2));
  const double big_g = g1 * g2 * (1 + dot(b1, b2));
  const double s = 1 + big_g + g1 + g2;
  return s * s / ((1 + big_g) * (1 + g1) * (1 + g2)) - 1;
}

// boost(b1) takes W coordinates to F1, which moves with b1 in W; boost(b2) takes F1 coordinates
// to F2, which moves with b2 relative to F1. F2's origin therefore moves with b2 in F1, and F1
// with b1 in W: its velocity in W is "b2 seen from a frame moving with b1", i.e.
// velocity_addition(b1, b2) = b1 (+) b2. That is the beta of decompose_lorentz(B(b2) B(b1)).
// W's origin moves with -b1 in F1 and F1 moves with -b2 in F2, so W's origin moves with
// (-b2) (+) (-b1) = -(b2 (+) b1) in F2; from L = R B(beta) it moves with -R beta. Hence
// R (b1 (+) b2) = b2 (+) b1 (the Thomas gyration), which fixes the sense of R.
TEST_F(Wigner, DecompositionOfTwoBoosts) {
  for (int i = 0; i < 1000; ++i) {
    const Vec3 b1 = random_beta(0.95), b2 = random_beta(0.95);
    const Mat4 l = boost(b2) * boost(b1);
    const BoostRotation br = decompose_lorentz(l);
    const Mat3& r = br.rotation;
    EXPECT_LT(max_abs_diff(r * r.transposed(), Mat3::identity()), 1e-12);
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
    const double s = max_abs_entry(l);
    EXPECT_LT(max_abs_diff(spatial_rotation(r) * boost(br.beta), l), 1e-13 * s);
    const Vec3 b12 = einstein_add(b1, b2), b21 = einstein_add(b2, b1);
    EXPECT_LT(dist(br.beta, b12), 1e-13);
    EXPECT_LT(dist(velocity_addition(b1, b2), b12), 1e-13);
    EXPECT_LT(dist(r * b12, b21), 1e-12);
    EXPECT_NEAR((r.m[0][0] + r.m[1][1] + r.m[2][2] - 1) / 2, wigner_cos(b1, b2), 1e-12);
    // The composite Lorentz factor is g1 g2 (1 + b1.b2).
    EXPECT_NEAR(l.m[0][0], gamma_of(length(b1)) * gamma_of(length(b2)) * (1 + dot(b1, b2)),
                1e-13 * s);
  }
}

TEST_F(Wigner, PerpendicularBoostsClosedForm) {
  for (double u : {0.1, 0.6, 0.9, 0.99}) {
    for (double v : {0.2, 0.8, 0.95}) {
      const Vec3 b1{u, 0, 0}, b2{0, v, 0};
      const BoostRotation br = decompose_lorentz(boost(b2) * boost(b1));
      const double gu = gamma_of(u), gv = gamma_of(v);
      const double cos_theta = (gu + gv) / (1 + gu * gv);
      const double sin_theta = gu * gv * u * v / (1 + gu * gv);
      EXPECT_NEAR(cos_theta * cos_theta + sin_theta * sin_theta, 1.0, 1e-14);
      // Rotation about +z = b1 x b2 by +theta: the gyration argument above with
      // b1 (+) b2 = (u, v/gu, 0) and b2 (+) b1 = (u/gv, v, 0) (the latter is further toward y).
      const Mat3 expected = Mat3::rotation({0, 0, 1}, std::atan2(sin_theta, cos_theta));
      EXPECT_LT(max_abs_diff(br.rotation, expected), 1e-13) << u << " " << v;
      EXPECT_LT(dist(br.beta, {u, v / gu, 0}), 1e-14);
    }
  }
  // A worked number: u = v = 0.8 (gamma 5/3): cos(theta) = (10/3)/(1 + 25/9) = 15/17,
  // theta = 28.07 degrees.
  const BoostRotation br = decompose_lorentz(boost({0, 0.8, 0}) * boost({0.8, 0, 0}));
  EXPECT_NEAR(br.rotation.m[0][0], 15.0 / 17.0, 1e-14);
  EXPECT_NEAR(br.rotation.m[1][0], 8.0 / 17.0, 1e-14);
}

TEST_F(Wigner, CollinearBoostsAddRapidities) {
  for (int i = 0; i < 300; ++i) {
    const Vec3 n = random_unit();
    const double a = uniform(-0.99, 0.99), b = uniform(-0.99, 0.99);
    const BoostRotation br = decompose_lorentz(boost(n * b) * boost(n * a));
    EXPECT_LT(max_abs_diff(br.rotation, Mat3::identity()), 1e-12);
    const double expected = std::tanh(std::atanh(a) + std::atanh(b));
    EXPECT_LT(dist(br.beta, n * expected), 1e-13);
    EXPECT_LT(dist(velocity_addition(n * a, n * b), n * expected), 1e-13);
  }
}

// =============================================================================================
// velocity_addition

// Lorentz contraction against the boost itself: the rest-frame events of a point at rest offset
// d, carried into the frame where the body moves with beta, meet that frame's instant t = 0 at
// contracted_offset(d, beta); rest_offset_of undoes it.
TEST(LorentzContraction, OffsetsAtOneInstantAgainstTheBoost) {
  const Vec3 beta{0.5, -0.3, 0.6};
  const Mat4 to_moving = boost(beta * -1.0);  // rest frame -> the frame where the body moves
  for (const Vec3& d : {Vec3{1, 0, 0}, Vec3{0.3, -2, 0.7}, Vec3{-1, 1, 1}}) {
    // The rest-frame event (tau, d) maps to t = 0 for one tau (t is linear in tau).
    const Vec4 a = to_moving * Vec4{0, d}, b = to_moving * Vec4{1, d};
    const double tau = -a.t / (b.t - a.t);
    const Vec4 at_zero = to_moving * Vec4{tau, d};
    const Vec4 origin_a = to_moving * Vec4{0, {}}, origin_b = to_moving * Vec4{1, {}};
    const double tau0 = -origin_a.t / (origin_b.t - origin_a.t);
    const Vec3 origin = (to_moving * Vec4{tau0, {}}).x;
    EXPECT_LT(length(contracted_offset(d, beta) - (at_zero.x - origin)), 1e-12);
    EXPECT_LT(length(rest_offset_of(contracted_offset(d, beta), beta) - d), 1e-12);
  }
  EXPECT_EQ(contracted_offset({1, 2, 3}, {}).y, 2);
}

// The bracketed root for light delay without a closed form, against the closed form of a
// straight line in flat space (retarded_delay), from the receiver's time and from guesses on
// either side; a late end where the source's light never arrives (+infinity) is moved back; a
// NaN (no such light) gives none.
TEST(EmissionTimeRoot, MatchesTheClosedFormOfAStraightLine) {
  const Vec3 x0{3, -1, 2}, beta{-0.6, 0.3, 0.5};
  const double t_r = 10;
  const auto late = [&](double t) { return t + length(x0 + beta * t) - t_r; };
  const double want = t_r - retarded_delay(x0 + beta * t_r, beta);
  for (const double start : {t_r, want - 3.0, want + 0.5, want - 1e-6}) {
    const auto root = emission_time_root(late, t_r, start, late(start));
    ASSERT_TRUE(root) << start;
    EXPECT_NEAR(*root, want, 1e-12 * (1 + std::abs(want))) << start;
  }
  const auto never_after = [&](double t) {
    return t > want + 1 ? std::numeric_limits<double>::infinity() : late(t);
  };
  const auto root = emission_time_root(never_after, t_r, t_r, never_after(t_r));
  ASSERT_TRUE(root);
  EXPECT_NEAR(*root, want, 1e-12 * (1 + std::abs(want)));
  const auto none = [&](double t) {
    return t < want + 0.5 ? std::numeric_limits<double>::quiet_NaN() : late(t);
  };
  EXPECT_FALSE(emission_time_root(none, t_r, t_r, none(t_r)));
}

TEST_F(VelocityAddition, ParallelEinsteinFormula) {
  // (a + b) / (1 + a b) along a common line.
  for (double a : {-0.9, -0.3, 0.0, 0.5, 0.99})
    for (double b : {-0.99, -0.5, 0.0, 0.25, 0.9}) {
      const Vec3 w = velocity_addition({a, 0, 0}, {b, 0, 0});
      EXPECT_NEAR(w.x, (a + b) / (1 + a * b), 1e-15) << a << " " << b;
      EXPECT_EQ(w.y, 0.0);
      EXPECT_EQ(w.z, 0.0);
    }
  // 0.5 + 0.5 = 0.8.
  EXPECT_NEAR(velocity_addition({0, 0.5, 0}, {0, 0.5, 0}).y, 0.8, 1e-15);
}

TEST_F(VelocityAddition, GeneralEinsteinFormula) {
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a = random_beta(0.999), b = random_beta(0.999);
    const Vec3 w = velocity_addition(a, b);
    EXPECT_LT(dist(w, einstein_add(a, b)), 1e-12);
    EXPECT_LT(dot(w, w), 1.0);
    // gamma_w = gamma_a gamma_b (1 + a.b), from the time component of the composed 4-velocity.
    EXPECT_NEAR(lorentz_gamma(w), gamma_of(length(a)) * gamma_of(length(b)) * (1 + dot(a, b)),
                1e-9 * lorentz_gamma(w));
  }
  // Perpendicular, worked by hand: frame at 0.6 x, body at 0.8 y in it: (0.6, 0.8 * 0.8, 0).
  const Vec3 w = velocity_addition({0.6, 0, 0}, {0, 0.8, 0});
  EXPECT_NEAR(w.x, 0.6, 1e-15);
  EXPECT_NEAR(w.y, 0.64, 1e-15);
}

TEST_F(VelocityAddition, NeverReachesLight) {
  const double a = 0.9999, b = 0.9999;
  const Vec3 w = velocity_addition({a, 0, 0}, {b, 0, 0});
  EXPECT_LT(length(w), 1.0);
  // 1 - w = (1 - a)(1 - b)/(1 + a b) = 5.0005e-9.
  EXPECT_NEAR(1 - w.x, (1 - a) * (1 - b) / (1 + a * b), 1e-6 * 5e-9);
  // Perpendicular: 1 - |w|^2 = (1 - a^2)(1 - b^2).
  const Vec3 p = velocity_addition({a, 0, 0}, {0, b, 0});
  EXPECT_LT(length(p), 1.0);
  EXPECT_NEAR(1 - dot(p, p), (1 - a * a) * (1 - b * b), 1e-6 * (1 - a * a) * (1 - b * b));
  // Random directions at 0.9999.
  for (int i = 0; i < 300; ++i) {
    const Vec3 v = velocity_addition(random_unit() * 0.9999, random_unit() * 0.9999);
    EXPECT_LT(length(v), 1.0);
  }
}

// =============================================================================================
// retarded_delay

// Residual of the light-cone condition |delta - beta tau| - tau, in long double.
long double light_cone_residual(const Vec3& delta, const Vec3& beta, double tau) {
  const long double x = (long double)delta.x - (long double)beta.x * tau;
  const long double y = (long double)delta.y - (long double)beta.y * tau;
  const long double z = (long double)delta.z - (long double)beta.z * tau;
  return std::sqrt(x * x + y * y + z * z) - tau;
}

TEST_F(RetardedDelay, SatisfiesLightConeCondition) {
  for (double scale : {1e-9, 1e-3, 1.0, 1e3, 1e9}) {
    for (int i = 0; i < 1000; ++i) {
      const Vec3 delta = random_unit() * (scale * uniform(0.1, 1.0));
      const Vec3 beta = (i % 4 == 0) ? random_unit() * 0.9999 : random_beta(0.9999);
      const double tau = retarded_delay(delta, beta);
      ASSERT_GE(tau, 0.0);
      EXPECT_LE(std::abs(light_cone_residual(delta, beta, tau)), 1e-12L * tau)
          << "scale " << scale << " beta " << length(beta);
      // Light cannot outrun the body: tau lies between |delta|/(1 + b) and |delta|/(1 - b).
      const double b = length(beta), dl = length(delta);
      EXPECT_GE(tau, dl / (1 + b) * (1 - 1e-12));
      EXPECT_LE(tau, dl / (1 - b) * (1 + 1e-12));
    }
  }
}

TEST_F(RetardedDelay, StaticBodyIsDistance) {
  for (int i = 0; i < 100; ++i) {
    const Vec3 delta = random_unit() * uniform(1e-9, 1e9);
    EXPECT_DOUBLE_EQ(retarded_delay(delta, {0, 0, 0}), length(delta));
  }
  EXPECT_EQ(retarded_delay({0, 0, 0}, {0.5, 0, 0}), 0.0);
  EXPECT_EQ(retarded_delay({0, 0, 0}, {0, 0, 0}), 0.0);
}

TEST_F(RetardedDelay, HeadOnClosedForms) {
  // Body now at delta = D x; emission tau earlier, it was at D x - beta tau.
  // Approaching (beta = -b x): it was farther away, D + b tau = tau, so tau = D / (1 - b).
  // Receding (beta = +b x): D - b tau = tau, so tau = D / (1 + b).
  for (double d : {1e-9, 1.0, 10.0, 1e9}) {
    for (double b : {0.1, 0.5, 0.9, 0.99, 0.9999}) {
      EXPECT_NEAR(retarded_delay({d, 0, 0}, {-b, 0, 0}), d / (1 - b), 1e-12 * d / (1 - b));
      EXPECT_NEAR(retarded_delay({d, 0, 0}, {b, 0, 0}), d / (1 + b), 1e-14 * d / (1 + b));
      // Same along an arbitrary line of sight. n * b rounds |beta| by a few eps, which
      // D / (1 - b) amplifies by b / (1 - b) (~1e4 at 0.9999): hence the gamma^2 eps scale.
      const Vec3 n = random_unit();
      EXPECT_NEAR(retarded_delay(n * d, n * -b), d / (1 - b), 16 * gamma2_eps(n * b) * d / (1 - b));
      EXPECT_NEAR(retarded_delay(n * d, n * b), d / (1 + b), 1e-13 * d / (1 + b));
    }
  }
  // Worked numbers (docs/design/light-delay.md): D = 10, b = 0.9: 100 approaching, 5.263 receding.
  EXPECT_NEAR(retarded_delay({10, 0, 0}, {-0.9, 0, 0}), 100.0, 1e-12);
  EXPECT_NEAR(retarded_delay({10, 0, 0}, {0.9, 0, 0}), 10.0 / 1.9, 1e-13);
  // Transverse motion (beta perpendicular to delta): tau^2 = D^2 + b^2 tau^2, tau = gamma D.
  EXPECT_NEAR(retarded_delay({0, 3, 0}, {0.8, 0, 0}), 5.0, 1e-14);
}

TEST_F(RetardedDelay, StableForRecedingBodiesAgainstLongDouble) {
  // beta.delta > 0 and large: the textbook root (-bd + sqrt(bd^2 + (1 - b^2) d^2)) / (1 - b^2)
  // cancels badly in double (error ~ eps b / (1 - b)). Evaluated in long double it is accurate
  // to ~1e-15 here; the kernel must agree to 1e-13.
  for (double b : {0.9, 0.99, 0.999, 0.9999}) {
    for (double scale : {1e-9, 1.0, 1e9}) {
      for (int i = 0; i < 200; ++i) {
        const Vec3 n = random_unit();
        const Vec3 beta = n * b;
        // Mostly along the motion, with a small transverse part.
        const Vec3 delta = (n + random_unit() * uniform(0.0, 0.05)) * scale;
        const long double bx = beta.x, by = beta.y, bz = beta.z;
        const long double dx = delta.x, dy = delta.y, dz = delta.z;
        const long double bd = bx * dx + by * dy + bz * dz;
        const long double d2 = dx * dx + dy * dy + dz * dz;
        const long double omb2 = 1.0L - (bx * bx + by * by + bz * bz);
        const long double ref = (-bd + std::sqrt(bd * bd + omb2 * d2)) / omb2;
        const double tau = retarded_delay(delta, beta);
        EXPECT_NEAR(tau, static_cast<double>(ref), 1e-13 * static_cast<double>(ref))
            << "b " << b << " scale " << scale;
      }
    }
  }
}

TEST_F(RetardedDelay, AgreesWithRestFrameConstruction) {
  // Independent route: map into the body's rest frame with rest_frame_map, where the body is
  // static at x' = 0. There light from it reaches the receiver R' after |x'_R|, so the emission
  // event is E' = (t'_R - |x'_R|, 0). Map E' back to W (e = B(-beta) e' + body event) and read
  // tau = t_R - t_E. The emission event must lie on the body's world-line and on the receiver's
  // past light cone.
  for (double scale : {1e-6, 1.0, 1e6}) {
    for (int i = 0; i < 500; ++i) {
      const Vec4 receiver = random_event(scale);
      const Vec3 delta = random_unit() * (scale * uniform(0.01, 1.0));
      const Vec3 beta = random_beta(0.999);
      const Vec4 body_now{receiver.t, receiver.x + delta};  // on the body's world-line
      const AffineMap4 to_body = rest_frame_map(body_now, beta);
      const Vec4 r_body = to_body(receiver);
      const Vec4 e_body{r_body.t - length(r_body.x), {0, 0, 0}};
      const Vec4 e_world = boost(-beta) * e_body + body_now;
      const double tau_ref = receiver.t - e_world.t;
      const double tau = retarded_delay(delta, beta);
      const double g = 1.0 / std::sqrt(1.0 - dot(beta, beta));
      const double tol = 1e-12 * g * g * (scale + tau);
      EXPECT_NEAR(tau, tau_ref, tol) << "scale " << scale << " beta " << length(beta);
      // Kernel's emission event: on the world-line by construction; check the interval to R.
      const Vec4 emit{receiver.t - tau, body_now.x - beta * tau};
      const Vec4 sep = receiver - emit;
      EXPECT_NEAR(std::sqrt(dot(sep.x, sep.x)), sep.t, tol);
      // The rest-frame emission event is on the world-line: x_E = x_now - beta tau_ref.
      EXPECT_LT(dist(e_world.x, body_now.x - beta * tau_ref), tol);
    }
  }
}

TEST_F(RetardedDelay, ScalesLinearlyWithDistance) {
  // Powers of two scale exactly in floating point.
  for (int i = 0; i < 200; ++i) {
    const Vec3 delta = random_unit() * uniform(0.5, 2.0);
    const Vec3 beta = random_beta(0.9999);
    const double tau = retarded_delay(delta, beta);
    EXPECT_EQ(retarded_delay(delta * 0x1p30, beta), tau * 0x1p30);
    EXPECT_EQ(retarded_delay(delta * 0x1p-30, beta), tau * 0x1p-30);
  }
}

}  // namespace
}  // namespace lightcone

// Null geodesics of one Schwarzschild black hole, in closed form (PHYSICS.md, "Curved
// spacetime"): G = c = 1, M the gravitational radius, f = 1 - 2M/r, u = 1/r, impact parameter
// b = L/E, and the orbit equation (du/dphi)^2 = 1/b^2 - u^2 (1 - 2Mu). No step size anywhere:
// the turning points are the roots of a cubic (trigonometric form), the swept angle is
// Carlson's R_F (Carlson 1995; Boost.Math) and the coordinate time his R_F, R_D, R_J and R_C,
// so the answers are exact to rounding, also near the critical impact parameter
// b_c = 3 sqrt(3) M, where the angle and the time diverge logarithmically.
#pragma once

namespace lightcone {

// The most rays whose orbits and sweeps are prepared at once (photon_orbits, prepare_sweeps): a
// packet of camera rays.
inline constexpr int kMaxSweeps = 8;

// Jacobi's elliptic functions sn, cn, dn of one modulus k at many arguments. Descending Landen
// (Gauss) transformations k -> k_1 -> k_2 ..., k_{i+1} = (1 - k_i') / (1 + k_i') (DLMF 22.7.1-4),
// taken from k' so that k -> 1 loses no digits, at least three and on (up to kMaxSteps) until the
// modulus is below Boost.Math's threshold for its asymptotic form (A&S 16.13: sin, cos and 1 with
// their terms in k^2); then one evaluation is a sine and a cosine there and a division or so per
// step back up, where Boost's jacobi_elliptic would run its arithmetic-geometric mean with a sine
// and an arcsine per level on every call. Where three steps reach the threshold (k'^2 above 0.3:
// rays that turn beyond b = 5.8 M) the values are Boost's at k_3 to the bit.
struct JacobiModulus {
  // k'^2 down to some 1e-20 takes at most 7 steps, and no orbit but b = b_c has a smaller one (its
  // k'^2 is of order 1 - b_c / b or its square root); below, Boost evaluates the seventh modulus.
  static constexpr int kMaxSteps = 7;
  int steps = 0;
  double k[kMaxSteps] = {};  // k_1, k_2, ...
  double c[kMaxSteps] = {};  // 1 - k_1, 1 - k_2, ... (without cancellation)
  bool unit = false;         // k = 1 exactly (k' = 0): every k_i is 1
  double k2 = 0, kc2 = 0;    // k^2 and k'^2
  // The last modulus's argument per unit of the caller's: the caller's rate of k's argument
  // times the product of 1 / (1 + k_i), multiplied in that order.
  double rate = 1;
};
// From k^2 and k'^2 = 1 - k^2, both computed without cancellation, and k's argument per unit of
// the caller's.
JacobiModulus jacobi_modulus(double k2, double kc2, double rate = 1);
struct JacobiValues {
  double sn, cn, dn;
};
// sn, cn, dn of modulus k at argument y / modulus.rate: y is the argument of the last modulus.
JacobiValues jacobi_functions(const JacobiModulus& modulus, double y);

// b_c = 3 sqrt(3) M: rays with b < b_c that come from outside the photon sphere r = 3M fall
// into the hole; rays with b > b_c turn at a periapsis outside it.
double critical_impact_parameter(double mass);

// The turning points of the rays of impact parameter b about mass M. In w = b/r the orbit
// equation is (dw/dphi)^2 = 1 - w^2 + 2 (M/b) w^3; in v = r/b its roots solve the depressed cubic
// v^3 - v + 2M/b = 0, whose three real roots (b > b_c) are
//   v = (2/sqrt 3) cos(pi/3 - a), (2/sqrt 3) cos(pi/3 + a), -(2/sqrt 3) cos(a),
// with 3a = arccos(b_c/b); for b < b_c its one real root is -(2/sqrt 3) cosh(h) with
// 3h = arccosh(b_c/b). Both angles are taken from 1 - b_c/b, which keeps the roots and their
// gaps accurate as b -> b_c.
struct PhotonOrbit {
  double mass = 0;
  double impact = 0;  // b >= 0
  // b > b_c (every b > 0 when M = 0): rays outside r >= periapsis and rays inside
  // r <= inner_turning, nothing between. b <= b_c: every radius is reached.
  bool turning = false;
  double periapsis = 0;      // r_p in (3M, b] when turning, else 0
  double inner_turning = 0;  // r_3 in (2M, 3M) when turning (0 when M = 0), else 0
  bool critical = false;     // b = b_c exactly
  // The integrals' constants, in w = b/r (see schwarzschild.cpp).
  double w_neg = 0;  // -w_1 > 0: the negative root w_1 of 1 - w^2 + 2 (M/b) w^3
  double v_pos = 0;  // turning: r_p / b
  double v_gap = 0;  // turning: (r_p - r_3) / b, accurate as b -> b_c
  double scale = 0;  // turning: (r_p / b) (-1 / w_1); b <= b_c: 2M/b (the cubic's leading term)
  double quad_a = 0, modulus_c2 = 0;  // b <= b_c: A and k'^2 of Byrd & Friedman 239.00
  // b <= b_c: with z = w - w_1 the cubic is scale z ((z - pair_c)^2 + pair_n^2).
  double pair_c = 0, pair_n = 0;
  // The path r(phi) in Jacobi elliptic functions of modulus k (radius_after_angle), taken through
  // descending Landen steps from k' computed from the gaps above, so that k -> 1 (b -> b_c) loses
  // no digits: the argument at the last modulus advances by jacobi.rate per radian swept. No
  // steps for b = 0.
  JacobiModulus jacobi;
};

PhotonOrbit photon_orbit(double mass, double impact);
// photon_orbit for up to kMaxSweeps impact parameters at once (*out[i] for impacts[i]), each the
// same to the bit: their Landen moduli are taken together, step by step.
void photon_orbits(double mass, const double* impacts, PhotonOrbit* const* out, int n);

// The angle (>= 0) swept about the hole by a ray of this orbit between radii r_a and r_b
// (either may be infinity), along a stretch on which r is monotonic: the two radii lie in one
// allowed region, and a turning point may be either end. A radius in the forbidden gap
// (inner_turning, periapsis) whose orbit equation fails only by rounding counts as the nearer
// turning point (a ray sent tangentially); any other there gives NaN. Infinity if b = b_c
// exactly and the stretch reaches the photon sphere r = 3M.
double swept_angle(const PhotonOrbit& orbit, double r_a, double r_b);

// The radial tortoise coordinate r_* = r + 2M ln(r/2M - 1) (r > 2M; r when M = 0): the
// coordinate time of a radial ray is the difference of r_* at its ends.
double tortoise_coordinate(double mass, double r);

// The Schwarzschild coordinate time (>= 0) that light of this orbit takes between radii r_a and
// r_b, both > 2M, on one stretch on which r is monotonic (the conditions of swept_angle; a
// turning point may be either end). In closed form: dt/dphi = r^2 / (b f) is reduced to
// elliptic integrals of the first, second and third kind (Carlson 1989, 1991; R_F, R_D, R_J,
// R_C of Boost.Math, see schwarzschild.cpp and docs/physics.md). M = 0: the Euclidean length
// of the segment; b = 0: the difference of r_*. NaN for a radius <= 2M or one no ray of this b
// reaches on that stretch; infinity if a radius is infinite, or if b = b_c exactly and the
// stretch reaches the photon sphere r = 3M.
double coordinate_time(const PhotonOrbit& orbit, double r_a, double r_b);

// A ray between radius r (> 2M, in the region from which this orbit reaches infinity without
// turning: r >= periapsis when it turns) and infinity takes infinite coordinate time; its
// regularised time is
//   T_inf(r) = lim_{R -> inf} [ coordinate_time(r, R) - r_*(R) ],
// finite, with coordinate_time(r, R) = T_inf(r) + r_*(R) - b^2 / 2R + O(1 / R^2). So a ray leaving
// r at t_0 crosses a far radius R at t_0 + T_inf(r) + r_*(R), and the difference between two rays
// arriving far away is the difference of their T_inf. Radial: -r_*(r); M = 0: -sqrt(r^2 - b^2).
// NaN when no such stretch exists (inner region, forbidden gap, r <= 2M); infinity if b = b_c
// exactly and r <= 3M.
double coordinate_time_to_infinity(const PhotonOrbit& orbit, double r);

// Where a ray that passes radius r0 (> 2M) goes, and the angle it sweeps on the way.
enum class RayFate {
  kEscapes,       // to r = infinity
  kCaptured,      // to the horizon r = 2M
  kPhotonSphere,  // b = b_c exactly: it winds onto r = 3M forever
};
struct RayCourse {
  RayFate fate = RayFate::kEscapes;
  double turning_radius = 0;  // where dr/dphi changes sign on the way, 0 if it does not
  double angle_to_turn = 0;   // swept from r0 to the turning point (0 without one)
  double angle_total = 0;     // swept from r0 to infinity or to the horizon (infinity for
                              // kPhotonSphere)
};
// outward: whether r increases at r0. NaN angles if no ray of this b passes r0.
RayCourse ray_course(const PhotonOrbit& orbit, double r0, bool outward);

// The radius that a ray reaches after sweeping angle phi >= 0 along its path, the inverse of
// swept_angle: the ray passes r0 (> 0; infinity with outward false for a ray arriving from
// afar) with r increasing (outward) or decreasing, and goes on through its turning point if it
// has one (as ray_course describes). +infinity once it has escaped (phi >= ray_course's
// angle_total for an escaping ray), 2M once it has reached the horizon. For b = b_c exactly a ray
// of fate kPhotonSphere tends to 3M (3M at phi = infinity), and one that starts at r0 = 3M stays
// there. In closed form: r = b / w with w a rational function of Jacobi's sn and cn (Boost.Math)
// at an argument linear in phi (see schwarzschild.cpp); no root-finding. Accurate to a few ulps
// of the argument: the relative error of r is some eps (1 + phi) |d ln r / dphi| (which is
// ~ r / b far out), plus the same from the start's angle, also near b_c. A radial ray (b = 0)
// sweeps no angle: r0 for phi = 0, and its end (infinity outward, 2M inward) for any phi > 0.
// From inside the horizon (0 < r0 < 2M) only outward: a backward ray from there moves outward
// (every future-directed ray there moves inward), through r = 2M and on as from outside. NaN if
// no ray of this b passes r0 (r0 <= 0, inward inside 2M, or in the forbidden gap), or phi < 0
// or NaN.
double radius_after_angle(const PhotonOrbit& orbit, double r0, bool outward, double phi);

// The same, prepared once per ray (orbit, r0, direction) for many angles: prepare_sweep costs
// ray_course and one more of Carlson's R_F; radius_after_angle(sweep, phi) one Jacobi evaluation
// (jacobi_functions: a sine and a cosine) and a few flops, no allocation. The function above is
// these two composed.
struct AngleSweep {
  // Each form measures its argument from an end of the orbit equation's interval that the ray
  // never reaches (schwarzschild.cpp, "The path r(phi)").
  enum class Form : unsigned char {
    kAt,           // r0 for phi = 0, `end` for any phi > 0 (b = 0, or nothing left to sweep)
    kOuter,        // b > b_c, r >= periapsis: from w = w_1 < 0
    kInner,        // b > b_c, r <= inner_turning: from r = 0
    kCaptured,     // b <= b_c, starting at z = w - w_1 <= A: from z = 0 (w = w_1)
    kCapturedFar,  // b <= b_c, starting at z > A: from z = infinity (r = 0)
    kInvalid,      // NaN
  };
  Form form = Form::kInvalid;
  double r0 = 0;
  double angle_total = 0;      // ray_course's: the path ends here
  double turning_radius = 0;   // ray_course's, 0 without one (kAt, kInvalid: 0)
  double angle_to_turn = 0;    // ray_course's
  double end = 0;              // the radius past angle_total: infinity, 2M (3M for b = b_c exactly)
  double horizon = 0;          // 2M
  double phase = 0, rate = 0;  // the last modulus's argument at phi: phase + rate phi
  JacobiModulus jacobi;        // the orbit's
  double scale = 0, coef = 0;  // the form's constants (schwarzschild.cpp)
  double impact = 0, w_neg = 0;
};
AngleSweep prepare_sweep(const PhotonOrbit& orbit, double r0, bool outward);
// prepare_sweep for up to kMaxSweeps rays at once (a packet of camera rays), each sweep the same
// to the bit as its own: their Carlson integrals run together, where one ray's alone wait on
// their chains of square roots (*out[i] from starts[i]).
struct SweepStart {
  const PhotonOrbit* orbit;
  double r0;
  bool outward;
};
void prepare_sweeps(const SweepStart* starts, AngleSweep* const* out, int n);
double radius_after_angle(const AngleSweep& sweep, double phi);

// The total deflection of a ray from infinity that escapes again, b > b_c: 2 phi(r_p -> inf)
// - pi, which is Darwin's (1959) elliptic integral of the first kind in the periapsis. It is
// more than 2 pi n for rays that wind n times. Infinity for b <= b_c (no such ray).
double deflection_angle(double mass, double impact);

// A static observer at r > 2M sees a ray arrive (or sends one) at angle alpha from the outward
// radial direction: b = r sin(alpha) / sqrt(f(r)).
double static_impact_parameter(double mass, double r, double sin_alpha);

// The angular radius of the hole's shadow for a static observer at r > 2M, measured from the
// direction of the hole: sin(alpha_sh) = 3 sqrt(3) M sqrt(f(r)) / r (Synge 1966), above 90
// degrees inside the photon sphere (r < 3M).
double static_shadow_angle(double mass, double r);

// g = nu_received / nu_emitted between two static observers: sqrt(f(r_emitter) /
// f(r_observer)).
double static_frequency_shift(double mass, double r_emitter, double r_observer);

}  // namespace lightcone

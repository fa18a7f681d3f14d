// One leg of light from a point light to a surface patch (light_path.hpp) against derivations
// made here, independently of the kernels: closed forms for head-on and transverse geometries,
// an explicit boost of the photon's 4-momentum (PHYSICS.md's boost written out again below),
// the boosted stress-energy tensor of the light, energy, momentum and photon-number balance
// over a sphere of receivers, aberration, and seed 004's interceptor (the worked numbers of
// docs/design/light-transport.md).
//
// Conventions: the emitter (light) is P, the receiver (surface patch) S. A leg's `direction`
// is the propagation direction (from the light toward the patch) in S's rest frame;
// `emitted_direction` the same in P's rest frame. Rest frames are pure boosts of the common
// frame in which events and velocities are given.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "lightcone/physics/aberration.hpp"
#include "lightcone/physics/light_path.hpp"
#include "lightcone/physics/retarded_time.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;

// --- Independent helpers (none of them calls the kernels under test) ---

// Coordinates of event e in the frame moving with beta (origins coincide), written out from
// PHYSICS.md: t' = g (t - b.x), x' = x + [(g - 1)/b^2 (b.x) - g t] b.
Vec4 to_frame(const Vec3& beta, const Vec4& e) {
  const double b2 = dot(beta, beta);
  if (b2 == 0) return e;
  const double g = 1.0 / std::sqrt(1.0 - b2);
  const double bx = dot(beta, e.x);
  return {g * (e.t - bx), e.x + beta * ((g - 1.0) / b2 * bx - g * e.t)};
}

// The common frame's coordinates of an event given in the rest frame of a body moving with beta.
Vec4 from_frame(const Vec3& beta, const Vec4& e) {
  return to_frame(-beta, e);
}

double gamma_of(double b) {
  return 1.0 / std::sqrt(1.0 - b * b);
}

// A body at X0 + beta t and a flash at the origin at t = 0: the time t >= 0 at which the flash
// reaches the body, the root of |X0 + beta t| = t, i.e.
// (1 - b^2) t^2 - 2 (b.X0) t - |X0|^2 = 0.
double flash_arrival_time(const Vec3& x0, const Vec3& beta) {
  const double bx = dot(beta, x0), a = 1.0 - dot(beta, beta);
  return (bx + std::sqrt(bx * bx + a * dot(x0, x0))) / a;
}

// A light at X0 + beta t and a receiver at rest at the origin at t = 0: how long ago, tau >= 0,
// the light that arrives left it, the root of |X0 - beta tau| = tau.
double emission_delay(const Vec3& x0, const Vec3& beta) {
  const double bx = dot(beta, x0), a = 1.0 - dot(beta, beta);
  return (-bx + std::sqrt(bx * bx + a * dot(x0, x0))) / a;
}

void expect_vec_near(const Vec3& got, const Vec3& want, double tol) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> n(0, 1);
  return normalize(Vec3{n(rng), n(rng), n(rng)});
}

Vec3 random_velocity(std::mt19937& rng, double max_speed) {
  std::uniform_real_distribution<double> u(0, 1);
  return random_unit(rng) * (max_speed * std::cbrt(u(rng)));
}

// --- Limits ---

TEST(LightPath, EverythingAtRestIsTheInverseSquareLaw) {
  // A light at (1, 2, -2) and a patch at (3, 5, 4): 7 apart, light 7 time units on its way.
  const Vec4 emission{-4, {1, 2, -2}};
  const Vec4 reception{3, {3, 5, 4}};
  const ReceivedLeg leg = receive_leg(emission, {}, reception, {});
  EXPECT_EQ(leg.doppler, 1.0);
  EXPECT_DOUBLE_EQ(leg.distance, 7.0);
  expect_vec_near(leg.direction, Vec3{2, 3, 6} / 7.0, 1e-15);
  expect_vec_near(leg.emitted_direction, Vec3{2, 3, 6} / 7.0, 1e-15);
  EXPECT_DOUBLE_EQ(point_source_irradiance(leg, 2.5, 0.6), 2.5 * 0.6 / 49.0);
  EXPECT_DOUBLE_EQ(point_source_spectral_factor(leg, 0.6), 0.6 / 49.0);
  // Light from behind the patch, or grazing it, gives nothing.
  EXPECT_EQ(point_source_irradiance(leg, 2.5, -0.3), 0.0);
  EXPECT_EQ(point_source_irradiance(leg, 2.5, 0.0), 0.0);
  EXPECT_EQ(point_source_spectral_factor(leg, -0.3), 0.0);

  // At rest the time of the events does not matter (the approximate modes): the same leg.
  const ReceivedLeg late = receive_leg(emission, {}, {100, reception.x}, {});
  EXPECT_EQ(late.doppler, 1.0);
  EXPECT_DOUBLE_EQ(late.distance, 7.0);
  EXPECT_DOUBLE_EQ(point_source_irradiance(late, 2.5, 1.0), 2.5 / 49.0);
}

// A plane wave is the limit of a point source far away: a source of intensity I = E r_P^2 at
// distance r_P in its own frame gives irradiance E there. Seen by a receiver for which the
// source moves (r_S = D r_P), the point-source law D^4 I / r_S^2 is D^2 E, the plane-wave law,
// and likewise D^5 I_lambda / r_S^2 = D^3 E_lambda per wavelength.
TEST(LightPath, PlaneWaveIsThePointSourceLawAtInfinity) {
  for (const double beta : {0.6, -0.3, 0.0})
    for (const double r : {1e3, 1e6}) {
      const Vec4 emission{-r, {r, 0, 0}};  // on the past light cone of the origin event
      const ReceivedLeg leg = receive_leg(emission, {-beta, 0, 0}, {0, {0, 0, 0}}, {});
      const double d = leg.doppler, r_p = leg.distance / d, e = 2.5, cos_a = 0.7;
      EXPECT_NEAR(d, std::sqrt((1 + beta) / (1 - beta)), 1e-12);
      EXPECT_NEAR(plane_wave_irradiance(d, e, cos_a),
                  point_source_irradiance(leg, e * r_p * r_p, cos_a), 1e-12 * e);
      EXPECT_NEAR(plane_wave_spectral_factor(d, cos_a),
                  point_source_spectral_factor(leg, cos_a) * r_p * r_p, 1e-12);
    }
  EXPECT_EQ(plane_wave_irradiance(2.0, 1.0, -0.1), 0.0);
  EXPECT_EQ(plane_wave_spectral_factor(2.0, 0.0), 0.0);
}

// --- Closed forms: a static light at the origin flashing at t = 0, a moving patch ---
//
// With the light at rest in the common frame (P = common frame), the reception event is
// (r_P, r_P n_P) and the patch, moving with beta, sees
//   D = gamma (1 - beta.n_P)            (the photon's energy in S over that in P),
//   r_S = gamma (r_P - beta.r_P n_P) = D r_P   (time component of the boosted separation),
//   E_S = D^4 I cos / r_S^2 = D^2 I cos / r_P^2.
// beta = 0.6 makes the numbers exact: gamma = 1.25, sqrt(1.6/0.4) = 2.

struct HandLeg {
  const char* name;
  Vec4 emission;
  Vec3 beta_light;
  Vec4 reception;
  Vec3 beta_patch;
  double doppler, r_patch, r_light;
  Vec3 n_patch, n_light;
};

void check_hand_leg(const HandLeg& c) {
  SCOPED_TRACE(c.name);
  const ReceivedLeg leg = receive_leg(c.emission, c.beta_light, c.reception, c.beta_patch);
  EXPECT_NEAR(leg.doppler, c.doppler, 1e-13 * c.doppler);
  EXPECT_NEAR(leg.distance, c.r_patch, 1e-12 * c.r_patch);
  EXPECT_NEAR(c.r_patch, c.doppler * c.r_light, 1e-12 * c.r_patch);  // r_S = D r_P
  expect_vec_near(leg.direction, c.n_patch, 1e-13);
  expect_vec_near(leg.emitted_direction, c.n_light, 1e-13);
  const double intensity = 3.0;
  for (double cos_a : {1.0, 0.5, 0.1}) {
    const double surface_frame =
        std::pow(c.doppler, 4) * intensity * cos_a / (c.r_patch * c.r_patch);
    const double light_frame = c.doppler * c.doppler * intensity * cos_a / (c.r_light * c.r_light);
    const double e = point_source_irradiance(leg, intensity, cos_a);
    EXPECT_NEAR(e, surface_frame, 1e-12 * surface_frame);
    EXPECT_NEAR(e, light_frame, 1e-12 * light_frame);
    const double spectral = std::pow(c.doppler, 5) * cos_a / (c.r_patch * c.r_patch);
    EXPECT_NEAR(point_source_spectral_factor(leg, cos_a), spectral, 1e-12 * spectral);
  }
}

TEST(LightPath, MovingPatchHeadOnAndTransverseClosedForms) {
  const double b = 0.6, g = gamma_of(b), L = 10, h = 10;
  ASSERT_DOUBLE_EQ(g, 1.25);
  const Vec4 flash{0, {}};

  // Approaching head-on: the patch starts at (L, 0, 0) and moves toward the light. The flash
  // meets it at t = L/(1 + b); D = sqrt((1 + b)/(1 - b)) = 2. In its own frame the patch sat at
  // gamma L from the emission point all along: r_S = gamma L = D r_P.
  {
    const Vec3 x0{L, 0, 0}, beta{-b, 0, 0};
    const double t = flash_arrival_time(x0, beta);
    EXPECT_NEAR(t, L / (1 + b), 1e-12);
    check_hand_leg({"patch approaching",
                    flash,
                    {},
                    {t, x0 + beta * t},
                    beta,
                    2.0,
                    g * L,
                    L / (1 + b),
                    {1, 0, 0},
                    {1, 0, 0}});
  }
  // Receding head-on: t = L/(1 - b); D = sqrt((1 - b)/(1 + b)) = 1/2; again r_S = gamma L.
  {
    const Vec3 x0{L, 0, 0}, beta{b, 0, 0};
    const double t = flash_arrival_time(x0, beta);
    EXPECT_NEAR(t, L / (1 - b), 1e-12);
    check_hand_leg({"patch receding",
                    flash,
                    {},
                    {t, x0 + beta * t},
                    beta,
                    0.5,
                    g * L,
                    L / (1 - b),
                    {1, 0, 0},
                    {1, 0, 0}});
  }
  // 90 degrees IN THE LIGHT'S FRAME: the light reaches the patch along +y while the patch moves
  // along +x (beta.n_P = 0). The patch passes (0, h, 0) at t = h, so it started at (-b h, h, 0).
  // D = gamma (the transverse blueshift of a receiver moving across the light), r_S = gamma h,
  // and in the patch's frame the light comes tilted against the motion:
  // n_S = n_P/gamma - beta = (-0.6, 0.8, 0) (aberration toward the direction of motion).
  {
    const Vec3 x0{-b * h, h, 0}, beta{b, 0, 0};
    const double t = flash_arrival_time(x0, beta);
    EXPECT_NEAR(t, h, 1e-12);
    check_hand_leg({"90 degrees in the light's frame",
                    flash,
                    {},
                    {t, x0 + beta * t},
                    beta,
                    g,
                    g * h,
                    h,
                    {-b, 1 / g, 0},
                    {0, 1, 0}});
  }
  // 90 degrees IN THE PATCH'S FRAME: the light reaches the patch perpendicular to its motion as
  // the patch measures it (beta.n_S = 0). That is the patch at closest approach (0, h, 0) at the
  // flash: the flash arrives at t = gamma h, n_P = n_S/gamma + beta = (0.6, 0.8, 0), and
  // D = gamma (1 - b^2) = 1/gamma (the transverse redshift of a source moving across the line
  // of sight); r_S = h, r_P = gamma h.
  {
    const Vec3 x0{0, h, 0}, beta{b, 0, 0};
    const double t = flash_arrival_time(x0, beta);
    EXPECT_NEAR(t, g * h, 1e-12);
    check_hand_leg({"90 degrees in the patch's frame",
                    flash,
                    {},
                    {t, x0 + beta * t},
                    beta,
                    1 / g,
                    h,
                    g * h,
                    {0, 1, 0},
                    {b, 1 / g, 0}});
  }
}

// --- Closed forms: a patch at rest at the origin receiving at t = 0, a moving light ---
//
// The light is at X0 + v t; its emission event is at -tau with |X0 - v tau| = tau.
// D = 1 / (gamma (1 - v.n_S)), r_S = tau, r_P = r_S / D.

TEST(LightPath, MovingLightHeadOnAndTransverseClosedForms) {
  const double b = 0.6, g = gamma_of(b), L = 10, h = 10;
  const Vec4 patch{0, {}};
  auto emission = [](const Vec3& x0, const Vec3& v, double tau) {
    // The kernel that the renderer uses for this must agree with the closed form here.
    EXPECT_NEAR(retarded_delay(x0, v), tau, 1e-12 * tau);
    return Vec4{-tau, x0 - v * tau};
  };

  // Approaching head-on: the light, now at (-L, 0, 0), flies toward the patch. It left the
  // light tau = L/(1 - b) ago (r_S = 25); D = sqrt((1 + b)/(1 - b)) = 2; r_P = r_S/D = gamma L.
  {
    const Vec3 x0{-L, 0, 0}, v{b, 0, 0};
    const double tau = emission_delay(x0, v);
    EXPECT_NEAR(tau, L / (1 - b), 1e-12);
    check_hand_leg({"light approaching",
                    emission(x0, v, tau),
                    v,
                    patch,
                    {},
                    2.0,
                    L / (1 - b),
                    g * L,
                    {1, 0, 0},
                    {1, 0, 0}});
  }
  // Receding: tau = L/(1 + b), D = 1/2, r_P = gamma L again.
  {
    const Vec3 x0{-L, 0, 0}, v{-b, 0, 0};
    const double tau = emission_delay(x0, v);
    EXPECT_NEAR(tau, L / (1 + b), 1e-12);
    check_hand_leg({"light receding",
                    emission(x0, v, tau),
                    v,
                    patch,
                    {},
                    0.5,
                    L / (1 + b),
                    g * L,
                    {1, 0, 0},
                    {1, 0, 0}});
  }
  // 90 degrees IN THE PATCH'S FRAME: the light was emitted from (0, -h, 0), straight below the
  // patch, at t = -h, so it is now at (b h, -h, 0). D = 1/gamma; r_S = h, r_P = gamma h; in
  // the light's frame the light left along n_P = (-b, 1/gamma, 0).
  {
    const Vec3 x0{b * h, -h, 0}, v{b, 0, 0};
    const double tau = emission_delay(x0, v);
    EXPECT_NEAR(tau, h, 1e-12);
    check_hand_leg({"90 degrees in the patch's frame",
                    emission(x0, v, tau),
                    v,
                    patch,
                    {},
                    1 / g,
                    h,
                    g * h,
                    {0, 1, 0},
                    {-b, 1 / g, 0}});
  }
  // 90 degrees IN THE LIGHT'S FRAME: the light is at its closest approach (0, -h, 0) now;
  // tau = gamma h, it left from (-b gamma h, -h, 0); n_S = (b, 1/gamma, 0), n_P = (0, 1, 0),
  // D = gamma, r_S = gamma h, r_P = h. (This is seed 004's interceptor as the moon sees it.)
  {
    const Vec3 x0{0, -h, 0}, v{b, 0, 0};
    const double tau = emission_delay(x0, v);
    EXPECT_NEAR(tau, g * h, 1e-12);
    check_hand_leg({"90 degrees in the light's frame",
                    emission(x0, v, tau),
                    v,
                    patch,
                    {},
                    g,
                    g * h,
                    h,
                    {b, 1 / g, 0},
                    {0, 1, 0}});
  }
}

// --- General legs against an explicit boost of the photon's 4-momentum ---

struct RandomLeg {
  Vec4 emission, reception;
  Vec3 beta_light, beta_patch;
};

RandomLeg random_null_leg(std::mt19937& rng, double max_speed) {
  std::uniform_real_distribution<double> u(-20, 20), len(0.01, 50);
  RandomLeg c;
  c.emission = {u(rng), {u(rng), u(rng), u(rng)}};
  const double r = len(rng);
  c.reception = c.emission + Vec4{r, random_unit(rng) * r};
  c.beta_light = random_velocity(rng, max_speed);
  c.beta_patch = random_velocity(rng, max_speed);
  return c;
}

TEST(LightPath, GeneralLegEqualsTheBoostedPhotonMomentum) {
  std::mt19937 rng(11);
  for (int i = 0; i < 2000; ++i) {
    const RandomLeg c = random_null_leg(rng, 0.95);
    // The separation is along the photon's 4-momentum; its time component in a frame is the
    // distance there and is proportional to the photon's energy there.
    const Vec4 k = c.reception - c.emission;
    const Vec4 k_s = to_frame(c.beta_patch, k), k_p = to_frame(c.beta_light, k);
    const double d = k_s.t / k_p.t;
    const ReceivedLeg leg = receive_leg(c.emission, c.beta_light, c.reception, c.beta_patch);
    EXPECT_NEAR(leg.doppler, d, 1e-11 * d);
    EXPECT_NEAR(leg.distance, k_s.t, 1e-11 * k_s.t);
    expect_vec_near(leg.direction, k_s.x / k_s.t, 1e-11);
    expect_vec_near(leg.emitted_direction, k_p.x / k_p.t, 1e-11);
    // E = D^4 I cos / r_S^2 = D^2 I cos / r_P^2.
    const double e = point_source_irradiance(leg, 1.7, 0.4);
    const double want = d * d * 1.7 * 0.4 / (k_p.t * k_p.t);
    EXPECT_NEAR(e, want, 1e-10 * want);
  }
}

// The irradiance from the light's stress-energy tensor: in P's rest frame the light at the
// reception event is null dust streaming along n_P with energy flux I / r_P^2, so
// T^{mu nu} = (I / r_P^2) (1, n_P)^mu (1, n_P)^nu. Carried to S's rest frame by the full Lorentz
// matrix Lambda = B(beta_S) B(-beta_P) (T_S = Lambda T Lambda^T), the energy flux through a patch
// with unit normal N (S's frame) is -T_S^{0i} N_i. No Doppler factor appears in this derivation.
TEST(LightPath, IrradianceEqualsTheEnergyFluxOfTheBoostedStressEnergyTensor) {
  std::mt19937 rng(12);
  for (int i = 0; i < 500; ++i) {
    const RandomLeg c = random_null_leg(rng, 0.95);
    const double intensity = 2.0;
    const Vec4 k = c.reception - c.emission;
    const Vec4 k_p = to_frame(c.beta_light, k);
    const double r_p = k_p.t;
    const Vec3 n_p = k_p.x / r_p;
    // Lambda as a matrix: column j is the image of the j-th basis 4-vector.
    double lambda[4][4];
    for (int j = 0; j < 4; ++j) {
      Vec4 basis{j == 0 ? 1.0 : 0.0, {j == 1 ? 1.0 : 0.0, j == 2 ? 1.0 : 0.0, j == 3 ? 1.0 : 0.0}};
      const Vec4 col = to_frame(c.beta_patch, from_frame(c.beta_light, basis));
      lambda[0][j] = col.t;
      for (int a = 0; a < 3; ++a) lambda[a + 1][j] = col.x[a];
    }
    const double kp[4] = {1.0, n_p.x, n_p.y, n_p.z};
    double t_p[4][4], t_s[4][4];
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) t_p[a][b] = intensity / (r_p * r_p) * kp[a] * kp[b];
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        double s = 0;
        for (int m = 0; m < 4; ++m)
          for (int n = 0; n < 4; ++n) s += lambda[a][m] * t_p[m][n] * lambda[b][n];
        t_s[a][b] = s;
      }
    const Vec3 poynting{t_s[0][1], t_s[0][2], t_s[0][3]};
    // A patch normal facing the incoming light within 80 degrees.
    const Vec3 n_s = normalize(poynting);
    Vec3 normal = normalize(-n_s + random_unit(rng) * 0.9);
    if (dot(normal, n_s) > -0.2) normal = -n_s;
    const double flux = -dot(poynting, normal);

    const ReceivedLeg leg = receive_leg(c.emission, c.beta_light, c.reception, c.beta_patch);
    const double cos_a = -dot(normal, leg.direction);
    EXPECT_NEAR(point_source_irradiance(leg, intensity, cos_a), flux, 1e-10 * flux);
    // The light's energy density there, T_S^00, is D^2 I / r_P^2 = D^4 I / r_S^2.
    EXPECT_NEAR(point_source_irradiance(leg, intensity, 1.0), t_s[0][0], 1e-10 * t_s[0][0]);
  }
}

// The irradiance is the same whatever common frame the events and velocities are written in:
// D and the receiver-frame distance are invariants of the leg (the directions are not: rest
// frames defined as pure boosts of different common frames differ by a Wigner rotation).
TEST(LightPath, DopplerAndDistanceDoNotDependOnTheCommonFrame) {
  std::mt19937 rng(13);
  auto moved = [](const Vec3& frame, const Vec3& beta) {
    const double g = 1.0 / std::sqrt(1.0 - dot(beta, beta));
    const Vec4 u = to_frame(frame, Vec4{g, beta * g});
    return u.x / u.t;
  };
  for (int i = 0; i < 500; ++i) {
    RandomLeg c = random_null_leg(rng, 0.9);
    if (i % 2) c.reception.t += 5;  // also the approximate (non-null) legs
    const Vec3 frame = random_velocity(rng, 0.9);
    const ReceivedLeg a = receive_leg(c.emission, c.beta_light, c.reception, c.beta_patch);
    const ReceivedLeg b = receive_leg(to_frame(frame, c.emission), moved(frame, c.beta_light),
                                      to_frame(frame, c.reception), moved(frame, c.beta_patch));
    EXPECT_NEAR(a.doppler, b.doppler, 1e-10 * a.doppler);
    EXPECT_NEAR(a.distance, b.distance, 1e-10 * a.distance);
    EXPECT_NEAR(dot(a.direction, a.direction), 1.0, 1e-14);
  }
}

// --- Aberration of the incidence direction ---
//
// aberration.hpp takes LOOK directions (toward the source), the opposite of propagation: the
// patch looks toward the light along -n_S, the light "looks" back along -n_P. From P's frame to
// S's frame go out of P's frame into the common frame, then into S's frame (both pure boosts).
TEST(LightPath, IncidenceDirectionIsTheAberratedEmissionDirection) {
  std::mt19937 rng(14);
  for (int i = 0; i < 1000; ++i) {
    RandomLeg c = random_null_leg(rng, 0.95);
    const ReceivedLeg leg = receive_leg(c.emission, c.beta_light, c.reception, c.beta_patch);
    const Vec3 look_common = aberrate_out_of_moving_frame(-leg.emitted_direction, c.beta_light);
    expect_vec_near(-leg.direction, aberrate_into_moving_frame(look_common, c.beta_patch), 1e-11);
    const Vec3 back = aberrate_out_of_moving_frame(-leg.direction, c.beta_patch);
    expect_vec_near(-leg.emitted_direction, aberrate_into_moving_frame(back, c.beta_light), 1e-11);
    // A light at rest in the common frame: a single aberration.
    const ReceivedLeg rest = receive_leg(c.emission, {}, c.reception, c.beta_patch);
    expect_vec_near(
        -rest.direction,
        aberrate_into_moving_frame(-normalize(c.reception.x - c.emission.x), c.beta_patch), 1e-11);
  }
}

// --- Energy, momentum and photon number over a sphere of receivers ---
//
// A light moving with v flashes for a proper time dt at the origin. Receivers at rest in the
// common frame S on a sphere of radius R all receive that flash. Each receives for a time dt/D
// (proper-time intervals scale as frequencies), so the energy per area it collects is
// E_S dt / D = D^3 I dt / R^2. In total that must be the energy of the flash in S: in P's frame
// it is 4 pi I dt with zero momentum, so in S it is gamma 4 pi I dt with momentum
// gamma v 4 pi I dt. The photon count (energy over photon energy D e_P) is invariant: 4 pi I
// dt/e_P. (Analytically: integral of D^3 dOmega = 4 pi gamma, of D^2 dOmega = 4 pi.)
TEST(LightPath, SphereOfReceiversCollectsTheFlashsEnergyMomentumAndPhotons) {
  const Vec3 v = normalize(Vec3{1, 2, 2}) * 0.8;
  const double g = 1.0 / std::sqrt(1.0 - dot(v, v));
  const double intensity = 1.3, radius = 7.0, dt = 1.0;
  const int n_mu = 2000, n_phi = 128;
  double energy = 0, photons = 0;
  Vec3 momentum;
  for (int i = 0; i < n_mu; ++i) {
    const double mu = -1.0 + (i + 0.5) * 2.0 / n_mu;
    const double s = std::sqrt(1.0 - mu * mu);
    for (int j = 0; j < n_phi; ++j) {
      const double phi = 2 * kPi * j / n_phi;
      const Vec3 n{s * std::cos(phi), s * std::sin(phi), mu};
      const ReceivedLeg leg = receive_leg({0, {}}, v, {radius, n * radius}, {});
      const double area = radius * radius * (2.0 / n_mu) * (2 * kPi / n_phi);
      const double collected = point_source_irradiance(leg, intensity, 1.0) * dt / leg.doppler;
      energy += collected * area;
      momentum += n * (collected * area);
      photons += collected * area / leg.doppler;  // in units of the emitted photon energy
    }
  }
  const double emitted = 4 * kPi * intensity * dt;
  EXPECT_NEAR(energy, g * emitted, 1e-5 * g * emitted);
  expect_vec_near(momentum, v * (g * emitted), 1e-5 * g * emitted);
  EXPECT_NEAR(photons, emitted, 1e-5 * emitted);
}

// --- Spectral irradiance ---

// Planck's law in units where hc/k = 1: B(T, lambda) = lambda^-5 / (exp(1/(lambda T)) - 1).
double planck(double temperature, double lambda) {
  return std::pow(lambda, -5) / std::expm1(1.0 / (lambda * temperature));
}

TEST(LightPath, SpectralFactorShiftsABlackbodyAndIntegratesToTheIrradiance) {
  std::mt19937 rng(15);
  for (int i = 0; i < 50; ++i) {
    const RandomLeg c = random_null_leg(rng, 0.9);
    const ReceivedLeg leg = receive_leg(c.emission, c.beta_light, c.reception, c.beta_patch);
    const double d = leg.doppler, r = leg.distance, cos_a = 0.7;
    const double factor = point_source_spectral_factor(leg, cos_a);
    // A point blackbody of temperature T lights the patch like one of temperature D T:
    // D^5 B(T, D lambda) = B(D T, lambda).
    const double temperature = 1.0;
    for (double lambda : {0.05, 0.2, 0.5, 2.0}) {
      const double want = planck(d * temperature, lambda) * cos_a / (r * r);
      EXPECT_NEAR(factor * planck(temperature, d * lambda), want, 1e-10 * want);
    }
    // Integrated over the patch's wavelengths the spectral irradiance gives the irradiance of
    // the integrated intensity: a spectrum I_lambda = lambda^2 exp(-lambda), I = 2.
    const int n = 20000;
    const double top = 60.0 / d, step = top / n;
    double sum = 0;
    for (int j = 0; j < n; ++j) {
      const double l = (j + 0.5) * step * d;
      sum += factor * l * l * std::exp(-l) * step;
    }
    const double want = point_source_irradiance(leg, 2.0, cos_a);
    EXPECT_NEAR(sum, want, 1e-6 * want);
  }
}

// --- Legs that are not null (the approximate light-delay modes) ---
//
// The kernel takes the receiver-frame spatial separation as the light's path: distance and
// direction from it, D and the emitted direction from the null 4-vector (1, direction) of the
// receiver's frame. Checked by hand and against the explicit boost.
TEST(LightPath, NonNullLegsUseTheReceiverFrameSeparation) {
  // "none" mode, by hand: a light at rest at the origin and a patch at (10, 0, 0) moving away
  // at 0.6 along +x, both at W time 0. In the patch's frame that separation is
  // (t, x) = (-gamma b L, gamma L, 0, 0) = (-7.5, 12.5, 0, 0): distance 12.5 along +x, and a
  // photon along +x reaching a receiver that recedes at 0.6 has D = sqrt(0.4/1.6) = 1/2.
  {
    const ReceivedLeg leg = receive_leg({0, {}}, {}, {0, {10, 0, 0}}, {0.6, 0, 0});
    EXPECT_NEAR(leg.distance, 12.5, 1e-12);
    EXPECT_NEAR(leg.doppler, 0.5, 1e-13);
    expect_vec_near(leg.direction, {1, 0, 0}, 1e-15);
    expect_vec_near(leg.emitted_direction, {1, 0, 0}, 1e-15);
    EXPECT_NEAR(point_source_irradiance(leg, 1.0, 1.0), 0.0625 / 156.25, 1e-15);
  }
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> u(-20, 20);
  for (int i = 0; i < 1000; ++i) {
    const Vec4 emission{u(rng), {u(rng), u(rng), u(rng)}};
    const Vec4 reception{u(rng), {u(rng), u(rng), u(rng)}};  // spacelike or timelike
    const Vec3 b_p = random_velocity(rng, 0.95), b_s = random_velocity(rng, 0.95);
    const Vec4 sep_s = to_frame(b_s, reception - emission);
    const double r = length(sep_s.x);
    if (r < 1e-3) continue;
    const Vec3 n_s = sep_s.x / r;
    const Vec4 k_p = to_frame(b_p, from_frame(b_s, Vec4{1.0, n_s}));
    const ReceivedLeg leg = receive_leg(emission, b_p, reception, b_s);
    EXPECT_NEAR(leg.distance, r, 1e-11 * r);
    expect_vec_near(leg.direction, n_s, 1e-11);
    EXPECT_NEAR(leg.doppler, 1.0 / k_p.t, 1e-11 / k_p.t);
    expect_vec_near(leg.emitted_direction, k_p.x / k_p.t, 1e-11);
  }
}

// --- Seed 004's interceptor: the worked numbers of docs/design/light-transport.md ---
//
// The moon is at rest in W; the lit point is at the origin with its normal along +y. The
// interceptor (a point light) flies at 0.5c along +x at height h = 10 over the point:
// X(t) = (0.5 t, 10, 0), overhead at t = 0. The camera is at rest at (0, 100, 0), 100 above the
// point, and observes at t_obs = 100, so the point it sees was lit at t = 0, when the
// interceptor was overhead.
//  surface: the light's event on the past light cone of the surface event (0, 0):
//           tau = gamma h = 11.547, at x = -b gamma h = -5.774: the light comes from
//           asin(b) = 30 degrees behind the normal; D = gamma; E = D^4 I cos / r^2 = gamma I/h^2.
//  camera:  the light's event on the camera's past light cone: with t_c its time,
//           (H - t_c)^2 = (b t_c)^2 + (H - h)^2, t_c = (H - sqrt(H^2 - (1 - b^2)(2 H h - h^2)))
//           / (1 - b^2) = 9.865, at x = b t_c = 4.932: 26.255 degrees ahead of the normal.
//  none:    the light at t_obs: x = 50, 78.690 degrees ahead.
TEST(LightPath, InterceptorWorkedNumbers) {
  const double b = 0.5, h = 10, big_h = 100, g = gamma_of(b);
  const Vec3 v{b, 0, 0};
  auto light_at = [&](double t) { return Vec3{b * t, h, 0}; };
  const Vec3 normal{0, 1, 0};
  const Vec4 camera{big_h, {0, big_h, 0}};
  // The surface event on the camera's past light cone (everything at rest but the light).
  const Vec4 surface{camera.t - length(camera.x), {}};
  ASSERT_EQ(surface.t, 0.0);

  const double tau_s = retarded_delay(light_at(surface.t) - surface.x, v);
  const Vec4 event_s{surface.t - tau_s, light_at(surface.t - tau_s)};
  const double tau_c = retarded_delay(light_at(camera.t) - camera.x, v);
  const Vec4 event_c{camera.t - tau_c, light_at(camera.t - tau_c)};
  const Vec4 event_n{camera.t, light_at(camera.t)};

  const ReceivedLeg surface_leg = receive_leg(event_s, v, surface, {});
  const ReceivedLeg camera_leg = receive_leg(event_c, v, surface, {});
  const ReceivedLeg none_leg = receive_leg(event_n, v, surface, {});

  // Closed forms.
  EXPECT_NEAR(tau_s, g * h, 1e-12);
  const double t_c =
      (big_h - std::sqrt(big_h * big_h - (1 - b * b) * (2 * big_h * h - h * h))) / (1 - b * b);
  EXPECT_NEAR(event_c.t, t_c, 1e-11);
  auto degrees = [](double rad) { return rad * 180 / kPi; };
  const double to_light_s = degrees(std::asin(b));  // behind the normal (-x side)
  const double to_light_c = degrees(std::atan(b * t_c / h));
  const double to_light_n = degrees(std::atan(b * big_h / h));
  EXPECT_NEAR(degrees(std::acos(-dot(surface_leg.direction, normal))), to_light_s, 1e-9);
  EXPECT_GT(surface_leg.direction.x, 0);  // Light from the -x side travels toward +x...
  EXPECT_NEAR(degrees(std::acos(-dot(camera_leg.direction, normal))), to_light_c, 1e-9);
  EXPECT_LT(camera_leg.direction.x, 0);  // ...and from the +x side in camera mode.
  const double between = degrees(std::acos(dot(surface_leg.direction, camera_leg.direction)));
  EXPECT_NEAR(between, to_light_s + to_light_c, 1e-9);

  // The numbers written in docs/design/light-transport.md.
  EXPECT_NEAR(tau_s, 11.547, 5e-4);
  EXPECT_NEAR(event_s.t, -11.547, 5e-4);
  EXPECT_NEAR(event_s.x.x, -5.774, 5e-4);
  EXPECT_NEAR(tau_c, 90.135, 5e-4);
  EXPECT_NEAR(event_c.x.x, 4.932, 5e-4);
  EXPECT_NEAR(event_c.t, 9.865, 5e-4);  // after the surface event (t = 0) it lights
  EXPECT_NEAR(to_light_s, 30.0, 1e-9);
  EXPECT_NEAR(to_light_c, 26.255, 5e-4);
  EXPECT_NEAR(between, 56.255, 5e-4);
  EXPECT_NEAR(to_light_n, 78.690, 5e-4);
  EXPECT_NEAR(degrees(std::acos(dot(surface_leg.direction, none_leg.direction))), 108.690, 5e-4);
  // Doppler factors and irradiance in units of I / h^2 (a static light overhead gives 1).
  const double unit = 1.0 / (h * h);
  auto lit = [&](const ReceivedLeg& leg) {
    return point_source_irradiance(leg, 1.0, -dot(leg.direction, normal)) / unit;
  };
  EXPECT_NEAR(surface_leg.doppler, g, 1e-12);
  EXPECT_NEAR(lit(surface_leg), g, 1e-12);  // D^4 cos / r^2 = g^4 (1/g) / (g h)^2 = g / h^2
  EXPECT_NEAR(surface_leg.doppler, 1.155, 5e-4);
  EXPECT_NEAR(camera_leg.doppler, 0.709, 5e-4);
  EXPECT_NEAR(none_leg.doppler, 0.581, 5e-4);
  EXPECT_NEAR(lit(surface_leg), 1.155, 5e-4);
  EXPECT_NEAR(lit(camera_leg), 0.182, 5e-4);
  EXPECT_NEAR(lit(none_leg), 0.00086, 5e-6);
  EXPECT_NEAR(lit(surface_leg) / lit(camera_leg), 6.3, 0.05);

  // The camera-mode light direction at the moon depends on where the camera is; the surface
  // mode's cannot. The camera 100 from the point on the -x side, at (-60, 80, 0), observing
  // at t = 100: the light's camera-cone event is at t = 5.869, 16.353 degrees ahead.
  const Vec4 other_camera{100, {-60, 80, 0}};
  const double tau_other = retarded_delay(light_at(other_camera.t) - other_camera.x, v);
  EXPECT_NEAR(other_camera.t - tau_other, 5.869, 5e-4);
  const ReceivedLeg other_leg = receive_leg(
      {other_camera.t - tau_other, light_at(other_camera.t - tau_other)}, v, surface, {});
  EXPECT_NEAR(degrees(std::acos(-dot(other_leg.direction, normal))), 16.353, 5e-4);

  // The surface mode's own failure: lights are inertial. The interceptor braking with
  // coordinate acceleration a = 0.001 (X(t) = (b t - a t^2 / 2, h, 0), still at 0.5c at t = 0)
  // really lit the point from its event on the point's past light cone, found here by
  // bisection: x = -5.863 instead of -5.774, 30.384 degrees instead of 30.
  const double a = 0.001;
  auto braking = [&](double t) { return Vec3{b * t - a * t * t / 2, h, 0}; };
  double lo = 0, hi = 100;
  for (int i = 0; i < 200; ++i) {
    const double mid = (lo + hi) / 2;
    (length(braking(-mid)) > mid ? lo : hi) = mid;
  }
  const Vec3 braking_at = braking(-lo);
  EXPECT_NEAR(braking_at.x, -5.863, 5e-4);
  const double braking_angle = degrees(std::acos(braking_at.y / length(braking_at)));
  EXPECT_NEAR(braking_angle, 30.384, 5e-4);
  EXPECT_NEAR(braking_angle - to_light_s, 0.38, 5e-3);
}

}  // namespace
}  // namespace lightcone

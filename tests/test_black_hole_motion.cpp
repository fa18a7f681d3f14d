// A camera moving freely near a Schwarzschild black hole (docs/scene-format.md, "black_hole";
// physics/schwarzschild_geodesics.hpp): the closed forms of radial free fall and of circular
// orbits against the geodesic equations integrated step by step here (RK4), the metric's
// normalisation, quadratures of the proper time to the horizon and to r = 0, and the local
// speeds; the loader's `motion.orbit` and `motion.fall` and their defaults (their refusals are
// tests/test_black_hole_refusals.cpp's); and the command: info, render and animate along these
// motions, the shadow a falling camera sees (Synge's, aberrated by sqrt(2M/r)). Units: G = c = 1.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/hole_view.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/physics/schwarzschild_geodesics.hpp"
#include "lightcone/trace/scene_info.hpp"
#include "support/scene_file_test.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// Independent integrations

// A radial geodesic, integrated in proper time by classical RK4: d^2r/dtau^2 = -M/r^2 (from
// (dr/dtau)^2 = E^2 - 1 + 2M/r), dt/dtau = E / f.
struct RadialState {
  double r, p, t;  // r, dr/dtau, t
};
RadialState integrate_radial(double mass, double energy, RadialState s, double tau, int steps) {
  const double h = tau / steps;
  const auto derivative = [&](const RadialState& y) {
    return RadialState{y.p, -mass / (y.r * y.r), energy / (1 - 2 * mass / y.r)};
  };
  const auto add = [](const RadialState& y, const RadialState& d, double k) {
    return RadialState{y.r + k * d.r, y.p + k * d.p, y.t + k * d.t};
  };
  for (int i = 0; i < steps; ++i) {
    const RadialState k1 = derivative(s), k2 = derivative(add(s, k1, h / 2)),
                      k3 = derivative(add(s, k2, h / 2)), k4 = derivative(add(s, k3, h));
    s.r += h / 6 * (k1.r + 2 * k2.r + 2 * k3.r + k4.r);
    s.p += h / 6 * (k1.p + 2 * k2.p + 2 * k3.p + k4.p);
    s.t += h / 6 * (k1.t + 2 * k2.t + 2 * k3.t + k4.t);
  }
  return s;
}

// Composite Gauss-Legendre (5 points) of a smooth f on [a, b].
double integrate(const std::function<double(double)>& f, double a, double b, int pieces) {
  static constexpr double x[5] = {0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                  0.9061798459386640};
  static constexpr double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                  0.2369268850561891, 0.2369268850561891};
  const double h = (b - a) / pieces;
  double sum = 0;
  for (int i = 0; i < pieces; ++i) {
    const double mid = a + (i + 0.5) * h;
    for (int k = 0; k < 5; ++k) sum += w[k] * f(mid + x[k] * h / 2);
  }
  return sum * h / 2;
}

// ---------------------------------------------------------------------------------------------
// Radial fall from rest at r0

TEST(RadialFall, FromRestFollowsTheIntegratedGeodesic) {
  for (const double mass : {1.0, 1.5}) {
    const double r0 = 12 * mass, energy = std::sqrt(1 - 2 * mass / r0);
    const RadialFall fall = RadialFall::from_rest(mass, r0);
    EXPECT_DOUBLE_EQ(fall.energy(), energy);
    EXPECT_FALSE(fall.is_from_infinity());
    const double horizon = fall.horizon_proper_time();
    for (const double fraction : {0.1, 0.5, 0.9, 0.99}) {
      const double tau = fraction * horizon;
      SCOPED_TRACE(testing::Message() << "M " << mass << " tau " << tau);
      const RadialState s = integrate_radial(mass, energy, {r0, 0, 0}, tau, 40000);
      const RadialFallPoint p = fall.at_proper_time(tau);
      EXPECT_NEAR(p.radius, s.r, 1e-10 * r0);
      EXPECT_NEAR(p.coordinate_time, s.t, 1e-9 * s.t);
      // The static observer measures (dr/dtau) / E.
      EXPECT_NEAR(p.local_velocity, s.p / energy, 1e-9);
      // 1 - v^2 = f / E^2.
      EXPECT_NEAR(1 - p.local_velocity * p.local_velocity,
                  (1 - 2 * mass / p.radius) / (energy * energy), 1e-12);
      // Back from the radius and from the coordinate time.
      EXPECT_NEAR(fall.proper_time_at_radius(p.radius), tau, 1e-9 * horizon);
      EXPECT_NEAR(fall.proper_time_at_coordinate_time(p.coordinate_time), tau, 1e-12 * horizon);
    }
  }
}

TEST(RadialFall, BeforeTheStartItRisesOnTheSameGeodesic) {
  const double mass = 1, r0 = 10;
  const RadialFall fall = RadialFall::from_rest(mass, r0);
  const RadialFallPoint start = fall.at_proper_time(0);
  EXPECT_EQ(start.radius, r0);
  EXPECT_EQ(start.coordinate_time, 0);
  EXPECT_EQ(start.local_velocity, 0);
  for (const double tau : {0.5, 7.0, 30.0}) {
    const RadialFallPoint later = fall.at_proper_time(tau), earlier = fall.at_proper_time(-tau);
    EXPECT_DOUBLE_EQ(earlier.radius, later.radius);
    EXPECT_DOUBLE_EQ(earlier.coordinate_time, -later.coordinate_time);
    EXPECT_DOUBLE_EQ(earlier.local_velocity, -later.local_velocity);
    EXPECT_GT(earlier.local_velocity, 0);
    // Integrated backward from the start.
    const RadialState s =
        integrate_radial(mass, std::sqrt(1 - 2 * mass / r0), {r0, 0, 0}, -tau, 40000);
    EXPECT_NEAR(earlier.radius, s.r, 1e-10 * r0);
    EXPECT_NEAR(earlier.coordinate_time, s.t, 1e-9 * std::abs(s.t));
    EXPECT_NEAR(fall.proper_time_at_coordinate_time(earlier.coordinate_time), -tau, 1e-11);
  }
}

// The proper time from rest at r0 to the horizon and to r = 0, by quadrature of
// dtau = dr / sqrt(2M/r - 2M/r0) with r = r0 - w^2 (dtau = 2 sqrt(r r0 / 2M) dw, smooth).
TEST(RadialFall, ProperTimeToTheHorizonAndToTheSingularity) {
  for (const double mass : {1.0, 0.25})
    for (const double r0_in_m : {2.5, 6.0, 40.0}) {
      const double r0 = r0_in_m * mass;
      SCOPED_TRACE(testing::Message() << "M " << mass << " r0 " << r0);
      const RadialFall fall = RadialFall::from_rest(mass, r0);
      const auto dtau_dw = [&](double w) { return 2 * std::sqrt((r0 - w * w) * r0 / (2 * mass)); };
      EXPECT_NEAR(fall.horizon_proper_time(), integrate(dtau_dw, 0, std::sqrt(r0 - 2 * mass), 200),
                  1e-12 * fall.horizon_proper_time());
      // To r = 0: (pi / 2) sqrt(r0^3 / 2M) (the integrand is a quarter circle).
      const double singularity = kPi / 2 * std::sqrt(r0 * r0 * r0 / (2 * mass));
      EXPECT_NEAR(fall.proper_time_at_radius(0), singularity, 1e-14 * singularity);
      EXPECT_LT(fall.horizon_proper_time(), singularity);
      // Inside the horizon only the radius is given, 0 from the singularity on.
      const RadialFallPoint inside =
          fall.at_proper_time((fall.horizon_proper_time() + singularity) / 2);
      EXPECT_LT(inside.radius, 2 * mass);
      EXPECT_GT(inside.radius, 0);
      EXPECT_TRUE(std::isnan(inside.coordinate_time));
      EXPECT_EQ(fall.at_proper_time(2 * singularity).radius, 0);
    }
}

TEST(RadialFall, CoordinateTimeGrowsWithoutBoundAtTheHorizon) {
  const RadialFall fall = RadialFall::from_rest(1, 10);
  double previous = -1;
  for (double gap = 1; gap > 1e-12; gap /= 10) {
    const double tau = fall.proper_time_at_radius(2 + gap);
    const RadialFallPoint p = fall.at_proper_time(tau);
    EXPECT_NEAR(p.radius, 2 + gap, 1e-12 * 10 + 1e-3 * gap);
    EXPECT_GT(p.coordinate_time, previous);
    previous = p.coordinate_time;
    // The local speed approaches that of light.
    EXPECT_NEAR(-p.local_velocity, std::sqrt(1 - (gap / (2 + gap)) / 0.8), 1e-9);
  }
  EXPECT_GT(previous, 90);  // t grows like 4M ln(1 / gap)
  // Far later than double precision resolves: the horizon's proper time.
  EXPECT_EQ(fall.proper_time_at_coordinate_time(1e6), fall.horizon_proper_time());
  EXPECT_EQ(fall.proper_time_at_coordinate_time(-1e6), -fall.horizon_proper_time());
}

// ---------------------------------------------------------------------------------------------
// Radial fall from rest at infinity

TEST(RadialFall, FromInfinityFollowsTheIntegratedGeodesic) {
  for (const double mass : {1.0, 3.0}) {
    const double reference = 30 * mass;
    const RadialFall fall = RadialFall::from_infinity(mass, reference);
    EXPECT_TRUE(fall.is_from_infinity());
    EXPECT_EQ(fall.energy(), 1);
    const RadialState start{reference, -std::sqrt(2 * mass / reference), 0};
    const double horizon = fall.horizon_proper_time();
    for (const double tau :
         {-200 * mass, -10 * mass, 0.3 * horizon, 0.9 * horizon, 0.999 * horizon}) {
      SCOPED_TRACE(testing::Message() << "M " << mass << " tau " << tau);
      const RadialState s = integrate_radial(mass, 1, start, tau, 40000);
      const RadialFallPoint p = fall.at_proper_time(tau);
      EXPECT_NEAR(p.radius, s.r, 1e-10 * s.r);
      EXPECT_NEAR(p.coordinate_time, s.t, 1e-9 * std::abs(s.t));
      EXPECT_NEAR(p.local_velocity, s.p, 1e-9);
      // The local speed is the escape speed sqrt(2M/r).
      EXPECT_NEAR(p.local_velocity, -std::sqrt(2 * mass / p.radius), 1e-14);
      EXPECT_NEAR(fall.proper_time_at_radius(p.radius), tau, 1e-10 * std::abs(tau) + 1e-12);
      EXPECT_NEAR(fall.proper_time_at_coordinate_time(p.coordinate_time), tau,
                  1e-11 * std::abs(tau) + 1e-12);
    }
    // r = (9M/2)^(1/3) (tau_0 - tau)^(2/3), tau_0 the proper time at r = 0.
    const double tau0 = fall.proper_time_at_radius(0);
    EXPECT_NEAR(tau0, 2.0 / 3 * std::pow(reference, 1.5) / std::sqrt(2 * mass), 1e-13 * tau0);
    for (const double tau : {-50.0, 0.0, 0.5 * horizon})
      EXPECT_NEAR(fall.at_proper_time(tau).radius,
                  std::cbrt(4.5 * mass) * std::pow(tau0 - tau, 2.0 / 3), 1e-13 * reference);
    // t = -2M [F(x) - F(x_ref)], F(x) = 2/3 x^3 + 2x + ln((x - 1)/(x + 1)), written plainly.
    const auto F = [&](double r) {
      const double x = std::sqrt(r / (2 * mass));
      return 2.0 / 3 * x * x * x + 2 * x + std::log((x - 1) / (x + 1));
    };
    for (const double tau : {-500.0, 0.5 * horizon}) {
      const RadialFallPoint p = fall.at_proper_time(tau);
      EXPECT_NEAR(p.coordinate_time, -2 * mass * (F(p.radius) - F(reference)),
                  1e-12 * std::abs(p.coordinate_time) * 10);
    }
  }
}

TEST(RadialFall, ExtremeScalesStayFinite) {
  // A tiny mass far away: the flat limit, at rest or on t = tau.
  const RadialFall rest = RadialFall::from_rest(1e-300, 1e10);
  const RadialFallPoint p = rest.at_proper_time(5);
  EXPECT_DOUBLE_EQ(p.radius, 1e10);
  EXPECT_DOUBLE_EQ(p.coordinate_time, 5);
  EXPECT_EQ(rest.proper_time_at_coordinate_time(5), 5);
  const RadialFall far = RadialFall::from_infinity(1e-300, 1e300);
  const RadialFallPoint q = far.at_proper_time(-3);
  EXPECT_DOUBLE_EQ(q.radius, 1e300);
  EXPECT_DOUBLE_EQ(q.coordinate_time, -3);
  EXPECT_TRUE(std::isfinite(q.local_velocity));
  // A huge mass.
  const RadialFall huge = RadialFall::from_rest(1e300, 1e301);
  const RadialFallPoint h = huge.at_proper_time(0.5 * huge.horizon_proper_time());
  EXPECT_TRUE(std::isfinite(h.coordinate_time));
  EXPECT_GT(h.radius, 2e300);
  EXPECT_LT(h.radius, 1e301);
}

// ---------------------------------------------------------------------------------------------
// Circular orbits

TEST(CircularOrbit, PeriodNormalisationAndTheIntegratedGeodesic) {
  for (const double mass : {1.0, 2.0})
    for (const double r_in_m : {3.5, 7.0, 10.0}) {
      const double r = r_in_m * mass;
      SCOPED_TRACE(testing::Message() << "M " << mass << " r " << r);
      const double omega = std::sqrt(mass / (r * r * r)), period = 2 * kPi / omega;
      const double tau_period = circular_orbit_proper_time(mass, r, period);
      const CircularOrbitPoint p = circular_orbit_at_proper_time(mass, r, tau_period);
      EXPECT_NEAR(p.coordinate_time, period, 1e-13 * period);
      EXPECT_NEAR(p.angle, 2 * kPi, 1e-13);
      // -1 = (-f + r^2 Omega^2) (dt/dtau)^2, with dt/dtau = t / tau.
      const double f = 1 - 2 * mass / r, ut = p.coordinate_time / tau_period;
      EXPECT_NEAR((-f + r * r * omega * omega) * ut * ut, -1, 1e-13);
      // The radial geodesic equation: Gamma^r_tt (u^t)^2 + Gamma^r_phiphi (u^phi)^2 = 0, i.e.
      // (M f / r^2) (u^t)^2 = r f (u^phi)^2.
      const double uphi = p.angle / tau_period;
      EXPECT_NEAR(mass * f / (r * r) * ut * ut, r * f * uphi * uphi, 1e-14 * ut * ut);
      // Speed relative to the static observer: r dphi / (sqrt(f) dt).
      EXPECT_NEAR(p.local_speed, r * omega / std::sqrt(f), 1e-14);
      EXPECT_NEAR(p.local_speed, std::sqrt(mass / (r - 2 * mass)), 1e-15);
    }
  // Integrated in the plane: r'' = -M/r^2 + L^2/r^3 - 3 M L^2/r^4, phi' = L/r^2, t' = E/f,
  // from the closed form's u^t and u^phi, over a quarter turn.
  const double mass = 1, r0 = 8;
  const double f0 = 1 - 2 * mass / r0, ut = 1 / std::sqrt(1 - 3 * mass / r0);
  const double L = r0 * r0 * std::sqrt(mass / (r0 * r0 * r0)) * ut, E = f0 * ut;
  std::array<double, 4> y{r0, 0, 0, 0};  // r, dr/dtau, phi, t
  const auto derivative = [&](const std::array<double, 4>& s) {
    const double r = s[0];
    return std::array<double, 4>{
        s[1], -mass / (r * r) + L * L / (r * r * r) - 3 * mass * L * L / (r * r * r * r),
        L / (r * r), E / (1 - 2 * mass / r)};
  };
  const double tau =
      circular_orbit_proper_time(mass, r0, kPi / 2 / std::sqrt(mass / (r0 * r0 * r0)));
  const int steps = 20000;
  const double h = tau / steps;
  for (int i = 0; i < steps; ++i) {
    std::array<double, 4> k[4], s = y;
    k[0] = derivative(y);
    for (int j = 0; j < 4; ++j) s[j] = y[j] + h / 2 * k[0][j];
    k[1] = derivative(s);
    for (int j = 0; j < 4; ++j) s[j] = y[j] + h / 2 * k[1][j];
    k[2] = derivative(s);
    for (int j = 0; j < 4; ++j) s[j] = y[j] + h * k[2][j];
    k[3] = derivative(s);
    for (int j = 0; j < 4; ++j) y[j] += h / 6 * (k[0][j] + 2 * k[1][j] + 2 * k[2][j] + k[3][j]);
  }
  const CircularOrbitPoint p = circular_orbit_at_proper_time(mass, r0, tau);
  EXPECT_NEAR(y[0], r0, 1e-10);
  EXPECT_NEAR(y[2], p.angle, 1e-10);
  EXPECT_NEAR(y[2], kPi / 2, 1e-10);
  EXPECT_NEAR(y[3], p.coordinate_time, 1e-9);
  EXPECT_TRUE(std::isnan(circular_orbit_at_proper_time(1, 3, 1).coordinate_time));
}

// ---------------------------------------------------------------------------------------------
// The scene format

using BlackHoleMotion = test::SceneFileTest;

// The camera's keys on line 2, the hole `hole` on line 3.
std::string camera_near(const std::string& camera, const std::string& hole = R"({"mass": 1})") {
  return "{\n  \"camera\": {" + camera + "},\n  \"black_hole\": " + hole + "\n}";
}

using test::expect_vec;

TEST_F(BlackHoleMotion, OrbitPlacesTheCameraOnItsCircle) {
  // Normal +y: the reference axis is +x, and counter-clockwise about +y turns +x toward -z.
  const Scene s =
      load(camera_near(R"("motion": {"orbit": {"radius": 10, "normal": [0, 2, 0], "phase": 90}})",
                       R"({"mass": 2, "position": [1, 2, 3]})"));
  const double r = 20, v = std::sqrt(2 / (r - 4));
  expect_vec(s.camera.world_line.position, {1, 2, 3 - r}, 1e-12);
  expect_vec(s.camera.world_line.velocity, {-v, 0, 0}, 1e-15);
  EXPECT_EQ(s.camera.world_line.time, 0);
  ASSERT_TRUE(s.camera.motion.geodesic);
  // A quarter period later (in coordinate time), a quarter turn on: at -x.
  const double omega = std::sqrt(2 / (r * r * r));
  const double tau = kPi / 2 / omega * std::sqrt(1 - 6 / r);
  const Scene later = load(camera_near(
      fmt::format(R"("motion": {{"orbit": {{"radius": 10, "normal": [0, 1, 0], "phase": 90}}}},
                   "proper_time": {:.17g})",
                  tau),
      R"({"mass": 2, "position": [1, 2, 3]})"));
  expect_vec(later.camera.world_line.position, {1 - r, 2, 3}, 1e-12);
  expect_vec(later.camera.world_line.velocity, {0, 0, v}, 1e-14);
  EXPECT_NEAR(later.camera.world_line.time, kPi / 2 / omega, 1e-12);
  EXPECT_DOUBLE_EQ(later.camera.world_line.proper_time, tau);
  // observation_after moves along the orbit too.
  const WorldLine after = observation_after(s.camera, tau);
  expect_vec(after.position, later.camera.world_line.position, 1e-12);
}

TEST_F(BlackHoleMotion, OrbitDefaultsAndTheReferenceAxis) {
  // Defaults: normal [0, 1, 0], phase 0: at +x, moving toward -z.
  const Scene s = load(camera_near(R"("motion": {"orbit": {"radius": 6}})"));
  expect_vec(s.camera.world_line.position, {6, 0, 0}, 1e-15);
  expect_vec(s.camera.world_line.velocity, {0, 0, -0.5}, 1e-15);  // 1/2 at the ISCO
  // A normal along x: the reference axis is +z; counter-clockwise about +x turns +z toward -y.
  const Scene x = load(camera_near(R"("motion": {"orbit": {"radius": 8, "normal": [-3, 0, 0]}})"));
  expect_vec(x.camera.world_line.position, {0, 0, 8}, 1e-15);
  expect_vec(x.camera.world_line.velocity, {0, std::sqrt(1 / 6.0), 0}, 1e-15);
  // Otherwise +x projected onto the plane: normal [1, 0, 1] gives [1, 0, -1] / sqrt(2).
  const Scene tilted =
      load(camera_near(R"("motion": {"orbit": {"radius": 8, "normal": [1, 0, 1]}})"));
  expect_vec(tilted.camera.world_line.position, {8 / std::sqrt(2), 0, -8 / std::sqrt(2)}, 1e-14);
}

TEST_F(BlackHoleMotion, FallFromRestAtR0) {
  // From camera.position: from rest there, along its direction.
  const std::string hole = R"({"mass": 2, "position": [1, 2, 3]})";
  const Scene at =
      load(camera_near(R"("position": [1, 2, 43], "motion": {"fall": {"time": 5}})", hole));
  expect_vec(at.camera.world_line.position, {1, 2, 43}, 0);
  expect_vec(at.camera.world_line.velocity, {0, 0, 0}, 0);
  EXPECT_EQ(at.camera.world_line.time, 5);
  // The same from "from" and "direction", observed later.
  const Scene later = load(camera_near(
      R"("motion": {"fall": {"from": 20, "direction": [0, 0, 3], "time": 5}}, "proper_time": 150)",
      hole));
  const RadialFallPoint p = RadialFall::from_rest(2, 40).at_proper_time(150);
  expect_vec(later.camera.world_line.position, {1, 2, 3 + p.radius}, 1e-12);
  expect_vec(later.camera.world_line.velocity, {0, 0, p.local_velocity}, 1e-15);
  EXPECT_DOUBLE_EQ(later.camera.world_line.time, 5 + p.coordinate_time);
  EXPECT_LT(p.local_velocity, -0.2);
  // All three given, agreeing.
  EXPECT_EQ(
      error(camera_near(
          R"("position": [1, 2, 43], "motion": {"fall": {"from": 20, "direction": [0, 0, 1]}})",
          hole)),
      "");
  // Before the start: rising on the same geodesic.
  const Scene before = load(camera_near(
      R"("motion": {"fall": {"from": 20, "direction": [0, 0, 1], "time": 5}}, "proper_time": -150)",
      hole));
  EXPECT_NEAR(before.camera.world_line.position.z, later.camera.world_line.position.z, 1e-12);
  EXPECT_NEAR(before.camera.world_line.velocity.z, -p.local_velocity, 1e-15);
  EXPECT_NEAR(before.camera.world_line.time, 5 - p.coordinate_time, 1e-12);
}

TEST_F(BlackHoleMotion, FallFromInfinityAndTheSpeedOfLight) {
  // speed_of_light 10: times in the scene's units (the fall's time 0.5 and proper time 2 are
  // 5 and 20 in the model's), lengths untouched.
  const Scene s = load(R"({
  "speed_of_light": 10,
  "camera": {"position": [0, 30, 0], "motion": {"fall": {"from": "infinity", "time": 0.5}},
             "proper_time": 2},
  "black_hole": {"mass": 1}
})");
  const RadialFallPoint p = RadialFall::from_infinity(1, 30).at_proper_time(20);
  expect_vec(s.camera.world_line.position, {0, p.radius, 0}, 1e-12);
  EXPECT_NEAR(s.camera.world_line.velocity.y, -std::sqrt(2 / p.radius), 1e-15);
  EXPECT_DOUBLE_EQ(s.camera.world_line.time, 5 + p.coordinate_time);
  EXPECT_DOUBLE_EQ(s.camera.motion.proper_time, 20);
}

// ---------------------------------------------------------------------------------------------
// What the camera sees

// Synge (1966): sin(alpha) = 3 sqrt(3) M sqrt(1 - 2M/r) / r (r >= 3M); aberrated for a camera
// moving toward the hole at beta: cos(alpha') = (cos(alpha) + beta) / (1 + beta cos(alpha)).
double synge_aberrated(double r, double beta) {
  const double a = std::asin(3 * std::sqrt(3.0) * std::sqrt(1 - 2 / r) / r);
  const double alpha = r >= 3 ? a : kPi - a;
  return std::acos((std::cos(alpha) + beta) / (1 + beta * std::cos(alpha)));
}

TEST_F(BlackHoleMotion, HoleFallingFromInfinitySeesSyngesShadowAberratedBySqrt2MOverR) {
  const RadialFall fall = RadialFall::from_infinity(1, 50);
  for (const double fraction : {-1.0, 0.0, 0.5, 0.9, 0.999}) {
    const double tau = fraction * fall.horizon_proper_time();
    SCOPED_TRACE(tau);
    const Scene s = load(camera_near(fmt::format(
        R"("position": [0, 0, 50], "motion": {{"fall": {{"from": "infinity"}}}}, "proper_time": {:.17g})",
        tau)));
    const HoleView hole = *hole_view(s);
    const double r = hole.camera_radius, beta = std::sqrt(2 / r);
    EXPECT_NEAR(length(s.camera.world_line.velocity), beta, 1e-15);
    const double expected = synge_aberrated(r, beta);
    EXPECT_NEAR(shadow_angle_for_camera(hole, s.camera.world_line.velocity), expected, 1e-9);
    // The rays themselves: the edge, by bisection, between captured and escaping.
    double lo = 0, hi = kPi;
    for (int i = 0; i < 100; ++i) {
      const double mid = (lo + hi) / 2;
      const Vec3 look{std::sin(mid), 0, -std::cos(mid)};
      (follow_curved_ray(hole, look).end == CurvedRayEnd::kHorizon ? lo : hi) = mid;
    }
    EXPECT_NEAR((lo + hi) / 2, expected, 1e-9);
  }
}

// Through the command: info and render for a camera on each motion; animate along a fall up to
// the horizon, refused there by frame.
TEST_F(BlackHoleMotion, InfoRenderAndAnimate) {
  const std::string sky = R"(,
  "sky": {"grid": {"background": [0.1, 0.1, 0.1]}})";
  const fs::path orbit = write("orbit.json",
                               "{\n  \"camera\": {\"width\": 48, \"height\": 27, "
                               "\"motion\": {\"orbit\": {\"radius\": 10, \"phase\": "
                               "30}}, \"proper_time\": 5},\n  \"black_hole\": "
                               "{\"mass\": 1, \"disk\": {}}" +
                                   sky + "\n}");
  const fs::path fall =
      write("fall.json",
            "{\n  \"camera\": {\"position\": [0, 0, 12], \"forward\": [0, 0, -1], \"fov\": 90, "
            "\"width\": 48, \"height\": 27, \"motion\": {\"fall\": {}}},\n  \"black_hole\": "
            "{\"mass\": 1}" +
                sky + "\n}");
  const test::CommandResult info = test::run_lightcone("info " + test::quoted(orbit));
  EXPECT_EQ(info.status, 0) << info.err;
  EXPECT_NE(info.out.find("camera at r = 10 (10 M)"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("speed 0.353553 c"), std::string::npos) << info.out;  // sqrt(1/8)
  for (const fs::path& scene : {orbit, fall}) {
    const fs::path out = dir_ / (scene.stem().string() + ".exr");
    const test::CommandResult r =
        test::run_lightcone("render " + test::quoted(scene) + " -o " + test::quoted(out));
    ASSERT_EQ(r.status, 0) << r.err;
    const auto image = load_image_file(out);
    for (const float v : image->rgb) ASSERT_TRUE(std::isfinite(v));
  }
  // From rest at 12M the horizon is reached at proper time 44.77, r = 0.05M at 46.2: frames 10
  // apart, the last past it.
  const RadialFall law = RadialFall::from_rest(1, 12);
  ASSERT_GT(law.horizon_proper_time(), 40);
  ASSERT_LT(law.proper_time_at_radius(0.05), 50);
  // The exposure is fixed: an automatic one is smoothed over neighbouring frames, which a
  // single render does not have.
  const std::string fixed_exposure = " --set render.exposure=0";
  const test::CommandResult frames =
      test::run_lightcone("animate " + test::quoted(fall) + fixed_exposure +
                          " --fps 0.1 --frames 0-5 --exr " + test::quoted(dir_ / "f%d.exr"));
  EXPECT_EQ(frames.status, 2);
  EXPECT_NE(frames.err.find(fmt::format("frame 5: at proper time 50 the falling camera has "
                                        "reached the singularity r = 0 (at proper time {}): the "
                                        "camera is drawn down to r = 0.05M",
                                        law.proper_time_at_radius(0))),
            std::string::npos)
      << frames.err;
  EXPECT_FALSE(fs::exists(dir_ / "f5.exr"));
  // Seen from the falling camera the shadow is Synge's aberrated by its speed: from 23.28
  // degrees in radius at rest at 12M it first shrinks (22.21 at proper time 10, 0.078c), then
  // grows as the camera gets closer (24.30 at 30, 8.53M; 31.27 at 40, 5.02M).
  std::vector<int> dark;
  for (int i = 0; i < 5; ++i) {
    SCOPED_TRACE(i);
    ASSERT_TRUE(fs::exists(dir_ / fmt::format("f{}.exr", i)));
    const auto image = load_image_file(dir_ / fmt::format("f{}.exr", i));
    int count = 0;
    for (std::size_t p = 0; p < image->rgb.size(); p += 3)
      count += image->rgb[p] == 0 && image->rgb[p + 1] == 0 && image->rgb[p + 2] == 0;
    dark.push_back(count);
  }
  EXPECT_LT(dark[1], dark[0]);
  EXPECT_GT(dark[3], dark[0]);
  EXPECT_GT(dark[4], dark[3]);
  // Frame 3 is the scene seen at proper time 30.
  const fs::path single = dir_ / "single.exr";
  ASSERT_EQ(test::run_lightcone("render " + test::quoted(fall) + fixed_exposure +
                                " --set camera.proper_time=30 -o " + test::quoted(single))
                .status,
            0);
  EXPECT_EQ(load_image_file(single)->rgb, load_image_file(dir_ / "f3.exr")->rgb);
  // By world time: the same fall, frames at coordinate times 0, 10, 20.
  const test::CommandResult world = test::run_lightcone(
      "animate " + test::quoted(fall) + " --clock world --fps 0.1 --frames 0-2 -o " +
      test::quoted(dir_ / "w%d.png"));
  EXPECT_EQ(world.status, 0) << world.err;
  EXPECT_TRUE(fs::exists(dir_ / "w2.png"));
}

// ---------------------------------------------------------------------------------------------
// The documentation and the schema

TEST(BlackHoleMotionSchema, ListsTheKeysTheLoaderReads) {
  const auto schema = nlohmann::json::parse(test::read_source_file("schema/scene.schema.json"));
  const auto& defs = schema.at("$defs");
  EXPECT_EQ(defs.at("camera").at("properties").at("motion").at("$ref"), "#/$defs/bodyMotion");
  const auto& geodesic = defs.at("geodesicMotion").at("properties");
  EXPECT_EQ(test::keys_of(geodesic), (std::vector<std::string>{"fall", "orbit"}));
  EXPECT_EQ(test::keys_of(geodesic.at("orbit").at("properties")),
            (std::vector<std::string>{"normal", "phase", "radius"}));
  EXPECT_EQ(geodesic.at("orbit").at("properties").at("radius").at("exclusiveMinimum"), 3);
  EXPECT_EQ(test::keys_of(geodesic.at("fall").at("properties")),
            (std::vector<std::string>{"direction", "from", "time"}));
  const std::string doc = test::read_source_file("docs/scene-format.md");
  for (const char* word :
       {"`orbit`", "`fall`", "`radius`", "`normal`", "`phase`", "`from`", "`\"infinity\"`",
        "`direction`", "unstable", "2M (1 + 10^-9)", "not drawn yet", "MTW eq. 31.10"})
    EXPECT_NE(doc.find(word), std::string::npos) << word;
}

}  // namespace
}  // namespace lightcone

// Light from a lamp to a surface near a Schwarzschild hole (physics/schwarzschild_lens.hpp's
// ray_between, physics/hole_light_leg.hpp) against derivations made here: the orbit equation
// integrated step by step (the ray reaches the other end, in its time, and neighbouring rays
// spread as the bundle's formula says), the same ray from either end, the straight line of flat
// space (the bundle's area is the squared distance, and a moving lamp and surface give the flat
// leg of light_path.hpp), the radial ray's closed form dA / dOmega = (r_b - r_a)^2 / f_emitter,
// and the static observers' g = sqrt(f_e / f_r).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "lightcone/physics/hole_light_leg.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/schwarzschild.hpp"
#include "lightcone/physics/schwarzschild_lens.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;

struct Case {
  double r_a, r_b, psi;
};
const Case kCases[] = {{30, 20, 2.0}, {8, 30, 0.7},  {50, 100, 2.9}, {12, 40, 1.2},
                       {20, 20, 1.0}, {4, 25, 2.5},  {2.5, 9, 0.4},  {2.6, 2.9, 1.5},
                       {40, 6, 3.1},  {10, 7, 1e-6}, {7, 10, 0.01}};

TEST(RayBetween, IsTheSameRaySeenFromEitherEnd) {
  for (const Case& c : kCases)
    for (int order = 0; order <= 1; ++order) {
      SCOPED_TRACE(testing::Message() << c.r_a << " " << c.r_b << " " << c.psi << " " << order);
      const auto ray = ray_between(1, c.r_a, c.r_b, c.psi, order);
      const auto back = ray_between(1, c.r_b, c.r_a, c.psi, order);
      ASSERT_TRUE(ray && back);
      EXPECT_NEAR(back->impact, ray->impact, 1e-9 * ray->impact);
      EXPECT_NEAR(back->time, ray->time, 1e-9 * ray->time);
      EXPECT_NEAR(back->cos_a, ray->cos_b, 1e-9);
      EXPECT_NEAR(back->sin_a, ray->sin_b, 1e-9);
      EXPECT_NEAR(back->spread_a_to_b, ray->spread_b_to_a, 1e-9 * ray->spread_b_to_a);
    }
}

test::IntegratedOrbit follow(double m, double r0, double cos_alpha, double sin_alpha, double phi) {
  return test::integrate_orbit_from(m, r0, cos_alpha, sin_alpha, phi, 200000);
}

TEST(RayBetween, ReachesTheOtherEndInItsTimeAndSpreadsAsNeighbouringRaysDo) {
  const double m = 1;
  for (const Case& c : kCases)
    for (int order = 0; order <= 1; ++order) {
      if (c.psi < 0.1) continue;  // (the integration's start needs a tangential part)
      SCOPED_TRACE(testing::Message() << c.r_a << " " << c.r_b << " " << c.psi << " " << order);
      const auto ray = ray_between(m, c.r_a, c.r_b, c.psi, order);
      ASSERT_TRUE(ray);
      const test::IntegratedOrbit end = follow(m, c.r_a, ray->cos_a, ray->sin_a, ray->sweep);
      EXPECT_NEAR(end.r, c.r_b, 1e-7 * c.r_b);
      EXPECT_NEAR(end.t, ray->time, 1e-7 * ray->time);
      // The bundle from end a: two neighbouring rays followed over the sweep reach radii r+
      // and r-; the ray through r_b sweeps dsweep / dalpha = -(dr / dalpha) / (dr / dphi) more
      // per unit look angle, with dr / dphi = r^2 sqrt(1 / b^2 - u^2 + 2 M u^3) at r_b (moving
      // outward or inward there). The bundle's cross-section there per unit solid angle at a
      // is r_b^2 sin(psi) |cos(beta_b)| (dsweep / dalpha) / sin(alpha_a): the sphere's area
      // element at angle psi from a's axis.
      const double delta = 1e-5, alpha = std::atan2(ray->sin_a, ray->cos_a);
      const auto r_at = [&](double a) {
        return follow(m, c.r_a, std::cos(a), std::sin(a), ray->sweep).r;
      };
      const double dr_dalpha = (r_at(alpha + delta) - r_at(alpha - delta)) / (2 * delta);
      const double u = 1 / c.r_b, b = ray->impact;
      const double dr_dphi = c.r_b * c.r_b * std::sqrt(1 / (b * b) - u * u + 2 * m * u * u * u);
      const double rate = std::abs(dr_dalpha / dr_dphi);
      const double f_b = 1 - 2 * m / c.r_b;
      const double sin_beta = b * std::sqrt(f_b) / c.r_b;
      const double spread =
          c.r_b * c.r_b * std::sin(c.psi) * std::sqrt(1 - sin_beta * sin_beta) * rate / ray->sin_a;
      EXPECT_NEAR(ray->spread_a_to_b, spread, 1e-5 * spread);
    }
}

// The light a lamp sends round the hole more than once (image orders 2 and up) is left out of
// the lighting. Between points outside r = 4M (lamps out to 100M) it is at most 2.3 % of the
// direct light more than 30 degrees off the line through the hole, 0.8 % beyond 60 degrees
// (docs/design/black-hole.md, "Lights"); nearer the line it grows toward the caustic there.
TEST(RayBetween, SecondOrderLightIsAFewPercentOfTheDirect) {
  for (const auto& [bound, least_degrees] : {std::pair{0.023, 30}, {0.008, 60}})
    for (const double r_a : {4.0, 6.0, 10.0, 20.0})
      for (const double r_b : {4.0, 6.0, 10.0, 30.0, 100.0})
        for (int degrees = least_degrees; degrees < 180; degrees += 3) {
          const double psi = degrees * kPi / 180;
          SCOPED_TRACE(testing::Message() << r_a << " " << r_b << " " << degrees);
          const auto direct = ray_between(1, r_a, r_b, psi, 0);
          const auto twice = ray_between(1, r_a, r_b, psi, 2);
          ASSERT_TRUE(direct && twice);
          // The flux is inversely as the spread.
          EXPECT_LT(direct->spread_a_to_b / twice->spread_a_to_b, bound);
        }
}

TEST(RayBetween, InFlatSpaceIsTheStraightLine) {
  for (const double m : {0.0, 1e-12})
    for (const Case& c : {Case{10, 7, 1.1}, Case{3, 9, 2.5}, Case{5, 5, 0.3}, Case{4, 8, 1e-7}}) {
      SCOPED_TRACE(testing::Message() << m << " " << c.r_a << " " << c.r_b << " " << c.psi);
      const double dx = c.r_b * std::cos(c.psi) - c.r_a, dy = c.r_b * std::sin(c.psi);
      const double d = std::hypot(dx, dy);
      const auto ray = ray_between(m, c.r_a, c.r_b, c.psi, 0);
      ASSERT_TRUE(ray);
      EXPECT_NEAR(ray->cos_a, dx / d, 1e-8);
      EXPECT_NEAR(ray->sin_a, dy / d, 1e-8);
      EXPECT_NEAR(ray->time, d, 1e-9 * d);
      EXPECT_NEAR(ray->spread_a_to_b, d * d, 1e-7 * d * d);
      EXPECT_NEAR(ray->spread_b_to_a, d * d, 1e-7 * d * d);
    }
  // A plane wave is not focused.
  const auto far = ray_between(0, 6, std::numeric_limits<double>::infinity(), 1.3, 0);
  ASSERT_TRUE(far);
  EXPECT_NEAR(far->focusing, 1, 1e-9);
}

TEST(RayBetween, RadialBundleHasItsClosedForm) {
  // Along the radial line, for b -> 0 the ray sweeps phi = b (1/r_a - 1/r_b) (dphi/dr = b / r^2
  // to first order in b), b = r_a alpha / sqrt(f_a): dA_b / dOmega_a = r_b^2 (dphi/dalpha)^2 =
  // (r_b - r_a)^2 / f_a, and back (r_b - r_a)^2 / f_b.
  const double m = 1;
  for (const auto& [r_a, r_b] : {std::pair{3.0, 10.0}, {10.0, 3.0}, {2.2, 50.0}, {40.0, 6.0}})
    for (const double psi : {0.0, 1e-9}) {
      SCOPED_TRACE(testing::Message() << r_a << " " << r_b << " " << psi);
      const auto ray = ray_between(m, r_a, r_b, psi, 0);
      ASSERT_TRUE(ray);
      const double d2 = (r_b - r_a) * (r_b - r_a);
      EXPECT_NEAR(ray->spread_a_to_b, d2 / (1 - 2 * m / r_a), 1e-6 * d2);
      EXPECT_NEAR(ray->spread_b_to_a, d2 / (1 - 2 * m / r_b), 1e-6 * d2);
      EXPECT_NEAR(ray->time, std::abs(tortoise_coordinate(m, r_b) - tortoise_coordinate(m, r_a)),
                  1e-9 * std::sqrt(d2));
    }
}

TEST(RayBetween, StartedFromAnotherSolveIsTheSameRay) {
  // Starts from a neighbouring ray, from other cases' rays (far off, on the other stretch or
  // with the ends swapped), and from look angles at the stretch's ends with rates far off.
  std::vector<RayBetweenStart> starts;
  for (const Case& c : kCases)
    for (int order = 0; order <= 1; ++order) {
      RayBetweenStart start;
      if (ray_between(1, c.r_a, c.r_b, c.psi, order, &start)) starts.push_back(start);
    }
  ASSERT_GT(starts.size(), 20u);
  for (const double alpha : {1e-9, 0.5, 1.5, 3.0})
    for (const double rate : {1e-6, 1.0, 1e6}) starts.push_back({alpha, rate, true, false});
  for (const Case& c : kCases)
    for (int order = 0; order <= 1; ++order) {
      SCOPED_TRACE(testing::Message() << c.r_a << " " << c.r_b << " " << c.psi << " " << order);
      const auto cold = ray_between(1, c.r_a, c.r_b, c.psi, order);
      ASSERT_TRUE(cold);
      RayBetweenStart near;
      ASSERT_TRUE(ray_between(1, c.r_a * 1.01, c.r_b, c.psi * 0.99, order, &near));
      starts.push_back(near);
      for (const RayBetweenStart& from : starts) {
        RayBetweenStart start = from;
        const auto warm = ray_between(1, c.r_a, c.r_b, c.psi, order, &start);
        ASSERT_TRUE(warm);
        // The same root to the sweep's own rounding, which near the radial ray and inside the
        // photon sphere is some 1e-14 of the impact parameter.
        EXPECT_NEAR(warm->impact, cold->impact, 1e-13 * cold->impact);
        EXPECT_NEAR(warm->time, cold->time, 1e-12 * cold->time);
        EXPECT_NEAR(warm->cos_a, cold->cos_a, 1e-14);
        EXPECT_NEAR(warm->sin_b, cold->sin_b, 1e-14);
        EXPECT_NEAR(warm->spread_b_to_a, cold->spread_b_to_a, 1e-8 * cold->spread_b_to_a);
        // The start is now this ray's.
        EXPECT_NEAR(start.rate, cold->sweep_rate, 1e-8 * cold->sweep_rate);
      }
      starts.pop_back();
    }
}

TEST(RayBetween, UntimedIsTheSameRayWithoutItsTime) {
  // A lamp at rest asks no time: the ray is the one solved with it, to the bit, its time NaN.
  for (const Case& c : kCases)
    for (int order = 0; order <= 1; ++order) {
      SCOPED_TRACE(testing::Message() << c.r_a << " " << c.r_b << " " << c.psi << " " << order);
      const auto timed = ray_between(1, c.r_a, c.r_b, c.psi, order);
      const auto untimed = ray_between(1, c.r_a, c.r_b, c.psi, order, nullptr, nullptr, false);
      ASSERT_TRUE(timed && untimed);
      EXPECT_TRUE(std::isfinite(timed->time));
      EXPECT_TRUE(std::isnan(untimed->time));
      EXPECT_EQ(untimed->impact, timed->impact);
      EXPECT_EQ(untimed->cos_a, timed->cos_a);
      EXPECT_EQ(untimed->sin_b, timed->sin_b);
      EXPECT_EQ(untimed->spread_b_to_a, timed->spread_b_to_a);
      EXPECT_EQ(untimed->sweep_rate, timed->sweep_rate);
      const Vec3 lamp{c.r_b * std::cos(c.psi), c.r_b * std::sin(c.psi), 0}, surface{c.r_a, 0, 0};
      const auto leg = hole_light_leg(1, lamp, {}, surface, {}, order);
      const auto untimed_leg =
          hole_light_leg(1, lamp, {}, surface, {}, order, nullptr, nullptr, false);
      ASSERT_TRUE(leg && untimed_leg);
      EXPECT_TRUE(std::isnan(untimed_leg->time));
      EXPECT_NEAR(leg->time, timed->time, 1e-12 * timed->time);
      EXPECT_EQ(untimed_leg->leg.distance, leg->leg.distance);
      EXPECT_EQ(untimed_leg->leg.doppler, leg->leg.doppler);
    }
}

TEST(HoleLightLeg, IsNoneOnlyWhereItLightsTheBackOfAStaticSurface) {
  // Surfaces round balls beside the hole (nearer the hole than the lamp and, the last, farther),
  // facing every way, lit by a lamp and a plane wave,
  // their legs solved one after another from the last (as a picture's neighbouring points are):
  // the same legs as solved alone, none only where the light arrives from behind the surface.
  const double m = 1;
  const Vec3 lamp{-14, 10, 6}, propagation = normalize(Vec3{-1, -0.3, -0.2});
  const Vec3 centres[] = {{7, 0, 0}, {-9.5, 1.2, 0.9}, {-1, -0.2, 13.5}, {15, 8, 5}};
  const Vec3 moving{0.3, 0, -0.2};
  RayBetweenStart lamp_starts[2], wave_starts[2];
  int lit = 0, dark = 0, culled = 0, wave_lit = 0, wave_dark = 0, wave_culled = 0;
  for (const Vec3& centre : centres)
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 32; ++j) {
        const double theta = kPi * (i + 0.5) / 16, phi = 2 * kPi * j / 32;
        const Vec3 normal{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                          std::cos(theta)};
        const Vec3 surface = centre + normal;
        // A moving surface's light is turned by aberration: it is never culled.
        for (const Vec3& w : {Vec3{}, moving})
          for (int order = 0; order <= 1; ++order) {
            SCOPED_TRACE(testing::Message() << i << " " << j << " " << order);
            const auto alone = hole_light_leg(m, lamp, {}, surface, w, order);
            const auto leg =
                hole_light_leg(m, lamp, {}, surface, w, order, &lamp_starts[order], &normal);
            const auto wave_alone = hole_plane_wave(m, surface, w, propagation, order);
            const auto wave =
                hole_plane_wave(m, surface, w, propagation, order, &wave_starts[order], &normal);
            ASSERT_TRUE(alone && wave_alone);
            const bool behind = dot(normal, alone->leg.direction) > 0;
            const bool wave_behind = dot(normal, wave_alone->direction) > 0;
            // None only from behind a static surface, and then mostly.
            if (!leg) {
              ASSERT_TRUE(behind && dot(w, w) == 0);
            }
            if (!wave) {
              ASSERT_TRUE(wave_behind && dot(w, w) == 0);
            }
            const bool still = dot(w, w) == 0;
            lit += !behind, dark += behind && still, culled += !leg;
            wave_lit += !wave_behind, wave_dark += wave_behind && still, wave_culled += !wave;
            if (leg) {
              EXPECT_NEAR(leg->leg.distance, alone->leg.distance, 1e-8 * alone->leg.distance);
              EXPECT_NEAR(leg->leg.doppler, alone->leg.doppler, 1e-13);
              EXPECT_LT(length(leg->leg.direction - alone->leg.direction), 1e-13);
              EXPECT_NEAR(leg->time, alone->time, 1e-13 * alone->time);
            }
            if (wave) {
              EXPECT_NEAR(wave->focusing, wave_alone->focusing, 1e-8 * wave_alone->focusing);
              EXPECT_LT(length(wave->direction - wave_alone->direction), 1e-13);
            }
          }
      }
  EXPECT_GT(lit, 1000);
  EXPECT_GT(wave_lit, 1000);
  // (a bracket may still hold directions on both sides when its root is found)
  EXPECT_GT(culled, 0.95 * dark);
  EXPECT_GT(wave_culled, 0.95 * wave_dark);
}

TEST(HoleLightLeg, StaticEndsSeeTheGravitationalShift) {
  const double m = 1;
  const Vec3 lamp{0, 12, 0}, surface{5, -3, 1};
  const auto leg = hole_light_leg(m, lamp, {}, surface, {});
  ASSERT_TRUE(leg);
  EXPECT_NEAR(leg->leg.doppler, std::sqrt((1 - 2 * m / 12) / (1 - 2 * m / length(surface))), 1e-12);
  // At rest the flux is g^2 I dOmega / dA: r_eff^2 = g^2 dA_surface / dOmega_lamp.
  const double psi = std::acos(dot(normalize(lamp), normalize(surface)));
  const auto ray = ray_between(m, length(surface), 12, psi, 0);
  ASSERT_TRUE(ray);
  const double g2 = leg->leg.doppler * leg->leg.doppler;
  EXPECT_NEAR(leg->leg.distance * leg->leg.distance, g2 * ray->spread_b_to_a,
              1e-12 * ray->spread_b_to_a);
  EXPECT_NEAR(leg->time, ray->time, 1e-12 * ray->time);
  // The light arrives from the lamp's side and leaves toward the surface's.
  EXPECT_LT(dot(leg->leg.direction, normalize(surface - lamp)), 1.0);
  EXPECT_GT(dot(leg->leg.direction, normalize(surface - lamp)), 0.8);
  EXPECT_GT(dot(leg->leg.emitted_direction, normalize(surface - lamp)), 0.8);
}

TEST(HoleLightLeg, InFlatSpaceIsTheFlatLegBetweenMovingEnds) {
  const Vec3 lamp{1, 9, -2}, surface{4, -3, 2};
  const Vec3 w_lamp{0.3, -0.5, 0.1}, w_surface{-0.6, 0.2, 0.4};
  const double d = length(surface - lamp);
  const ReceivedLeg flat = receive_leg({0, lamp}, w_lamp, {d, surface}, w_surface);
  const auto leg = hole_light_leg(1e-12, lamp, w_lamp, surface, w_surface);
  ASSERT_TRUE(leg);
  EXPECT_NEAR(leg->leg.doppler, flat.doppler, 1e-8);
  EXPECT_NEAR(leg->leg.distance, flat.distance, 1e-8 * flat.distance);
  EXPECT_LT(length(leg->leg.direction - flat.direction), 1e-8);
  EXPECT_LT(length(leg->leg.emitted_direction - flat.emitted_direction), 1e-8);
  EXPECT_NEAR(leg->time, d, 1e-9 * d);
}

TEST(HoleLightLeg, PlaneWaveIsBlueshiftedAndFocusedFallingIn) {
  // Flat: the Doppler factor of a moving receiver, no focusing.
  const Vec3 propagation = normalize(Vec3{1, -2, 0.5}), w{0.4, 0.1, -0.3};
  const auto flat = hole_plane_wave(1e-12, {3, 4, 5}, w, propagation);
  ASSERT_TRUE(flat);
  EXPECT_NEAR(flat->doppler, lorentz_gamma(w) * (1 - dot(w, propagation)), 1e-9);
  EXPECT_NEAR(flat->focusing, 1, 1e-8);
  // A static receiver far from the hole's axis: blueshifted by 1 / sqrt(f); straight below the
  // source (psi = 0) focused by the radial closed form, 1 / (f (dpsi/dalpha)^2) with dpsi/dalpha
  // = 1 / sqrt(f) for r_b -> infinity: 1.
  const double m = 1, r = 10;
  const auto below = hole_plane_wave(m, {0, r, 0}, {}, {0, -1, 0});
  ASSERT_TRUE(below);
  EXPECT_NEAR(below->doppler, 1 / std::sqrt(1 - 2 * m / r), 1e-12);
  EXPECT_NEAR(below->focusing, 1, 1e-6);
  EXPECT_LT(length(below->direction - Vec3{0, -1, 0}), 1e-12);
  // Beside the hole the wave arrives bent toward it, and converging (focused).
  const auto beside = hole_plane_wave(m, {r, 0, 0}, {}, {0, -1, 0});
  ASSERT_TRUE(beside);
  EXPECT_LT(beside->direction.x, 0);
  EXPECT_GT(beside->focusing, 1);
}

}  // namespace
}  // namespace lightcone

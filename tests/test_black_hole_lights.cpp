// Lit bodies near a Schwarzschild black hole (frame/lighting.hpp's near-hole legs, with the
// curved shadow paths of frame/curved_bodies.hpp), against derivations made here: the flat
// renderer's lit picture as M -> 0 (moving lights and bodies, every kind of light, shadows), the
// irradiance of a lamp straight above a surface in closed form, E = g^2 I f_lamp / (r_l - r_s)^2
// with g^2 = f_lamp / f_surface (times the Doppler factor's square for a moving surface), the
// light round the far side added to the direct light, and blockers that shadow each where its
// curved path passes, not where the straight line between lamp and surface does. G = c = 1.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/frame/lighting.hpp"
#include "lightcone/physics/hole_light_leg.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/schwarzschild.hpp"
#include "lightcone/physics/schwarzschild_lens.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;

Material lit(Rgb albedo) {
  Material m;
  m.pattern = SolidColor{albedo};
  m.unlit = false;
  return m;
}

Light light_of(const std::string& name,
               std::variant<PointLight, SpotLight, DirectionalLight, SphereLight> kind,
               const Vec3& position, double intensity, const Vec3& velocity = {}) {
  Light l;
  l.name = name;
  l.kind = kind;
  l.world_line.position = position;
  l.world_line.velocity = velocity;
  l.spectrum.emission = Rgb{1, 0.9f, 0.8f};
  l.intensity = intensity;
  return l;
}

Scene lit_scene(double mass) {
  Scene s;
  s.camera.world_line.position = {0, 0, 40};
  s.camera.fov_degrees = 30;
  s.camera.width = 160;
  s.camera.height = 90;
  s.camera.samples = 2;
  s.black_hole = BlackHole{{0, 0, 0}, mass, std::nullopt};
  s.objects.push_back(
      test::make_object("ball", Sphere{2}, {3, 0, -20}, {0.3, 0, 0.2}, lit({0.8f, 0.7f, 0.6f})));
  s.objects.push_back(
      test::make_object("box", Box{{3, 1, 2}}, {-4, 1, 15}, {}, lit({0.3f, 0.8f, 0.5f})));
  // Between the lamp and the ball: a shadow on it.
  s.objects.push_back(
      test::make_object("blocker", Sphere{0.7}, {6, 5, -18}, {}, lit({0.9f, 0.9f, 0.9f})));
  s.lights.push_back(light_of("lamp", PointLight{}, {12, 12, -14}, 400, {0, -0.2, 0.1}));
  SpotLight spot;
  spot.direction = normalize(Vec3{0, -1, 0.2});
  spot.cone_degrees = 60;
  s.lights.push_back(light_of("spot", spot, {-4, 8, 14}, 120));
  DirectionalLight sun;
  sun.direction = normalize(Vec3{1, -0.5, -0.4});
  sun.irradiance = 0.8;
  s.lights.push_back(light_of("sun", sun, {}, 0, {0.2, 0, 0}));
  SphereLight bulb;
  bulb.radius = 1;
  s.lights.push_back(light_of("bulb", bulb, {-8, -6, -10}, 200));
  return s;
}

TEST(BlackHoleLights, FlatLimitIsTheFlatRenderersLitPicture) {
  Scene curved = lit_scene(1e-12);
  curved.objects[0].world_line.time = -55;  // seen about when it is there
  Scene flat = curved;
  flat.black_hole.reset();
  const Image a = render_image(curved, {}), b = render_image(flat, {});
  EXPECT_LT(test::fraction_differing(a, b), 0.001);
  // Not black: the lights reach the bodies.
  double sum = 0;
  for (const float v : a.rgb) sum += v;
  EXPECT_GT(sum, 1.0);
}

// Lighting for one surface event near a hole of mass 1 at the origin, lit by the scene's lights.
struct LitEvent {
  // (The scene is kept: the resolved scene points into it.)
  explicit LitEvent(Scene s)
      : scene(std::move(s)),
        resolved(resolve_scene(scene)),
        tracer(resolved),
        bodies(resolved, tracer),
        lighting(resolved, &tracer, &bodies) {}
  // The radiance a white (albedo 1/2) surface at `at`, facing `normal`, sends out, moving with
  // w against the static observer there.
  double radiance(const Vec4& at, const Vec3& normal, const Vec3& w = {}) const {
    Hit hit;
    hit.body = 0;
    hit.shape_normal = normal;
    const Lighting::HoleSurface surface{at, normal, w};
    PointEmission emission;
    emission.rest_rgb = {0.5, 0.5, 0.5};
    const Lighting::LitPoint point{&hit, {}, 1.0, emission, {0.5, 0.5}, &surface};
    LinearRgb out;
    lighting.received(std::span(&point, 1), std::span(&out, 1));
    return out.g;
  }
  Scene scene;
  ResolvedScene resolved;
  Tracer tracer;
  CurvedBodies bodies;
  Lighting lighting;
};

// A hole of mass 1 and a white lamp of intensity I at `lamp`; the lit body (body 0, far off)
// only lends its material; `blocker` (if any) is a sphere of radius 0.3 there.
Scene lamp_scene(const Vec3& lamp, double intensity, std::optional<Vec3> blocker = {}) {
  Scene s;
  s.camera.world_line.position = {0, 0, 80};
  s.black_hole = BlackHole{{0, 0, 0}, 1, std::nullopt};
  // Colour without its Doppler shift, brightness with the physical laws.
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kPhysical;
  s.objects.push_back(test::make_object("far", Sphere{1}, {0, 0, 60}, {}, lit({0.5f, 0.5f, 0.5f})));
  if (blocker)
    s.objects.push_back(
        test::make_object("blocker", Sphere{0.3}, *blocker, {}, lit({0.5f, 0.5f, 0.5f})));
  Light l = light_of("lamp", PointLight{}, lamp, intensity);
  l.spectrum.emission = Rgb{1, 1, 1};
  s.lights.push_back(l);
  return s;
}

TEST(BlackHoleLights, LampStraightAboveGivesTheClosedFormIrradiance) {
  // The radial bundle: dOmega_lamp / dA = f_lamp / (r_l - r_s)^2 (static frames), and the flux
  // g^2 I dOmega / dA with g^2 = f_lamp / f_surface; reflected as albedo / pi.
  const double r_l = 12, r_s = 4, intensity = 50;
  const LitEvent lit_event(lamp_scene({0, r_l, 0}, intensity));
  const double f_l = 1 - 2 / r_l, f_s = 1 - 2 / r_s;
  const double expected = 0.5 / kPi * intensity * (f_l / f_s) * f_l / ((r_l - r_s) * (r_l - r_s));
  EXPECT_NEAR(lit_event.radiance({0, {0, r_s, 0}}, {0, 1, 0}), expected, 1e-9 * expected);
  // Moving up toward the lamp at v: blueshifted by gamma (1 + v), brighter by its square.
  const double v = 0.5, d = (1 + v) / std::sqrt(1 - v * v);
  EXPECT_NEAR(lit_event.radiance({0, {0, r_s, 0}}, {0, 1, 0}, {0, v, 0}), d * d * expected,
              1e-9 * d * d * expected);
  // Facing away: dark.
  EXPECT_EQ(lit_event.radiance({0, {0, r_s, 0}}, {0, -1, 0}), 0.0);
}

TEST(BlackHoleLights, LightComesDirectlyAndRoundTheFarSideAndEachIsShadowedOnItsPath) {
  // A surface and a lamp at r = 6 on either side of the hole, 150 degrees apart about it: the
  // straight line between them passes 6 cos(75 deg) = 1.55M from the centre (through the
  // horizon), the direct light's path at its periapsis r_p, farther out; the light round the
  // far side sweeps 210 degrees the other way.
  const double r = 6, psi = 150 * kPi / 180, intensity = 50;
  const Vec3 surface{r, 0, 0}, lamp{r * std::cos(psi), r * std::sin(psi), 0};
  const Vec4 event{0, surface};
  const Vec3 normal = normalize(lamp - surface);
  // What each path brings (physical searchlight, colour unshifted), reflected as albedo / pi.
  const auto brought = [&](int order) {
    const auto leg = hole_light_leg(1, lamp, {}, surface, {}, order);
    EXPECT_TRUE(leg);
    return 0.5 / kPi *
           point_source_irradiance(leg->leg, intensity, dot(normal, -leg->leg.direction));
  };
  const double direct = brought(0), round = brought(1);
  EXPECT_GT(round, 0.05 * direct);  // a third of it at 150 degrees: not negligible
  const double open = LitEvent(lamp_scene(lamp, intensity)).radiance(event, normal);
  EXPECT_NEAR(open, direct + round, 1e-9 * open);
  // The middle of each path: at its periapsis, half way round.
  const auto middle = [&](int order) {
    const auto ray = ray_between(1, r, r, psi, order);
    EXPECT_TRUE(ray);
    const double half = (order == 0 ? 1 : -1) * ray->sweep / 2;
    return Vec3{std::cos(half), std::sin(half), 0} * photon_orbit(1, ray->impact).periapsis;
  };
  const Vec3 on_direct = middle(0), on_round = middle(1);
  ASSERT_GT(length(on_direct), 3);
  EXPECT_NEAR(LitEvent(lamp_scene(lamp, intensity, on_direct)).radiance(event, normal), round,
              1e-9 * open);
  EXPECT_NEAR(LitEvent(lamp_scene(lamp, intensity, on_round)).radiance(event, normal), direct,
              1e-9 * open);
  // Half way between the direct path and the horizon, on the straight line's side: off both.
  const Vec3 off_path = normalize(on_direct) * ((length(on_direct) + 2) / 2 + 0.3);
  EXPECT_EQ(LitEvent(lamp_scene(lamp, intensity, off_path)).radiance(event, normal), open);
  // A blocker beyond the lamp does not shadow.
  EXPECT_EQ(LitEvent(lamp_scene(lamp, intensity, lamp * 1.5)).radiance(event, normal), open);
}

TEST(HoleLegStarts, KeepEachBodysLastLegWithinATileAndForgetThemAtTheNext) {
  // A picture's tile starts each body's legs from that body's last, per light and order, and
  // the next tile from nothing (whichever thread rendered the tiles before it).
  HoleLegStarts starts;
  starts.begin_tile(7);
  for (std::size_t body = 0; body < 10; ++body)
    for (std::size_t light = 0; light < 2; ++light)
      for (int order = 0; order <= 1; ++order)
        starts.at(body, light, order) = {0.1 * body + 0.01 * light + 0.001 * order, 1.0, true,
                                         false};
  for (std::size_t body = 0; body < 10; ++body)
    for (std::size_t light = 0; light < 2; ++light)
      for (int order = 0; order <= 1; ++order)
        EXPECT_EQ(starts.at(body, light, order).alpha, 0.1 * body + 0.01 * light + 0.001 * order);
  starts.begin_tile(8);
  for (std::size_t body = 0; body < 10; ++body) EXPECT_EQ(starts.at(body, 1, 0).rate, 0);
}

}  // namespace
}  // namespace lightcone

// Lights in motion through the whole renderer (docs/design/light-transport.md): the classical
// limit for every light type, the D^6 of a light carried with the camera, the light-source
// delay modes against closed forms (the interceptor), the shadow of a fast occluder where the
// retarded geometry puts it, the principle of relativity with lights and shadows, and bad
// states (no lights, a light at the lit point).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/light_path.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/scene/reframe.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;

using test::make_object;

using test::lit;
Material lit_checker(Rgb a, Rgb b) {
  Material m;
  m.pattern = Checker{1.0, {a, b}};
  m.unlit = false;
  return m;
}
Material emitter(Rgb c) {
  Material m;
  m.pattern = SolidColor{c};
  return m;
}

Light make_light(std::variant<PointLight, SpotLight, DirectionalLight, SphereLight> kind,
                 Vec3 position, double intensity, Rgb colour = {1, 1, 1}, Vec3 velocity = {}) {
  Light l;
  l.name = "light";
  l.kind = kind;
  l.world_line.position = position;
  l.world_line.velocity = velocity;
  l.spectrum.emission = colour;
  l.intensity = intensity;
  return l;
}

// A camera at rest at `eye` (observing at t = 0) looking straight down at a large lit plane
// y = 0: image x along +x, image y along +z.
Scene top_down(Vec3 eye, double fov_degrees, int size, Rgb albedo = {0.5f, 0.5f, 0.5f}) {
  Scene s;
  s.camera.world_line.position = eye;
  s.camera.forward = {0, -1, 0};
  s.camera.up = {0, 0, -1};
  s.camera.fov_degrees = fov_degrees;
  s.camera.width = size;
  s.camera.height = size;
  s.objects.push_back(make_object("ground", Plane{400, 400}, {}, {}, lit(albedo)));
  s.sky.pattern = SolidColor{{0, 0, 0}};
  return s;
}

// The point of the plane y = 0 seen through the centre of pixel (i, j) by a camera at rest.
Vec3 plane_point(const Scene& s, int i, int j) {
  const Vec3 eye = s.camera.world_line.position;
  const Vec3 u = look_direction(camera_basis(s.camera), i + 0.5, j + 0.5);
  Vec3 p = eye + u * (eye.y / -u.y);
  p.y = 0;
  return p;
}

LinearRgb pixel(const Image& image, int i, int j) {
  const float* p = &image.rgb[3 * (static_cast<std::size_t>(j) * image.width + i)];
  return {p[0], p[1], p[2]};
}

// Irradiance per unit intensity of a static point light at `light` on the plane y = 0 at p
// (normal +y), times the Lambertian 1/pi: what a pixel shows per unit albedo and colour.
double lambert(const Vec3& light, const Vec3& p) {
  const Vec3 d = light - p;
  const double r2 = dot(d, d);
  return std::max(0.0, d.y / std::sqrt(r2)) / (kPi * r2);
}

void expect_rgb_near(const LinearRgb& got, const LinearRgb& want, double relative,
                     const std::string& where) {
  auto tol = [&](double w) { return relative * std::abs(w) + 1e-12; };
  EXPECT_NEAR(got.r, want.r, tol(want.r)) << where;
  EXPECT_NEAR(got.g, want.g, tol(want.g)) << where;
  EXPECT_NEAR(got.b, want.b, tol(want.b)) << where;
}

std::string at(int i, int j) {
  return "pixel (" + std::to_string(i) + ", " + std::to_string(j) + ")";
}

const char* delay_name(LightSourceDelay d) {
  static const char* const names[] = {"surface", "camera", "none"};
  return names[static_cast<int>(d)];
}

// ---------------------------------------------------------------------------------------------
// 1. beta = 0: a static light and static surfaces give classical Lambertian shading exactly,
// for every light type and every colour model.

TEST(StaticLighting, PointLightIsLambertTimesTheInverseSquareLawForEveryColourModel) {
  const Rgb colour{1.0f, 0.8f, 0.6f};  // hue 30 degrees: the hue model is the identity at rest
  const Vec3 light{0.7, 2.5, -0.4};
  const double intensity = 6;
  const DopplerModel dopplers[] = {DopplerModel::kSpectral, DopplerModel::kRgb3, DopplerModel::kHue,
                                   DopplerModel::kOff};
  const SearchlightModel searchlights[] = {SearchlightModel::kPhysical,
                                           SearchlightModel::kChang1996, SearchlightModel::kOff};
  for (const DopplerModel d : dopplers)
    for (const SearchlightModel sl : searchlights)
      for (const LightSourceDelay delay :
           {LightSourceDelay::kSurface, LightSourceDelay::kCamera, LightSourceDelay::kNone}) {
        SCOPED_TRACE("doppler " + std::to_string(static_cast<int>(d)) + ", searchlight " +
                     std::to_string(static_cast<int>(sl)) + ", delay " + delay_name(delay));
        Scene s = top_down({0, 5, 0}, 40, 9);
        s.lights.push_back(make_light(PointLight{}, light, intensity, colour));
        s.render.doppler = d;
        s.render.searchlight = sl;
        s.render.light_source_delay = delay;
        const Image image = render_image(s, {});
        for (int j = 0; j < 9; ++j)
          for (int i = 0; i < 9; ++i) {
            const double e = 0.5 * intensity * lambert(light, plane_point(s, i, j));
            expect_rgb_near(pixel(image, i, j), {e * colour.r, e * colour.g, e * colour.b}, 1e-6,
                            at(i, j));
          }
      }
}

TEST(StaticLighting, ClassicalPictureAgreesWithTheRelativisticOneAtRest) {
  Scene s = top_down({0, 5, 0}, 40, 9);
  s.lights.push_back(make_light(PointLight{}, {0.7, 2.5, -0.4}, 6));
  Scene classical = s;
  classical.render.relativity = false;
  EXPECT_EQ(render_image(s, {}).rgb, render_image(classical, {}).rgb);
}

// The classical picture draws every body where it is at the camera's time; a moving light
// lights them from where it is then too, with no Doppler factor or aberration: the same image
// as a light at rest there.
TEST(StaticLighting, ClassicalPictureLightsFromWhereAMovingLightIsAtTheCamerasTime) {
  const Vec3 at_camera_time{0.7, 2.5, -0.4}, velocity{0.6, 0, -0.3};
  const double t0 = -4;  // the light's reference event, 4 before the camera's time 0
  Scene moving = top_down({0, 5, 0}, 40, 9);
  moving.render.relativity = false;
  Light lamp =
      make_light(PointLight{}, at_camera_time - velocity * (0 - t0), 6, {1, 1, 1}, velocity);
  lamp.world_line.time = t0;
  moving.lights.push_back(lamp);
  Scene still = moving;
  still.lights[0].world_line = {};
  still.lights[0].world_line.position = at_camera_time;
  const Image image = render_image(moving, {});
  EXPECT_EQ(image.rgb, render_image(still, {}).rgb);
  const double e = 0.5 * 6 * lambert(at_camera_time, plane_point(moving, 4, 4));
  expect_rgb_near(pixel(image, 4, 4), {e, e, e}, 1e-6, at(4, 4));
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

TEST(StaticLighting, SpotLightIsFullInsideItsConeZeroOutsideAndSmoothInTheFalloff) {
  const Vec3 light{0.3, 4, -0.2};
  const Vec3 axis = normalize(Vec3{0.2, -1, 0.1});
  SpotLight spot;
  spot.direction = {0.2, -1, 0.1};  // not unit: the renderer normalises it
  spot.cone_degrees = 50;
  spot.falloff_degrees = 12;  // full inside 13 degrees, zero beyond 25
  const double intensity = 10;
  for (const DopplerModel d : {DopplerModel::kSpectral, DopplerModel::kOff}) {
    Scene s = top_down({0, 8, 0}, 36, 25);
    s.lights.push_back(make_light(spot, light, intensity));
    s.render.doppler = d;
    const Image image = render_image(s, {});
    int inside = 0, falloff = 0, outside = 0;
    for (int j = 0; j < 25; ++j)
      for (int i = 0; i < 25; ++i) {
        const Vec3 p = plane_point(s, i, j);
        const double angle =
            std::acos(std::clamp(dot(normalize(p - light), axis), -1.0, 1.0)) * 180 / kPi;
        const double factor = 1 - smoothstep(13, 25, angle);
        inside += angle < 12.9;
        falloff += angle > 13.1 && angle < 24.9;
        outside += angle > 25.1;
        const double e = 0.5 * intensity * factor * lambert(light, p);
        const LinearRgb got = pixel(image, i, j);
        expect_rgb_near(got, {e, e, e}, 1e-6, at(i, j));
        if (angle > 25.0) {
          EXPECT_EQ(got.r, 0.0f) << at(i, j);
        }
      }
    // The view holds all three regions.
    EXPECT_GT(inside, 20);
    EXPECT_GT(falloff, 40);
    EXPECT_GT(outside, 100);
  }
}

TEST(StaticLighting, DirectionalLightIsItsIrradianceTimesTheCosine) {
  DirectionalLight sun;
  sun.direction = {0.3, -1, 0.2};
  sun.irradiance = 2.5;
  const double cos_i = 1 / length(sun.direction);
  const double e = sun.irradiance * cos_i / kPi;
  // The RGB models multiply the albedo's and the light's RGB; the spectral one their spectra,
  // whose colour differs a little (here by up to 3 %) for a coloured light on a coloured surface.
  const LinearRgb albedo{0.5, 0.25, 0.125}, light{1.0, 0.9, 0.8};
  const RgbAlbedoSpectrum rho = RgbAlbedoSpectrum::from_rgb(albedo);
  const RgbEmitterSpectrum source = RgbEmitterSpectrum::from_rgb(light);
  const LinearRgb product =
      linear_srgb_from_xyz(xyz_from_spectrum([&](double l) { return rho(l) * source(l); }));
  const struct {
    DopplerModel model;
    LinearRgb want;
  } cases[] = {{DopplerModel::kSpectral, {e * product.r, e * product.g, e * product.b}},
               {DopplerModel::kOff, {0.5 * e, 0.25 * 0.9 * e, 0.125 * 0.8 * e}}};
  for (const auto& c : cases) {
    Scene s = top_down({0, 5, 0}, 40, 9, {0.5f, 0.25f, 0.125f});
    s.lights.push_back(make_light(sun, {}, 1, {1.0f, 0.9f, 0.8f}));
    s.render.doppler = c.model;
    const Image image = render_image(s, {});
    for (int j = 0; j < 9; ++j)
      for (int i = 0; i < 9; ++i) expect_rgb_near(pixel(image, i, j), c.want, 1e-6, at(i, j));
  }
  EXPECT_GT(std::abs(product.r / (0.5 * 1.0) - 1), 1e-3);  // the two really differ
}

// A plane wave's irradiance scales as D^2 (its energy density does): sunlight falling straight
// down on a floor rising toward the sun at beta, seen from straight above by a camera at rest,
// is brighter than the floor at rest by D^2 (irradiance in the floor's frame) times D^4 (the
// reflected radiance beamed to the camera, which the floor also approaches): D^6, with
// D = sqrt((1 + beta) / (1 - beta)) on both legs. Head-on, nothing is aberrated.
TEST(MovingSurface, PlaneWaveOnAFloorRisingTowardTheSunBrightensByD6) {
  DirectionalLight sun;
  sun.direction = {0, -1, 0};
  sun.irradiance = 1.5;
  Scene rest = top_down({0, 50, 0}, 2, 5);
  rest.lights.push_back(make_light(sun, {}, 1));
  rest.render.doppler = DopplerModel::kOff;
  for (const double beta : {0.3, -0.4}) {
    Scene moving = rest;
    moving.objects[0].world_line.velocity = {0, beta, 0};
    const double d = std::sqrt((1 + beta) / (1 - beta));
    const double expected = pixel(render_image(rest, {}), 2, 2).r * std::pow(d, 6);
    EXPECT_NEAR(pixel(render_image(moving, {}), 2, 2).r, expected, 1e-6 * expected) << beta;
  }
}

TEST(StaticLighting, SphereLightConvergesToTheIrradianceOfAUniformSphere) {
  // A sphere of uniform radiance L = I / (pi R^2) entirely above a patch's horizon subtends
  // a cap whose projected solid angle is pi (R/d)^2 cos(alpha): E = pi L (R/d)^2 cos(alpha) =
  // I cos(alpha) / d^2 (d: the distance to its centre), exactly the point light at its centre,
  // however close. Here the sphere (R = 1, centre 1.5 above the plane) is close enough that a
  // wrong area estimator would show, and the point-light render, with the same sample
  // positions in each pixel, is the reference (its own exactness is tested above).
  const Vec3 centre{0.2, 1.5, 0.1};
  const double intensity = 4;
  const int size = 15, samples = 8192;
  Scene sphere_scene = top_down({0, 6, 0}, 30, size);
  sphere_scene.camera.samples = samples;
  Scene point_scene = sphere_scene;
  sphere_scene.lights.push_back(make_light(SphereLight{1.0}, centre, intensity));
  point_scene.lights.push_back(make_light(PointLight{}, centre, intensity));
  sphere_scene.render.doppler = point_scene.render.doppler = DopplerModel::kOff;
  const Image got = render_image(sphere_scene, {});
  const Image want = render_image(point_scene, {});
  double sum = 0;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double ratio = pixel(got, i, j).g / pixel(want, i, j).g;
      // One pixel: 8192 samples of an estimator with a relative spread of about 2.7 (the
      // sphere is close: 1 / distance^2 varies 25-fold over it), so about 3%.
      EXPECT_NEAR(ratio, 1.0, 0.2) << at(i, j);
      sum += ratio;
    }
  // All pixels: about 1.8e6 samples, a standard error of about 0.2% (deterministic samples:
  // 0.1% here); a 2.5% error in the estimator's weight fails.
  EXPECT_NEAR(sum / (size * size), 1.0, 0.008);
}

// GGX with Smith's exact masking and Schlick's Fresnel (Walter et al. 2007), written out.
double ggx(double roughness, double f0, const Vec3& n, const Vec3& l, const Vec3& v) {
  const double a2 = std::pow(roughness, 4);  // alpha = roughness^2
  const Vec3 h = normalize(l + v);
  const double nh = dot(n, h), nl = dot(n, l), nv = dot(n, v);
  const double q = nh * nh * (a2 - 1) + 1;
  const double distribution = a2 / (kPi * q * q);
  auto g1 = [&](double c) { return 2 * c / (c + std::sqrt(a2 + (1 - a2) * c * c)); };
  const double fresnel = f0 + (1 - f0) * std::pow(1 - dot(h, v), 5);
  return distribution * g1(nl) * g1(nv) * fresnel / (4 * nl * nv);
}

TEST(StaticLighting, GlossySurfaceAtRestIsTheGgxFormulaEvaluatedByHand) {
  // The camera 6 above the origin, the light at (1.5, 3, 0): the mirror point is (1, 0, 0),
  // inside the view, so the image holds the specular peak and its tails.
  const Vec3 eye{0, 6, 0}, light{1.5, 3, 0};
  const double intensity = 9, albedo = 0.5;
  Scene s = top_down(eye, 26, 15);
  s.objects[0].material.glossy = Glossy{0.3, 0.04};
  s.lights.push_back(make_light(PointLight{}, light, intensity));
  s.render.doppler = DopplerModel::kOff;
  const Image image = render_image(s, {});
  double peak = 0, least = 1e9;
  for (int j = 0; j < 15; ++j)
    for (int i = 0; i < 15; ++i) {
      const Vec3 p = plane_point(s, i, j), n{0, 1, 0};
      const Vec3 l = normalize(light - p), v = normalize(eye - p);
      const double specular = ggx(0.3, 0.04, n, l, v);
      const double brdf = (1 - 0.04) * albedo / kPi + specular;
      const double e = brdf * intensity * l.y / dot(light - p, light - p);
      expect_rgb_near(pixel(image, i, j), {e, e, e}, 1e-6, at(i, j));
      peak = std::max(peak, specular * kPi / albedo);
      least = std::min(least, specular * kPi / albedo);
    }
  // Not trivially Lambertian: the lobe dominates at the mirror point and vanishes far from it.
  EXPECT_GT(peak, 1.5);
  EXPECT_LT(least, 0.01);
}

// ---------------------------------------------------------------------------------------------
// 2. A light carried with the camera toward a Lambertian wall: D^2 on the irradiance (at the
// same light-frame distance r_L) and D^4 on the reflected radiance reaching the camera.

TEST(CoMovingLight, HeadOnWallBrightensByD6OverTheStaticWallAtTheSameLightFrameDistance) {
  const double a = 19.5;  // the wall's face is at z = -a in W, where the wall is at rest
  const double albedo = 0.5, intensity = 50;
  for (const double b : {0.5, -0.5, 0.9}) {
    SCOPED_TRACE("closing speed " + std::to_string(b));
    const double d = std::sqrt((1 + b) / (1 - b));
    const Vec3 velocity{0, 0, -b};
    // Camera and light at the origin at t = 0, both moving with `velocity`. The centre pixel
    // sees S = (-a, (0, 0, -a)); the light left E on S's past light cone:
    // t_S - t_E = z_L(t_E) - z_S = -b t_E + a, so t_E = -2 a / (1 - b).
    const double t_e = -2 * a / (1 - b);
    const Vec4 s_event{-a, {0, 0, -a}}, e_event{t_e, Vec3{0, 0, -b * t_e}};
    // The light-frame distance: |(S - E) boosted into the light's frame| = a D.
    const double r_l = length((boost(velocity) * (s_event - e_event)).x);
    ASSERT_NEAR(r_l, a * d, 1e-9 * a * d);
    // The kernels agree: in the wall's frame the distance is D r_L and the factor D.
    const ReceivedLeg leg = receive_leg(e_event, velocity, s_event, {});
    ASSERT_NEAR(leg.doppler, d, 1e-12);
    ASSERT_NEAR(leg.distance, d * r_l, 1e-9 * d * r_l);

    Scene moving;
    moving.camera.world_line.velocity = velocity;
    moving.camera.width = moving.camera.height = 5;
    moving.camera.fov_degrees = 1;
    moving.objects.push_back(
        make_object("wall", Box{{40, 40, 1}}, {0, 0, -a - 0.5}, {}, lit({0.5f, 0.5f, 0.5f})));
    moving.lights.push_back(make_light(PointLight{}, {}, intensity, {1, 1, 1}, velocity));
    moving.render.doppler = DopplerModel::kOff;
    moving.render.searchlight = SearchlightModel::kPhysical;
    // The same wall, camera and light at rest at the light-frame distance r_L.
    Scene still = moving;
    still.camera.world_line = {0, {0, 0, -a + r_l}, {}};
    still.lights[0].world_line = still.camera.world_line;

    const double rest = albedo / kPi * intensity / (r_l * r_l);
    const double got_still = pixel(render_image(still, {}), 2, 2).g;
    const double got_moving = pixel(render_image(moving, {}), 2, 2).g;
    EXPECT_NEAR(got_still, rest, 1e-6 * rest);
    EXPECT_NEAR(got_moving / got_still, std::pow(d, 6), 1e-6 * std::pow(d, 6));
  }
}

// ---------------------------------------------------------------------------------------------
// 3. The light-source delay modes.

// A busy lit scene, all at rest in W (a light too), seen by a camera moving at `camera`.
Scene static_lit_scene(const Vec3& camera) {
  Scene s;
  s.camera.world_line.position = {0, 1.5, 6};
  s.camera.world_line.velocity = camera;
  s.camera.forward = {0, -0.25, -1};
  s.camera.width = 96;
  s.camera.height = 64;
  s.camera.fov_degrees = 70;
  s.objects.push_back(make_object("ground", Plane{30, 30}, {0, -1, -3}, {},
                                  lit_checker({0.8f, 0.8f, 0.8f}, {0.3f, 0.5f, 0.2f})));
  s.objects.push_back(make_object("ball", Sphere{0.8}, {-1, 0, -2}, {}, lit({0.9f, 0.3f, 0.2f})));
  Object box = make_object("box", Box{{1, 1.5, 1}}, {1.6, -0.25, -3}, {}, lit({0.2f, 0.4f, 0.9f}));
  box.rotation = Mat3::rotation({0, 1, 0}, 0.6);
  box.material.glossy = Glossy{0.4, 0.05};
  s.objects.push_back(box);
  s.lights.push_back(make_light(PointLight{}, {0.5, 3, -1}, 12, {1.0f, 0.9f, 0.7f}));
  SpotLight spot;
  spot.direction = {-0.4, -1, -0.2};
  s.lights.push_back(make_light(spot, {2, 3.5, 0}, 15));
  s.sky.pattern = SkyGrid{};
  return s;
}

TEST(LightSourceDelay, ModesAgreeForALightAtRestWithTheSurfacesItLights) {
  // A light at rest in W is at the same place at every time: its surface-cone, camera-cone and
  // camera-time events differ only in time, and a static surface receives the same light from
  // each (the separations have the same spatial part in the surface's frame, D = 1), and the
  // static occluders cast the same shadows. Even for a camera moving at 0.6c.
  const Scene base = static_lit_scene({0.36, 0, -0.48});
  const Image surface = render_image(base, {});
  // The picture is lit and shadowed: some pixels are dark, most are not.
  int lit_pixels = 0;
  for (std::size_t p = 0; p < surface.rgb.size(); p += 3) lit_pixels += surface.rgb[p + 1] > 1e-3f;
  EXPECT_GT(lit_pixels, static_cast<int>(surface.rgb.size() / 3 / 2));
  for (const LightSourceDelay delay : {LightSourceDelay::kCamera, LightSourceDelay::kNone}) {
    SCOPED_TRACE(delay_name(delay));
    Scene other = base;
    other.render.light_source_delay = delay;
    const Image got = render_image(other, {});
    int differing = 0;
    for (std::size_t k = 0; k < got.rgb.size(); ++k)
      differing +=
          std::abs(got.rgb[k] - surface.rgb[k]) > 1e-6 * std::max(1.0f, std::abs(surface.rgb[k]));
    EXPECT_EQ(differing, 0);
  }
}

// Seed 004's interceptor (light-transport.md, worked example): a point light at b = 0.5 along
// +x, h = 10 above the lit point at the origin, overhead at t = 0; a camera at rest 100 above,
// observing at t = 100, so that it sees the point lit at t_S = 0.
struct ModePrediction {
  Vec3 light_position;  // the light's event
  double t = 0;
  double pixel_physical = 0, pixel_off = 0;  // searchlight physical, off (doppler off)
  Vec3 direction_to_light;
};

ModePrediction interceptor_prediction(double t_emit, double b, double h, double intensity,
                                      double albedo) {
  ModePrediction m;
  m.t = t_emit;
  m.light_position = {b * t_emit, h, 0};
  // The surface is at rest in W: its frame is W. Propagation n from the light's event to the
  // point, distance r; D = 1 / (gamma (1 - beta.n)) for an emitter moving with beta.
  const Vec3 sep = Vec3{} - m.light_position;
  const double r = length(sep);
  const Vec3 n = sep / r;
  const double gamma = 1 / std::sqrt(1 - b * b);
  const double d = 1 / (gamma * (1 - b * n.x));
  m.direction_to_light = -n;
  const double cos_i = -n.y;
  m.pixel_off = albedo / kPi * intensity * cos_i / (r * r);
  m.pixel_physical = m.pixel_off * std::pow(d, 4);
  return m;
}

TEST(LightSourceDelay, InterceptorModesDisagreeByThePredictedAngleAndBrightness) {
  const double b = 0.5, h = 10, big_h = 100, t_obs = 100, intensity = 100, albedo = 0.5;
  const double gamma = 1 / std::sqrt(1 - b * b);
  // surface: the past light cone of S = (0, origin): t^2 = (b t)^2 + h^2, t < 0.
  const double t_surface = -gamma * h;
  // camera: the past light cone of (t_obs, (0, H, 0)): (t_obs - t)^2 = (b t)^2 + (H - h)^2.
  const double t_camera =
      (t_obs -
       std::sqrt(t_obs * t_obs - (1 - b * b) * (t_obs * t_obs - (big_h - h) * (big_h - h)))) /
      (1 - b * b);
  const ModePrediction surface = interceptor_prediction(t_surface, b, h, intensity, albedo);
  const ModePrediction camera = interceptor_prediction(t_camera, b, h, intensity, albedo);
  const ModePrediction none = interceptor_prediction(t_obs, b, h, intensity, albedo);
  // The worked example's numbers (light-transport.md).
  const double deg = 180 / kPi;
  EXPECT_NEAR(surface.light_position.x, -5.774, 1e-3);
  EXPECT_NEAR(camera.light_position.x, 4.932, 1e-3);
  EXPECT_NEAR(std::acos(dot(surface.direction_to_light, camera.direction_to_light)) * deg, 56.255,
              1e-3);
  const double unit = albedo / kPi * intensity / (h * h);
  EXPECT_NEAR(surface.pixel_physical / unit, 1.155, 1e-3);
  EXPECT_NEAR(camera.pixel_physical / unit, 0.182, 1e-3);
  EXPECT_NEAR(none.pixel_physical / unit, 0.00086, 1e-5);

  Scene s = top_down({0, big_h, 0}, 1, 5);
  s.camera.world_line.time = t_obs;
  s.lights.push_back(make_light(PointLight{}, {0, h, 0}, intensity, {1, 1, 1}, {b, 0, 0}));
  s.render.doppler = DopplerModel::kOff;
  const struct {
    LightSourceDelay delay;
    const ModePrediction& want;
  } modes[] = {{LightSourceDelay::kSurface, surface},
               {LightSourceDelay::kCamera, camera},
               {LightSourceDelay::kNone, none}};
  for (const auto& m : modes)
    for (const SearchlightModel sl : {SearchlightModel::kPhysical, SearchlightModel::kOff}) {
      SCOPED_TRACE(std::string(delay_name(m.delay)) +
                   (sl == SearchlightModel::kOff ? ", searchlight off" : ", physical"));
      s.render.light_source_delay = m.delay;
      s.render.searchlight = sl;
      const double want = sl == SearchlightModel::kOff ? m.want.pixel_off : m.want.pixel_physical;
      EXPECT_NEAR(pixel(render_image(s, {}), 2, 2).g, want, 1e-6 * want);
    }
}

// ---------------------------------------------------------------------------------------------
// 4. The shadow of an occluder moving at 0.9c.

TEST(Shadows, FastOccluderShadowFallsWhereTheRetardedGeometryPutsIt) {
  // A static point light L = (0, 3, 0) above the lit plane y = 0; a small sphere (radius 0.2,
  // at rest in its frame) at height 1.5 crossing along +x at 0.9c, through (x0, 1.5, 0) at
  // t = 0; a camera at rest 60 above, observing at t = 0, so that it sees the plane point p as
  // it was at t_S(p) = -|C - p|. The light reaching S = (t_S, p) left L at t_S - |p - L|; the
  // shadow ray is that null segment, and the sphere blocks it where the sphere is at each of
  // its events. Its centre lies on the segment where the segment crosses height 1.5, i.e. at
  // lambda = 1/2 of the way from L to p, at time t_c = t_S - |p - L| / 2: the shadow centre
  // solves lambda x = x0 + v t_c(x) (z = 0 by symmetry).
  const Vec3 light{0, 3, 0}, eye{0.5, 60, 0};
  const double v = 0.9, radius = 0.2, height = 1.5, x0 = 55.6;
  const double lambda = 1 - height / light.y;
  const int size = 151;
  Scene s = top_down(eye, 2 * std::atan(3.0 / eye.y) * 180 / kPi, size);
  s.objects.push_back(make_object("ball", Sphere{radius}, {x0, height, 0}, {v, 0, 0},
                                  emitter({1, 0, 0})));  // red: never mistaken for shadow
  s.lights.push_back(make_light(PointLight{}, light, 9));
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kOff;

  auto t_s = [&](const Vec3& p) { return -length(eye - p); };
  auto centre_mismatch = [&](double x) {
    const Vec3 p{x, 0, 0};
    const double t_c = t_s(p) - (1 - lambda) * length(p - light);
    return lambda * x - (x0 + v * t_c);
  };
  // The mismatch grows with x here (slope about 0.5); bisection.
  double lo = -2.5, hi = 3.5;
  ASSERT_LT(centre_mismatch(lo), 0);
  ASSERT_GT(centre_mismatch(hi), 0);
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (centre_mismatch(mid) < 0 ? lo : hi) = mid;
  }
  const double x_star = 0.5 * (lo + hi);

  // Every pixel's shadow, predicted independently: the null segment carried into the
  // sphere's rest frame (where it is static, centred on the origin) passes within its radius.
  const Mat4 to_ball = boost({v, 0, 0});
  const Vec4 ball_origin{0, {x0, height, 0}};
  auto shadow_margin = [&](const Vec3& p) {
    const Vec4 surface_event{t_s(p), p};
    const Vec4 light_event{t_s(p) - length(p - light), light};
    const Vec3 a = (to_ball * (light_event - ball_origin)).x;
    const Vec3 b = (to_ball * (surface_event - ball_origin)).x;
    const double t = std::clamp(-dot(a, b - a) / dot(b - a, b - a), 0.0, 1.0);
    return length(a + (b - a) * t) - radius;  // < 0: in shadow
  };

  const Image image = render_image(s, {});
  const CameraBasis basis = camera_basis(s.camera);
  double sum_x = 0, sum_y = 0;
  int dark = 0, mismatched = 0, red_near = 0, predicted = 0;
  double predicted_x = 0, predicted_y = 0;
  int lo_i = size, hi_i = -1, lo_j = size, hi_j = -1;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const LinearRgb c = pixel(image, i, j);
      const bool shadowed = c.r == 0 && c.g == 0 && c.b == 0;
      if (shadowed) {
        ++dark;
        sum_x += i + 0.5;
        sum_y += j + 0.5;
        lo_i = std::min(lo_i, i), hi_i = std::max(hi_i, i);
        lo_j = std::min(lo_j, j), hi_j = std::max(hi_j, j);
      }
      const double margin = shadow_margin(plane_point(s, i, j));
      if (std::abs(margin) > 1e-3 * radius && (margin < 0) != shadowed) ++mismatched;
      if (margin < 0) {
        ++predicted;
        predicted_x += i + 0.5;
        predicted_y += j + 0.5;
      }
    }
  for (int j = std::max(0, lo_j - 3); j <= std::min(size - 1, hi_j + 3); ++j)
    for (int i = std::max(0, lo_i - 3); i <= std::min(size - 1, hi_i + 3); ++i)
      red_near += pixel(image, i, j).r > 0 && pixel(image, i, j).g == 0;
  ASSERT_GT(dark, 100);    // a shadow many pixels across (about 9 by 28)
  EXPECT_EQ(red_near, 0);  // and the ball's own image does not cover any of it
  // Pixel for pixel the predicted shadow (but for pixels within 1e-3 radius of its edge).
  EXPECT_EQ(mismatched, 0);
  EXPECT_NEAR(sum_x / dark, predicted_x / predicted, 0.1);
  EXPECT_NEAR(sum_y / dark, predicted_y / predicted, 0.1);
  // Centred on the shadow of the ball's centre, to within the asymmetry of the shadow of a
  // sphere (which is not centred on the shadow of its centre; here 1.1 pixels along x).
  const ImagePoint want = project_direction(basis, Vec3{x_star, 0, 0} - eye);
  EXPECT_NEAR(sum_x / dark, want.x, 1.5);
  EXPECT_NEAR(sum_y / dark, want.y, 0.5);

  // The naive geometries put it far away: the sphere where it is at the camera's time, or
  // at the surface event's time (the shadow leg taken as instantaneous).
  const double pixel_size = 6.0 / size;
  const double at_camera_time = x0 / lambda;
  const double at_surface_time = (x0 + v * t_s({x_star, 0, 0})) / lambda;
  EXPECT_GT(std::abs(at_camera_time - x_star), 5 * pixel_size);
  EXPECT_GT(std::abs(at_surface_time - x_star), 5 * pixel_size);
  // The latter is in view, and lit.
  const ImagePoint naive = project_direction(basis, Vec3{at_surface_time, 0, 0} - eye);
  ASSERT_GE(naive.x, 0);
  ASSERT_LT(naive.x, size);
  EXPECT_GT(pixel(image, static_cast<int>(naive.x), static_cast<int>(naive.y)).g, 0.0f);
}

TEST(Shadows, DirectionalLightShadowFallsOnTheSideAwayFromTheSun) {
  // A sun shining along (0.6, -1, 0) onto the plane y = 0; a ball of radius 0.3 centred 1
  // above (-1, 0, 0) shadows the plane around (-1 + 0.6, 0, 0). A second ball below the plane,
  // centred at (1, -1, 0), is behind the lit side: it must shadow nothing (a shadow ray that
  // ran along the sun's light instead of back toward the sun would find it from (0.4, 0, 0)).
  DirectionalLight sun;
  sun.direction = {0.6, -1, 0};
  sun.irradiance = 3;
  Scene s = top_down({0, 20, 0}, 2 * std::atan(2.0 / 20) * 180 / kPi, 41);
  s.objects.push_back(make_object("above", Sphere{0.3}, {-1, 1, 0}, {}, lit({1, 1, 1})));
  s.objects.push_back(make_object("below", Sphere{0.3}, {1, -1, 0}, {}, lit({1, 1, 1})));
  s.lights.push_back(make_light(sun, {}, 1));
  s.render.doppler = DopplerModel::kOff;
  const Image image = render_image(s, {});
  const CameraBasis basis = camera_basis(s.camera);
  const double lit_value = 0.5 * 3 / length(sun.direction) / kPi;
  auto value_at = [&](const Vec3& p) {
    const ImagePoint q = project_direction(basis, p - s.camera.world_line.position);
    return pixel(image, static_cast<int>(q.x), static_cast<int>(q.y)).g;
  };
  EXPECT_EQ(value_at({-0.4, 0, 0}), 0.0f) << "no shadow under the ball between sun and plane";
  EXPECT_NEAR(value_at({0.4, 0, 0}), lit_value, 1e-6 * lit_value)
      << "a ball below the plane shadows the lit side";
  EXPECT_NEAR(value_at({1.5, 0, 1.5}), lit_value, 1e-6 * lit_value);
}

// ---------------------------------------------------------------------------------------------
// 5. The principle of relativity with lights in motion, surface delay and shadows.

using test::fraction_differing;

Scene moving_lights_scene() {
  Scene s;
  s.camera.world_line.position = {0, 1.5, 7};
  s.camera.world_line.velocity = {0.2, -0.1, -0.5};
  s.camera.forward = {0, -0.2, -1};
  s.camera.width = 120;
  s.camera.height = 80;
  s.camera.fov_degrees = 70;
  s.objects.push_back(make_object("ground", Plane{30, 30}, {0, -1, -3}, {},
                                  lit_checker({0.8f, 0.8f, 0.8f}, {0.4f, 0.5f, 0.3f})));
  Object ball =
      make_object("ball", Sphere{0.8}, {-1.5, 0, -2}, {0.6, 0, 0}, lit({0.9f, 0.4f, 0.2f}));
  ball.world_line.time = -8;
  ball.material.glossy = Glossy{0.35, 0.05};
  s.objects.push_back(ball);
  Object box = make_object("box", Box{{1, 1.5, 1}}, {1.8, -0.25, -3}, {}, lit({0.3f, 0.5f, 0.9f}));
  box.rotation = Mat3::rotation({0.2, 1, 0}, 0.6);
  s.objects.push_back(box);
  Object ember = make_object("ember", Box{{0.8, 0.8, 0.8}}, {-3, 0.5, -4}, {0, 0.1, 0.5},
                             emitter({1, 0.5f, 0.2f}));
  ember.world_line.time = -8;
  s.objects.push_back(ember);
  // A light flying at 0.63c over the scene, and a spot light at 0.41c (moving, so that its
  // axis is turned by a Wigner rotation when the scene is described from another frame).
  Light flyer = make_light(PointLight{}, {-0.5, 2, -1.5}, 8, {1.0f, 0.9f, 0.8f}, {0.6, 0, 0.2});
  flyer.world_line.time = -8;
  s.lights.push_back(flyer);
  SpotLight spot;
  spot.direction = {-0.3, -1, -0.5};
  spot.cone_degrees = 70;
  spot.falloff_degrees = 10;
  Light lamp = make_light(spot, {2, 3, -0.5}, 15, {1, 1, 1}, {-0.1, 0, 0.4});
  lamp.world_line.time = -8;
  lamp.spectrum.emission = Blackbody{4000, 1};
  s.lights.push_back(lamp);
  s.sky.pattern = SkyGrid{};
  s.render.doppler = DopplerModel::kSpectral;
  s.render.searchlight = SearchlightModel::kPhysical;
  s.render.light_source_delay = LightSourceDelay::kSurface;
  s.render.shadows = true;
  return s;
}

TEST(PrincipleOfRelativity, HoldsWithMovingLightsSurfaceDelayAndShadows) {
  const Scene scene = moving_lights_scene();
  const Image image = render_image(scene, {});
  // The lights really are at work: without them (or without the moving one) most (or much)
  // of the picture changes.
  Scene dark = scene;
  dark.lights.clear();
  EXPECT_GT(fraction_differing(image, render_image(dark, {})), 0.4);
  Scene one = scene;
  one.lights.erase(one.lights.begin());
  EXPECT_GT(fraction_differing(image, render_image(one, {})), 0.1);
  for (const Vec3 frame : {Vec3{0.4, -0.3, 0.5}, Vec3{-0.8, 0.1, 0.2}}) {
    const Scene other = describe_in_frame(scene, frame);
    ASSERT_GT(length(other.camera.world_line.velocity - scene.camera.world_line.velocity), 0.1);
    // The lights are re-described too (their world-lines and the spot's axis).
    ASSERT_EQ(other.lights.size(), scene.lights.size());
    EXPECT_GT(length(other.lights[0].world_line.velocity - scene.lights[0].world_line.velocity),
              0.1);
    EXPECT_GT(length(other.lights[1].world_line.velocity - scene.lights[1].world_line.velocity),
              0.1);
    EXPECT_LT(fraction_differing(image, render_image(other, {})), 0.003);
  }
}

TEST(PrincipleOfRelativity, HoldsForTheCameraModeButNotForTheNoneMode) {
  // The camera mode's light event (on the camera's past light cone) and its leg (along the
  // separation, in the surface's frame) are frame-independent: the picture is the same from
  // any frame, even though it differs from the exact one. The none mode takes the light where
  // it is at the camera's time in the frame the scene is written in: a frame-dependent
  // choice, which the comparison must detect.
  const Scene scene = moving_lights_scene();
  const Vec3 frame{0.4, -0.3, 0.5};
  Scene camera_mode = scene;
  camera_mode.render.light_source_delay = LightSourceDelay::kCamera;
  const Image camera_image = render_image(camera_mode, {});
  EXPECT_GT(fraction_differing(render_image(scene, {}), camera_image), 0.05);
  EXPECT_LT(
      fraction_differing(camera_image, render_image(describe_in_frame(camera_mode, frame), {})),
      0.003);
  Scene none_mode = scene;
  none_mode.render.light_source_delay = LightSourceDelay::kNone;
  EXPECT_GT(fraction_differing(render_image(none_mode, {}),
                               render_image(describe_in_frame(none_mode, frame), {})),
            0.05);
}

// ---------------------------------------------------------------------------------------------
// 6. Bad states.

bool all_finite(const Image& image) {
  return std::all_of(image.rgb.begin(), image.rgb.end(), [](float v) { return std::isfinite(v); });
}

TEST(BadStates, LitSurfacesWithNoLightsAreBlackAndEmittersStillShine) {
  Scene s = static_lit_scene({0.3, 0, -0.5});
  s.lights.clear();
  s.sky.pattern = SolidColor{{0, 0, 0}};
  s.objects.push_back(make_object("ember", Sphere{1}, {0, 0.5, -1}, {}, emitter({1, 0.5f, 0.2f})));
  for (const DopplerModel d : {DopplerModel::kSpectral, DopplerModel::kOff}) {
    s.render.doppler = d;
    const Image image = render_image(s, {});
    ASSERT_TRUE(all_finite(image));
    int shining = 0, black = 0;
    for (std::size_t p = 0; p < image.rgb.size(); p += 3) {
      const bool zero = image.rgb[p] == 0 && image.rgb[p + 1] == 0 && image.rgb[p + 2] == 0;
      black += zero;
      shining += !zero;
    }
    // Only the ember shows: it covers a small part of the view.
    EXPECT_GT(shining, 30);
    EXPECT_GT(black, static_cast<int>(image.rgb.size() / 3) * 3 / 4);
  }
}

TEST(BadStates, ALightExactlyAtTheLitPointGivesFinitePixels) {
  // The centre pixel of a camera at rest above the plane sees the origin; a light whose
  // world-line passes through that very surface event (r = 0 in every mode for a light at
  // rest there; in the surface mode for a moving one too).
  Scene s = top_down({0, 5, 0}, 20, 5);
  const ResolvedScene r = resolve_scene(s);
  const Tracer tracer(r);
  // The surface event exactly as the renderer computes it.
  const Vec3 u = look_direction(r.camera, 2.5, 2.5);
  const auto hit = tracer.trace(u);
  ASSERT_TRUE(hit.has_value());
  const Vec4 surface = r.trace_to_world(Vec4{r.ray_time * hit->s, u * hit->s});
  ASSERT_EQ(surface.x.x, 0.0);
  ASSERT_EQ(surface.x.y, 0.0);
  ASSERT_EQ(surface.x.z, 0.0);
  SpotLight spot;
  spot.direction = {0, -1, 0};
  for (const auto& kind : std::vector<std::variant<PointLight, SpotLight, SphereLight>>{
           PointLight{}, spot, SphereLight{0.3}})
    for (const Vec3 velocity : {Vec3{}, Vec3{0.5, 0, 0}})
      for (const LightSourceDelay delay :
           {LightSourceDelay::kSurface, LightSourceDelay::kCamera, LightSourceDelay::kNone})
        for (const DopplerModel d : {DopplerModel::kSpectral, DopplerModel::kOff}) {
          SCOPED_TRACE(std::string("kind ") + std::to_string(kind.index()) + ", speed " +
                       std::to_string(velocity.x) + ", " + delay_name(delay));
          Scene t = s;
          Light light;
          std::visit([&](const auto& k) { light.kind = k; }, kind);
          light.world_line = {surface.t, surface.x, velocity};
          light.intensity = 2;
          t.lights.push_back(light);
          t.render.light_source_delay = delay;
          t.render.doppler = d;
          const Image image = render_image(t, {});
          EXPECT_TRUE(all_finite(image));
          // Without the spectral estimate (whose change term may make a channel negative),
          // every term is a product of non-negative factors.
          if (d == DopplerModel::kOff) {
            for (const float v : image.rgb) EXPECT_GE(v, 0.0f);
          }
        }
}

// The bodies' world-frame maps, which shadow rays (and curved rays) read, are resolved for
// scenes with lights, one a body, and not carried by unlit scenes: a swarm of unlit bodies
// does not pay for them. Each maps a body's W events to its shape as its own frame does.
TEST(WorldShapeMaps, OnlyScenesWithLightsOrAHoleCarryThem) {
  Scene s = top_down({0, 5, 0}, 60, 8);
  s.objects.push_back(
      make_object("ball", Sphere{0.5}, {1, 0.5, 2}, {0.3, 0, -0.2}, emitter({1, 0, 0})));
  EXPECT_TRUE(resolve_scene(s).world_maps.empty());
  s.lights.push_back(make_light(PointLight{}, {0, 3, 0}, 10));
  const ResolvedScene r = resolve_scene(s);
  ASSERT_EQ(r.world_maps.size(), r.bodies.size());
  // The ball's centre is its shape's origin at every W time on its world-line.
  for (const double t : {-3.0, 0.0, 2.5}) {
    const Vec3 centre = Vec3{1, 0.5, 2} + Vec3{0.3, 0, -0.2} * t;
    const Vec3 p = r.world_maps[1].shape_point(Vec4{t, centre});
    EXPECT_NEAR(length(p), 0, 1e-12) << t;
  }
}

}  // namespace
}  // namespace lightcone

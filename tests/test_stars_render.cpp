// The stars as point sources in the tracer's pictures (frame/star_field.hpp), against
// derivations made here: the aberration formula cos(theta') = (cos(theta) + beta) / (1 + beta
// cos(theta)) for where a star lands; Planck's law for its received flux (a blackbody at T whose
// spectral flux F_lambda(lambda) becomes D^3 F_lambda(D lambda) is, by B_lambda(D lambda; T) =
// D^-5 B_lambda(lambda; D T), a blackbody at D T with D^-2 its scale: bolometric D^2); every
// star's flux kept whole at the picture's edges and across crops, and steady along a camera
// path; and near a black hole, each image's direction and magnification by a lens solve made
// here (the orbit equation u'' = 3 M u^2 - u integrated step by step to u = 0).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "lightcone/color/spectrum.hpp"
#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/star_field.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/physics/celestial.hpp"
#include "lightcone/physics/stars.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;

Scene star_scene(std::vector<CatalogueStar> stars, int width = 200, int height = 200,
                 double fov = 40) {
  Scene s;
  s.camera.width = width;
  s.camera.height = height;
  s.camera.fov_degrees = fov;
  s.sky.stars = SkyStars{};
  s.sky.stars->stars = std::make_shared<std::vector<CatalogueStar>>(std::move(stars));
  return s;
}

// The flux in a window of a picture: sum of radiance times pixel solid angle (as XYZ), and the
// flux-weighted centroid of the window's pixel centres.
struct Measured {
  Xyz flux;
  double x = 0, y = 0;
};
Measured measure(const Image& image, const CameraBasis& camera, int x0, int y0, int x1, int y1) {
  Measured m;
  for (int j = std::max(0, y0); j < std::min(image.height, y1); ++j)
    for (int i = std::max(0, x0); i < std::min(image.width, x1); ++i) {
      const float* c = &image.rgb[3 * (static_cast<std::size_t>(j) * image.width + i)];
      const double omega = pixel_solid_angle(camera, i, j);
      const Xyz xyz = xyz_from_linear_srgb({c[0] * omega, c[1] * omega, c[2] * omega});
      m.flux.x += xyz.x, m.flux.y += xyz.y, m.flux.z += xyz.z;
      m.x += xyz.y * (i + 0.5), m.y += xyz.y * (j + 0.5);
    }
  if (m.flux.y > 0) m.x /= m.flux.y, m.y /= m.flux.y;
  return m;
}
Measured measure_all(const Image& image, const CameraBasis& camera) {
  return measure(image, camera, 0, 0, image.width, image.height);
}

// A direction d seen by an observer moving with speed beta along unit n: its angle theta from n
// becomes theta' with cos(theta') = (cos(theta) + beta) / (1 + beta cos(theta)), in the same
// plane.
Vec3 aberrated(const Vec3& d, const Vec3& n, double beta) {
  const double c = dot(d, n);
  const Vec3 side = d - n * c;
  const double c2 = (c + beta) / (1 + beta * c);
  const double s2 = std::sqrt(std::max(0.0, 1 - c2 * c2));
  return length(side) > 0 ? n * c2 + normalize(side) * s2 : n * c2;
}

// The pixel filter against its defining properties: wherever the point lies its weights sum to
// one and their centroid is the point (a quadratic B-spline reproduces linear functions), and
// each is the kernel B(dx) B(dy) at its pixel's centre.
TEST(StarsRender, TheFilterKeepsFluxAndCentroid) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-40, 40);
  for (int k = 0; k < 1000; ++k) {
    const double x = u(rng), y = u(rng);
    const StarFootprint f = star_footprint(x, y);
    double sum = 0, cx = 0, cy = 0;
    for (int b = 0; b < 3; ++b)
      for (int a = 0; a < 3; ++a) {
        const double w = f.wx[a] * f.wy[b];
        const double px = f.i0 + a + 0.5, py = f.j0 + b + 0.5;
        EXPECT_NEAR(w, star_filter_weight(px - x, py - y), 1e-15);
        sum += w, cx += w * px, cy += w * py;
      }
    EXPECT_NEAR(sum, 1, 1e-14);
    EXPECT_NEAR(cx, x, 1e-12);
    EXPECT_NEAR(cy, y, 1e-12);
  }
}

// A pixel's solid angle against the integral of cos^3(theta) dA / f^2 over it, taken here on a
// 64 x 64 grid of its area, for pixels at the centre, an edge and a corner of a wide view.
TEST(StarsRender, APixelsSolidAngleIsTheIntegralOverIt) {
  Camera cam;
  cam.width = 40, cam.height = 30, cam.fov_degrees = 100;
  const CameraBasis camera = camera_basis(cam);
  for (const auto& [i, j] : {std::pair{20, 15}, std::pair{0, 15}, std::pair{39, 0}}) {
    // The pixel on the image plane at unit distance.
    const double w = 2 * camera.tan_half_fov * camera.aspect / camera.width;
    const double h = 2 * camera.tan_half_fov / camera.height;
    const double a0 = -camera.tan_half_fov * camera.aspect + i * w;
    const double c0 = camera.tan_half_fov - (j + 1) * h;
    double integral = 0;
    for (int p = 0; p < 64; ++p)
      for (int q = 0; q < 64; ++q) {
        const double a = a0 + (p + 0.5) * w / 64, c = c0 + (q + 0.5) * h / 64;
        integral += std::pow(1 + a * a + c * c, -1.5) * (w / 64) * (h / 64);
      }
    EXPECT_NEAR(pixel_solid_angle(camera, i, j), integral, 1e-6 * integral) << i << " " << j;
  }
}

TEST(StarsRender, EachStarLandsWhereTheAberrationFormulaPutsIt) {
  std::vector<CatalogueStar> stars;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 40; ++k) stars.push_back({normalize(Vec3{u(rng), u(rng), u(rng)}), 2, 0.6f});
  for (const double beta : {0.0, 0.5, 0.9, 0.99}) {
    SCOPED_TRACE(beta);
    const Vec3 n = normalize(Vec3{0.3, -0.2, -1});
    Scene s = star_scene(stars, 1000, 800, 90);
    s.camera.world_line.velocity = n * beta;
    const Image image = render_image(s, {});
    const CameraBasis camera = camera_basis(s.camera);
    int checked = 0;
    for (const CatalogueStar& star : stars) {
      const ImagePoint p = project_direction(camera, aberrated(star.direction, n, beta));
      // Stars whose footprints lie inside and apart from every other.
      if (!p.in_front || p.x < 3 || p.y < 3 || p.x > 997 || p.y > 797) continue;
      bool alone = true;
      for (const CatalogueStar& other : stars) {
        const ImagePoint q = project_direction(camera, aberrated(other.direction, n, beta));
        if (&other != &star && q.in_front && std::abs(q.x - p.x) < 4 && std::abs(q.y - p.y) < 4)
          alone = false;
      }
      if (!alone) continue;
      const int i = static_cast<int>(p.x), j = static_cast<int>(p.y);
      const Measured m = measure(image, camera, i - 2, j - 2, i + 3, j + 3);
      EXPECT_NEAR(m.x, p.x, 0.1);
      EXPECT_NEAR(m.y, p.y, 0.1);
      ++checked;
    }
    EXPECT_GE(checked, 5);
  }
}

// F_lambda at rest a blackbody at T with CIE Y = F0; seen with D, D^-2 F0 / Y(T) times the
// blackbody at D T, whose bolometric flux is then D^-2 D^4 = D^2 times the star's
// (Stefan-Boltzmann).
TEST(StarsRender, ASingleStarsFluxIsABlackbodyAtDTimesTWithBolometricDSquared) {
  const double b_minus_v = 0.65, magnitude = 1;
  const double t = star_temperature(b_minus_v);
  const double f0 = kMagnitudeZeroFlux * std::pow(10, -0.4 * magnitude);
  const Vec3 ahead{0, 0, -1};
  for (const double d : {0.5, 0.8, 1.0, 1.5, 2.5}) {
    SCOPED_TRACE(d);
    Scene s = star_scene({{ahead, static_cast<float>(magnitude), static_cast<float>(b_minus_v)}});
    // Moving toward the star with D = gamma (1 + beta).
    s.camera.world_line.velocity = ahead * ((d * d - 1) / (d * d + 1));
    const Measured m = measure_all(render_image(s, {}), camera_basis(s.camera));
    const Xyz blackbody = xyz_from_spectrum(BlackbodySpectrum{d * t, 1});
    const double k = f0 / (xyz_from_spectrum(BlackbodySpectrum{t, 1}).y * d * d);
    EXPECT_NEAR(m.flux.x, k * blackbody.x, 0.01 * k * blackbody.x);
    EXPECT_NEAR(m.flux.y, k * blackbody.y, 0.01 * k * blackbody.y);
    EXPECT_NEAR(m.flux.z, k * blackbody.z, 0.01 * k * blackbody.z);
  }
}

// A star seen off the camera's motion, where the sky is not the camera's picture's centre: the
// same law with D = 1 / (gamma (1 - beta cos(theta'))).
TEST(StarsRender, AnObliqueStarsFluxFollowsItsDopplerFactor) {
  const double beta = 0.9, gamma = 1 / std::sqrt(1 - beta * beta);
  const Vec3 star = normalize(Vec3{0.8, 0.1, -1});
  Scene s = star_scene({{star, 0, 0.0f}}, 300, 300, 60);
  s.camera.world_line.velocity = {0, 0, -beta};
  const CameraBasis camera = camera_basis(s.camera);
  const Vec3 seen = aberrated(star, {0, 0, -1}, beta);
  const double d = 1 / (gamma * (1 - beta * dot(seen, {0, 0, -1})));
  const double t = star_temperature(0);
  const Measured m = measure_all(render_image(s, {}), camera);
  const double expected = kMagnitudeZeroFlux * xyz_from_spectrum(BlackbodySpectrum{d * t, 1}).y /
                          (xyz_from_spectrum(BlackbodySpectrum{t, 1}).y * d * d);
  EXPECT_NEAR(m.flux.y, expected, 0.01 * expected);
}

// Every star's flux reaches the picture but for the part of its footprint outside it: summed
// over the whole catalogue, for cameras turned every way, the picture holds exactly the stars'
// fluxes times their footprints' weights inside (star_footprint, the filter's definition);
// and four crops of a picture hold exactly what it does.
TEST(StarsRender, NoStarIsLostAtThePicturesEdgesOrBetweenCrops) {
  const Scene loaded = test::load_repository_scene("stars.json");
  const std::vector<CatalogueStar>& stars = *loaded.sky.stars->stars;
  ASSERT_GT(stars.size(), 8000u);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int turn = 0; turn < 4; ++turn) {
    Scene s = loaded;
    s.camera.width = 320, s.camera.height = 200, s.camera.samples = 1;
    s.camera.forward = normalize(Vec3{u(rng), u(rng), u(rng)});
    s.camera.up = normalize(Vec3{u(rng), u(rng), u(rng)});
    s.render.tonemap = ToneMap::kClamp;
    s.render.auto_exposure = false, s.render.exposure = 0;
    s.sky.rotation = Mat3{};  // the catalogue's directions are then the camera frame's
    const Image image = render_image(s, {});
    const CameraBasis camera = camera_basis(s.camera);
    double expected = 0;
    for (const CatalogueStar& star : stars) {
      const ImagePoint p = project_direction(camera, star.direction);
      if (!p.in_front) continue;
      const StarFootprint f = star_footprint(p.x, p.y);
      double inside = 0;
      for (int b = 0; b < 3; ++b)
        for (int a = 0; a < 3; ++a)
          if (f.i0 + a >= 0 && f.i0 + a < 320 && f.j0 + b >= 0 && f.j0 + b < 200)
            inside += f.wx[a] * f.wy[b];
      expected += inside * kMagnitudeZeroFlux * std::pow(10, -0.4 * star.magnitude);
    }
    const double total = measure_all(image, camera).flux.y;
    EXPECT_NEAR(total, expected, 1e-3 * expected);
    double quarters = 0;
    for (const PixelWindow w : {PixelWindow{0, 0, 160, 100}, PixelWindow{160, 0, 320, 100},
                                PixelWindow{0, 100, 160, 200}, PixelWindow{160, 100, 320, 200}}) {
      RenderOptions crop;
      crop.crop = w;
      const Image part = render_image(s, crop);
      for (int j = 0; j < part.height; ++j)
        for (int i = 0; i < part.width; ++i) {
          const float* c = &part.rgb[3 * (static_cast<std::size_t>(j) * part.width + i)];
          const float* whole =
              &image.rgb[3 * (static_cast<std::size_t>(j + w.y0) * 320 + i + w.x0)];
          ASSERT_EQ(c[1], whole[1]);
          const double omega = pixel_solid_angle(camera, i + w.x0, j + w.y0);
          quarters += xyz_from_linear_srgb({c[0] * omega, c[1] * omega, c[2] * omega}).y;
        }
    }
    EXPECT_NEAR(quarters, total, 1e-6 * total);
  }
}

// Along a 60-frame pan at rest a star's summed flux stays the same to under 1 % (it is the same
// star), while its peak pixel moves across pixels.
TEST(StarsRender, AStarsFluxDoesNotFlickerAlongACameraPath) {
  Scene s = star_scene({{normalize(Vec3{0.02, 0.01, -1}), 1, 0.3f}}, 160, 120, 30);
  double lo = 1e300, hi = 0;
  for (int frame = 0; frame < 60; ++frame) {
    const double angle = 0.0011 * frame;  // about a third of a pixel a frame
    s.camera.forward = {std::sin(angle), 0.3 * std::sin(angle), -std::cos(angle)};
    const double flux = measure_all(render_image(s, {}), camera_basis(s.camera)).flux.y;
    lo = std::min(lo, flux), hi = std::max(hi, flux);
  }
  EXPECT_LT((hi - lo) / hi, 0.01);
  EXPECT_GT(lo, 0);
}

// A body in front of a star hides it; beside the body the star is seen whole.
TEST(StarsRender, BodiesHideTheStarsBehindThem) {
  const Vec3 star = normalize(Vec3{0, 0, -1});
  Scene s = star_scene({{star, 0, 0.5f}}, 100, 100, 30);
  Object ball;
  ball.shape = Sphere{1};
  ball.world_line.position = {0, 0, -10};
  ball.material.unlit = true;
  ball.material.pattern = SolidColor{{0, 0, 0}};
  s.objects.push_back(ball);
  const CameraBasis camera = camera_basis(s.camera);
  EXPECT_EQ(measure_all(render_image(s, {}), camera).flux.y, 0);
  s.objects[0].world_line.position = {3, 0, -10};
  const double expected = kMagnitudeZeroFlux;
  EXPECT_NEAR(measure_all(render_image(s, {}), camera).flux.y, expected, 1e-3 * expected);
}

// The look angle alpha (from the outward radial direction, static frame at r0) of the ray that
// reaches infinity after sweeping `sweep` about a hole of mass 1: u(sweep) = 0 on the orbit
// integrated from the camera, by bisection (u(sweep) < 0 for rays that escape sooner, > 0 for
// those that sweep further or are captured).
double look_angle_to_infinity(double r0, double sweep, double lo, double hi) {
  const auto u_at_sweep = [&](double alpha) {
    return 1 / test::integrate_orbit_from(1, r0, std::cos(alpha), std::sin(alpha), sweep, 20000).r;
  };
  for (int i = 0; i < 50; ++i) {
    const double mid = (lo + hi) / 2;
    (u_at_sweep(mid) < 0 ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

// A star behind a hole seen by a static camera at r0 = 15 M: its primary and secondary images lie
// where the integrated orbits leave the camera, and their fluxes are in the ratio of their
// magnifications, sin(alpha) |d alpha| / (sin(psi) |d psi|) (both are seen with the same shift).
TEST(StarsRender, AStarBehindAHoleHasItsLensedImagesWhereTheOrbitsPutThem) {
  const double r0 = 15, epsilon = 0.25;  // the star's angle from the axis behind the hole
  const Vec3 toward{std::sin(epsilon), 0, -std::cos(epsilon)};
  Scene s = star_scene({{toward, 0, 0.3f}}, 1000, 1000, 90);
  s.camera.world_line.position = {0, 0, r0};
  s.black_hole = BlackHole{{0, 0, 0}, 1, std::nullopt};
  const Image image = render_image(s, {});
  const CameraBasis camera = camera_basis(s.camera);
  const double psi = kPi - epsilon;
  // The shadow's edge: alpha_edge = pi - asin(3 sqrt(3) sqrt(f) / r0) (Synge 1966).
  const double edge = kPi - std::asin(3 * std::sqrt(3.0) * std::sqrt(1 - 2 / r0) / r0);
  double flux[2];
  for (int order = 0; order < 2; ++order) {
    SCOPED_TRACE(order);
    const auto alpha_of = [&](double p) {
      return look_angle_to_infinity(r0, order == 0 ? p : 2 * kPi - p, 0.01, edge - 1e-9);
    };
    const double alpha = alpha_of(psi), h = 1e-4;
    const double magnification =
        std::sin(alpha) * std::abs(alpha_of(psi + h) - alpha_of(psi - h)) / (2 * h) / std::sin(psi);
    // Even orders leave toward the star's side (+x), odd ones round the other side.
    const Vec3 look{(order == 0 ? 1 : -1) * std::sin(alpha), 0, std::cos(alpha)};
    const ImagePoint p = project_direction(camera, look);
    ASSERT_TRUE(p.in_front);
    const int i = static_cast<int>(p.x), j = static_cast<int>(p.y);
    const Measured m = measure(image, camera, i - 3, j - 3, i + 4, j + 4);
    EXPECT_NEAR(m.x, p.x, 0.1);
    EXPECT_NEAR(m.y, p.y, 0.1);
    flux[order] = m.flux.y / magnification;
  }
  EXPECT_NEAR(flux[1] / flux[0], 1, 0.01);
}

// The raster renderer's sprites and the tracer's filter: every isolated star at the same place
// to 0.25 px and with the same flux to 2 %, for a camera at rest and at 0.9c, with a body hiding
// some and near a black hole (both images); and the whole catalogue's flux the same, none lost
// at the picture's edges.
TEST(StarsRender, TheRasterRendererDrawsTheTracersStars) {
  std::vector<CatalogueStar> stars;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1), colour(-0.2, 1.8);
  for (int k = 0; k < 300; ++k)
    stars.push_back({normalize(Vec3{u(rng), u(rng), u(rng)}), 1, static_cast<float>(colour(rng))});
  struct Case {
    const char* name;
    Vec3 velocity;
    bool body, hole;
  };
  for (const Case& c :
       {Case{"at rest", {}, false, false}, Case{"0.9c", {0.3, 0, -0.85}, true, false},
        Case{"near a hole", {}, false, true}}) {
    SCOPED_TRACE(c.name);
    Scene s = star_scene(stars, 400, 300, 90);
    s.camera.world_line.velocity = c.velocity;
    if (c.body) {
      Object ball;
      ball.shape = Sphere{2};
      ball.world_line.position = {1, 0, -4};
      // Too dim to count, but it marks the stars beside its outline (which both draw to the
      // pixel, not to the same fraction of a pixel) as not alone.
      ball.material.pattern = SolidColor{{1e-9f, 1e-9f, 1e-9f}};
      s.objects.push_back(ball);
    }
    if (c.hole) {
      s.camera.world_line.position = {0, 0, 15};
      s.black_hole = BlackHole{{0, 0, 0}, 1, std::nullopt};
    }
    const Image traced = render_image(s, {});
    const Image rastered = render_raster(s);
    const CameraBasis camera = camera_basis(s.camera);
    const Measured all_traced = measure_all(traced, camera),
                   all_rastered = measure_all(rastered, camera);
    EXPECT_NEAR(all_rastered.flux.y, all_traced.flux.y, 0.02 * all_traced.flux.y);
    // Each star: a 5x5 window about a local peak of the tracer's picture that holds nothing else.
    int compared = 0;
    for (int j = 3; j < 297; ++j)
      for (int i = 3; i < 397; ++i) {
        const auto y_at = [&](const Image& image, int x, int y) {
          const float* p = &image.rgb[3 * (static_cast<std::size_t>(y) * 400 + x)];
          return xyz_from_linear_srgb({p[0], p[1], p[2]}).y;
        };
        const double centre = y_at(traced, i, j);
        if (!(centre > 0)) continue;
        bool peak = true, ring_dark = true;
        for (int b = -3; b <= 3; ++b)
          for (int a = -3; a <= 3; ++a) {
            const double v = y_at(traced, i + a, j + b);
            if (std::max(std::abs(a), std::abs(b)) <= 1 && v > centre) peak = false;
            if (std::max(std::abs(a), std::abs(b)) >= 3 && v != 0) ring_dark = false;
          }
        if (!peak || !ring_dark) continue;
        const Measured t = measure(traced, camera, i - 2, j - 2, i + 3, j + 3);
        const Measured r = measure(rastered, camera, i - 2, j - 2, i + 3, j + 3);
        EXPECT_NEAR(r.x, t.x, 0.25);
        EXPECT_NEAR(r.y, t.y, 0.25);
        EXPECT_NEAR(r.flux.y, t.flux.y, 0.02 * t.flux.y);
        ++compared;
      }
    EXPECT_GE(compared, 10);
  }
}

// Stars whose filters straddle the picture's edges and corners: the raster renderer's sprites
// keep the part inside as the tracer does (a GL point whose centre leaves the viewport would be
// clipped whole).
TEST(StarsRender, TheRasterRendererKeepsStarsAtThePicturesEdges) {
  Scene s = star_scene({}, 120, 80, 50);
  const CameraBasis camera = camera_basis(s.camera);
  std::vector<CatalogueStar> stars;
  for (const double x : {-1.3, -0.6, -0.1, 0.4, 119.7, 120.2, 121.1})
    for (const double y : {-1.2, 0.3, 40.0, 79.9, 80.6})
      stars.push_back({look_direction(camera, x, y), 1, 0.5f});
  s.sky.stars->stars = std::make_shared<std::vector<CatalogueStar>>(stars);
  const double traced = measure_all(render_image(s, {}), camera).flux.y;
  const double rastered = measure_all(render_raster(s), camera).flux.y;
  ASSERT_GT(traced, 0);
  EXPECT_NEAR(rastered, traced, 1e-3 * traced);
}

// Near a hole each image of a star lies where the tracer's own camera ray reaches that star's
// direction far away, with that ray's image order and shift: for a static camera, one moving
// across the hole's direction, one falling radially (outside the horizon), and a sky that
// moves and is turned.
TEST(StarsRender, EachLensedImageIsWhereACameraRayMeetsItsStar) {
  std::vector<CatalogueStar> stars;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 400; ++k) stars.push_back({normalize(Vec3{u(rng), u(rng), u(rng)}), 1, 0.5f});
  struct Case {
    const char* name;
    const char* overrides[3];
  };
  const Case cases[] = {
      {"static", {"camera.position=0,0,12", "camera.fov=120", ""}},
      {"moving", {"camera.position=0,0,12", "camera.velocity=0.6,0,0", "camera.fov=120"}},
      {"falling",
       {R"(camera.motion={"fall": {"from": 30, "direction": [0, 0, 1]}})", "camera.proper_time=100",
        "camera.fov=120"}},
      {"sky moving and turned",
       {"camera.position=0,0,12", "sky.velocity=0,0.5,0",
        R"(sky.rotation={"axis": [1, 1, 0], "degrees": 40})"}}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    std::vector<std::string> overrides = {"camera.width=300", "camera.height=300",
                                          "camera.forward=0,0,-1", "camera.up=0,1,0"};
    for (const char* o : c.overrides)
      if (*o) overrides.push_back(o);
    SceneLoadReport report;
    const auto dir = test::fresh_temp_dir("lensed-stars");
    test::write_text(dir / "scene.json", R"({"camera": {},
        "black_hole": {"mass": 1}, "sky": {"stars": true}})");
    const Scene loaded = load_scene_file(dir / "scene.json", overrides, report);
    std::filesystem::remove_all(dir);
    Scene s = loaded;
    s.sky.stars->stars = std::make_shared<std::vector<CatalogueStar>>(stars);
    const ResolvedScene resolved = resolve_scene(s);
    ASSERT_TRUE(resolved.hole);
    const StarPhotometry photometry = star_photometry(resolved);
    const std::vector<StarImage> images = star_images(resolved, photometry);
    ASSERT_GT(images.size(), 20u);
    int secondary = 0;
    for (const StarImage& image : images) {
      if (image.x < 0 || image.y < 0 || image.x > 300 || image.y > 300) continue;
      const Vec3 look = look_direction(resolved.camera, image.x, image.y);
      const CurvedRay ray = follow_curved_ray(*resolved.hole, look);
      ASSERT_EQ(ray.end, CurvedRayEnd::kSky);
      // The star whose direction (in the sky's pattern coordinates) the ray reaches.
      double best = -2;
      for (const CatalogueStar& star : stars)
        best = std::max(best, dot(star.direction, ray.sky_direction));
      EXPECT_GT(best, std::cos(1e-6)) << image.x << " " << image.y << " order " << ray.order;
      secondary += ray.order >= 1;
    }
    EXPECT_GT(secondary, 5);
  }
}

// locate --direction takes a direction in the sky's rest frame near a hole as in flat space: the
// ray through each image it gives reaches that direction, which the pattern (and the stars)
// have at sky.rotation^T of it.
TEST(StarsRender, LocateADirectionNearAHoleInTheSkysFrame) {
  Scene s;
  s.camera.world_line.position = {0, 0, 12};
  s.black_hole = BlackHole{{0, 0, 0}, 1, std::nullopt};
  s.sky.rotation = Mat3::rotation(normalize(Vec3{1, 1, 0}), 0.7);
  const Vec3 d = normalize(Vec3{0.3, 0.2, -1});
  LocateQuery query;
  query.kind = LocateQuery::Kind::SkyDirection;
  query.value = d;
  const LocateResult result = locate(s, query);
  ASSERT_GE(result.images.size(), 2u);
  const ResolvedScene resolved = resolve_scene(s);
  for (const LocateImage& image : result.images) {
    const CurvedRay ray = follow_curved_ray(*resolved.hole, image.direction);
    ASSERT_EQ(ray.end, CurvedRayEnd::kSky);
    EXPECT_GT(dot(ray.sky_direction, s.sky.rotation.transposed() * d), std::cos(1e-7));
    EXPECT_EQ(ray.order, image.order);
  }
}

}  // namespace
}  // namespace lightcone

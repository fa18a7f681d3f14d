// Colour through the whole renderer: the Doppler colour models and the searchlight checked on
// rendered images against closed forms (a blackbody stays a blackbody at D T; a flat spectrum
// brightens by exactly D^5, D or 1; RGB emitters by D^4, D or 1), the limit beta -> 0, the
// principle of relativity with colour on, and agreement of `locate`'s Doppler factor with
// what is drawn.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/colour_models.hpp"
#include "lightcone/color/spectrum.hpp"
#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/received_colour.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/doppler.hpp"
#include "lightcone/scene/reframe.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr double kT = 5762;  // K, the Sun's effective temperature

double head_on_doppler(double beta) {
  return std::sqrt((1 + beta) / (1 - beta));
}

using test::make_object;

Material checker(double size, Rgb a, Rgb b) {
  return {Checker{size, {a, b}}, true, {}};
}
Material solid(Rgb c) {
  return {SolidColor{c}, true, {}};
}
Material blackbody(double temperature_k, double luminance) {
  return {Blackbody{temperature_k, luminance}, true, {}};
}
// A reddish tabulated spectrum that also has ultraviolet and infrared to shift into view.
Material tabulated() {
  return {EmissionSpectrum{{200, 400, 550, 700, 1000, 2000}, {0.05, 0.1, 0.3, 0.8, 0.6, 0.2}},
          true,
          {}};
}
// Flat over every wavelength that can be shifted into view.
Material flat(double value) {
  return {EmissionSpectrum{{1, 1e7}, {value, value}}, true, {}};
}

// A wall (a large box) filling a narrow view straight ahead of a camera at the origin looking
// along -z. The camera (odd size, so that the centre pixel's centre is the image centre) moves
// along z with `camera_vz`; the wall with `wall_vz`.
Scene wall_scene(Material material, double camera_vz, double wall_vz, int size, int samples) {
  Scene s;
  s.camera.world_line.velocity = {0, 0, camera_vz};
  s.camera.width = size;
  s.camera.height = size;
  s.camera.fov_degrees = 1.0;
  s.camera.samples = samples;
  s.objects.push_back(
      make_object("wall", Box{{40, 40, 1}}, {0, 0, -20}, {0, 0, wall_vz}, std::move(material)));
  s.sky.pattern = SolidColor{{0, 0, 0}};
  return s;
}

// The mean colour of the (2 r + 1)^2 pixels around the image centre (odd sizes).
LinearRgb centre_mean(const Image& image, int r) {
  const int ci = image.width / 2, cj = image.height / 2;
  LinearRgb sum;
  int n = 0;
  for (int j = cj - r; j <= cj + r; ++j)
    for (int i = ci - r; i <= ci + r; ++i) {
      const float* p = &image.rgb[3 * (static_cast<std::size_t>(j) * image.width + i)];
      sum.r += p[0];
      sum.g += p[1];
      sum.b += p[2];
      ++n;
    }
  return {sum.r / n, sum.g / n, sum.b / n};
}

LinearRgb pixel(const Image& image, int i, int j) {
  const float* p = &image.rgb[3 * (static_cast<std::size_t>(j) * image.width + i)];
  return {p[0], p[1], p[2]};
}

struct Chromaticity {
  double x, y, luminance;
};
Chromaticity chromaticity(const LinearRgb& c) {
  const Xyz xyz = xyz_from_linear_srgb(c);
  const double sum = xyz.x + xyz.y + xyz.z;
  return {xyz.x / sum, xyz.y / sum, xyz.y};
}

const char* searchlight_name(SearchlightModel s) {
  static const char* const names[] = {"physical", "chang1996", "off"};
  return names[static_cast<int>(s)];
}

// The Doppler factor the renderer uses for the centre pixel of a wall scene.
double centre_doppler(const Scene& s) {
  const ResolvedScene r = resolve_scene(s);
  const Vec3 u = look_direction(r.camera, 0.5 * s.camera.width, 0.5 * s.camera.height);
  return r.doppler(u, r.bodies[0].velocity);
}

// ---------------------------------------------------------------------------------------------
// 1. A blackbody at T seen with factor D is exactly a blackbody at D T with the same Planck
// scale (PHYSICS.md, "Colour"): shift and D^5 searchlight together.

struct BlackbodyCase {
  const char* name;
  double camera_vz, wall_vz, beta;  // beta: the closing speed (negative: receding)
};

TEST(BlackbodyUnderDoppler, RendersExactlyAsABlackbodyAtDTWithTheSamePlanckScale) {
  const BlackbodyCase cases[] = {
      {"camera approaching at 0.5", -0.5, 0.0, 0.5},
      {"camera receding at 0.5", 0.5, 0.0, -0.5},
      {"wall approaching at 0.3", 0.0, 0.3, 0.3},
      {"wall receding at 0.7", 0.0, -0.7, -0.7},
  };
  const BlackbodySpectrum rest_spectrum = BlackbodySpectrum::with_luminance(kT, 1.0);
  for (const BlackbodyCase& c : cases) {
    SCOPED_TRACE(c.name);
    const Scene moving = wall_scene(blackbody(kT, 1.0), c.camera_vz, c.wall_vz, 5, 1);
    const double d = head_on_doppler(c.beta);
    ASSERT_NEAR(centre_doppler(moving), d, 1e-12);

    // The same Planck scale at D T: with_luminance is linear in the luminance, so the luminance
    // with that scale is the scale over the scale of luminance 1.
    const double hot = d * kT;
    const double luminance = rest_spectrum.scale / BlackbodySpectrum::with_luminance(hot, 1).scale;
    ASSERT_NEAR(BlackbodySpectrum::with_luminance(hot, luminance).scale, rest_spectrum.scale,
                1e-12 * rest_spectrum.scale);
    const Scene reference = wall_scene(blackbody(hot, luminance), 0.0, 0.0, 5, 1);
    const Scene at_rest = wall_scene(blackbody(kT, 1.0), 0.0, 0.0, 5, 1);

    const Chromaticity got = chromaticity(centre_mean(render_image(moving, {}), 2));
    const Chromaticity want = chromaticity(centre_mean(render_image(reference, {}), 2));
    const Chromaticity rest = chromaticity(centre_mean(render_image(at_rest, {}), 2));
    // The estimator is the tabulated 1 nm quadrature: its error is that of the table's
    // interpolation, relative to what is received. What is left here is the spread of D over
    // the 25 pixels averaged (about 1e-4 in D^4).
    EXPECT_NEAR(got.luminance / want.luminance, 1.0, 5e-4);
    EXPECT_NEAR(got.x, want.x, 1e-4);
    EXPECT_NEAR(got.y, want.y, 1e-4);
    // Not trivially so: the colour and the brightness really changed (without the searchlight
    // the luminance would be D^-5 times the reference's; without the shift the chromaticity
    // would be the rest one).
    EXPECT_GT(std::abs(std::log(got.luminance / rest.luminance)), 0.5);
    EXPECT_GT(std::hypot(got.x - rest.x, got.y - rest.y), 0.02);
  }
}

// ---------------------------------------------------------------------------------------------
// 2. A spectrally flat emitter: L(D lambda) = L(lambda), so the received spectral radiance is
// exactly s(D) times the rest one at every wavelength, and so is every output channel.

TEST(FlatSpectrum, BrightensByD5PhysicalByDChangAndNotAtAllWithSearchlightOff) {
  for (const double beta : {0.5, -0.5}) {
    const Scene rest_scene = wall_scene(flat(0.3), 0.0, 0.0, 5, 1);
    const LinearRgb rest = centre_mean(render_image(rest_scene, {}), 2);
    // The rest colour is 0.3 times equal-energy white: Y = 0.3 exactly.
    ASSERT_NEAR(xyz_from_linear_srgb(rest).y, 0.3, 1e-6);
    const double d = head_on_doppler(beta);
    const struct {
      SearchlightModel model;
      double factor;
    } models[] = {{SearchlightModel::kPhysical, std::pow(d, 5)},
                  {SearchlightModel::kChang1996, d},
                  {SearchlightModel::kOff, 1.0}};
    for (const auto& m : models) {
      SCOPED_TRACE("beta " + std::to_string(beta) + ", searchlight " + searchlight_name(m.model));
      Scene moving = wall_scene(flat(0.3), -beta, 0.0, 5, 1);
      moving.render.doppler = DopplerModel::kSpectral;
      moving.render.searchlight = m.model;
      ASSERT_NEAR(centre_doppler(moving), d, 1e-12);
      const LinearRgb got = centre_mean(render_image(moving, {}), 2);
      // A flat spectrum's table is constant: the lookup is exact to rounding. What is left is
      // the spread of D over the 25 pixels averaged (about 1e-4 in D^5).
      const double tolerance = 3e-4 * m.factor;
      EXPECT_NEAR(got.r / rest.r, m.factor, tolerance);
      EXPECT_NEAR(got.g / rest.g, m.factor, tolerance);
      EXPECT_NEAR(got.b / rest.b, m.factor, tolerance);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 3. beta -> 0: every colour model tends to the colour-free render, and at beta = 0 exactly the
// relativistic render is the classical one bit for bit.

// Every hue in this scene lies in [0, 300] degrees, where the hue model is the identity at D = 1.
Scene colour_scene(const Vec3& camera_velocity, double speed) {
  Scene s;
  s.camera.world_line.position = {0, 0.5, 6};
  s.camera.world_line.velocity = camera_velocity;
  s.camera.width = 60;
  s.camera.height = 40;
  s.camera.fov_degrees = 70;
  s.camera.samples = 2;
  s.objects.push_back(make_object("sphere", Sphere{1.0}, {-1.5, 0.5, -2}, {speed, 0, 0},
                                  checker(0.3, {1, 0.2, 0.1}, {0.1, 0.2, 1})));
  Object box = make_object("box", Box{{1, 1.5, 0.8}}, {1.8, 0.3, -1}, {0, speed * 0.5, 0.4 * speed},
                           checker(0.25, {0.9, 0.9, 0.2}, {0.1, 0.5, 0.1}));
  box.rotation = Mat3::rotation({0.3, 1, 0.2}, 0.7);
  box.scale = {1.2, 0.8, 1.0};
  s.objects.push_back(box);
  s.objects.push_back(make_object("ground", Plane{20, 20}, {0, -1, -3}, {},
                                  checker(1.0, {0.8, 0.8, 0.8}, {0.2, 0.2, 0.2})));
  s.objects.push_back(
      make_object("sun", Sphere{0.7}, {0.2, 1.8, -4}, {-0.6 * speed, 0, 0}, blackbody(kT, 1.0)));
  s.objects.push_back(
      make_object("ember", Box{{0.8, 0.8, 0.8}}, {-3, -0.2, -3}, {0, 0, speed}, tabulated()));
  s.sky.pattern = SkyGrid{};
  s.sky.velocity = {0, speed, 0};
  return s;
}

// The colours of colour_scene at rest, for the hue precondition.
std::vector<LinearRgb> colour_scene_colours() {
  std::vector<LinearRgb> colours = {{1, 0.2, 0.1},   {0.1, 0.2, 1},     {0.9, 0.9, 0.2},
                                    {0.1, 0.5, 0.1}, {0.8, 0.8, 0.8},   {0.2, 0.2, 0.2},
                                    {1, 1, 1},       {0.02, 0.02, 0.05}};
  colours.push_back(
      linear_srgb_from_xyz(xyz_from_spectrum(BlackbodySpectrum::with_luminance(kT, 1))));
  const Material t = tabulated();
  const auto& e = std::get<EmissionSpectrum>(t.pattern);
  colours.push_back(
      linear_srgb_from_xyz(xyz_from_spectrum(TabulatedSpectrum{e.wavelengths_nm, e.values})));
  return colours;
}

const DopplerModel kDopplerModels[] = {DopplerModel::kSpectral, DopplerModel::kRgb3,
                                       DopplerModel::kHue, DopplerModel::kOff};
const SearchlightModel kSearchlightModels[] = {
    SearchlightModel::kPhysical, SearchlightModel::kChang1996, SearchlightModel::kOff};

std::string model_name(DopplerModel d, SearchlightModel s) {
  static const char* const doppler[] = {"spectral", "rgb3", "hue", "off"};
  return std::string("doppler ") + doppler[static_cast<int>(d)] + ", searchlight " +
         searchlight_name(s);
}

TEST(ColourLimit, TinySpeedsRenderAsTheColourFreeImageWithEveryModel) {
  for (const LinearRgb& c : colour_scene_colours()) {
    const Hsv hsv = hsv_from_rgb(c);
    ASSERT_GE(hsv.h, 0.0);
    ASSERT_LE(hsv.h, 300.0) << c.r << "," << c.g << "," << c.b;
  }
  Scene colour_free = colour_scene({0.0, 0.0, -1e-9}, 1e-9);
  colour_free.render.doppler = DopplerModel::kOff;
  colour_free.render.searchlight = SearchlightModel::kOff;
  const Image reference = render_image(colour_free, {});
  // The picture has several colours in it, the blackbody and the spectrum included.
  int changes = 0;
  for (std::size_t i = 3; i < reference.rgb.size(); i += 3)
    changes += reference.rgb[i] != reference.rgb[i - 3];
  EXPECT_GT(changes, 50);
  for (const DopplerModel d : kDopplerModels)
    for (const SearchlightModel s : kSearchlightModels) {
      SCOPED_TRACE(model_name(d, s));
      Scene slow = colour_free;
      slow.render.doppler = d;
      slow.render.searchlight = s;
      const Image got = render_image(slow, {});
      ASSERT_EQ(got.rgb.size(), reference.rgb.size());
      float worst = 0;
      for (std::size_t i = 0; i < got.rgb.size(); ++i)
        worst = std::max(worst, std::abs(got.rgb[i] - reference.rgb[i]));
      EXPECT_LT(worst, 1e-6);
    }
}

TEST(ColourLimit, AtRestEveryModelRendersBitForBitAsTheClassicalPicture) {
  for (const DopplerModel d : kDopplerModels)
    for (const SearchlightModel s : kSearchlightModels) {
      SCOPED_TRACE(model_name(d, s));
      Scene relativistic = colour_scene({0, 0, 0}, 0.0);
      relativistic.render.doppler = d;
      relativistic.render.searchlight = s;
      Scene classical = relativistic;
      classical.render.relativity = false;
      EXPECT_EQ(render_image(relativistic, {}).rgb, render_image(classical, {}).rgb);
    }
}

TEST(ColourLimit, AtDOneTheSpectralModelIsExactlyTheRestColour) {
  // received_colour.hpp: at D = 1 (everything at rest) the spectral model shows the rest colour,
  // whatever the searchlight model, for RGB emitters, blackbodies and tabulated spectra alike.
  Scene colour_free = colour_scene({0, 0, 0}, 0.0);
  colour_free.render.doppler = DopplerModel::kOff;
  colour_free.render.searchlight = SearchlightModel::kOff;
  const Image reference = render_image(colour_free, {});
  for (const SearchlightModel s : kSearchlightModels) {
    SCOPED_TRACE(model_name(DopplerModel::kSpectral, s));
    Scene spectral = colour_free;
    spectral.render.doppler = DopplerModel::kSpectral;
    spectral.render.searchlight = s;
    const Image got = render_image(spectral, {});
    float worst = 0;
    for (std::size_t i = 0; i < got.rgb.size(); ++i)
      worst = std::max(worst, std::abs(got.rgb[i] - reference.rgb[i]));
    EXPECT_LE(worst, 1e-7);
  }
}

TEST(ColourLimit, TheHueModelFadesMagentaEvenAtRest) {
  // Seed 003's shader, a documented property: hues above 300 degrees fade toward black even
  // at D = 1, so the hue model is not the identity at rest for them (and the test above keeps
  // to hues in [0, 300]).
  const Rgb magenta{1.0f, 0.0f, 0.5f};  // hue 330: faded to half
  Scene s = wall_scene(solid(magenta), 0.0, 0.0, 5, 1);
  s.render.doppler = DopplerModel::kHue;
  const LinearRgb got = pixel(render_image(s, {}), 2, 2);
  const LinearRgb want = hue_shift({1.0, 0.0, 0.5}, 1.0, false);
  EXPECT_NEAR(got.r, want.r, 1e-7);
  EXPECT_NEAR(got.g, want.g, 1e-7);
  EXPECT_NEAR(got.b, want.b, 1e-7);
  EXPECT_NEAR(got.r, 0.5, 1e-7);  // V halved, hue clamped to 300: (0.5, 0, 0.5)
  EXPECT_NEAR(got.b, 0.5, 1e-7);
  // With the hue loop it is the identity.
  s.render.hue_loop = true;
  const LinearRgb looped = pixel(render_image(s, {}), 2, 2);
  EXPECT_NEAR(looped.r, 1.0, 1e-6);
  EXPECT_NEAR(looped.g, 0.0, 1e-6);
  EXPECT_NEAR(looped.b, 0.5, 1e-6);
}

// ---------------------------------------------------------------------------------------------
// 4. The principle of relativity with Doppler colour and the searchlight on.

using test::fraction_differing;

TEST(PrincipleOfRelativity, HoldsWithDopplerColourAndSearchlight) {
  const struct {
    DopplerModel doppler;
    SearchlightModel searchlight;
  } models[] = {{DopplerModel::kSpectral, SearchlightModel::kPhysical},
                {DopplerModel::kRgb3, SearchlightModel::kPhysical},
                {DopplerModel::kHue, SearchlightModel::kChang1996}};
  for (const auto& m : models) {
    SCOPED_TRACE(model_name(m.doppler, m.searchlight));
    Scene scene = colour_scene({0.2, -0.1, -0.5}, 0.7);
    scene.camera.width = 120;
    scene.camera.height = 80;
    scene.camera.samples = 1;
    scene.sky.velocity = {0.3, 0.1, 0.0};
    scene.render.doppler = m.doppler;
    scene.render.searchlight = m.searchlight;
    const Image image = render_image(scene, {});
    // Colour is really at work: most of the picture differs from the colour-free render.
    Scene colour_free = scene;
    colour_free.render.doppler = DopplerModel::kOff;
    colour_free.render.searchlight = SearchlightModel::kOff;
    EXPECT_GT(fraction_differing(image, render_image(colour_free, {})), 0.5);
    for (const Vec3 frame : {Vec3{0.4, -0.3, 0.5}, Vec3{-0.8, 0.1, 0.2}}) {
      const Scene other = describe_in_frame(scene, frame);
      ASSERT_GT(length(other.camera.world_line.velocity - scene.camera.world_line.velocity), 0.1);
      ASSERT_GT(length(other.objects[3].world_line.velocity - scene.objects[3].world_line.velocity),
                0.1);
      EXPECT_LT(fraction_differing(image, render_image(other, {})), 0.003);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 5. The searchlight on RGB emitters, and the rgb3 model through the renderer.

TEST(Searchlight, WhiteRgbWallApproachedHeadOnScalesByD4DOr1) {
  const double d = head_on_doppler(0.5);  // sqrt(3): D^4 = 9
  const struct {
    SearchlightModel model;
    double factor;
    int power;
  } models[] = {{SearchlightModel::kPhysical, 9.0, 4},
                {SearchlightModel::kChang1996, d, 1},
                {SearchlightModel::kOff, 1.0, 0}};
  for (const auto& m : models) {
    SCOPED_TRACE(searchlight_name(m.model));
    Scene s = wall_scene(solid({1, 1, 1}), -0.5, 0.0, 17, 1);
    s.render.doppler = DopplerModel::kOff;
    s.render.searchlight = m.model;
    // The renderer's own per-sample radiance, in double precision: exact to 1e-9.
    const ResolvedScene r = resolve_scene(s);
    const Tracer tracer(r);
    const EmissionTable emission(r);
    const LinearRgb exact = radiance_along(r, emission, tracer, r.camera.forward);
    EXPECT_NEAR(exact.r, m.factor, 1e-9 * m.factor);
    EXPECT_NEAR(exact.g, m.factor, 1e-9 * m.factor);
    EXPECT_NEAR(exact.b, m.factor, 1e-9 * m.factor);
    // The image (stored as float): the centre pixel looks straight ahead, and every pixel is
    // D^power for the D of its own look direction, to float precision.
    const Image image = render_image(s, {});
    const LinearRgb centre = pixel(image, 8, 8);
    EXPECT_NEAR(centre.r, m.factor, 1e-7 * m.factor);
    EXPECT_NEAR(centre.g, m.factor, 1e-7 * m.factor);
    EXPECT_NEAR(centre.b, m.factor, 1e-7 * m.factor);
    for (int j = 0; j < 17; ++j)
      for (int i = 0; i < 17; ++i) {
        const Vec3 u = look_direction(r.camera, i + 0.5, j + 0.5);
        // D for the light from the static wall along -u to the camera moving at 0.5 along -z,
        // computed in W (the wall at rest there) with the aberrated direction.
        const double dij = r.doppler(u, r.bodies[0].velocity);
        const double want = std::pow(dij, m.power);
        const LinearRgb p = pixel(image, i, j);
        EXPECT_NEAR(p.r, want, 2e-7 * want);
        EXPECT_NEAR(p.g, want, 2e-7 * want);
        EXPECT_NEAR(p.b, want, 2e-7 * want);
      }
  }
}

TEST(Rgb3, ALineShiftedOutOfTheVisibleRangeVanishesThroughTheRenderer) {
  // beta = 0.3 head-on: D = sqrt(1.3 / 0.7) = 1.363; the blue line (465 nm) moves to 341 nm and
  // leaves the visible range, green (392 nm) and red (459 nm) stay.
  const double beta = 0.3, d = head_on_doppler(beta);
  ASSERT_LT(kRgb3Wavelengths[2] / d, kCieMinWavelength);
  ASSERT_GT(kRgb3Wavelengths[1] / d, kCieMinWavelength);
  const LinearRgb rest{0.8, 0.5, 0.3};
  Scene s = wall_scene(solid({0.8f, 0.5f, 0.3f}), -beta, 0.0, 17, 1);
  s.render.doppler = DopplerModel::kRgb3;
  s.render.searchlight = SearchlightModel::kPhysical;
  const double dc = centre_doppler(s);
  ASSERT_NEAR(dc, d, 1e-12);
  const LinearRgb got = pixel(render_image(s, {}), 8, 8);
  const LinearRgb want = rgb3_shift(rest, dc, std::pow(dc, 4));
  EXPECT_NEAR(got.r, want.r, 1e-6 * std::abs(want.r) + 1e-7);
  EXPECT_NEAR(got.g, want.g, 1e-6 * std::abs(want.g) + 1e-7);
  EXPECT_NEAR(got.b, want.b, 1e-6 * std::abs(want.b) + 1e-7);
  // Independently: only the red and green lines' powers, moved and multiplied by D^4.
  const LinearRgb p = rgb3_line_powers(rest);
  const Xyz red = cie_cmf(kRgb3Wavelengths[0] / d), green = cie_cmf(kRgb3Wavelengths[1] / d);
  const double k = std::pow(d, 4) / cie_y_integral();
  const LinearRgb two_lines =
      linear_srgb_from_xyz({k * (p.r * red.x + p.g * green.x), k * (p.r * red.y + p.g * green.y),
                            k * (p.r * red.z + p.g * green.z)});
  EXPECT_NEAR(got.r, two_lines.r, 1e-6 * std::abs(two_lines.r) + 1e-7);
  EXPECT_NEAR(got.g, two_lines.g, 1e-6 * std::abs(two_lines.g) + 1e-7);
  EXPECT_NEAR(got.b, two_lines.b, 1e-6 * std::abs(two_lines.b) + 1e-7);
  // The blue line carried real power: keeping it would change the colour.
  ASSERT_GT(p.b, 0.01);
}

// ---------------------------------------------------------------------------------------------
// 6. `locate`'s Doppler factor is the one the renderer uses.

TEST(Locate, DopplerAgreesWithTheRenderedBrighteningOfAFlatSpectrum) {
  const struct {
    Vec3 camera_velocity, ball_position, ball_velocity;
  } cases[] = {
      {{0.2, 0.0, -0.4}, {1.0, 0.5, -8}, {-0.6, 0.1, 0.3}},    // blueshifted
      {{-0.3, 0.1, 0.2}, {-2.0, -0.5, -7}, {0.1, 0.2, -0.6}},  // redshifted
  };
  bool blue = false, red = false;
  for (const auto& c : cases) {
    Scene s;
    s.camera.world_line.velocity = c.camera_velocity;
    s.objects.push_back(
        make_object("ball", Sphere{1.0}, c.ball_position, c.ball_velocity, flat(0.3)));
    s.camera.width = 15;
    s.camera.height = 15;
    s.camera.samples = 1;
    // Aim the camera at the apparent centre of the ball with a narrow view: the located pixel
    // is then the centre one, and D hardly varies across it.
    const LocateResult first = locate(s, {LocateQuery::Kind::ObjectPoint, "ball", {0, 0, 0}});
    s.camera.forward = first.direction;
    s.camera.up = {0, 1, 0};
    s.camera.fov_degrees = 0.5;
    const LocateResult l = locate(s, {LocateQuery::Kind::ObjectPoint, "ball", {0, 0, 0}});
    ASSERT_TRUE(l.in_view);
    ASSERT_NEAR(l.pixel_x, 7.5, 1e-6);
    ASSERT_NEAR(l.pixel_y, 7.5, 1e-6);
    const ResolvedScene r = resolve_scene(s);
    const auto hit = Tracer(r).trace(look_direction(r.camera, l.pixel_x, l.pixel_y));
    ASSERT_TRUE(hit.has_value());
    // Independently of the renderer: D from the emission event toward the camera, in W.
    const Vec3 n = normalize(Vec3{0, 0, 0} - *l.emission_position);  // camera at the origin
    EXPECT_NEAR(l.doppler, doppler_factor(n, c.ball_velocity, c.camera_velocity), 1e-9);
    blue |= l.doppler > 1.3;
    red |= l.doppler < 0.8;

    // The reference: the same picture with the searchlight off, which for a flat spectrum is
    // exactly the rest colour.
    Scene rest = s;
    rest.render.searchlight = SearchlightModel::kOff;
    const LinearRgb moving_colour = pixel(render_image(s, {}), 7, 7);
    const LinearRgb rest_colour = pixel(render_image(rest, {}), 7, 7);
    const double want = std::pow(l.doppler, 5);
    // A flat spectrum's table is constant, so only float rounding remains.
    const double tolerance = 1e-6 * want;
    EXPECT_NEAR(moving_colour.r / rest_colour.r, want, tolerance);
    EXPECT_NEAR(moving_colour.g / rest_colour.g, want, tolerance);
    EXPECT_NEAR(moving_colour.b / rest_colour.b, want, tolerance);
  }
  EXPECT_TRUE(blue);
  EXPECT_TRUE(red);
}

// The sky seen along every direction is its emission there received with its own Doppler factor
// there, by each colour model: at rest (one colour, which the renderer receives once), seen
// from a moving camera (a colour that changes with D) and with a pattern.
TEST(ColourRender, TheSkyIsReceivedWithItsOwnDopplerFactorInEveryDirection) {
  for (const DopplerModel model :
       {DopplerModel::kSpectral, DopplerModel::kRgb3, DopplerModel::kHue, DopplerModel::kOff})
    for (const double camera_speed : {0.0, 0.6})
      for (const bool grid : {false, true}) {
        SCOPED_TRACE("model " + std::to_string(static_cast<int>(model)) + " at " +
                     std::to_string(camera_speed) + (grid ? ", grid" : ", solid"));
        Scene s;
        s.camera.world_line.velocity = {camera_speed, 0, 0};
        s.camera.fov_degrees = 150;
        s.render.doppler = model;
        if (grid)
          s.sky.pattern = SkyGrid{};
        else
          s.sky.pattern = SolidColor{{0.2f, 0.5f, 0.3f}};
        const ResolvedScene r = resolve_scene(s);
        const Tracer tracer(r);
        const EmissionTable emission(r);
        std::vector<LinearRgb> seen;
        for (int j = 0; j <= 8; ++j)
          for (int i = 0; i <= 8; ++i) {
            const Vec3 u =
                look_direction(r.camera, i * s.camera.width / 8.0, j * s.camera.height / 8.0);
            const LinearRgb got = radiance_along(r, emission, tracer, u);
            const LinearRgb want = received_colour(emission.sky(r.sky_direction(u)),
                                                   r.doppler(u, r.sky_velocity), s.render);
            EXPECT_EQ(got.r, want.r);
            EXPECT_EQ(got.g, want.g);
            EXPECT_EQ(got.b, want.b);
            seen.push_back(got);
          }
        // Seen from a moving camera the solid sky's colour (or, with `doppler: off`, its
        // brightness) changes across the view, so the directions above do test its D.
        const bool varies = std::any_of(seen.begin(), seen.end(), [&](const LinearRgb& c) {
          return c.r != seen[0].r || c.g != seen[0].g || c.b != seen[0].b;
        });
        if (!grid) {
          EXPECT_EQ(varies, camera_speed > 0);
        }
      }
}

}  // namespace
}  // namespace lightcone

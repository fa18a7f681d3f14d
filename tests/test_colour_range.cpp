// The colour tables cover every shift a picture shows, and nothing else (issue 53, B1 and item
// 4). A body held just outside the horizon (at r0 = 2.000001 M, seen from r = 30 M with
// g = 7.3e-4) was drawn with negative radiance: its shifts were missing from the tables' range,
// which extrapolated. Now a range that is not finite and a factor outside a table are refused,
// and as g -> 0 every colour model receives nothing, exactly: the received spectral radiance is
// g^5 L_E(g lambda), and where g lambda lies in a blackbody's far Wien tail for every visible
// lambda, L_E is 0 in double precision. Units: G = c = 1, M = 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/doppler_table.hpp"
#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/color/spectrum.hpp"
#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/received_colour.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Issue 53's B1 scene: a ball held at rest at r0 = 2.000001 M (its centre seen with
// g = sqrt(f(r0) / f(30)) = 7.3e-4), beside the hole as seen from the camera, so that its
// surface from the horizon out to r = 2.5 M is in view, with `material`.
Scene b1_scene(const std::string& material) {
  return test::scene_from_json(R"({
    "camera": {"position": [0, 0, 30], "fov": 12, "width": 96, "height": 96, "samples": 1},
    "black_hole": {"mass": 1},
    "objects": [
      {"name": "ball", "shape": {"sphere": {"radius": 0.5}},
       "motion": {"fall": {"from": 2.000001, "direction": [1, 0, 0], "time": 0}},
       "material": )" + material +
                               R"(}
    ],
    "sky": {"color": [0, 0, 0]},
    "render": {"exposure": 0, "tonemap": "clamp"}
  })");
}
const char* const kWhite = R"({"color": [1, 1, 1]})";
const char* const kSun = R"({"blackbody": {"temperature": 5762, "luminance": 1}})";

Xyz xyz_of(const LinearRgb& c) {
  return xyz_from_linear_srgb(c);
}
// Light, not a negative amount of it: X, Y and Z >= 0 (linear sRGB channels may be negative
// for a colour outside the sRGB gamut, as a body redshifted toward the spectral red is), to the
// rounding of the sRGB matrices applied to the channels' magnitude, plus `absolute`.
bool non_negative(const LinearRgb& c, double absolute = 0) {
  const double tolerance =
      1e-6 * std::max({std::abs(c.r), std::abs(c.g), std::abs(c.b)}) + absolute;
  const Xyz xyz = xyz_of(c);
  return xyz.x >= -tolerance && xyz.y >= -tolerance && xyz.z >= -tolerance;
}
int negative_pixels(const Image& image) {
  // Pixels are floats, which keep fewer bits below 1.2e-38: each channel rounds by up to half
  // the smallest subnormal there.
  const double rounding = 2 * std::numeric_limits<float>::denorm_min();
  int bad = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Rgb c = image.texel(x, y);
      if (!non_negative({c.r, c.g, c.b}, rounding) && ++bad <= 3)
        ADD_FAILURE() << "pixel " << x << ", " << y << ": " << c.r << ", " << c.g << ", " << c.b;
    }
  return bad;
}

TEST(ColourRange, AGridRefusesARangeThatIsNotFinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(DopplerGrid::covering(nan, 0.1), std::invalid_argument);
  EXPECT_THROW(DopplerGrid::covering(-0.1, kInfinity), std::invalid_argument);
  EXPECT_THROW(DopplerGrid::covering(-kInfinity, 0.1), std::invalid_argument);
  EXPECT_THROW(DopplerGrid::covering(nan), std::invalid_argument);
  // Reaching toward D = 0 needs a spectrum that is constant somewhere.
  EXPECT_THROW(DopplerGrid::reaching(-kInfinity, 0.1, 0), std::invalid_argument);
  EXPECT_THROW(DopplerGrid::reaching(-1, kInfinity, 100), std::invalid_argument);
  EXPECT_NO_THROW(DopplerGrid::reaching(-kInfinity, 0.1, 100));
}

TEST(ColourRange, ATableRefusesAFactorOutsideItsRangeInsteadOfExtrapolating) {
  const DopplerGrid grid = DopplerGrid::covering(-0.1, 0.1);
  EXPECT_FALSE(grid.settled);
  const DopplerXyzTable white =
      DopplerXyzTable::of([](double l) { return rgb_white_spectrum(l); }, grid);
  for (const double d : {std::exp(-0.1), 1.0, std::exp(0.1)}) EXPECT_NO_THROW(white(d)) << d;
  for (const double d : {std::exp(0.2), 2.0, 0.5, 1e-3, 0.0, std::nan("")})
    EXPECT_THROW(white(d), std::out_of_range) << d;
  // The same for a lit surface's table, in either factor.
  const RgbAlbedoSpectrum red = RgbAlbedoSpectrum::from_rgb({0.8, 0.1, 0.1});
  const ReflectionXyzTable lit = ReflectionXyzTable::of(
      red, [](double l) { return rgb_white_spectrum(l); }, grid, grid);
  EXPECT_NO_THROW(lit(grid_stencil(grid, 1.05), 0.95));
  EXPECT_THROW(lit(grid_stencil(grid, 1.05), 2.0), std::out_of_range);
  EXPECT_THROW(grid_stencil(grid, 0.3), std::out_of_range);
}

TEST(ColourRange, PlanckTailIsExactlyZeroBelowItsZeroWavelength) {
  for (const double t : {30.0, 300.0, 2500.0, 6504.0, 1e5, 1e9}) {
    const double zero = planck_zero_wavelength(t);
    for (const double f : {1.0, 0.999, 0.5, 1e-3, 1e-100})
      EXPECT_EQ(planck_radiance(zero * f, t), 0.0) << t << " K at " << zero * f << " nm";
    // ... and no further: a fraction of a per cent longer it is light (a subnormal number).
    EXPECT_GT(planck_radiance(zero * 1.01, t), 0.0) << t;
  }
  // The 6504 K white's visible band is all in it below D = 3.4e-3.
  EXPECT_NEAR(planck_zero_wavelength(6504) / kCieMaxWavelength, 3.4e-3, 0.1e-3);
  EXPECT_EQ(planck_zero_wavelength(0), kInfinity);
}

// Below the factor at which the quadrature samples only where a spectrum is constant, a table
// on a grid reaching it is that constant, exactly, as the quadrature itself is; above it, the
// table is the quadrature's interpolation (never negative).
TEST(ColourRange, BelowASettledGridATableIsExactlyItsLimit) {
  const auto check = [](const auto& spectrum, const char* name) {
    SCOPED_TRACE(name);
    const DopplerGrid grid = DopplerGrid::reaching(-kInfinity, 0.5, spectrum.constant_below());
    EXPECT_TRUE(grid.settled);
    const DopplerXyzTable table = DopplerXyzTable::of(spectrum, grid);
    const double limit = spectrum.constant_below() / kCieMaxWavelength;
    const Xyz constant = xyz_seen_with_doppler(spectrum, limit);
    // Below node 1 of the grid, which lies a step or more below the limit.
    for (const double d : {limit * std::exp(-2 * DopplerGrid::kStep), 1e-3 * limit, 1e-30, 0.0}) {
      const Xyz seen = table(d), exact = xyz_seen_with_doppler(spectrum, d);
      EXPECT_EQ(seen.x, constant.x) << d;
      EXPECT_EQ(seen.y, constant.y) << d;
      EXPECT_EQ(seen.z, constant.z) << d;
      EXPECT_EQ(exact.y, constant.y) << d;
    }
    for (double d = 1.05 * limit; d < std::exp(0.5); d *= 1.07) {
      const Xyz seen = table(d), exact = xyz_seen_with_doppler(spectrum, d);
      EXPECT_GE(seen.x, 0) << d;
      EXPECT_GE(seen.y, 0) << d;
      EXPECT_GE(seen.z, 0) << d;
      // (Where the tail nears the smallest doubles, the quadrature's own samples lose bits.)
      if (exact.y > 1e-250) {
        EXPECT_LE(std::abs(seen.y - exact.y), 1e-3 * exact.y) << d;
      }
    }
    return constant;
  };
  // Blackbodies (and so every RGB emitter) go to 0; a table holds its first value.
  const Xyz sun = check(BlackbodySpectrum::with_luminance(5762, 1), "5762 K");
  EXPECT_EQ(sun.y, 0.0);
  EXPECT_EQ(check(BlackbodySpectrum::with_luminance(3e4, 1), "30000 K").y, 0.0);
  EXPECT_EQ(check(RgbEmitterSpectrum::from_rgb({0.9, 0.4, 0.1}), "orange").y, 0.0);
  const TabulatedSpectrum held{{200, 600, 2000}, {0.25, 1, 0.5}};
  EXPECT_NEAR(check(held, "table").y, 0.25, 1e-9);
  // A grid told that a spectrum is constant where it is not is refused when the table is built.
  EXPECT_THROW(DopplerXyzTable::of(BlackbodySpectrum::with_luminance(6504, 1),
                                   DopplerGrid::reaching(-kInfinity, 0.5, 100)),
               std::logic_error);
}

// Every colour model and searchlight law receives no light from the B1 body as g -> 0 (at
// g = 1e-3 and 1e-6, below the 6504 K white's 3.4e-3): the spectral model exactly 0 (its
// visible band sees the far Wien tail), rgb3 exactly 0 (every line beyond 830 nm), hue exactly
// 0 (faded past red), and those that keep the rest colour (off, and the looping hue) the rest
// colour times the searchlight's D^4 or D. Never a negative amount of light.
TEST(ColourRange, EveryColourModelReceivesNothingAsGGoesToZero) {
  for (const char* material : {kWhite, kSun}) {
    SCOPED_TRACE(material);
    const Scene scene = b1_scene(material);
    for (const DopplerModel model :
         {DopplerModel::kSpectral, DopplerModel::kRgb3, DopplerModel::kHue, DopplerModel::kOff})
      for (const bool loop : {false, true}) {
        if (loop && model != DopplerModel::kHue) continue;
        for (const SearchlightModel searchlight :
             {SearchlightModel::kPhysical, SearchlightModel::kChang1996, SearchlightModel::kOff}) {
          Scene s = scene;
          s.render.doppler = model;
          s.render.searchlight = searchlight;
          s.render.hue_loop = loop;
          const ResolvedScene resolved = resolve_scene(s);
          const EmissionTable emission(resolved);
          const PointEmission& ball = emission.object_colour(0, 0);
          SCOPED_TRACE(static_cast<int>(model) * 10 + static_cast<int>(searchlight) + 100 * loop);
          const LinearRgb rest = received_colour(ball, 1, s.render);
          const auto brightest = [](const LinearRgb& c) { return std::max({c.r, c.g, c.b}); };
          for (const double g : {1.0, 0.5, 0.1, 0.01, 7.3e-4, 1e-3, 1e-6}) {
            const LinearRgb c = received_colour(ball, g, s.render);
            EXPECT_TRUE(non_negative(c)) << g << ": " << c.r << ", " << c.g << ", " << c.b;
            if (g > 3e-3) continue;
            if (model == DopplerModel::kOff) {
              const double kept = integrated_searchlight(g, searchlight);
              EXPECT_NEAR(c.r, kept * rest.r, 1e-12 * kept) << g;
              EXPECT_NEAR(c.g, kept * rest.g, 1e-12 * kept) << g;
              EXPECT_NEAR(c.b, kept * rest.b, 1e-12 * kept) << g;
            } else if (loop) {  // the hue turns; its value is kept
              const double kept = integrated_searchlight(g, searchlight) * brightest(rest);
              EXPECT_NEAR(brightest(c), kept, 1e-12 * kept) << g;
            } else {
              EXPECT_EQ(c.r, 0.0) << g;
              EXPECT_EQ(c.g, 0.0) << g;
              EXPECT_EQ(c.b, 0.0) << g;
            }
          }
        }
      }
  }
}

// The B1 scene through both renderers: no pixel has a negative amount of light, with the
// searchlight or without. (Their tables once covered only the sky's g = 1.035: the body's
// pixels came out as [0.06, -0.15, 0.03], and -20 without the searchlight.)
TEST(ColourRange, AFallingBodyAtTheHorizonRendersNoNegativeLight) {
  for (const char* material : {kWhite, kSun})
    for (const SearchlightModel searchlight :
         {SearchlightModel::kPhysical, SearchlightModel::kOff}) {
      SCOPED_TRACE(std::string(material) + (searchlight == SearchlightModel::kOff ? " off" : ""));
      Scene s = b1_scene(material);
      s.render.searchlight = searchlight;
      const Image traced = render_image(s, {});
      const Image rastered = render_raster(s);
      EXPECT_EQ(negative_pixels(traced), 0);
      EXPECT_EQ(negative_pixels(rastered), 0);
      // The ball is in the picture.
      int lit = 0;
      for (const float v : traced.rgb) lit += v > 0;
      EXPECT_GT(lit, 100);
    }
}

// A blackbody body's light along each ray that meets it grows with the ray's g (a blackbody at T
// seen with g is one at g T, whose radiance grows with its temperature at every wavelength):
// towards the horizon it goes to 0, never below.
TEST(ColourRange, ABlackbodyBodyDimsMonotonicallyTowardTheHorizon) {
  const Scene s = b1_scene(kSun);
  const ResolvedScene resolved = resolve_scene(s);
  const Tracer tracer(resolved);
  const CurvedBodies bodies(resolved, tracer);
  const EmissionTable emission(resolved);
  std::vector<std::pair<double, double>> seen;  // (g, Y)
  for (int j = 0; j < 96; ++j)
    for (int i = 0; i < 96; ++i) {
      const CurvedRay ray = follow_curved_ray(
          *resolved.hole, look_direction(resolved.camera, i + 0.5, j + 0.5), &bodies);
      if (ray.end != CurvedRayEnd::kBody) continue;
      seen.emplace_back(ray.shift, xyz_of(curved_radiance(resolved, emission, ray)).y);
    }
  ASSERT_GT(seen.size(), 100u);
  std::sort(seen.begin(), seen.end());
  EXPECT_LT(seen.front().first, 0.1);
  EXPECT_GE(seen.front().second, 0.0);
  for (std::size_t k = 1; k < seen.size(); ++k)
    EXPECT_GE(seen[k].second, seen[k - 1].second * (1 - 1e-5))
        << "g " << seen[k - 1].first << " to " << seen[k].first;
}

}  // namespace
}  // namespace lightcone

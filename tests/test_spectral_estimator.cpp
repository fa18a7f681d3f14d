// The spectral estimator (docs/design/spectral.md): colours seen with a Doppler factor come
// from per-render tables of a deterministic quadrature, so one sample a pixel is already exact
// to a small relative error, however dim the received light; greys stay grey under any shift;
// lit surfaces agree with an independent quadrature of the reflected spectrum; and the sample
// pattern is decorrelated, so that edges converge with the number of samples.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/doppler_table.hpp"
#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/color/spectrum.hpp"
#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/lighting.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/sampler.hpp"
#include "lightcone/physics/light_path.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;
using test::make_object;

// The camera speed toward a wall straight ahead that gives the Doppler factor d.
double closing_speed(double d) {
  return (d * d - 1) / (d * d + 1);
}

// A large wall 20 ahead of a camera at the origin looking along -z, with a narrow view; the
// camera moves toward it (along -z) at `speed`.
Scene wall_scene(Material material, double speed, int size = 5) {
  Scene s;
  s.camera.world_line.velocity = {0, 0, -speed};
  s.camera.width = size;
  s.camera.height = size;
  s.camera.fov_degrees = 1.0;
  s.objects.push_back(make_object("wall", Box{{40, 40, 1}}, {0, 0, -20}, {}, std::move(material)));
  return s;
}

Material unlit(Pattern pattern) {
  Material m;
  m.pattern = std::move(pattern);
  return m;
}

// What the renderer's own per-sample path returns for the centre of the view (double
// precision, one sample), with the Doppler factor it used.
struct CentreColour {
  LinearRgb rgb;
  double d = 1;
};
CentreColour centre_colour(const Scene& s) {
  const ResolvedScene r = resolve_scene(s);
  const Tracer tracer(r);
  const EmissionTable emission(r);
  const Lighting lighting(r, &tracer);
  const Vec3 u = look_direction(r.camera, 0.5 * s.camera.width, 0.5 * s.camera.height);
  return {radiance_along(r, emission, tracer, u, &lighting), r.doppler(u, r.bodies[0].velocity)};
}

// An independent high-accuracy reference: D^5 times the integral of L(D lambda) against the
// CIE observer by the trapezoidal rule on a 0.05 nm grid (the observer linearly interpolated
// between its 1 nm rows), normalised like the renderer's 1 nm sums.
template <class Spectrum>
LinearRgb reference_received(const Spectrum& spectrum, double d) {
  constexpr double kStep = 0.05;
  Xyz sum;
  const int n = static_cast<int>((kCieMaxWavelength - kCieMinWavelength) / kStep);
  for (int i = 0; i <= n; ++i) {
    const double lambda = kCieMinWavelength + i * kStep;
    const double w = (i == 0 || i == n) ? 0.5 * kStep : kStep;
    const double l = spectrum(d * lambda) * w;
    const Xyz c = cie_cmf(lambda);
    sum.x += l * c.x;
    sum.y += l * c.y;
    sum.z += l * c.z;
  }
  const double k = std::pow(d, 5) / cie_y_integral();
  return linear_srgb_from_xyz({sum.x * k, sum.y * k, sum.z * k});
}

double relative_rms(const LinearRgb& got, const LinearRgb& want) {
  const double e = std::hypot(got.r - want.r, got.g - want.g, got.b - want.b);
  return e / std::hypot(want.r, want.g, want.b);
}

double luminance(const LinearRgb& c) {
  return xyz_from_linear_srgb(c).y;
}

struct Chromaticity {
  double x, y;
};
Chromaticity chromaticity(const Xyz& c) {
  const double sum = c.x + c.y + c.z;
  return {c.x / sum, c.y / sum};
}

// ---------------------------------------------------------------------------------------------
// 1. Uniform emitters at one sample a pixel, against the high-accuracy reference.

TEST(SpectralEstimator, UniformEmittersAtOneSampleAreWithinHalfAPercentDownToTheDimmest) {
  struct Emitter {
    std::string name;
    Material material;
    std::function<double(double)> spectrum;
  };
  std::vector<Emitter> emitters;
  for (const LinearRgb c :
       {LinearRgb{1, 0, 0}, LinearRgb{0, 1, 0}, LinearRgb{0, 0, 1}, LinearRgb{0.5, 0.5, 0.5},
        LinearRgb{1, 1, 1}, LinearRgb{0.9, 0.4, 0.1}}) {
    const Rgb rgb{static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b)};
    const RgbEmitterSpectrum s = RgbEmitterSpectrum::from_rgb({rgb.r, rgb.g, rgb.b});
    emitters.push_back(
        {"rgb " + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b),
         unlit(SolidColor{rgb}), [s](double l) { return s(l); }});
  }
  const BlackbodySpectrum sun = BlackbodySpectrum::with_luminance(5778, 1.0);
  emitters.push_back(
      {"blackbody 5778 K", unlit(Blackbody{5778, 1.0}), [sun](double l) { return sun(l); }});
  const TabulatedSpectrum table{{20, 200, 400, 550, 700, 1000, 3000, 12000},
                                {0.02, 0.05, 0.1, 0.3, 0.8, 0.6, 0.2, 0.05}};
  emitters.push_back({"tabulated", unlit(EmissionSpectrum{table.wavelengths_nm, table.values}),
                      [table](double l) { return table(l); }});

  double dimmest = 1;
  for (const Emitter& e : emitters)
    for (const double d : {0.05, 0.2, 0.45, 1.0, 2.3, 4.36, 14.0}) {
      SCOPED_TRACE(e.name + ", D = " + std::to_string(d));
      const CentreColour got = centre_colour(wall_scene(e.material, closing_speed(d)));
      ASSERT_NEAR(got.d, d, 1e-9 * d);
      const LinearRgb want = reference_received(e.spectrum, got.d);
      const double rest = luminance(reference_received(e.spectrum, 1.0));
      const double ratio = luminance(want) / rest;
      if (!(luminance(want) > 1e-280)) continue;  // below what the image can hold
      dimmest = std::min(dimmest, ratio);
      EXPECT_LT(relative_rms(got.rgb, want), 0.005)
          << "received " << ratio << " of the rest luminance";
    }
  EXPECT_LT(dimmest, 1e-8);  // the deep tails were really tested
}

// The same through the whole image path (float pixels, tone mapping off): one sample a pixel
// is the per-sample value.
TEST(SpectralEstimator, TheImageAtOneSampleIsTheExactPerSampleColour) {
  const Scene s = wall_scene(unlit(SolidColor{{0.9f, 0.4f, 0.1f}}), closing_speed(2.3));
  const Image image = render_image(s, {});
  const CentreColour c = centre_colour(s);
  const float* p = &image.rgb[3 * (2 * 5 + 2)];
  EXPECT_NEAR(p[0], c.rgb.r, 1e-6 * c.rgb.r);
  EXPECT_NEAR(p[1], c.rgb.g, 1e-6 * c.rgb.g);
  EXPECT_NEAR(p[2], c.rgb.b, 1e-6 * c.rgb.b);
}

// ---------------------------------------------------------------------------------------------
// 2. A blackbody at T seen with factor D is a blackbody at D T (the same Planck scale), with no
// bias floor, from 1e-8 to 1e4 times the rest luminance.

TEST(SpectralEstimator, BlackbodyIsTheBlackbodyAtDTFromOneBillionthToTenThousandTimes) {
  const double t = 3000;
  const BlackbodySpectrum rest = BlackbodySpectrum::with_luminance(t, 1.0);
  double lowest = 1, highest = 1;
  for (double d = 0.28; d < 25; d *= 1.2) {
    SCOPED_TRACE("D = " + std::to_string(d));
    const CentreColour got = centre_colour(wall_scene(unlit(Blackbody{t, 1.0}), closing_speed(d)));
    // Planck: D^5 B(D lambda, T) = B(lambda, D T) exactly.
    BlackbodySpectrum hot;
    hot.temperature_k = got.d * t;
    hot.scale = rest.scale;
    const Xyz want = xyz_from_spectrum(hot);
    const Xyz have = xyz_from_linear_srgb(got.rgb);
    const Chromaticity a = chromaticity(have), b = chromaticity(want);
    EXPECT_NEAR(a.x, b.x, 0.001);
    EXPECT_NEAR(a.y, b.y, 0.001);
    EXPECT_NEAR(have.y / want.y, 1.0, 0.005);
    lowest = std::min(lowest, want.y);
    highest = std::max(highest, want.y);
  }
  EXPECT_LT(lowest, 1e-8);
  EXPECT_GT(highest, 1e4);
}

// ---------------------------------------------------------------------------------------------
// 3. Greys are grey: an RGB emitter (g, g, g) behaves like g times the 6504 K blackbody of
// luminance 1 at every D in [0.1, 10].

TEST(RgbWhite, GreysFollowTheScaledBlackbodyAtEveryDopplerFactor) {
  const BlackbodySpectrum blackbody = BlackbodySpectrum::with_luminance(6504, 1.0);
  for (const double g : {0.05, 0.5, 1.0, 7.0}) {
    const RgbEmitterSpectrum grey = RgbEmitterSpectrum::from_rgb({g, g, g});
    EXPECT_EQ(grey.scale, 0.0);  // no chromatic part at all
    for (double d = 0.1; d <= 10.0001; d *= std::pow(100.0, 1.0 / 40)) {
      SCOPED_TRACE("g = " + std::to_string(g) + ", D = " + std::to_string(d));
      const Xyz a = xyz_seen_with_doppler(grey, d);
      const Xyz b = xyz_seen_with_doppler(blackbody, d);
      EXPECT_NEAR(a.y / (g * b.y), 1.0, 0.03);
      const Chromaticity ca = chromaticity(a), cb = chromaticity(b);
      EXPECT_NEAR(ca.x, cb.x, 0.01);
      EXPECT_NEAR(ca.y, cb.y, 0.01);
    }
  }
}

TEST(RgbWhite, IsExactlySrgbWhiteAndTheBlackbodyOutsideTheVisibleRange) {
  const LinearRgb white =
      linear_srgb_from_xyz(xyz_from_spectrum([](double l) { return rgb_white_spectrum(l); }));
  EXPECT_NEAR(white.r, 1.0, 1e-12);
  EXPECT_NEAR(white.g, 1.0, 1e-12);
  EXPECT_NEAR(white.b, 1.0, 1e-12);
  for (double l : {50.0, 200.0, 300.0, 720.0, 830.0, 2000.0, 1e5})
    EXPECT_NEAR(rgb_white_spectrum(l) / reference_illuminant(l), 1.0, 1e-3) << l;
}

// Saturated colours (one channel zero) keep the Jakob-Hanika shape in the visible range: the
// emitter is the fitted reflectance of its white-balanced colour times the illuminant.
TEST(RgbEmitterSpectrum, SaturatedColoursKeepTheJakobHanikaShape) {
  const LinearRgb w = reference_white();
  for (const LinearRgb c : {LinearRgb{1, 0, 0}, LinearRgb{0, 0.6, 0.2}, LinearRgb{0.3, 0, 0.9}}) {
    const RgbEmitterSpectrum s = RgbEmitterSpectrum::from_rgb(c);
    EXPECT_EQ(s.grey, 0.0);
    const double m = std::max({c.r / w.r, c.g / w.g, c.b / w.b});
    const SigmoidPolynomial jh =
        rgb_to_sigmoid({c.r / w.r / (2 * m), c.g / w.g / (2 * m), c.b / w.b / (2 * m)});
    double peak = 0;
    for (double l = 380; l <= 780; l += 5) peak = std::max(peak, jh(l));
    for (double l = 380; l <= 780; l += 5) {
      const double want = 2 * m * jh(l) * reference_illuminant(l);
      EXPECT_NEAR(s(l), want, 0.01 * 2 * m * peak * reference_illuminant(l)) << l;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 4. The tables against the quadrature they tabulate, between their nodes.

TEST(DopplerXyzTable, InterpolatesItsQuadratureToAFewPartsInTenThousandEvenForSteepSpectra) {
  const DopplerGrid grid = DopplerGrid::covering(std::log(20.0));
  const RgbEmitterSpectrum red = RgbEmitterSpectrum::from_rgb({0.9, 0.1, 0.05});
  const BlackbodySpectrum cool = BlackbodySpectrum::with_luminance(2500, 1.0);
  const DopplerXyzTable a = DopplerXyzTable::of(red, grid);
  const DopplerXyzTable b = DopplerXyzTable::of(cool, grid);
  for (double d = 0.051; d < 19; d *= 1.0377) {
    for (const auto& [table, exact] : {std::pair{&a, xyz_seen_with_doppler(red, d)},
                                       std::pair{&b, xyz_seen_with_doppler(cool, d)}}) {
      const Xyz got = (*table)(d);
      EXPECT_NEAR(got.x / exact.x, 1.0, 2.5e-4) << d;
      EXPECT_NEAR(got.y / exact.y, 1.0, 2.5e-4) << d;
      EXPECT_NEAR(got.z / exact.z, 1.0, 2.5e-4) << d;
    }
  }
  // At D = 1 the node is the rest colour's own sum.
  const Xyz rest = xyz_from_spectrum(red);
  EXPECT_EQ(a.at_rest().x, rest.x);
  EXPECT_EQ(a.at_rest().y, rest.y);
}

// A table's sRGB lookup (its cubics in the values kept in sRGB, taken there when it is made) is
// the sRGB of the exact quadrature, to the interpolation's own error, and its XYZ lookup is
// the XYZ of it, in every kind of interval: cubics in the values, in the logarithms, and
// linear where a node is zero.
TEST(DopplerXyzTable, ItsSrgbLookupIsTheSrgbOfTheQuadrature) {
  const DopplerGrid grid = DopplerGrid::covering(1.5);
  const RgbEmitterSpectrum red = RgbEmitterSpectrum::from_rgb({0.9, 0.1, 0.05});
  const BlackbodySpectrum cool = BlackbodySpectrum::with_luminance(2500, 1.0);
  const TabulatedSpectrum red_only{{599, 600, 2000}, {0, 1, 1}};
  // (the step spectrum's own interpolation error is larger: its sRGB is checked against its XYZ)
  const auto check = [&](const auto& spectrum, bool smooth) {
    const DopplerXyzTable table = DopplerXyzTable::of(spectrum, grid);
    const Xyz rest = table.at_rest();
    for (double d = 0.23; d < 4.4; d *= 1.0071) {
      const GridPosition p = grid_position(grid, d);
      const Xyz exact = xyz_seen_with_doppler(spectrum, d);
      const LinearRgb got = table.rgb(p), want = linear_srgb_from_xyz(exact);
      // (where the colour fades to black, the linear intervals' error is the rest colour's)
      const double scale = std::max({exact.x, exact.y, exact.z, 1e-3 * rest.y});
      if (smooth) {
        EXPECT_NEAR(got.r / scale, want.r / scale, 1e-3) << d;
        EXPECT_NEAR(got.g / scale, want.g / scale, 1e-3) << d;
        EXPECT_NEAR(got.b / scale, want.b / scale, 1e-3) << d;
      }
      const Xyz back = table(p), from_rgb = xyz_from_linear_srgb(got);
      EXPECT_NEAR(back.x / scale, from_rgb.x / scale, 1e-13) << d;
      EXPECT_NEAR(back.y / scale, from_rgb.y / scale, 1e-13) << d;
      EXPECT_NEAR(back.z / scale, from_rgb.z / scale, 1e-13) << d;
    }
  };
  check(red, true);
  check(cool, true);
  check(red_only, false);
}

TEST(DopplerGrid, ItsLogarithmIsStdLogToOnePartInATrillion) {
  for (double d = 1e-6; d < 1e6; d *= 1.0137)
    EXPECT_NEAR(grid_log(d), std::log(d), 1e-12 * std::max(1.0, std::abs(std::log(d)))) << d;
  EXPECT_EQ(grid_log(1.0), 0.0);
  EXPECT_NEAR(grid_log(std::nextafter(2.0, 0.0)), std::log(2.0), 1e-15);
}

TEST(DopplerGrid, CoversItsRangeWithTwoSpareNodesAndHoldsDOne) {
  const DopplerGrid g = DopplerGrid::covering(0.83, 1.1);
  EXPECT_LE(g.log_d(2), 0.83);
  EXPECT_GE(g.log_d(g.size() - 3), 1.1);
  EXPECT_LT(g.size(), 25);  // only the range asked for, not +-1.1
  const DopplerGrid symmetric = DopplerGrid::covering(0.5);
  EXPECT_EQ(symmetric.log_d(symmetric.rest_index()), 0.0);
  const GridPosition p = grid_position(symmetric, 1.0);
  EXPECT_EQ(p.first + 1, symmetric.rest_index());
  EXPECT_EQ(p.fraction, 0.0);
}

TEST(EmissionTable, ColoursPastTheTableLimitCombineTheSharedTablesToTheSameColour) {
  // More distinct colours than get tables of their own, at 0.6c: the last ones are combined
  // per lookup from the white's and the nodes' tables, and must show what a table gives over
  // the factors the image shows.
  Scene s;
  s.camera.width = 8;
  s.camera.height = 8;
  const int count = static_cast<int>(EmissionTable::kMaxColourTables) + 8;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> colour(0, 1);
  for (int i = 0; i < count; ++i) {
    Material m;
    m.pattern = SolidColor{{colour(rng), colour(rng), colour(rng)}};
    s.objects.push_back(
        test::make_object(fmt::format("s{}", i), Sphere{0.1}, {0, 0, -5.0 - i}, {0.6, 0, 0}, m));
  }
  const ResolvedScene resolved = resolve_scene(s);
  const EmissionTable emission(resolved);
  const Hit hit{};
  for (int i = count - 8; i < count; ++i) {
    const PointEmission combined = emission.surface(static_cast<std::size_t>(i), hit);
    // The same colour alone in a scene of the same velocities gets a table of its own.
    Scene alone = s;
    alone.objects = {s.objects[static_cast<std::size_t>(i)], s.objects[0]};
    const ResolvedScene resolved_alone = resolve_scene(alone);
    const EmissionTable own(resolved_alone);
    const PointEmission tabled = own.surface(0, hit);
    ASSERT_EQ(tabled.table_count, 1);
    EXPECT_GT(combined.table_count, 1) << i;
    const LogDopplerRange seen = visible_log_doppler(resolved, false);
    for (double f : {0.0, 0.3, 0.5, 0.9, 1.0}) {
      const double d = std::exp(seen.lo + f * (seen.hi - seen.lo));
      const Xyz a = combined.seen_with_doppler(d), b = tabled.seen_with_doppler(d);
      EXPECT_NEAR(a.y, b.y, 2e-3 * b.y + 1e-12) << i << " at D " << d;
      EXPECT_NEAR(chromaticity(a).x, chromaticity(b).x, 1e-3) << i << " at D " << d;
      EXPECT_NEAR(chromaticity(a).y, chromaticity(b).y, 1e-3) << i << " at D " << d;
    }
  }
}

TEST(EmissionTable, BodiesOfOneSpectrumShareItsTableAndOthersGetTheirOwn) {
  Scene s;
  s.camera.width = 8;
  s.camera.height = 8;
  const std::vector<Pattern> patterns = {EmissionSpectrum{{400, 700}, {1, 2}},
                                         EmissionSpectrum{{400, 700}, {1, 2}},
                                         EmissionSpectrum{{400, 700}, {2, 1}},
                                         EmissionSpectrum{{400, 500, 700}, {1, 2, 2}},
                                         Blackbody{3000, 1},
                                         Blackbody{3000, 1},
                                         Blackbody{3000, 2}};
  for (std::size_t i = 0; i < patterns.size(); ++i) {
    Material m;
    m.pattern = patterns[i];
    s.objects.push_back(test::make_object(fmt::format("s{}", i), Sphere{0.1},
                                          {0, 0, -5.0 - static_cast<double>(i)}, {0.5, 0, 0}, m));
  }
  const ResolvedScene resolved = resolve_scene(s);
  const EmissionTable emission(resolved);
  const auto table = [&](std::size_t i) { return emission.surface(i, Hit{}).tables[0]; };
  EXPECT_EQ(table(0), table(1));
  EXPECT_EQ(table(4), table(5));
  const std::set<const DopplerXyzTable*> distinct = {table(0), table(2), table(3), table(4),
                                                     table(6)};
  EXPECT_EQ(distinct.size(), 5u);
  // A shared table is the one the spectrum gets alone.
  Scene alone = s;
  alone.objects = {s.objects[1]};
  const ResolvedScene resolved_alone = resolve_scene(alone);
  const EmissionTable own(resolved_alone);
  // (Within the factors the picture shows, about 0.67 to 1.2: a table refuses others.)
  for (double d : {0.7, 1.0, 1.15}) {
    const Xyz a = emission.surface(1, Hit{}).seen_with_doppler(d);
    const Xyz b = own.surface(0, Hit{}).seen_with_doppler(d);
    EXPECT_NEAR(a.y, b.y, 1e-9 * b.y) << d;
  }
}

TEST(ViewExtremes, AreTheExtremesOfADenseSamplingOfTheImage) {
  // Wide and narrow views, turned cameras, and velocities in and out of view: the exact
  // extremes bound every sampled direction and a dense sampling comes within its spacing.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 60; ++trial) {
    Camera camera;
    camera.width = 40 + trial * 7;
    camera.height = 30 + (trial * 13) % 50;
    camera.fov_degrees = 10 + (trial * 37) % 160;
    camera.forward = normalize(Vec3{u(rng), u(rng), u(rng)});
    camera.up = normalize(cross(camera.forward, Vec3{u(rng), u(rng), u(rng)}));
    const CameraBasis basis = camera_basis(camera);
    const Vec3 b = Vec3{u(rng), u(rng), u(rng)} * (trial % 5 == 0 ? 1e-9 : 0.99);
    const ViewExtremes e = view_extremes_along(basis, b);
    for (const Vec3& extreme : {e.smallest, e.largest}) {
      const ImagePoint p = project_direction(basis, extreme);
      EXPECT_TRUE(p.in_front);
      EXPECT_GE(p.x, -1e-9 * camera.width);
      EXPECT_LE(p.x, camera.width * (1 + 1e-9));
      EXPECT_GE(p.y, -1e-9 * camera.height);
      EXPECT_LE(p.y, camera.height * (1 + 1e-9));
    }
    const int n = 200;
    double lo = 1e300, hi = -1e300;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double d = dot(
            b, look_direction(basis, camera.width * i / double(n), camera.height * j / double(n)));
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    const double tolerance = 1e-12 * length(b);
    EXPECT_LE(dot(b, e.smallest), lo + tolerance) << trial;
    EXPECT_GE(dot(b, e.largest), hi - tolerance) << trial;
    // A direction n-th of the view apart changes the product by at most about this much.
    const double spacing = 3 * length(b) * std::numbers::pi / n;
    EXPECT_GT(dot(b, e.smallest), lo - spacing) << trial;
    EXPECT_LT(dot(b, e.largest), hi + spacing) << trial;
  }
}

TEST(DopplerXyzTable, AZeroTailInterpolatesLinearlyAndNeverGoesNegative) {
  // Emits only beyond 600 nm: seen with D < 600/830 it is black.
  const TabulatedSpectrum red_only{{599, 600, 2000}, {0, 1, 1}};
  const DopplerGrid grid = DopplerGrid::covering(1.0);
  const DopplerXyzTable t = DopplerXyzTable::of(red_only, grid);
  for (double d = 0.4; d < 2.7; d *= 1.01) {
    const Xyz got = t(d);
    EXPECT_GE(got.x, 0);
    EXPECT_GE(got.y, 0);
    EXPECT_TRUE(std::isfinite(got.x) && std::isfinite(got.y) && std::isfinite(got.z));
  }
  EXPECT_EQ(t(0.5).y, 0.0);
}

// ---------------------------------------------------------------------------------------------
// 5. Lit surfaces against an independent quadrature of the reflected spectrum.

TEST(SpectralLighting, LitWallAgreesWithAnIndependentQuadratureAtDOf044And436) {
  const Rgb albedo{0.7f, 0.35f, 0.15f};
  const Rgb light_colour{0.9f, 0.8f, 1.0f};
  const double intensity = 30;
  for (const double d : {0.44, 4.36})
    for (const double light_speed : {0.0, 0.6}) {
      SCOPED_TRACE("D = " + std::to_string(d) + ", light speed " + std::to_string(light_speed));
      Material m;
      m.pattern = SolidColor{albedo};
      m.unlit = false;
      Scene s = wall_scene(m, closing_speed(d));
      Light light;
      light.kind = PointLight{};
      light.world_line.position = {0, 0, -15};
      light.world_line.velocity = {0, 0, -light_speed};  // toward the wall
      light.spectrum.emission = light_colour;
      light.intensity = intensity;
      s.lights.push_back(light);
      s.render.shadows = false;
      const CentreColour got = centre_colour(s);
      ASSERT_NEAR(got.d, d, 1e-9 * d);

      // Independently: the wall's front point on the axis (z = -19.5) receives, at its event
      // t_R on the camera's past light cone, the light that left the lamp at z(t) = -15 - v t
      // at t_e with t_R - t_e = z(t_e) + 19.5, in the wall's frame (W).
      const ResolvedScene r = resolve_scene(s);
      const Vec3 u = look_direction(r.camera, 2.5, 2.5);
      const auto hit = Tracer(r).trace(u);
      ASSERT_TRUE(hit.has_value());
      const Vec4 surface = r.trace_to_world({r.ray_time * hit->s, u * hit->s});
      const double v = light_speed;
      const double t_e = (surface.t - 4.5) / (1 - v);       // t_R - t_e = 4.5 - v t_e
      const double distance = surface.t - t_e;              // in the wall's frame
      const double d_light = std::sqrt((1 + v) / (1 - v));  // head-on toward the wall
      const RgbAlbedoSpectrum rho = RgbAlbedoSpectrum::from_rgb({albedo.r, albedo.g, albedo.b});
      const RgbEmitterSpectrum source =
          RgbEmitterSpectrum::from_rgb({light_colour.r, light_colour.g, light_colour.b});
      Xyz sum;
      for (int i = 0; i < kCieTableSize; ++i) {
        const double lambda = kCieMinWavelength + i;
        const double l = rho(d * lambda) * source(d_light * d * lambda);
        const Xyz c = cie_cmf(lambda);
        sum.x += l * c.x;
        sum.y += l * c.y;
        sum.z += l * c.z;
      }
      const double k = std::pow(d, 5) * std::pow(d_light, 5) * intensity / (distance * distance) /
                       kPi / cie_y_integral();
      const LinearRgb want = linear_srgb_from_xyz({sum.x * k, sum.y * k, sum.z * k});
      EXPECT_NEAR(got.rgb.r / want.r, 1.0, 1e-3);
      EXPECT_NEAR(got.rgb.g / want.g, 1.0, 1e-3);
      EXPECT_NEAR(got.rgb.b / want.b, 1.0, 1e-3);
    }
}

// ---------------------------------------------------------------------------------------------
// 6. Edges converge: a grey checker wall approached at 0.5c.

// sRGB-encoded 8-bit value of a linear value after exposure.
int srgb8(double v) {
  v = std::clamp(v, 0.0, 1.0);
  const double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
  return static_cast<int>(std::lround(255 * e));
}

TEST(Sampling, CheckerEdgesAt64SamplesAreWithinTwoLevelsOf1024AndOnlyMixTheirNeighbours) {
  Scene s;
  s.camera.world_line.position = {0.13, 0.07, 0};
  s.camera.world_line.velocity = {0, 0, -0.5};
  s.camera.width = 40;
  s.camera.height = 30;
  s.camera.fov_degrees = 30;
  s.objects.push_back(make_object("wall", Box{{40, 40, 1}}, {0, 0, -12}, {},
                                  unlit(Checker{1.1, {{0.3f, 0.3f, 0.3f}, {0.5f, 0.5f, 0.5f}}})));
  s.render.exposure = -3.4;  // D^4 is about 9 ahead
  Scene fine = s, coarse = s;
  s.camera.samples = 64;
  fine.camera.samples = 1024;
  coarse.camera.samples = 4;
  const Image a = render_image(s, {});
  const Image b = render_image(fine, {});
  const Image c = render_image(coarse, {});
  // The error converges: at 64 samples it is several times smaller than at 4.
  double error_64 = 0, error_4 = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    error_64 += (a.rgb[i] - b.rgb[i]) * (a.rgb[i] - b.rgb[i]);
    error_4 += (c.rgb[i] - b.rgb[i]) * (c.rgb[i] - b.rgb[i]);
  }
  EXPECT_LT(error_64, error_4 / 16);  // RMS at least 4x smaller
  int worst = 0, edges = 0;
  for (int j = 1; j < 29; ++j)
    for (int i = 1; i < 39; ++i) {
      const std::size_t p = 3 * (static_cast<std::size_t>(j) * 40 + i);
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(srgb8(a.rgb[p + c]) - srgb8(b.rgb[p + c])));
      // A grey seen with any D keeps one chromaticity across the picture's neighbourhood:
      // every pixel, edge or not, is a mix of the two squares' colours, which share it.
      const LinearRgb px{a.rgb[p], a.rgb[p + 1], a.rgb[p + 2]};
      const std::size_t q = p + 3;  // its right neighbour
      const LinearRgb right{a.rgb[q], a.rgb[q + 1], a.rgb[q + 2]};
      const Chromaticity cp = chromaticity(xyz_from_linear_srgb(px));
      const Chromaticity cr = chromaticity(xyz_from_linear_srgb(right));
      EXPECT_NEAR(cp.x, cr.x, 0.003) << i << "," << j;
      EXPECT_NEAR(cp.y, cr.y, 0.003) << i << "," << j;
      edges += std::abs(a.rgb[p] - a.rgb[q]) > 0.01 * a.rgb[p];
    }
  EXPECT_LE(worst, 2);
  EXPECT_GT(edges, 40);
}

TEST(Sampler, ShuffledIndexIsAPermutation) {
  for (std::uint32_t count : {1u, 2u, 3u, 7u, 64u, 100u, 1000u})
    for (std::uint32_t seed : {0u, 1u, 12345u, 0xdeadbeefu}) {
      std::set<std::uint32_t> seen;
      for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t p = shuffled_index(i, count, seed);
        EXPECT_LT(p, count);
        seen.insert(p);
      }
      EXPECT_EQ(seen.size(), count);
    }
}

TEST(Sampler, MultiJitteredPointsFillEveryRowColumnAndCell) {
  for (std::uint32_t count : {16u, 64u, 256u})
    for (std::uint32_t seed : {3u, 77u}) {
      const int side = static_cast<int>(std::lround(std::sqrt(count)));
      std::set<int> columns, rows, cells;
      for (std::uint32_t k = 0; k < count; ++k) {
        const auto p = multi_jittered(k, count, seed);
        ASSERT_GE(p[0], 0.0);
        ASSERT_LT(p[0], 1.0);
        ASSERT_GE(p[1], 0.0);
        ASSERT_LT(p[1], 1.0);
        columns.insert(static_cast<int>(p[0] * count));
        rows.insert(static_cast<int>(p[1] * count));
        cells.insert(static_cast<int>(p[0] * side) * side + static_cast<int>(p[1] * side));
      }
      EXPECT_EQ(columns.size(), count);
      EXPECT_EQ(rows.size(), count);
      EXPECT_EQ(cells.size(), count);
    }
}

TEST(Sampler, DimensionsArePixelsAreAndSeedsAreDecorrelated) {
  // Over many pixels, a sample's position in the pixel and its point on a light are
  // uncorrelated; the same seed repeats and another seed differs.
  double sxy = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
  const int n = 20000;
  for (int p = 0; p < n; ++p) {
    const PixelSample s = pixel_sample(p % 200, p / 200, 3, 16, 0);
    sx += s.x, sy += s.light[0], sxy += s.x * s.light[0], sxx += s.x * s.x;
    syy += s.light[0] * s.light[0];
  }
  const double cov = sxy / n - (sx / n) * (sy / n);
  const double corr = cov / std::sqrt((sxx / n - sx * sx / n / n) * (syy / n - sy * sy / n / n));
  EXPECT_LT(std::abs(corr), 0.03);
  const PixelSample a = pixel_sample(5, 7, 2, 16, 0), b = pixel_sample(5, 7, 2, 16, 0),
                    c = pixel_sample(5, 7, 2, 16, 1);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.light[1], b.light[1]);
  EXPECT_NE(a.x, c.x);
}

}  // namespace
}  // namespace lightcone

namespace lightcone {
namespace {

// Emission tables built with a margin serve the next frames of the same Scene object while its
// factors stay inside them (the viewer keeps them), and give the colours a table built for each
// frame gives; another Scene, another colour model or a factor beyond the margin needs new ones.
TEST(EmissionTableReuse, ServesTheNextFramesOfTheSameScene) {
  Scene scene = test::load_repository_scene("street.json");
  scene.camera.width = 64, scene.camera.height = 36;
  const ResolvedScene first = resolve_scene(scene);
  const EmissionTable kept(first, 0.25);
  EXPECT_TRUE(kept.serves(first));

  scene.camera.forward = normalize(Vec3{0.05, 0, -1});  // the next frame turns a little
  const ResolvedScene next = resolve_scene(scene);
  ASSERT_TRUE(kept.serves(next));
  const EmissionTable fresh(next);
  // Over the factors the fresh tables hold inside their ends (the nodes of both are the same).
  const DopplerGrid& grid = fresh.white_table().grid();
  int compared = 0;
  for (std::size_t i = 0; i < scene.objects.size(); i += 7)
    for (double log_d = (grid.first + 2) * DopplerGrid::kStep;
         log_d <= (grid.last - 2) * DopplerGrid::kStep; log_d += 0.0137) {
      const Xyz a = kept.object_colour(i, 0).seen_with_doppler(std::exp(log_d));
      const Xyz b = fresh.object_colour(i, 0).seen_with_doppler(std::exp(log_d));
      EXPECT_NEAR(a.y, b.y, 1e-12 * b.y) << i << " " << log_d;
      EXPECT_NEAR(a.z, b.z, 1e-12 * b.z) << i << " " << log_d;
      ++compared;
    }
  EXPECT_GT(compared, 50);

  Scene copy = scene;  // the same content, another object
  EXPECT_FALSE(kept.serves(resolve_scene(copy)));
  scene.render.doppler = DopplerModel::kRgb3;
  EXPECT_FALSE(kept.serves(resolve_scene(scene)));
  scene.render.doppler = DopplerModel::kSpectral;
  scene.camera.world_line.velocity = {0, 0, -0.95};  // from 0.8c: ln D grows by 0.4 ahead
  EXPECT_FALSE(kept.serves(resolve_scene(scene)));
}

// The lights' tables likewise (the raster renderer keeps them): a Lighting made 0.25 of ln D
// wide serves the next frame, reflecting each lit colour under each lamp as a fresh one does;
// not another scene, other settings, or a camera delay whose emission events moved.
TEST(LightingReuse, ServesTheNextFramesOfTheSameScene) {
  Scene scene = test::load_repository_scene("street-lit.json");
  scene.camera.width = 64, scene.camera.height = 36;
  const ResolvedScene first = resolve_scene(scene);
  Lighting kept(first, nullptr, nullptr, 0.25);
  EXPECT_TRUE(kept.serves(first));

  scene.camera.forward = normalize(Vec3{0.05, 0, -1});  // the next frame turns a little
  const ResolvedScene next = resolve_scene(scene);
  ASSERT_TRUE(kept.serves(next));
  kept.follow(next);
  const Lighting fresh(next, nullptr);
  const LogDopplerRange range = visible_log_doppler(next, true);
  int compared = 0;
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    if (scene.objects[o].material.unlit) continue;
    for (std::size_t l = 0; l < scene.lights.size(); l += 3)
      for (double log_d = range.lo; log_d <= range.hi; log_d += 0.0731) {
        const Xyz a = kept.reflected(o, 0, l, std::exp(log_d), 1.0);
        const Xyz b = fresh.reflected(o, 0, l, std::exp(log_d), 1.0);
        EXPECT_NEAR(a.y, b.y, 1e-9 * std::abs(b.y) + 1e-15) << o << " " << l << " " << log_d;
        EXPECT_NEAR(a.x, b.x, 1e-9 * std::abs(b.x) + 1e-15) << o << " " << l << " " << log_d;
        ++compared;
      }
  }
  EXPECT_GT(compared, 50);

  Scene copy = scene;  // the same content, another object
  EXPECT_FALSE(kept.serves(resolve_scene(copy)));
  scene.render.searchlight = SearchlightModel::kOff;
  EXPECT_FALSE(kept.serves(resolve_scene(scene)));
  scene.render.searchlight = SearchlightModel::kPhysical;
  scene.render.light_source_delay = LightSourceDelay::kCamera;
  const ResolvedScene camera_delay = resolve_scene(scene);
  Lighting at_camera(camera_delay, nullptr, nullptr, 0.25);
  EXPECT_TRUE(at_camera.serves(camera_delay));
  scene.camera.world_line.position.z -= 1;  // the lamps' events on its light cone move
  EXPECT_FALSE(at_camera.serves(resolve_scene(scene)));
  scene.render.light_source_delay = LightSourceDelay::kSurface;
  scene.camera.world_line.velocity = {0, 0, -0.95};  // from 0.8c: ln D grows by 0.4 ahead
  EXPECT_FALSE(kept.serves(resolve_scene(scene)));
}

}  // namespace
}  // namespace lightcone

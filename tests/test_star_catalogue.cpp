// The star catalogue (io/star_catalogue.hpp): the equatorial axes, the bundled catalogue against
// independent coordinates of named stars, and the compact file's checks.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/star_catalogue.hpp"
#include "lightcone/physics/celestial.hpp"
#include "lightcone/physics/stars.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = std::numbers::pi / 180;

double hours(double h, double m, double s) {
  return (h + m / 60 + s / 3600) * 15 * kDegree;
}
double degrees(double d, double m, double s) {
  return (std::signbit(d) ? -1 : 1) * (std::abs(d) + m / 60 + s / 3600) * kDegree;
}

// PHYSICS.md: the pole is +y, RA 0h on the equator -z, RA 6h -x, and an equirectangular sky
// map's longitude atan2(x, -z) is -RA.
TEST(Celestial, EquatorialAxes) {
  const auto near = [](const Vec3& a, const Vec3& b) { return length(a - b) < 1e-12; };
  EXPECT_TRUE(near(equatorial_direction(0, 0), {0, 0, -1}));
  EXPECT_TRUE(near(equatorial_direction(std::numbers::pi / 2, 0), {-1, 0, 0}));
  EXPECT_TRUE(near(equatorial_direction(1.234, std::numbers::pi / 2), {0, 1, 0}));
  const Vec3 d = equatorial_direction(0.7, -0.3);
  EXPECT_NEAR(std::atan2(d.x, -d.z), -0.7, 1e-12);
  EXPECT_NEAR(std::asin(d.y), -0.3, 1e-12);
}

// Ballesteros (2012) against measured temperatures: the Sun (B-V 0.653, Ramirez et al. 2012;
// T_eff 5772 K, the IAU's nominal value, 2015) within 0.5 %, Procyon (B-V 0.42, T_eff 6530 K,
// Kervella et al. 2004) within 5 % (a star is not quite a blackbody); hotter for bluer stars
// throughout the catalogue's range.
TEST(StarPhysics, TemperatureFromColourIndex) {
  EXPECT_NEAR(star_temperature(0.653), 5772, 0.005 * 5772);
  EXPECT_NEAR(star_temperature(0.42), 6530, 0.05 * 6530);
  for (double bv = -0.35; bv < 2.0; bv += 0.05)
    EXPECT_GT(star_temperature(bv), star_temperature(bv + 0.05)) << bv;
}

// Pogson: five magnitudes are a factor of 100, one about 2.512.
TEST(StarPhysics, MagnitudesAreLogarithmic) {
  EXPECT_DOUBLE_EQ(magnitude_flux_ratio(0), 1);
  EXPECT_NEAR(magnitude_flux_ratio(5), 0.01, 1e-15);
  EXPECT_NEAR(magnitude_flux_ratio(-1.46) / magnitude_flux_ratio(0.03), std::pow(100.0, 1.49 / 5),
              1e-12);
  EXPECT_NEAR(magnitude_flux_ratio(1) * 2.5118864315, 1, 1e-10);
}

// The bundled catalogue holds the naked-eye stars, with Sirius, Vega and Polaris where the
// Bright Star Catalogue (Hoffleit & Warren 1991) puts them at J2000, to 0.01 degrees, and their
// V and B-V.
TEST(StarCatalogue, BundledCatalogueHasTheNakedEyeStarsWhereTheyAre) {
  const std::vector<CatalogueStar> stars = read_star_catalogue(bright_star_catalogue_path());
  EXPECT_GT(stars.size(), 8500u);
  EXPECT_LT(stars.size(), 10000u);
  for (const CatalogueStar& s : stars) ASSERT_LT(s.magnitude, 6.5);
  struct Named {
    const char* name;
    double ra, dec, v, b_v;
  };
  for (const Named& n : {Named{"Sirius", hours(6, 45, 8.9), degrees(-16, 42, 58), -1.46, 0.00},
                         Named{"Vega", hours(18, 36, 56.3), degrees(38, 47, 1), 0.03, 0.00},
                         Named{"Polaris", hours(2, 31, 49.1), degrees(89, 15, 51), 1.98, 0.60}}) {
    SCOPED_TRACE(n.name);
    const Vec3 want = equatorial_direction(n.ra, n.dec);
    const CatalogueStar* nearest = &stars.front();
    for (const CatalogueStar& s : stars)
      if (dot(s.direction, want) > dot(nearest->direction, want)) nearest = &s;
    EXPECT_LT(std::acos(std::min(1.0, dot(nearest->direction, want))) / kDegree, 0.01);
    EXPECT_NEAR(nearest->magnitude, n.v, 0.1);
    EXPECT_NEAR(nearest->colour_index, n.b_v, 0.05);
  }
}

TEST(StarCatalogue, KStarsRecordsAreReadByColumn) {
  std::istringstream in(
      "# a comment\n"
      "064508.92 -164258.0 -000546.0-001223.100379.2 -1.4400.01A0 1            , alp CMa, "
      "Sirius\n"
      "183656.34 +384701.3 000201.7 000286.7 00128.9  0.03-0.00A0 0\n"
      "000000.00 +000000.0 000000.0 000000.0 00000.0  7.00 0.50G2 0\n");
  const auto stars = parse_kstars_stars(in, 6.5);
  ASSERT_EQ(stars.size(), 2u);
  EXPECT_LT(
      length(stars[0].direction - equatorial_direction(hours(6, 45, 8.92), degrees(-16, 42, 58.0))),
      1e-12);
  EXPECT_FLOAT_EQ(stars[0].magnitude, -1.44f);
  EXPECT_FLOAT_EQ(stars[0].colour_index, 0.01f);
  EXPECT_FLOAT_EQ(stars[1].magnitude, 0.03f);
  std::istringstream bad("064508.92 -16x258.0 -000546.0-001223.100379.2 -1.4400.01A0 1\n");
  try {
    parse_kstars_stars(bad, 6.5);
    ADD_FAILURE() << "a bad record was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("line 1"), std::string::npos) << e.what();
  }
}

// The compact file round-trips; a missing file names the package that provides it, and a
// truncated or foreign one is refused by name.
TEST(StarCatalogue, CompactFileRoundTripsAndRefusesDamage) {
  const fs::path dir = test::fresh_temp_dir("star_catalogue");
  const std::vector<CatalogueStar> stars = {{normalize(Vec3{1, 2, 3}), 1.5f, 0.3f},
                                            {{0, 1, 0}, 5.25f, -0.1f}};
  write_star_catalogue(dir / "a.lcstars", stars);
  const auto back = read_star_catalogue(dir / "a.lcstars");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].direction.x, stars[0].direction.x);
  EXPECT_EQ(back[1].magnitude, 5.25f);
  EXPECT_EQ(back[1].colour_index, -0.1f);
  const auto refused = [&](const fs::path& path, const std::string& says) {
    try {
      read_star_catalogue(path);
      ADD_FAILURE() << path << " was read";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path.string()), std::string::npos) << what;
      EXPECT_NE(what.find(says), std::string::npos) << what;
    }
  };
  refused(dir / "missing.lcstars", "kstars-data");
  std::string bytes;
  {
    std::ifstream in(dir / "a.lcstars", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  test::write_text(dir / "short.lcstars", bytes.substr(0, bytes.size() - 1));
  refused(dir / "short.lcstars", "damaged");
  test::write_text(dir / "foreign.lcstars", "P6\n1 1\n255\n");
  refused(dir / "foreign.lcstars", "LCSTARS1");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lightcone

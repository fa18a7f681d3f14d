// The star catalogue (io/star_catalogue.hpp): the equatorial axes, the bundled catalogue against
// independent coordinates of named stars, and the compact file's checks (what it reads, and the
// ranges of V and B-V).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <thread>

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
// Kervella et al. 2004) within 5 % (a star is not quite a blackbody); finite, positive and
// hotter for bluer stars throughout the range a catalogue may hold.
TEST(StarPhysics, TemperatureFromColourIndex) {
  EXPECT_NEAR(star_temperature(0.653), 5772, 0.005 * 5772);
  EXPECT_NEAR(star_temperature(0.42), 6530, 0.05 * 6530);
  EXPECT_TRUE(std::isfinite(star_temperature(kBluestColourIndex)));
  EXPECT_GT(star_temperature(kReddestColourIndex), 0);
  for (double bv = kBluestColourIndex; bv < kReddestColourIndex; bv += 0.05)
    EXPECT_GT(star_temperature(bv), star_temperature(std::min(bv + 0.05, kReddestColourIndex)))
        << bv;
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

// What read_star_catalogue(path) throws, "(read)" if it reads the file, read in a child process
// that is killed after 10 s: a reader that opens whatever the path names blocks for ever on a
// FIFO and reads /dev/zero until memory runs out, and such a regression should fail, not hang.
std::string refusal_within_10_s(const fs::path& path) {
  int ends[2];
  if (::pipe(ends) != 0) return "(no pipe)";
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(ends[0]);
    std::string said = "(read)";
    try {
      read_star_catalogue(path);
    } catch (const InputError& e) {
      said = e.what();
    } catch (const std::exception& e) {
      said = std::string("(not an InputError: ") + e.what() + ")";
    }
    [[maybe_unused]] const ssize_t written = ::write(ends[1], said.data(), said.size());
    ::_exit(0);
  }
  ::close(ends[1]);
  int status = 0;
  bool ended = false;
  for (int tick = 0; tick < 1000 && !ended; ++tick) {
    ended = ::waitpid(child, &status, WNOHANG) == child;
    if (!ended) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!ended) {
    ::kill(child, SIGKILL);
    ::waitpid(child, &status, 0);
  }
  std::string said;
  char buffer[4096];
  for (ssize_t n; (n = ::read(ends[0], buffer, sizeof(buffer))) > 0;) said.append(buffer, n);
  ::close(ends[0]);
  return ended ? said : "(still reading after 10 s)";
}

// A FIFO (which blocks whoever opens it to read) and a link to /dev/zero (which never ends) are
// refused at once, by name, before they are opened; so is a file larger than the most stars a
// catalogue may hold, before it is read.
TEST(StarCatalogue, OnlyRegularFilesOfBoundedSizeAreRead) {
  const fs::path dir = test::fresh_temp_dir("star_catalogue_inputs");
  const fs::path fifo = dir / "fifo.lcstars", zero = dir / "zero.lcstars";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", zero);
  for (const fs::path& path : {fifo, zero}) {
    const std::string said = refusal_within_10_s(path);
    EXPECT_NE(
        said.find(path.string() + ": cannot read the star catalogue: it is not a regular file"),
        std::string::npos)
        << said;
  }
  // Sparse: one star more than the most a catalogue may hold (a 12-byte header, 32 bytes a star).
  const fs::path huge = dir / "huge.lcstars";
  test::write_text(huge, "LCSTARS1");
  fs::resize_file(huge, 12 + (std::uintmax_t{kMaxCatalogueStars} + 1) * 32);
  const std::string said = refusal_within_10_s(huge);
  EXPECT_NE(said.find(huge.string() + ": cannot read the star catalogue:"), std::string::npos)
      << said;
  EXPECT_NE(said.find("more than the limit"), std::string::npos) << said;
  fs::remove_all(dir);
}

// V and B-V are checked when the file is read, against the ranges the photometry is used for,
// naming the file, the star and the field (left to the render, B-V -1 gives a negative
// temperature and V -1e30 an infinite flux). The ranges' ends are read, B-V -0.40 (the bluest of
// KStars' catalogue, a float a little below -0.4) among them, and so is W Ori (B-V 3.33).
TEST(StarCatalogue, MagnitudeAndColourIndexAreCheckedWhenRead) {
  const fs::path dir = test::fresh_temp_dir("star_catalogue_ranges");
  const CatalogueStar vega{{0, 1, 0}, 0.03f, 0.0f};
  const fs::path ends = dir / "ends.lcstars";
  write_star_catalogue(
      ends,
      {vega,
       {{1, 0, 0}, static_cast<float>(kBrightestMagnitude), -0.4f},
       {{0, 0, 1}, static_cast<float>(kFaintestMagnitude), static_cast<float>(kReddestColourIndex)},
       {{0, 0, -1}, 6.1f, 3.33f}});
  EXPECT_EQ(read_star_catalogue(ends).size(), 4u);
  struct Bad {
    const char* name;
    float magnitude, colour_index;
    const char* says;
  };
  for (const Bad& bad :
       {Bad{"blue", 1, -1, "star 1: B-V colour index -1 is outside -0.4 to 6"},
        Bad{"red", 1, 6.5f, "star 1: B-V colour index 6.5 is outside"},
        Bad{"bright", -1e30f, 0.5f, "star 1: V magnitude -1e+30 is outside -2 to 30"},
        Bad{"faint", 31, 0.5f, "star 1: V magnitude 31 is outside"},
        Bad{"nan", std::nanf(""), 0.5f, "star 1: V magnitude nan is outside"}}) {
    const fs::path path = dir / (std::string(bad.name) + ".lcstars");
    write_star_catalogue(path, {vega, {{1, 0, 0}, bad.magnitude, bad.colour_index}});
    try {
      read_star_catalogue(path);
      ADD_FAILURE() << bad.name << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path.string() + ": " + bad.says), std::string::npos)
          << e.what();
    }
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lightcone

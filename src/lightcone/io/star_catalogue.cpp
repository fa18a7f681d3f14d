#include "lightcone/io/star_catalogue.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/input_file.hpp"
#include "lightcone/physics/celestial.hpp"
#include "lightcone/physics/stars.hpp"

namespace lightcone {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the catalogue file is little-endian, as the hosts lightcone builds on");

constexpr char kMagic[8] = {'L', 'C', 'S', 'T', 'A', 'R', 'S', '1'};
constexpr std::size_t kHeaderBytes = sizeof(kMagic) + sizeof(std::uint32_t);
constexpr std::size_t kStarBytes = 3 * sizeof(double) + 2 * sizeof(float);
constexpr std::uintmax_t kMaxFileBytes =
    kHeaderBytes + std::uintmax_t{kMaxCatalogueStars} * kStarBytes;

// Whether a value the file holds lies in [lo, hi], the bounds rounded to float32 as the file's
// values are (KStars' B-V -0.40 is stored a little below -0.4). NaN lies in no range.
bool within(float value, double lo, double hi) {
  return value >= static_cast<float>(lo) && value <= static_cast<float>(hi);
}

// The number in columns [first, first + width) of a line; NaN where there is none.
double field(const std::string& line, std::size_t first, std::size_t width) {
  if (line.size() < first + width) return std::nan("");
  const std::string text = line.substr(first, width);
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str()) return std::nan("");
  for (; *end; ++end)
    if (*end != ' ') return std::nan("");
  return value;
}

}  // namespace

std::vector<CatalogueStar> parse_kstars_stars(std::istream& in, double magnitude_limit) {
  std::vector<CatalogueStar> stars;
  std::string line;
  constexpr double kDegree = std::numbers::pi / 180;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    const double hours = field(line, 0, 2), minutes = field(line, 2, 2),
                 seconds = field(line, 4, 5);
    const double degrees = field(line, 11, 2), arcminutes = field(line, 13, 2),
                 arcseconds = field(line, 15, 4);
    const double magnitude = field(line, 45, 6), colour_index = field(line, 51, 5);
    const char sign = line.size() > 10 ? line[10] : '?';
    for (const double v :
         {hours, minutes, seconds, degrees, arcminutes, arcseconds, magnitude, colour_index})
      if (!std::isfinite(v) || (sign != '+' && sign != '-'))
        throw std::runtime_error(
            fmt::format("line {}: not a star record of KStars' stars.dat", number));
    if (!(magnitude < magnitude_limit)) continue;
    const double ra = (hours + minutes / 60 + seconds / 3600) * 15 * kDegree;
    const double dec =
        (sign == '-' ? -1 : 1) * (degrees + arcminutes / 60 + arcseconds / 3600) * kDegree;
    stars.push_back({equatorial_direction(ra, dec), static_cast<float>(magnitude),
                     static_cast<float>(colour_index)});
  }
  return stars;
}

void write_star_catalogue(const std::filesystem::path& path,
                          const std::vector<CatalogueStar>& stars) {
  std::string bytes(kMagic, sizeof(kMagic));
  const auto append = [&](const auto& value) {
    char raw[sizeof(value)];
    std::memcpy(raw, &value, sizeof(value));
    bytes.append(raw, sizeof(value));
  };
  append(static_cast<std::uint32_t>(stars.size()));
  for (const CatalogueStar& s : stars) {
    append(s.direction.x), append(s.direction.y), append(s.direction.z);
    append(s.magnitude), append(s.colour_index);
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write the star catalogue");
}

std::vector<CatalogueStar> read_star_catalogue(const std::filesystem::path& path) {
  const auto fail = [&](const std::string& why) { throw InputError(path.string() + ": " + why); };
  std::string reason;
  const std::optional<std::string> read = try_read_input_file(path, kMaxFileBytes, reason);
  if (!read) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
      fail(
          "the star catalogue is missing: it is made when lightcone is built, from Debian's "
          "kstars-data (./setup.sh installs it; then build again)");
    fail("cannot read the star catalogue: " + reason);
  }
  return parse_star_catalogue(*read, path);
}

std::vector<CatalogueStar> parse_star_catalogue(std::string_view bytes,
                                                const std::filesystem::path& path) {
  const auto fail = [&](const std::string& why) { throw InputError(path.string() + ": " + why); };
  if (bytes.size() < kHeaderBytes || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    fail("not a lightcone star catalogue (it does not start with LCSTARS1)");
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + sizeof(kMagic), sizeof(count));
  // The file's size is capped, so this also bounds what a corrupt count can ask for.
  if (bytes.size() != kHeaderBytes + std::size_t{count} * kStarBytes)
    fail(fmt::format("the star catalogue is damaged: {} bytes for {} stars", bytes.size(), count));
  std::vector<CatalogueStar> stars(count);
  const char* p = bytes.data() + kHeaderBytes;
  const auto take = [&](auto& value) {
    std::memcpy(&value, p, sizeof(value));
    p += sizeof(value);
  };
  for (std::uint32_t i = 0; i < count; ++i) {
    CatalogueStar& s = stars[i];
    take(s.direction.x), take(s.direction.y), take(s.direction.z);
    take(s.magnitude), take(s.colour_index);
    if (!(std::abs(length(s.direction) - 1) < 1e-9))
      fail(fmt::format("the star catalogue is damaged at star {}", i));
    // Checked here, by name: left to the render, such a star (a negative temperature, an
    // infinite flux) surfaces only as a picture of non-finite values.
    if (!within(s.magnitude, kBrightestMagnitude, kFaintestMagnitude))
      fail(
          fmt::format("star {}: V magnitude {} is outside {} to {}, the range of stars' magnitudes",
                      i, s.magnitude, kBrightestMagnitude, kFaintestMagnitude));
    if (!within(s.colour_index, kBluestColourIndex, kReddestColourIndex))
      fail(fmt::format(
          "star {}: B-V colour index {} is outside {} to {}, the range Ballesteros' colour "
          "temperature is used for",
          i, s.colour_index, kBluestColourIndex, kReddestColourIndex));
  }
  return stars;
}

namespace {

std::optional<std::filesystem::path>& star_catalogue_folder() {
  static std::optional<std::filesystem::path> folder;
  return folder;
}

}  // namespace

void set_star_catalogue_folder(const std::filesystem::path& folder) {
  star_catalogue_folder() = folder;
}

std::filesystem::path bright_star_catalogue_path() {
  if (const auto& folder = star_catalogue_folder()) return *folder / kBrightCatalogueFile;
  std::error_code ec;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path folder = ec ? std::filesystem::current_path() : program.parent_path();
  const std::filesystem::path beside = folder / "data" / kBrightCatalogueFile;
  const std::filesystem::path installed =
      folder.parent_path() / "share" / "lightcone" / kBrightCatalogueFile;
  if (!std::filesystem::exists(beside, ec) && std::filesystem::exists(installed, ec))
    return installed;
  return beside;
}

}  // namespace lightcone

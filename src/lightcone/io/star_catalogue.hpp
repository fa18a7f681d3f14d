// The star catalogue: the naked-eye stars of KStars' catalogue (Hipparcos positions at J2000,
// V magnitudes and B-V colour indices, from Debian's kstars-data), converted at build time into
// a compact file of lightcone's own and read from there (docs/design/stars.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <istream>
#include <string_view>
#include <vector>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The stars of KStars' stars.dat (its fixed columns: right ascension hhmmss.ss, declination
// +ddmmss.s, ..., V at columns 45-50, B-V at 51-55) brighter than `magnitude_limit`, in the
// file's order (brightest first). Throws std::runtime_error naming the line of a record it
// cannot read.
std::vector<CatalogueStar> parse_kstars_stars(std::istream& in, double magnitude_limit);

// The compact file: "LCSTARS1", the number of stars (uint32, little-endian), then per star its
// direction (3 float64), V and B-V (2 float32). A reader takes at most kMaxCatalogueStars: far
// more than any catalogue lightcone ships, a bound on what a corrupt count or a huge file can ask
// for.
inline constexpr std::uint32_t kMaxCatalogueStars = 10'000'000;
void write_star_catalogue(const std::filesystem::path& path,
                          const std::vector<CatalogueStar>& stars);
// Throws InputError naming the file when it is missing (and the package that provides it), not a
// regular file, larger than the most stars it may hold, unreadable, or not such a file, and
// naming the star and the field where a star's V or B-V lies outside the range the photometry
// is used for (physics/stars.hpp).
std::vector<CatalogueStar> read_star_catalogue(const std::filesystem::path& path);
// The same for the file's bytes, read from `path` (which messages name): the parser the fuzzer
// feeds arbitrary bytes.
std::vector<CatalogueStar> parse_star_catalogue(std::string_view bytes,
                                                const std::filesystem::path& path);

// The bundled catalogue's name, "bright", and where the program finds it: beside the program
// (the build folder's data/) or in the installed data folder (../share/lightcone/ from it).
inline constexpr const char* kBrightCatalogueFile = "stars-bright.lcstars";
std::filesystem::path bright_star_catalogue_path();
// Where bright_star_catalogue_path looks instead, for a library loaded by another program (the
// Python module keeps the catalogue in its package folder).
void set_star_catalogue_folder(const std::filesystem::path& folder);

}  // namespace lightcone

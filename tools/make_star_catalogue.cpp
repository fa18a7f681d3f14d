// Converts KStars' stars.dat (Debian's kstars-data) into lightcone's compact star catalogue at
// build time: make_star_catalogue STARS_DAT OUTPUT MAGNITUDE_LIMIT.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>

#include "lightcone/io/star_catalogue.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: make_star_catalogue STARS_DAT OUTPUT MAGNITUDE_LIMIT\n");
    return 2;
  }
  try {
    std::ifstream in(argv[1]);
    if (!in) throw std::runtime_error("cannot open it");
    const auto stars = lightcone::parse_kstars_stars(in, std::atof(argv[3]));
    lightcone::write_star_catalogue(argv[2], stars);
    std::printf("make_star_catalogue: %zu stars brighter than V = %s\n", stars.size(), argv[3]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_star_catalogue: %s: %s\n", argv[1], e.what());
    return 1;
  }
  return 0;
}

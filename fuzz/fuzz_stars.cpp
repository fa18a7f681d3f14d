// The star catalogue reader (the compact file the build makes from KStars' catalogue).
#include "fuzz_support.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/star_catalogue.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = lightcone::fuzz::input_file("stars.lcstars", data, size);
  try {
    lightcone::read_star_catalogue(file);
  } catch (const lightcone::InputError&) {
  }
  return 0;
}

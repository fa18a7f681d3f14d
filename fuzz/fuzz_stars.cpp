// The star catalogue reader (the compact file the build makes from KStars' catalogue), on
// arbitrary bytes: its parser, in memory, as read_star_catalogue calls it once the file's bytes
// are read (the reading itself, a regular file under a size cap, is the other harnesses').
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/star_catalogue.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    lightcone::parse_star_catalogue(std::string_view(reinterpret_cast<const char*>(data), size),
                                    "stars.lcstars");
  } catch (const lightcone::InputError&) {
  }
  return 0;
}

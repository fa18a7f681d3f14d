// The texture and sky image loader (PNG, JPEG, OpenEXR by their contents).
#include "fuzz_support.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = lightcone::fuzz::input_file("image", data, size);
  try {
    lightcone::load_image_file(file);
  } catch (const lightcone::InputError&) {
  }
  return 0;
}

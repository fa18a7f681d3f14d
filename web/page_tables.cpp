// The RGB-to-spectrum coefficient table in the page: the native build embeds it in the program
// (build/generated/rgb2spec_table.cpp, with an assembler directive the WebAssembly assembler
// lacks); the page reads the same file, which scripts/build-web.sh packs with the page's files.
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/color/sigmoid_polynomial.hpp"

const float* lightcone::detail::rgb_to_spectrum_table() {
  static const std::vector<float> table = [] {
    std::vector<float> values(kRgbToSpectrumTableFloats);
    std::FILE* file = std::fopen("/generated/rgb2spec_table.bin", "rb");
    const bool read = file != nullptr && std::fread(values.data(), sizeof(float), values.size(),
                                                    file) == values.size();
    if (file != nullptr) std::fclose(file);
    if (!read) throw std::runtime_error("the page's RGB-to-spectrum table is missing");
    return values;
  }();
  return table.data();
}

#include "lightcone/io/srgb.hpp"

#include <cmath>

namespace lightcone {

double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
}

double srgb_decode(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

const std::array<float, 256>& srgb_8bit_decoded() {
  static const std::array<float, 256> decoded = [] {
    std::array<float, 256> table;
    for (int i = 0; i < 256; ++i) table[i] = static_cast<float>(srgb_decode(i / 255.0));
    return table;
  }();
  return decoded;
}

}  // namespace lightcone

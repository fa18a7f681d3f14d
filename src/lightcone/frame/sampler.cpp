#include "lightcone/frame/sampler.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace lightcone {
namespace {

std::uint64_t mix(std::uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdULL;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ULL;
  x ^= x >> 33;
  return x;
}

double unit_float(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

// A bijection of [0, 2^bits) (mask = 2^bits - 1) keyed by seed: each step (xor with a
// constant, multiplication by an odd number, xor with a right shift of itself) is invertible
// modulo 2^bits.
std::uint32_t scramble_bits(std::uint32_t x, std::uint32_t mask, std::uint32_t seed) {
  // mask is 2^bits - 1; bit_width compiles to one instruction where popcount, without a
  // target that has it, is a library call.
  const int bits = std::bit_width(mask);
  const int shift = bits > 1 ? (bits + 1) / 2 : 1;
  for (std::uint32_t round = 0; round < 3; ++round) {
    const std::uint32_t key = static_cast<std::uint32_t>(mix(seed + 0x9e3779b9u * (round + 1)));
    x = (x ^ key) & mask;
    x = (x * (key | 1u)) & mask;
    x ^= x >> shift;
    x = (x * 0x2c1b3c6du) & mask;
    x ^= (x >> 1) & mask;
  }
  return x & mask;
}

}  // namespace

std::uint32_t shuffled_index(std::uint32_t index, std::uint32_t count, std::uint32_t seed) {
  if (count <= 1) return 0;
  std::uint32_t mask = count - 1;
  mask |= mask >> 1;
  mask |= mask >> 2;
  mask |= mask >> 4;
  mask |= mask >> 8;
  mask |= mask >> 16;
  // Cycle-walking: apply the bijection of the enclosing power of two until the value falls in
  // [0, count); this restricts it to a bijection of [0, count).
  std::uint32_t x = index;
  do x = scramble_bits(x, mask, seed);
  while (x >= count);
  return x;
}

std::array<double, 2> multi_jittered(std::uint32_t index, std::uint32_t count, std::uint32_t seed) {
  if (count <= 1) count = 1;
  const auto columns = static_cast<std::uint32_t>(std::max(1.0, std::floor(std::sqrt(count))));
  const std::uint32_t rows = (count + columns - 1) / columns;
  // Where count is not columns * rows, a pixel's points take a random count of the cells (a
  // different choice for each seed), so that every cell is equally likely and none is missed
  // on average.
  const std::uint32_t s = shuffled_index(index % count, columns * rows, seed);
  const std::uint32_t column = s % columns, row = s / columns;
  // Within its cell, the point's sub-column and sub-row are shuffled so that the count
  // sub-columns (and sub-rows) of the square each hold one point.
  const std::uint32_t sub_x = shuffled_index(row, rows, seed ^ 0x68bc21ebu);
  const std::uint32_t sub_y = shuffled_index(column, columns, seed ^ 0x02e5be93u);
  const double jx = unit_float(mix((static_cast<std::uint64_t>(seed) << 32) ^ s ^ 0xa511e9b3u));
  const double jy = unit_float(mix((static_cast<std::uint64_t>(seed) << 32) ^ s ^ 0x63d83595u));
  return {(column + (sub_x + jx) / rows) / columns, (row + (sub_y + jy) / columns) / rows};
}

PixelSample pixel_sample(int i, int j, int k, int n, std::uint64_t seed, bool with_light) {
  const std::uint64_t pixel = mix(mix(seed) ^ (static_cast<std::uint64_t>(j) << 32) ^
                                  static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)));
  const auto position_seed = static_cast<std::uint32_t>(mix(pixel ^ 0x1));
  const auto light_seed = static_cast<std::uint32_t>(mix(pixel ^ 0x2));
  PixelSample s;
  const auto count = static_cast<std::uint32_t>(n < 1 ? 1 : n);
  const auto index = static_cast<std::uint32_t>(k);
  if (count > 1) {
    const std::array<double, 2> p = multi_jittered(index, count, position_seed);
    s.x = p[0];
    s.y = p[1];
  }
  if (with_light) s.light = multi_jittered(index, count, light_seed);
  return s;
}

}  // namespace lightcone

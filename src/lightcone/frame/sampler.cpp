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

}  // namespace

// A bijection of [0, 2^bits) (mask = 2^bits - 1) keyed by seed: each step (xor with a
// constant, multiplication by an odd number, xor with a right shift of itself) is invertible
// modulo 2^bits.
Shuffle::Shuffle(std::uint32_t count, std::uint32_t seed) : count_(count) {
  if (count <= 1) return;
  mask_ = count - 1;
  mask_ |= mask_ >> 1;
  mask_ |= mask_ >> 2;
  mask_ |= mask_ >> 4;
  mask_ |= mask_ >> 8;
  mask_ |= mask_ >> 16;
  // mask is 2^bits - 1; bit_width compiles to one instruction where popcount, without a
  // target that has it, is a library call.
  const int bits = std::bit_width(mask_);
  shift_ = bits > 1 ? (bits + 1) / 2 : 1;
  for (std::uint32_t round = 0; round < 3; ++round)
    keys_[round] = static_cast<std::uint32_t>(mix(seed + 0x9e3779b9u * (round + 1)));
}

std::uint32_t Shuffle::operator()(std::uint32_t index) const {
  if (count_ <= 1) return 0;
  // Cycle-walking: apply the bijection of the enclosing power of two until the value falls in
  // [0, count); this restricts it to a bijection of [0, count).
  std::uint32_t x = index;
  do {
    for (const std::uint32_t key : keys_) {
      x = (x ^ key) & mask_;
      x = (x * (key | 1u)) & mask_;
      x ^= x >> shift_;
      x = (x * 0x2c1b3c6du) & mask_;
      x ^= (x >> 1) & mask_;
    }
    x &= mask_;
  } while (x >= count_);
  return x;
}

std::uint32_t shuffled_index(std::uint32_t index, std::uint32_t count, std::uint32_t seed) {
  return Shuffle(count, seed)(index);
}

namespace {

// The columns of the near-square grid of count (>= 1) cells.
std::uint32_t grid_columns(std::uint32_t count) {
  return static_cast<std::uint32_t>(std::max(1.0, std::floor(std::sqrt(count))));
}

}  // namespace

MultiJittered::MultiJittered(std::uint32_t count, std::uint32_t seed)
    : count_(std::max(count, 1u)),
      columns_(grid_columns(count_)),
      rows_((count_ + columns_ - 1) / columns_),
      seed_(seed),
      // Where count is not columns * rows, a pixel's points take a random count of the cells (a
      // different choice for each seed), so that every cell is equally likely and none is
      // missed on average.
      cells_(columns_ * rows_, seed),
      // Within its cell, the point's sub-column and sub-row are shuffled so that the count
      // sub-columns (and sub-rows) of the square each hold one point.
      sub_columns_(rows_, seed ^ 0x68bc21ebu),
      sub_rows_(columns_, seed ^ 0x02e5be93u) {}

std::array<double, 2> MultiJittered::operator()(std::uint32_t index) const {
  const std::uint32_t s = cells_(index % count_);
  const std::uint32_t column = s % columns_, row = s / columns_;
  const std::uint32_t sub_x = sub_columns_(row), sub_y = sub_rows_(column);
  const double jx = unit_float(mix((static_cast<std::uint64_t>(seed_) << 32) ^ s ^ 0xa511e9b3u));
  const double jy = unit_float(mix((static_cast<std::uint64_t>(seed_) << 32) ^ s ^ 0x63d83595u));
  return {(column + (sub_x + jx) / rows_) / columns_, (row + (sub_y + jy) / columns_) / rows_};
}

std::array<double, 2> multi_jittered(std::uint32_t index, std::uint32_t count, std::uint32_t seed) {
  return MultiJittered(count, seed)(index);
}

namespace {

std::uint64_t pixel_key(int i, int j, std::uint64_t seed) {
  return mix(mix(seed) ^ (static_cast<std::uint64_t>(j) << 32) ^
             static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)));
}

}  // namespace

void PixelSampler::make_patterns(int i, int j, int n, std::uint64_t seed, bool with_light) {
  const auto count = static_cast<std::uint32_t>(n < 1 ? 1 : n);
  const std::uint64_t pixel = pixel_key(i, j, seed);
  // One sample a pixel is its centre; the point on lights only where there are sphere lights.
  if (count > 1) position_.emplace(count, static_cast<std::uint32_t>(mix(pixel ^ 0x1)));
  if (with_light) light_.emplace(count, static_cast<std::uint32_t>(mix(pixel ^ 0x2)));
}

PixelSample PixelSampler::operator()(int k) const {
  PixelSample s;
  const auto index = static_cast<std::uint32_t>(k);
  if (position_) {
    const std::array<double, 2> p = (*position_)(index);
    s.x = p[0];
    s.y = p[1];
  }
  if (light_) s.light = (*light_)(index);
  return s;
}

PixelSample pixel_sample(int i, int j, int k, int n, std::uint64_t seed, bool with_light) {
  return PixelSampler(i, j, n, seed, with_light)(k);
}

}  // namespace lightcone

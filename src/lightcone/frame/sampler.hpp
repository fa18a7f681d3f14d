// The sample pattern of a pixel: correlated multi-jittered sampling (Kensler, "Correlated
// Multi-Jittered Sampling", 2013) for every two-dimensional quantity a sample needs, each
// scrambled per pixel and per dimension with its own seed, so that no two dimensions (the
// position in the pixel and the point on an area light) are correlated and every edge
// converges. Deterministic: the same pixel, sample and seed give the same numbers on any
// thread.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

namespace lightcone {

// A bijective shuffle of [0, count): the element at `index` under the permutation `seed`.
std::uint32_t shuffled_index(std::uint32_t index, std::uint32_t count, std::uint32_t seed);
// The same with the permutation's keys made once, for many indices.
class Shuffle {
 public:
  Shuffle(std::uint32_t count, std::uint32_t seed);
  std::uint32_t operator()(std::uint32_t index) const;

 private:
  std::uint32_t count_, mask_ = 0;
  int shift_ = 1;
  std::array<std::uint32_t, 3> keys_{};
};

// Point `index` of `count` of a correlated multi-jittered pattern in [0, 1)^2, scrambled by
// `seed`: each of the count columns and rows of the unit square holds one point, and so does
// each cell of a near-square grid (of exactly count cells where count is a product of two
// near-equal numbers; otherwise a seeded choice of count of its cells).
std::array<double, 2> multi_jittered(std::uint32_t index, std::uint32_t count, std::uint32_t seed);
// The same with its shuffles made once, for many indices.
class MultiJittered {
 public:
  MultiJittered(std::uint32_t count, std::uint32_t seed);
  std::array<double, 2> operator()(std::uint32_t index) const;

 private:
  std::uint32_t count_, columns_, rows_, seed_;
  Shuffle cells_, sub_columns_, sub_rows_;
};

struct PixelSample {
  double x = 0.5, y = 0.5;        // offset in the pixel (one sample a pixel: its centre)
  std::array<double, 2> light{};  // point on sphere lights
};

// Sample k of n of pixel (i, j), for the render seed `seed`; its point on sphere lights only
// `with_light` (a scene without sphere lights needs none).
PixelSample pixel_sample(int i, int j, int k, int n, std::uint64_t seed, bool with_light = true);
// The same for every sample of one pixel, its patterns made once.
class PixelSampler {
 public:
  PixelSampler() = default;  // every sample at the centre, no point on lights
  PixelSampler(int i, int j, int n, std::uint64_t seed, bool with_light = true) {
    // One sample a pixel and no point on lights: the centre, with no pattern to make (inline,
    // as that is most renders' every pixel).
    if (n > 1 || with_light) make_patterns(i, j, n, seed, with_light);
  }
  PixelSample operator()(int k) const;

 private:
  void make_patterns(int i, int j, int n, std::uint64_t seed, bool with_light);
  std::optional<MultiJittered> position_, light_;
};

}  // namespace lightcone

// The automatic exposure's light meter: histograms of a picture's log-luminance, of its pixels
// and of its subject's weight, from which the exposure rule (tone_map.hpp's auto_exposure) reads
// its two quantiles. A renderer fills one per thread as it finishes its tiles, so that the
// automatic exposure does not read the picture again.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <memory>

#include "lightcone/portable.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

class ExposureMeter {
 public:
  // A bin is 1/256 of an octave of luminance Y (of linear sRGB, in single precision): a float's
  // exponent and 8 leading mantissa bits, which order as its value does, so that a pixel's bin
  // is a shift of its luminance's bits. A quantile is read as its bin's geometric middle,
  // within half a bin (0.0028 EV) of the pixel's own luminance. Bin 0 holds black and what is
  // no luminance: negative, NaN or infinite.
  static constexpr int kShift = 23 - 8;
  static constexpr std::uint32_t kInfinityBits = 0x7f800000;
  static constexpr std::size_t kBins = kInfinityBits >> kShift;
  // A subject weight (a share of a pixel's samples, in [0, 1]) is counted in units of 2^-16,
  // so that sums are exact integers, the same in any order and on any number of threads.
  static constexpr float kWeightUnit = 65536.0f;

  // The histograms are zeroed pages fresh from the system (calloc), so that only the pages of
  // the bins a picture has are ever touched: zeroing them all was a few hundred page faults a
  // meter, a visible share of a render.
  ExposureMeter();

  // The bin of a pixel of linear sRGB radiance.
  static std::size_t bin_of(const float* rgb) {
    const auto bits =
        bit_cast<std::uint32_t>(0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2]);
    return bits < kInfinityBits ? bits >> kShift : 0;
  }
  // bin_of of each of 4 consecutive pixels (12 floats), computed 4 at a time: the same
  // products and sums in the same order, so the same bins.
  static std::array<std::uint32_t, 4> bins_of_four(const float* rgb) {
    const Bins4 bins = four_bins(rgb);
    std::array<std::uint32_t, 4> out;
    std::memcpy(out.data(), &bins, sizeof bins);
    return out;
  }
  // The luminance that stands for a bin: the geometric middle of its range (0 for bin 0).
  static double value_of(std::size_t bin);

  // The weight units of a subject share, rounded (0 for a negative or NaN share; at most 1).
  static std::uint64_t weight_units(float share) {
    return share > 0 ? static_cast<std::uint32_t>(
                           static_cast<std::int32_t>(std::min(share, 1.0f) * kWeightUnit + 0.5f))
                     : 0;
  }

  // Counts `pixels` consecutive pixels of linear radiance (3 floats each), `subject_shares[i]`
  // of pixel i met the subject (none, where null).
  void add(const float* rgb, std::size_t pixels, const float* subject_shares = nullptr) {
    if (subject_shares)
      count(rgb, pixels, [&](std::size_t i) { return weight_units(subject_shares[i]); });
    else
      count(rgb, pixels, [](std::size_t) { return std::uint64_t{0}; });
  }
  // The same for pixels `subject_samples[i]` of whose `samples` met the subject: a share of
  // float(subject_samples[i]) / samples, as a renderer's subject weights hold it.
  void add_samples(const float* rgb, std::size_t pixels, const int* subject_samples, int samples) {
    // (Most rows meet no subject: they are counted without asking each pixel.)
    int any = 0;
    for (std::size_t i = 0; i < pixels; ++i) any |= subject_samples[i];
    if (any == 0) return add(rgb, pixels);
    count(rgb, pixels, [&](std::size_t i) {
      return subject_samples[i] > 0 ? weight_units(static_cast<float>(subject_samples[i]) / samples)
                                    : std::uint64_t{0};
    });
  }

  // Adds another meter's pixels.
  void add(const ExposureMeter& other);

  std::uint64_t pixels() const;

  // The automatic exposure of the pixels counted (the rule of tone_map.hpp's auto_exposure).
  double ev(ToneMap curve) const;

 private:
  // Four floats and four bins, as vectors of the compiler's (SSE on x86, SIMD128 in the browser).
  using Floats4 = float __attribute__((vector_size(16)));
  using Bins4 = std::uint32_t __attribute__((vector_size(16)));
  // The bins of 4 pixels: their channels gathered from r0 g0 b0 r1 | g1 b1 r2 g2 | b2 r3 g3 b3
  // (shuffles of two vectors each, as x86's shufps takes them), then bin_of's arithmetic on 4
  // luminances at once.
  static Bins4 four_bins(const float* rgb) {
    Floats4 a, b, c;
    std::memcpy(&a, rgb, sizeof a);
    std::memcpy(&b, rgb + 4, sizeof b);
    std::memcpy(&c, rgb + 8, sizeof c);
    const Floats4 red =
        __builtin_shufflevector(a, __builtin_shufflevector(b, c, 2, 2, 5, 5), 0, 3, 4, 6);
    const Floats4 green =
        __builtin_shufflevector(__builtin_shufflevector(a, b, 1, 1, 4, 4),
                                __builtin_shufflevector(b, c, 3, 3, 6, 6), 0, 2, 4, 6);
    const Floats4 blue =
        __builtin_shufflevector(__builtin_shufflevector(a, b, 2, 2, 5, 5), c, 0, 2, 4, 7);
    const Floats4 y = 0.2126f * red + 0.7152f * green + 0.0722f * blue;
    Bins4 bits;
    std::memcpy(&bits, &y, sizeof bits);
    return (bits >> kShift) & static_cast<Bins4>(bits < kInfinityBits);
  }
  // Counts pixels, each in one of kLanes copies of its bin's counter, side by side in a cache
  // line: neighbours of one bin (a flat sky) then increment different counters, and none waits
  // on the store of the one before, as one counter would; nor is there a branch to mispredict
  // on a noisy picture, as counting runs of a bin had. The counters of 16 pixels are found
  // first, four at a time (four_bins), then counted (which ran faster than counting each four as
  // found); a row's last pixels, fewer than 16, one by one. Each pixel marks its bin's group
  // occupied, a store that waits on nothing, so that readers scan only the groups counted in.
  template <class WeightOf>
  void count(const float* rgb, std::size_t pixels, WeightOf weight_of) {
    static_assert(kLanes == 4);  // a pixel's lane is its place among four
    std::uint32_t* const counts = count_.get();
    const auto one = [&](std::size_t i, std::uint32_t counter) {
      ++counts[counter];
      occupied_[counter / kLanes >> kGroupShift] = 1;
      if (const std::uint64_t weight = weight_of(i)) weight_[counter / kLanes] += weight;
    };
    std::size_t i = 0;
    for (; i + 16 <= pixels; i += 16) {
      std::uint32_t at[16];
      for (std::size_t k = 0; k < 16; k += 4) {
        const Bins4 counters = (four_bins(rgb + 3 * (i + k)) << 2) | Bins4{0, 1, 2, 3};
        std::memcpy(at + k, &counters, sizeof counters);
      }
      for (std::size_t k = 0; k < 16; ++k) one(i + k, at[k]);
    }
    for (; i < pixels; ++i)
      one(i, static_cast<std::uint32_t>(bin_of(rgb + 3 * i) * kLanes + i % kLanes));
  }
  // The pixels counted in a bin.
  std::uint64_t count_of(std::size_t bin) const {
    std::uint64_t n = 0;
    for (std::size_t lane = 0; lane < kLanes; ++lane) n += count_[bin * kLanes + lane];
    return n;
  }
  // The first bin at which the histogram summed in order reaches `target` (the last non-empty
  // bin if none does, as a sort's last element would stand in).
  template <class ValueOf>
  std::size_t bin_reaching(ValueOf value_of_bin, double target) const;
  // Calls f(bin) for every bin of the occupied groups, in order, until it returns false.
  template <class F>
  void scan(F f) const {
    for (std::size_t group = 0; group < kGroups; ++group) {
      if (!occupied_[group]) continue;
      for (std::size_t bin = group << kGroupShift; bin < (group + 1) << kGroupShift; ++bin)
        if (!f(bin)) return;
    }
  }

  struct Free {
    void operator()(void* p) const;
  };
  static constexpr std::size_t kLanes = 4;
  std::unique_ptr<std::uint32_t[], Free> count_;  // (a picture has at most 2^27 pixels)
  std::unique_ptr<std::uint64_t[], Free> weight_;
  // Groups of 256 bins (an octave), and whether a pixel has been counted in each.
  static constexpr std::size_t kGroupShift = 8, kGroups = kBins >> kGroupShift;
  std::array<std::uint8_t, kGroups> occupied_{};
};

}  // namespace lightcone

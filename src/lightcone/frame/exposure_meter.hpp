// The automatic exposure's light meter: histograms of a picture's log-luminance, of its pixels
// and of its subject's weight, from which the exposure rule (tone_map.hpp's auto_exposure) reads
// its two quantiles. A renderer fills one per thread as it finishes its tiles, so that the
// automatic exposure does not read the picture again.
#pragma once

#include <algorithm>
#include <cstdint>
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
  // Counts pixels in runs of one bin (a flat sky), in registers, each added to the histograms
  // when it ends: incrementing one counter in memory pixel after pixel waits on the previous
  // increment's store every time. The run in progress is kept between calls.
  template <class WeightOf>
  void count(const float* rgb, std::size_t pixels, WeightOf weight_of) {
    std::size_t bin = run_bin_, first = first_bin_, last = last_bin_;
    std::uint32_t run = run_count_;
    std::uint64_t weight = run_weight_;
    for (std::size_t i = 0; i < pixels; ++i) {
      const std::size_t pixel_bin = bin_of(rgb + 3 * i);
      if (pixel_bin != bin) {
        if (run != 0) {
          count_[bin] += run;
          if (weight != 0) weight_[bin] += weight;
          first = std::min(first, bin);
          last = std::max(last, bin);
        }
        bin = pixel_bin;
        run = 0;
        weight = 0;
      }
      ++run;
      weight += weight_of(i);
    }
    run_bin_ = bin;
    first_bin_ = first;
    last_bin_ = last;
    run_count_ = run;
    run_weight_ = weight;
  }
  void end_run() const {
    if (run_count_ == 0) return;
    count_[run_bin_] += run_count_;
    weight_[run_bin_] += run_weight_;
    first_bin_ = std::min(first_bin_, run_bin_);
    last_bin_ = std::max(last_bin_, run_bin_);
    run_count_ = 0;
    run_weight_ = 0;
  }
  // The first bin at which the histogram summed in order reaches `target` (the last non-empty
  // bin if none does, as a sort's last element would stand in).
  template <class T>
  std::size_t bin_reaching(const T* histogram, double target) const;

  struct Free {
    void operator()(void* p) const;
  };
  // (mutable: the run is added to them by the const readers)
  std::unique_ptr<std::uint32_t[], Free> count_;  // (a picture has at most 2^27 pixels)
  std::unique_ptr<std::uint64_t[], Free> weight_;
  mutable std::size_t first_bin_ = kBins, last_bin_ = 0;  // the bins counted in lie between
  std::size_t run_bin_ = 0;
  mutable std::uint32_t run_count_ = 0;
  mutable std::uint64_t run_weight_ = 0;
};

}  // namespace lightcone

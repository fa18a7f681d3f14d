// The automatic exposure's light meter: histograms of a picture's log-luminance, of its pixels
// and of its subject's weight, from which the exposure rule (tone_map.hpp's auto_exposure) reads
// its two quantiles. A renderer fills one per thread while it writes its pixels, so that the
// automatic exposure does not read the picture again.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "lightcone/portable.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

class ExposureMeter {
 public:
  // A bin is 1/256 of an octave of luminance, from 2^-64 to 2^64 (below: black; above: the top
  // bin); a quantile is read as its bin's geometric middle, within 0.003 EV of the pixel itself.
  static constexpr int kOctaveBits = 8;
  static constexpr int kLowestOctave = -64, kOctaves = 128;
  static constexpr std::size_t kBins = 1 + (std::size_t{kOctaves} << kOctaveBits);
  // A subject weight (a share of a pixel's samples, in [0, 1]) is counted in units of 2^-16,
  // so that sums are exact integers, the same in any order and on any number of threads.
  static constexpr double kWeightUnit = 65536.0;

  ExposureMeter() : count_(kBins, 0), weight_(kBins, 0) {}

  // The luminance (Y of linear sRGB) the rule meters: 0 for a negative or non-finite value.
  static double luminance(const float* rgb) {
    const double y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    return std::isfinite(y) ? std::max(0.0, y) : 0.0;
  }

  // The weight units of a subject share, rounded (0 for a negative or NaN share; at most 1).
  static std::uint64_t weight_units(float share) {
    return share > 0 ? static_cast<std::uint64_t>(std::min(share, 1.0f) * kWeightUnit + 0.5) : 0;
  }

  // Counts a pixel of linear radiance rgb, `subject_share` of whose samples met the subject.
  void add(const float* rgb, float subject_share) {
    const std::size_t bin = bin_of(luminance(rgb));
    ++count_[bin];
    weight_[bin] += weight_units(subject_share);
  }
  void add(const float* rgb) { ++count_[bin_of(luminance(rgb))]; }

  // Adds another meter's pixels.
  void add(const ExposureMeter& other);

  std::uint64_t pixels() const;

  // The automatic exposure of the pixels counted (the rule of tone_map.hpp's auto_exposure).
  double ev(ToneMap curve) const;

  // The bin of a luminance: 0 below 2^-64, then 256 a octave by the bits of the double
  // (exponent and leading mantissa, which order as the value does).
  static std::size_t bin_of(double y) {
    constexpr std::int64_t kFirst = std::int64_t{1023 + kLowestOctave} << kOctaveBits;
    const auto top = static_cast<std::int64_t>(bit_cast<std::uint64_t>(y) >> (52 - kOctaveBits));
    const std::int64_t bin = std::clamp<std::int64_t>(top - kFirst, -1, kBins - 2);
    return static_cast<std::size_t>(bin + 1);
  }

  // The luminance that stands for bin b: the geometric middle of its range (0 for bin 0).
  static double value_of(std::size_t bin);

 private:
  std::vector<std::uint32_t> count_;
  std::vector<std::uint64_t> weight_;
};

}  // namespace lightcone

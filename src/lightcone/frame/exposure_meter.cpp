#include "lightcone/frame/exposure_meter.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>

#include "lightcone/frame/tone_map.hpp"

namespace lightcone {
namespace {

// The automatic exposure's constants (docs/design/colour.md): the subject's upper quartile of
// luminance is shown at kSubjectLevel, unless the brightest 2 % of the picture would then pass
// display_white.
constexpr double kSubjectQuantile = 0.75, kSubjectLevel = 0.5, kHighlightQuantile = 0.98;
// A subject smaller than this share of the picture (a distant speck) does not set the exposure;
// a share, not a count, so that a small metering render finds what the full one does.
constexpr double kMinSubjectShare = 1e-3;

}  // namespace

void ExposureMeter::Free::operator()(void* p) const {
  std::free(p);
}

ExposureMeter::ExposureMeter()
    : count_(static_cast<std::uint32_t*>(std::calloc(kBins * kLanes, sizeof(std::uint32_t)))),
      weight_(static_cast<std::uint64_t*>(std::calloc(kBins, sizeof(std::uint64_t)))) {
  if (!count_ || !weight_) throw std::bad_alloc();
}

template <class ValueOf>
std::size_t ExposureMeter::bin_reaching(ValueOf value_of_bin, double target) const {
  double below = 0;
  std::size_t last = 0;
  scan([&](std::size_t b) {
    const std::uint64_t value = value_of_bin(b);
    if (value == 0) return true;
    below += static_cast<double>(value);
    last = b;
    return below < target;
  });
  return last;
}

void ExposureMeter::add(const ExposureMeter& other) {
  other.scan([&](std::size_t b) {
    for (std::size_t lane = 0; lane < kLanes; ++lane)
      count_[b * kLanes + lane] += other.count_[b * kLanes + lane];
    weight_[b] += other.weight_[b];
    return true;
  });
  for (std::size_t group = 0; group < kGroups; ++group) occupied_[group] |= other.occupied_[group];
}

std::uint64_t ExposureMeter::pixels() const {
  std::uint64_t n = 0;
  scan([&](std::size_t b) {
    n += count_of(b);
    return true;
  });
  return n;
}

double ExposureMeter::value_of(std::size_t bin) {
  if (bin == 0) return 0;
  const auto edge = [](std::size_t b) -> double {
    return b == kBins ? 0x1p128 : bit_cast<float>(static_cast<std::uint32_t>(b << kShift));
  };
  return std::sqrt(edge(bin) * edge(bin + 1));
}

double ExposureMeter::ev(ToneMap curve) const {
  const std::uint64_t n = pixels();
  if (n == 0) return 0;
  // The highlights: the pixel of rank 0.98 (n - 1), as nth_element would find it.
  const auto rank = static_cast<std::uint64_t>(kHighlightQuantile * static_cast<double>(n - 1));
  const auto counted = [this](std::size_t b) { return count_of(b); };
  const auto weighed = [this](std::size_t b) { return weight_[b]; };
  const double highlights = value_of(bin_reaching(counted, static_cast<double>(rank + 1)));
  if (!(highlights > 0)) return 0;
  // The subject's level: a weighted quantile of its luminance (of the whole picture's where no
  // subject is given or seen). A quantile, not a mean, so that the subject's own black parts
  // (a pattern's dark checks shifted out of the visible) and a few bright pixels do not move it.
  std::uint64_t total = 0;
  scan([&](std::size_t b) {
    total += weight_[b];
    return true;
  });
  const bool weighted =
      static_cast<double>(total) >= kMinSubjectShare * static_cast<double>(n) * kWeightUnit;
  const double level =
      weighted ? value_of(bin_reaching(weighed, kSubjectQuantile * static_cast<double>(total)))
               : value_of(bin_reaching(counted, kSubjectQuantile * static_cast<double>(n)));
  const double bright_enough =
      level > 0 ? std::log2(kSubjectLevel / level) : std::numeric_limits<double>::infinity();
  return std::min(bright_enough, std::log2(display_white(curve) / highlights));
}

}  // namespace lightcone

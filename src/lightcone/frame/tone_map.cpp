#include "lightcone/frame/tone_map.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "lightcone/portable.hpp"

namespace lightcone {
namespace {

template <class T>
double luminance(const T* rgb) {
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

float clamp01(double v) {
  return static_cast<float>(std::clamp(std::isnan(v) ? 0.0 : v, 0.0, 1.0));
}

// The automatic exposure's constants (docs/design/colour.md): the subject's upper quartile of
// luminance is shown at kSubjectLevel, unless the brightest 2 % of the picture would then pass
// display_white.
constexpr double kSubjectQuantile = 0.75, kSubjectLevel = 0.5, kHighlightQuantile = 0.98;
// A subject smaller than this share of the picture (a distant speck) does not set the exposure;
// a share, not a count, so that a small metering render finds what the full one does.
constexpr double kMinSubjectShare = 1e-3;

// The automatic exposure's selections. A non-negative double's bits order as its value does, and
// their top bits (exponent, leading mantissa) bin it by log-luminance: a histogram of those bins
// finds the bin that holds a quantile, and further histograms over the lower bits of that bin's
// pixels alone find the pixel itself. The result is the value a sort would give, in O(n).
using Key = std::uint64_t;

struct Item {
  Key key;
  double weight;
};

// Pixels per piece of the parallel passes. Fixed pieces, summed in order, give the same sums
// (and so the same EV) whatever the number of threads.
constexpr std::size_t kPiece = std::size_t{1} << 16;
// The first histogram's bins: a key's top 12 bits (the sign is 0), half an octave wide.
constexpr int kTopShift = 51;
constexpr std::size_t kTopBins = std::size_t{1} << 12;
// Bits resolved by each further histogram.
constexpr int kLevelBits = 12;

double clean_luminance(const float* rgb) {
  const double v = luminance(rgb);
  return std::isfinite(v) ? std::max(0.0, v) : 0.0;
}

Key key_of(double y) {
  return bit_cast<Key>(y);
}

// A histogram's bin, and what is left of a target weight at its start.
struct Reach {
  std::size_t bin;
  double rest;
};

// The first bin of `histogram` at which the weight summed in order reaches `target`; past the
// end (rounding), the last non-empty bin and an unreachable target, so that its largest value
// stands in, as a sort's last element would.
template <class Weight>
Reach bin_reaching(std::span<const Weight> histogram, double target) {
  double below = 0;
  std::size_t last = 0;
  for (std::size_t b = 0; b < histogram.size(); ++b) {
    const auto weight = static_cast<double>(histogram[b]);
    if (weight == 0) continue;
    if (below + weight >= target) return {b, target - below};
    below += weight;
    last = b;
  }
  return {last, std::numeric_limits<double>::infinity()};
}

// Items gathered piece by piece.
using Parts = std::vector<Item>;

// Appends an item, or adds its weight to the last one where that has its key.
void add(Parts& part, Key key, double weight) {
  if (!part.empty() && part.back().key == key)
    part.back().weight += weight;
  else
    part.push_back({key, weight});
}

// The smallest key at which the weights of the items at or below it reach `target` (the largest
// key if none does): each round bins the bits in which the items still differ and keeps the
// bin that reaches the target.
Key select(std::vector<Parts> parts, double target) {
  std::vector<double> histogram;
  for (;;) {
    Key low = std::numeric_limits<Key>::max(), high = 0;
    for (const Parts& part : parts)
      for (const Item& item : part) {
        low = std::min(low, item.key);
        high = std::max(high, item.key);
      }
    if (low == high) return low;
    const int shift = std::max(0, static_cast<int>(std::bit_width(low ^ high)) - kLevelBits);
    const Key base = low >> shift;
    histogram.assign(((high >> shift) - base) + 1, 0.0);
    for (const Parts& part : parts)
      for (const Item& item : part) histogram[(item.key >> shift) - base] += item.weight;
    const Reach reach = bin_reaching(std::span<const double>(histogram), target);
    target = reach.rest;
    Parts kept;
    for (const Parts& part : parts)
      for (const Item& item : part)
        if ((item.key >> shift) - base == reach.bin) kept.push_back(item);
    parts.assign(1, std::move(kept));
  }
}

}  // namespace

double filmic_curve(double y) {
  y = std::max(0.0, y);
  return std::min(1.0, y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14));
}

void filmic_on_luminance(float* rgb) {
  double c[3];
  for (int k = 0; k < 3; ++k) c[k] = std::isnan(rgb[k]) ? 0.0 : std::max(0.0f, rgb[k]);
  const double y = luminance(c), top = std::max({c[0], c[1], c[2]});
  if (!(y > 0) || !std::isfinite(top)) {
    for (int k = 0; k < 3; ++k) rgb[k] = y > 0 ? 1.0f : 0.0f;
    return;
  }
  // The curve on the luminance, unless that would push the largest channel further up the
  // curve than the curve itself takes it: a saturated colour then follows its largest channel,
  // so that it reaches 1 only where a grey as bright would.
  const double scale = std::min(filmic_curve(y) / y, filmic_curve(top) / top);
  for (int k = 0; k < 3; ++k) rgb[k] = clamp01(c[k] * scale);
}

double display_white(ToneMap curve) {
  switch (curve) {
    case ToneMap::kClamp:
      return 0.9;
    case ToneMap::kReinhard:
      return 9;  // 9 / (1 + 9)
    case ToneMap::kFilmic:
      break;
  }
  // filmic_curve(y) = 0.9: 2.51 y^2 + 0.03 y = 0.9 (2.43 y^2 + 0.59 y + 0.14), a quadratic.
  const double a = 2.51 - 0.9 * 2.43, b = 0.03 - 0.9 * 0.59, c = -0.9 * 0.14;
  return (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
}

double auto_exposure(const Image& linear, ToneMap curve, std::span<const float> subject) {
  const std::size_t pixels = linear.rgb.size() / 3;
  if (pixels == 0) return 0;
  const bool with_subject = subject.size() == pixels;
  const float* rgb = linear.rgb.data();
  const std::size_t pieces = (pixels + kPiece - 1) / kPiece;
  const auto piece_end = [&](std::size_t p) { return std::min(pixels, (p + 1) * kPiece); };

  // One pass: each piece's histograms of log-luminance, of pixels and of subject weight, and
  // each pixel's bin, so that the second pass reads 2 bytes a pixel and recomputes only the
  // luminance of the two bins' pixels.
  std::vector<std::uint32_t> counts(pieces * kTopBins, 0);
  const std::unique_ptr<std::uint16_t[]> bins(new std::uint16_t[pixels]);
  std::vector<double> weights(with_subject ? pieces * kTopBins : 0, 0.0);
  parallel_for(std::size_t{0}, pieces, [&](std::size_t p) {
    std::uint32_t* count = &counts[p * kTopBins];
    double* weight = with_subject ? &weights[p * kTopBins] : nullptr;
    for (std::size_t i = p * kPiece; i < piece_end(p); ++i) {
      const auto bin =
          static_cast<std::uint16_t>(key_of(clean_luminance(&rgb[3 * i])) >> kTopShift);
      bins[i] = bin;
      ++count[bin];
      if (with_subject && subject[i] > 0) weight[bin] += subject[i];
    }
  });
  std::vector<std::uint64_t> count(kTopBins, 0);
  std::vector<double> weight(kTopBins, 0.0);
  for (std::size_t p = 0; p < pieces; ++p) {
    for (std::size_t b = 0; b < kTopBins; ++b) count[b] += counts[p * kTopBins + b];
    if (with_subject)
      for (std::size_t b = 0; b < kTopBins; ++b) weight[b] += weights[p * kTopBins + b];
  }
  // Summed bin by bin, as bin_reaching sums, so that the target it is given is reached.
  double total = 0;
  for (const double w : weight) total += w;

  // The highlights: the pixel of rank 0.98 (pixels - 1), as nth_element would find it.
  const auto rank = static_cast<std::size_t>(kHighlightQuantile * static_cast<double>(pixels - 1));
  const Reach highlight =
      bin_reaching(std::span<const std::uint64_t>(count), static_cast<double>(rank) + 1);
  // The subject's level: a weighted quantile of its luminance (of the whole picture's where no
  // subject is given or seen). A quantile, not a mean, so that the subject's own black parts
  // (a pattern's dark checks shifted out of the visible) and a few bright pixels do not move it.
  const bool weighted = with_subject && total >= kMinSubjectShare * static_cast<double>(pixels);
  const double subject_target = kSubjectQuantile * (weighted ? total : static_cast<double>(pixels));
  const Reach level_at = weighted
                             ? bin_reaching(std::span<const double>(weight), subject_target)
                             : bin_reaching(std::span<const std::uint64_t>(count), subject_target);

  // A second pass gathers the two bins' pixels, piece by piece. A run of equal values (a flat
  // sky) is one item, so that a bin of a few values stays short.
  std::vector<Parts> highlight_items(pieces), subject_items(pieces);
  const std::size_t highlight_bin = highlight.bin, subject_bin = level_at.bin;
  parallel_for(std::size_t{0}, pieces, [&](std::size_t p) {
    Parts& highlight_part = highlight_items[p];
    Parts& subject_part = subject_items[p];
    for (std::size_t i = p * kPiece; i < piece_end(p); ++i) {
      const std::size_t bin = bins[i];
      if (bin != highlight_bin && bin != subject_bin) [[likely]]
        continue;
      const Key key = key_of(clean_luminance(&rgb[3 * i]));
      if (bin == highlight_bin) add(highlight_part, key, 1.0);
      if (bin == subject_bin && !weighted) add(subject_part, key, 1.0);
      if (bin == subject_bin && weighted && subject[i] > 0) add(subject_part, key, subject[i]);
    }
  });
  const double highlights = bit_cast<double>(select(std::move(highlight_items), highlight.rest));
  if (!(highlights > 0)) return 0;
  const double level = bit_cast<double>(select(std::move(subject_items), level_at.rest));
  const double bright_enough =
      level > 0 ? std::log2(kSubjectLevel / level) : std::numeric_limits<double>::infinity();
  return std::min(bright_enough, std::log2(display_white(curve) / highlights));
}

double apply_exposure(Image& linear, const RenderSettings& settings,
                      std::span<const float> subject) {
  const double ev =
      settings.auto_exposure ? auto_exposure(linear, settings.tonemap, subject) : settings.exposure;
  const auto scale = static_cast<float>(std::exp2(ev));
  // In parallel: on one thread, a 1080p frame's scaling is a few ms, a visible share of a render.
  parallel_for_pieces(std::size_t{0}, linear.rgb.size(), std::size_t{1} << 16,
                      [&](std::size_t begin, std::size_t end) {
                        for (std::size_t i = begin; i < end; ++i) linear.rgb[i] *= scale;
                      });
  return ev;
}

namespace {

// out[i] = the curve on in[i], pixel by pixel (in may be out): in parallel, off the critical
// path of an animation's next frame and of a render's last steps.
void tone_map_pixels(const float* in, float* out, std::size_t pixels, ToneMap curve) {
  parallel_for_pieces(std::size_t{0}, pixels, std::size_t{4096},
                      [&](std::size_t begin, std::size_t end) {
                        for (std::size_t p = 3 * begin; p < 3 * end; p += 3) {
                          float* c = &out[p];
                          for (int k = 0; k < 3; ++k) c[k] = in[p + k];
                          switch (curve) {
                            case ToneMap::kClamp:
                              for (int k = 0; k < 3; ++k) c[k] = clamp01(c[k]);
                              break;
                            case ToneMap::kReinhard: {
                              const double scale = 1.0 / (1.0 + std::max(0.0, luminance(c)));
                              for (int k = 0; k < 3; ++k) c[k] = clamp01(c[k] * scale);
                              break;
                            }
                            case ToneMap::kFilmic:
                              filmic_on_luminance(c);
                              break;
                          }
                        }
                      });
}

}  // namespace

Image tone_map(const Image& linear, ToneMap curve) {
  Image out;
  out.width = linear.width;
  out.height = linear.height;
  out.rgb.resize(linear.rgb.size());
  tone_map_pixels(linear.rgb.data(), out.rgb.data(), out.rgb.size() / 3, curve);
  return out;
}

Image tone_map(Image&& linear, ToneMap curve) {
  Image out;
  out.width = linear.width;
  out.height = linear.height;
  out.rgb = std::move(linear.rgb);
  tone_map_pixels(out.rgb.data(), out.rgb.data(), out.rgb.size() / 3, curve);
  return out;
}

}  // namespace lightcone

#include "lightcone/frame/tone_map.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <span>
#include <vector>

#include "lightcone/frame/exposure_meter.hpp"
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
  const bool with_subject = subject.size() == pixels;
  const float* rgb = linear.rgb.data();
  // One meter a thread; their counts are integers, so the sum is the same however the pixels
  // were shared out.
  PerThread<ExposureMeter> meters;
  parallel_for_pieces(
      std::size_t{0}, pixels, std::size_t{1} << 15, [&](std::size_t begin, std::size_t end) {
        meters.local().add(&rgb[3 * begin], end - begin, with_subject ? &subject[begin] : nullptr);
      });
  return meters.combined().ev(curve);
}

float exposure_scale(double ev) {
  return static_cast<float>(std::exp2(ev));
}

std::size_t expose(Image& linear, double ev) {
  const float scale = exposure_scale(ev);
  std::atomic<std::size_t> non_finite{0};
  // In parallel: on one thread, a 1080p frame's scaling is a few ms, a visible share of a render.
  parallel_for_pieces(std::size_t{0}, linear.rgb.size(), std::size_t{1} << 16,
                      [&](std::size_t begin, std::size_t end) {
                        std::size_t found = 0;
                        float* v = linear.rgb.data();
                        if (scale == 1.0f)
                          for (std::size_t i = begin; i < end; ++i) found += !std::isfinite(v[i]);
                        else
                          for (std::size_t i = begin; i < end; ++i)
                            found += !std::isfinite(v[i] *= scale);
                        if (found) non_finite += found;
                      });
  return non_finite;
}

AppliedExposure apply_exposure(Image& linear, const RenderSettings& settings,
                               std::span<const float> subject) {
  const double ev =
      settings.auto_exposure ? auto_exposure(linear, settings.tonemap, subject) : settings.exposure;
  return {ev, expose(linear, ev)};
}

namespace {

// out[i] = the curve on in[i] times `scale`, pixel by pixel (in may be out), and how many of the
// scaled values are not finite: in parallel, off the critical path of an animation's next frame
// and of a render's last steps.
std::size_t tone_map_pixels(const float* in, float* out, std::size_t pixels, float scale,
                            ToneMap curve) {
  std::atomic<std::size_t> non_finite{0};
  parallel_for_pieces(std::size_t{0}, pixels, std::size_t{4096},
                      [&](std::size_t begin, std::size_t end) {
                        std::size_t found = 0;
                        for (std::size_t p = 3 * begin; p < 3 * end; p += 3) {
                          float* c = &out[p];
                          for (int k = 0; k < 3; ++k)
                            found += !std::isfinite(c[k] = in[p + k] * scale);
                          switch (curve) {
                            case ToneMap::kClamp:
                              for (int k = 0; k < 3; ++k) c[k] = clamp01(c[k]);
                              break;
                            case ToneMap::kReinhard: {
                              const double s = 1.0 / (1.0 + std::max(0.0, luminance(c)));
                              for (int k = 0; k < 3; ++k) c[k] = clamp01(c[k] * s);
                              break;
                            }
                            case ToneMap::kFilmic:
                              filmic_on_luminance(c);
                              break;
                          }
                        }
                        if (found) non_finite += found;
                      });
  return non_finite;
}

}  // namespace

Image tone_map(const Image& linear, ToneMap curve) {
  Image out;
  out.width = linear.width;
  out.height = linear.height;
  out.rgb.resize(linear.rgb.size());
  tone_map_pixels(linear.rgb.data(), out.rgb.data(), out.rgb.size() / 3, 1.0f, curve);
  return out;
}

Image tone_map(Image&& linear, ToneMap curve) {
  Image out;
  out.width = linear.width;
  out.height = linear.height;
  out.rgb = std::move(linear.rgb);
  tone_map_pixels(out.rgb.data(), out.rgb.data(), out.rgb.size() / 3, 1.0f, curve);
  return out;
}

Image expose_and_tone_map(Image&& linear, double ev, ToneMap curve, std::size_t& non_finite) {
  Image out;
  out.width = linear.width;
  out.height = linear.height;
  out.rgb = std::move(linear.rgb);
  non_finite = tone_map_pixels(out.rgb.data(), out.rgb.data(), out.rgb.size() / 3,
                               exposure_scale(ev), curve);
  return out;
}

}  // namespace lightcone

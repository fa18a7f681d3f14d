#include "lightcone/frame/tone_map.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

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

double auto_exposure(const Image& linear) {
  const std::size_t pixels = linear.rgb.size() / 3;
  if (pixels == 0) return 0;
  std::vector<double> y(pixels);
  for (std::size_t i = 0; i < pixels; ++i) y[i] = luminance(&linear.rgb[3 * i]);
  const auto nth = y.begin() + static_cast<std::ptrdiff_t>(0.95 * (pixels - 1));
  std::nth_element(y.begin(), nth, y.end());
  if (!(*nth > 0) || !std::isfinite(*nth)) return 0;
  return std::log2(0.8 / *nth);
}

double apply_exposure(Image& linear, const RenderSettings& settings) {
  const double ev = settings.auto_exposure ? auto_exposure(linear) : settings.exposure;
  const auto scale = static_cast<float>(std::exp2(ev));
  for (float& v : linear.rgb) v *= scale;
  return ev;
}

Image tone_map(const Image& linear, ToneMap curve) {
  Image out = linear;
  // Each pixel on its own: in parallel, off the critical path of an animation's next frame.
  const std::size_t pixels = out.rgb.size() / 3;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pixels, 4096), [&](const auto& range) {
    for (std::size_t p = 3 * range.begin(); p < 3 * range.end(); p += 3) {
      float* c = &out.rgb[p];
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
  return out;
}

}  // namespace lightcone

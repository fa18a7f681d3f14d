#include "lightcone/frame/false_colour.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <vector>

#include "lightcone/frame/image_text.hpp"

namespace lightcone {
namespace {

LinearRgb from_oklab(double l, double a, double b) {
  const double l_ = l + 0.3963377774 * a + 0.2158037573 * b;
  const double m_ = l - 0.1055613458 * a - 0.0638541728 * b;
  const double s_ = l - 0.0894841775 * a - 1.2914855480 * b;
  const double L = l_ * l_ * l_, M = m_ * m_ * m_, S = s_ * s_ * s_;
  return {4.0767416621 * L - 3.3077115913 * M + 0.2309699292 * S,
          -1.2684380046 * L + 2.6097574011 * M - 0.3413193965 * S,
          -0.0041960863 * L - 0.7034186147 * M + 1.7076147010 * S};
}

bool in_gamut(const LinearRgb& c) {
  return c.r >= 0 && c.r <= 1 && c.g >= 0 && c.g <= 1 && c.b >= 0 && c.b <= 1;
}

constexpr float kGrey = 0.18f;
constexpr double kHatch = 0.45;      // the sky's dark stripes
constexpr double kLegendDim = 0.12;  // the map beneath the legend

void put(Image& image, int x, int y, const LinearRgb& c) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  float* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
  p[0] = static_cast<float>(c.r);
  p[1] = static_cast<float>(c.g);
  p[2] = static_cast<float>(c.b);
}

std::string number(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.4g", v);
  return s;
}

}  // namespace

LinearRgb colour_map(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const double l = 0.30 + 0.62 * t;
  const double hue = (265.0 - 170.0 * t) * std::numbers::pi / 180;
  // The largest chroma up to 0.12 that sRGB shows at this lightness and hue.
  double lo = 0, hi = 0.12;
  if (in_gamut(from_oklab(l, hi * std::cos(hue), hi * std::sin(hue)))) lo = hi;
  for (int k = 0; k < 30 && hi - lo > 1e-6; ++k) {
    const double c = 0.5 * (lo + hi);
    (in_gamut(from_oklab(l, c * std::cos(hue), c * std::sin(hue))) ? lo : hi) = c;
  }
  const LinearRgb c = from_oklab(l, lo * std::cos(hue), lo * std::sin(hue));
  return {std::clamp(c.r, 0.0, 1.0), std::clamp(c.g, 0.0, 1.0), std::clamp(c.b, 0.0, 1.0)};
}

Image false_colour(const NamedChannel& channel, int width, int height, const std::string& label,
                   std::span<const float> sky) {
  double lo = INFINITY, hi = -INFINITY;
  for (const float v : channel.values)
    if (std::isfinite(v))
      lo = std::min(lo, static_cast<double>(v)), hi = std::max(hi, static_cast<double>(v));
  if (!(lo <= hi)) lo = hi = 0;
  const double span = hi > lo ? hi - lo : 1.0;

  Image image;
  image.width = width;
  image.height = height;
  image.rgb.assign(3 * static_cast<std::size_t>(width) * height, 0.0f);
  const int band_top = height - kLegendHeight;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * width + x;
      const float v = channel.values[p];
      LinearRgb c = std::isfinite(v) ? colour_map((v - lo) / span) : LinearRgb{kGrey, kGrey, kGrey};
      // The sky hatched (dark diagonal stripes, 3 of every 8 pixels), so that a surface of the
      // sky's value does not merge with it.
      if (!sky.empty() && sky[p] > 0.5f && (x + y) % 8 < 3)
        c = {c.r * kHatch, c.g * kHatch, c.b * kHatch};
      if (y >= band_top) c = {c.r * kLegendDim, c.g * kLegendDim, c.b * kLegendDim};
      put(image, x, y, c);
    }
  // The quantity beside the bar, on its left; the bar; its ticks with their values beneath.
  const int label_width = text_width(label);
  const int bar_top = band_top + 8, bar_bottom = band_top + 18;
  draw_text(image, 6, bar_top - 1, label);
  std::string lowest = number(lo), highest = number(hi);
  const int x0 = label_width + 12 + text_width(lowest) / 2;
  const int x1 = std::max(x0 + 1, width - 6 - text_width(highest) / 2);
  for (int x = x0; x <= x1; ++x)
    for (int y = bar_top; y < bar_bottom; ++y)
      put(image, x, y, colour_map(static_cast<double>(x - x0) / std::max(1, x1 - x0)));
  // Five values where they fit apart, else the two ends.
  int widest = 0;
  for (int k = 0; k <= 4; ++k)
    widest = std::max(widest, text_width(number(lo + (hi - lo) * k / 4)));
  const int ticks = (x1 - x0) / 4 >= widest + 8 ? 4 : 1;
  for (int k = 0; k <= ticks; ++k) {
    const int x = x0 + (x1 - x0) * k / ticks;
    for (int y = bar_bottom; y < bar_bottom + 4; ++y) put(image, x, y, {1, 1, 1});
    const std::string s = number(lo + (hi - lo) * k / ticks);
    draw_text(image, std::clamp(x - text_width(s) / 2, 0, std::max(0, width - text_width(s))),
              bar_bottom + 6, s);
  }
  return image;
}

}  // namespace lightcone

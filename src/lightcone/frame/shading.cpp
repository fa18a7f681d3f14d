#include "lightcone/frame/shading.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lightcone {
namespace {

Rgb lerp(const Rgb& a, const Rgb& b, double t) {
  const auto f = static_cast<float>(t);
  return {a.r + (b.r - a.r) * f, a.g + (b.g - a.g) * f, a.b + (b.b - a.b) * f};
}

int wrap_index(int i, int n) {
  return ((i % n) + n) % n;
}

double degrees(double radians) {
  return radians * 180.0 / std::numbers::pi;
}

// Angular distance, in degrees, from an angle to the nearest multiple of `spacing`.
double distance_to_grid(double angle, double spacing) {
  const double r = std::fmod(std::abs(angle), spacing);
  return std::min(r, spacing - r);
}

}  // namespace

Rgb sample_bilinear(const Image& image, double u, double v, bool wrap_v) {
  const double x = u * image.width - 0.5, y = v * image.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  auto row = [&](int j) {
    return wrap_v ? wrap_index(j, image.height) : std::clamp(j, 0, image.height - 1);
  };
  auto at = [&](int i, int j) { return image.texel(wrap_index(i, image.width), row(j)); };
  const Rgb top = lerp(at(x0, y0), at(x0 + 1, y0), x - fx);
  const Rgb bottom = lerp(at(x0, y0 + 1), at(x0 + 1, y0 + 1), x - fx);
  return lerp(top, bottom, y - fy);
}

int checker_index(const Checker& c, const Vec3& p) {
  // The parity of each cell index in floating point: no integer cast can overflow, however far
  // out the point (beyond 2^53 every cell index is even).
  const auto parity = [&](double x) {
    const double cell = std::floor(x / c.size);
    return std::isfinite(cell) ? std::abs(std::fmod(cell, 2.0)) : 0.0;
  };
  return static_cast<int>(std::fmod(parity(p.x) + parity(p.y) + parity(p.z), 2.0));
}

namespace {
// The fraction of the current period elapsed at proper time tau, in [0, 1).
double period_phase(double proper_time, double period) {
  const double cycles = proper_time / period;
  return std::clamp(cycles - std::floor(cycles), 0.0, std::nextafter(1.0, 0.0));
}
}  // namespace

int pattern_colours(const Material& m, Rgb colours[2]) {
  const auto two = [&](const Rgb(&c)[2]) {
    colours[0] = c[0];
    colours[1] = c[1];
    return 2;
  };
  if (const auto* c = std::get_if<SolidColor>(&m.pattern)) return colours[0] = c->color, 1;
  if (const auto* ch = std::get_if<Checker>(&m.pattern)) return two(ch->colors);
  if (const auto* b = std::get_if<Blink>(&m.pattern)) return two(b->colors);
  if (const auto* c = std::get_if<Clock>(&m.pattern)) return two(c->colors);
  return 0;
}

int blink_index(const Blink& b, double proper_time) {
  return period_phase(proper_time, b.period) < b.duty ? 1 : 0;
}

int clock_index(const Clock& c, const std::array<double, 2>& uv, double proper_time) {
  // The dial in the texture square, y up: a rim from 0.45 to 0.5 and a hand of length 0.4
  // and half-width 0.025, turned clockwise from 12 o'clock.
  const double x = uv[0] - 0.5, y = 0.5 - uv[1];
  const double r = std::hypot(x, y);
  if (r > 0.5) return 0;
  if (r >= 0.45) return 1;
  const double angle = 2 * std::numbers::pi * period_phase(proper_time, c.period);
  const double hx = std::sin(angle), hy = std::cos(angle);
  const double along = x * hx + y * hy, across = std::abs(x * hy - y * hx);
  return (along >= 0 && along <= 0.4 && across <= 0.025) || r <= 0.04 ? 1 : 0;
}

Rgb texture_colour(const Texture& t, const Hit& hit) {
  return sample_bilinear(*t.image, hit.uv[0], hit.uv[1], true);
}

Rgb sky_image_colour(const SkyImage& s, const Vec3& d) {
  const double u = 0.5 + std::atan2(d.x, -d.z) / (2 * std::numbers::pi);
  const double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / std::numbers::pi;
  return sample_bilinear(*s.image, u, v, false);
}

bool on_grid_line(const SkyGrid& g, const Vec3& d) {
  const double latitude = degrees(std::asin(std::clamp(d.y, -1.0, 1.0)));
  const double longitude = degrees(std::atan2(d.x, -d.z));
  const double half_width = g.line_width_degrees * 0.5;
  // Meridians are measured as arc length along the parallel, so lines keep their width.
  const double along_parallel =
      distance_to_grid(longitude, g.spacing_degrees) * std::cos(latitude * std::numbers::pi / 180);
  return distance_to_grid(latitude, g.spacing_degrees) <= half_width ||
         along_parallel <= half_width;
}

}  // namespace lightcone

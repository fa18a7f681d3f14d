#include "lightcone/render/shading.hpp"

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

Rgb surface_radiance(const Object& object, const Hit& hit) {
  struct Visitor {
    const Hit& hit;
    Rgb operator()(const SolidColor& c) const { return c.color; }
    Rgb operator()(const Checker& c) const {
      const Vec3& p = hit.shape_point;
      const long long sum = static_cast<long long>(std::floor(p.x / c.size)) +
                            static_cast<long long>(std::floor(p.y / c.size)) +
                            static_cast<long long>(std::floor(p.z / c.size));
      return c.colors[((sum % 2) + 2) % 2];
    }
    Rgb operator()(const Texture& t) const {
      return sample_bilinear(*t.image, hit.uv[0], hit.uv[1], true);
    }
  };
  return std::visit(Visitor{hit}, object.material.pattern);
}

Rgb sky_radiance(const Sky& sky, const Vec3& d) {
  struct Visitor {
    const Vec3& d;
    Rgb operator()(const SolidColor& c) const { return c.color; }
    Rgb operator()(const SkyImage& s) const {
      const double u = 0.5 + std::atan2(d.x, -d.z) / (2 * std::numbers::pi);
      const double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / std::numbers::pi;
      return sample_bilinear(*s.image, u, v, false);
    }
    Rgb operator()(const SkyGrid& g) const {
      const double latitude = degrees(std::asin(std::clamp(d.y, -1.0, 1.0)));
      const double longitude = degrees(std::atan2(d.x, -d.z));
      const double half_width = g.line_width_degrees * 0.5;
      // Meridians are measured as arc length along the parallel, so lines keep their width.
      const double along_parallel = distance_to_grid(longitude, g.spacing_degrees) *
                                    std::cos(latitude * std::numbers::pi / 180);
      const bool on_line = distance_to_grid(latitude, g.spacing_degrees) <= half_width ||
                           along_parallel <= half_width;
      return on_line ? g.line_color : g.background;
    }
  };
  return std::visit(Visitor{d}, sky.pattern);
}

}  // namespace lightcone

#include "lightcone/frame/star_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lightcone/color/spectrum.hpp"
#include "lightcone/frame/hole_view.hpp"
#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/pixel_lattice.hpp"
#include "lightcone/frame/received_colour.hpp"
#include "lightcone/physics/aberration.hpp"
#include "lightcone/physics/stars.hpp"
#include "lightcone/portable.hpp"

namespace lightcone {
namespace {

LinearRgb scaled(const LinearRgb& c, double k) {
  return {c.r * k, c.g * k, c.b * k};
}

double filter_1d(double t) {
  const double a = std::abs(t);
  if (a <= 0.5) return 0.75 - a * a;
  if (a < 1.5) return 0.5 * (1.5 - a) * (1.5 - a);
  return 0;
}

// One axis of the filter for a point at x: the pixel m whose centre m + 1/2 is nearest and the
// weights of pixels m - 1, m, m + 1 (the only ones within 1.5 of it).
void filter_axis(double x, int& first, std::array<double, 3>& w) {
  const double m = std::floor(x);
  first = static_cast<int>(m) - 1;
  for (int k = 0; k < 3; ++k) w[k] = filter_1d(m - 0.5 + k - x);
}

// The image-plane coordinates (at unit distance along forward) of image point x or y.
double plane_a(const CameraBasis& b, double x) {
  return (2.0 * x / b.width - 1.0) * b.tan_half_fov * b.aspect;
}
double plane_c(const CameraBasis& b, double y) {
  return (1.0 - 2.0 * y / b.height) * b.tan_half_fov;
}
// The solid angle of the rectangle [0, a] x [0, c] of the unit image plane, signed.
double corner_solid_angle(double a, double c) {
  return std::atan(a * c / std::sqrt(1 + a * a + c * c));
}

// Runs one(k, images) for every star k < count, blocks of stars in parallel, and returns the
// images in the stars' order (so that a picture adds them up the same way every run).
template <class One>
std::vector<StarImage> over_stars(std::size_t count, const One& one) {
  constexpr std::size_t kBlock = 512;
  std::vector<std::vector<StarImage>> parts((count + kBlock - 1) / kBlock);
  parallel_for(std::size_t{0}, parts.size(), [&](std::size_t b) {
    for (std::size_t k = b * kBlock; k < std::min(count, (b + 1) * kBlock); ++k) one(k, parts[b]);
  });
  std::size_t total = 0;
  for (const auto& part : parts) total += part.size();
  std::vector<StarImage> out;
  out.reserve(total);
  for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

}  // namespace

StarPhotometry::StarPhotometry(const SkyStars& sky_stars, const RenderSettings& settings,
                               double log_shift_lo, double log_shift_hi)
    : catalogue_(sky_stars.stars.get()),
      exposure_(sky_stars.exposure),
      settings_(settings),
      log_shift_lo_(log_shift_lo),
      log_shift_hi_(log_shift_hi) {
  if (!sky_stars.stars || sky_stars.stars->empty()) return;
  const std::vector<CatalogueStar>& stars = *sky_stars.stars;
  double hottest = 0, coolest = std::numeric_limits<double>::infinity();
  for (const CatalogueStar& s : stars) {
    const double t = star_temperature(s.colour_index);
    hottest = std::max(hottest, t);
    coolest = std::min(coolest, t);
  }
  // s = g tau over every star's tau (<= 1) and every shift, D = 1 included.
  const DopplerGrid grid = DopplerGrid::covering(
      std::log(coolest / hottest) + std::min(log_shift_lo, 0.0), std::max(log_shift_hi, 0.0));
  hottest_ = DopplerXyzTable::of(BlackbodySpectrum{hottest, 1}, grid);
  const double unit = kMagnitudeZeroFlux * std::exp2(sky_stars.exposure);
  stars_.reserve(stars.size());
  for (const CatalogueStar& s : stars) {
    Star star;
    star.tau = star_temperature(s.colour_index) / hottest;
    const Xyz rest = hottest_(grid_position(grid, star.tau));
    star.scale = unit * magnitude_flux_ratio(s.magnitude) / rest.y;
    star.rest_rgb =
        linear_srgb_from_xyz({rest.x * star.scale, rest.y * star.scale, rest.z * star.scale});
    stars_.push_back(star);
  }
}

LinearRgb StarPhotometry::received(std::size_t k, double g, double mu) const {
  const Star& star = stars_[k];
  if (settings_.doppler != DopplerModel::kSpectral) {
    PointEmission at_rest;
    at_rest.rest_rgb = star.rest_rgb;
    return scaled(received_colour(at_rest, g, settings_), mu);
  }
  const Xyz seen = hottest_(grid_position(hottest_.grid(), g * star.tau));
  const double k_seen = star.scale * spectral_searchlight(g, settings_.searchlight) * mu;
  return linear_srgb_from_xyz({seen.x * k_seen, seen.y * k_seen, seen.z * k_seen});
}

namespace {

// The range of ln g with which the scene's sky can be seen, in every direction.
LogShiftRange star_log_shift_range(const ResolvedScene& scene) {
  if (scene.hole) return sky_log_shift_range(*scene.hole);
  // D of the sky seen from F lies within e^(+-rapidity).
  const double rapidity = std::atanh(std::min(length(scene.sky_velocity), 1.0));
  return {-rapidity, rapidity};
}

}  // namespace

bool StarPhotometry::serves(const ResolvedScene& scene) const {
  const Scene& s = *scene.scene;
  const SkyStars none;
  const SkyStars& stars = s.sky.stars ? *s.sky.stars : none;
  const LogShiftRange range = star_log_shift_range(scene);
  return catalogue_ == stars.stars.get() && exposure_ == stars.exposure &&
         settings_.doppler == s.render.doppler && settings_.searchlight == s.render.searchlight &&
         settings_.hue_loop == s.render.hue_loop && log_shift_lo_ <= range.lo &&
         range.hi <= log_shift_hi_;
}

StarPhotometry star_photometry(const ResolvedScene& scene, double margin) {
  const Scene& s = *scene.scene;
  if (!s.sky.stars) return StarPhotometry(SkyStars{}, s.render, 0, 0);
  const LogShiftRange range = star_log_shift_range(scene);
  return StarPhotometry(*s.sky.stars, s.render, range.lo - margin, range.hi + margin);
}

std::vector<StarImage> star_images(const ResolvedScene& scene, const StarPhotometry& photometry,
                                   const FarImageTable* lens) {
  std::vector<StarImage> out;
  const Scene& s = *scene.scene;
  if (!s.sky.stars || !s.sky.stars->stars || photometry.size() == 0) return out;
  const std::vector<CatalogueStar>& stars = *s.sky.stars->stars;
  const CameraBasis& camera = scene.camera;
  // The image point of look direction u, where the filter (1.5 pixels from its point) reaches
  // into the picture.
  const auto seen = [&](const Vec3& u) -> std::optional<ImagePoint> {
    const ImagePoint p = project_direction(camera, u);
    if (!p.in_front ||
        !(p.x > -1.5 && p.x < camera.width + 1.5 && p.y > -1.5 && p.y < camera.height + 1.5))
      return std::nullopt;
    return p;
  };
  if (!scene.hole) {
    const SkyToLook to_look = scene.sky_to_look();
    return over_stars(stars.size(), [&](std::size_t k, std::vector<StarImage>& images) {
      const Vec3 u = to_look(stars[k].direction);
      const auto p = seen(u);
      if (!p) return;
      const double d = scene.doppler(u, scene.sky_velocity);
      images.push_back({p->x, p->y, photometry.received(k, d, 1 / (d * d))});
    });
  }
  const HoleView& hole = *scene.hole;
  // The camera's velocity against the static observer at its event; a falling camera's frame is
  // the static one boosted radially by u^r / E (physics/radial_observer.hpp), and inside the
  // horizon there is no static observer to carry the lens table's angles from.
  Vec3 camera_velocity = s.camera.world_line.velocity;
  if (hole.falling) {
    if (!(hole.camera_radius > 2 * hole.mass)) return out;
    camera_velocity = hole.outward * (hole.falling->radial_velocity / hole.falling->energy);
  }
  std::optional<FarImageTable> own;
  if (!lens || !star_lens_serves(*lens, hole)) lens = &own.emplace(star_lens_table(hole));
  const Vec3& e1 = hole.outward;
  return over_stars(stars.size(), [&](std::size_t k, std::vector<StarImage>& images) {
    // As locate's ray toward a direction far away: the look direction sweeps from e1 toward
    // the star (even orders) or round the other side, at the table's angle.
    const Vec3 toward =
        aberrate_out_of_moving_frame(s.sky.rotation * stars[k].direction, s.sky.velocity);
    const double psi = std::acos(std::clamp(dot(e1, toward), -1.0, 1.0));
    const Vec3 side = toward - e1 * dot(e1, toward);
    const Vec3 t = length(side) > 0 ? normalize(side) : any_perpendicular(e1);
    for (int order = 0; order < kStarImageOrders; ++order) {
      const auto image = lens->at(psi, order);
      if (!image) continue;
      const Vec3 turn = order % 2 == 0 ? t : t * -1.0;
      const Vec3 u = aberrate_into_moving_frame(
          e1 * std::cos(image->alpha) + turn * std::sin(image->alpha), camera_velocity);
      const auto p = seen(u);
      if (!p) continue;
      const HoleSkyImage i = hole_sky_image_seen(hole, toward, u, image->solid_angle_ratio);
      images.push_back({p->x, p->y, photometry.received(k, i.shift, i.magnification)});
    }
  });
}

FarImageTable star_lens_table(const HoleView& hole) {
  return FarImageTable(hole.mass, hole.camera_radius, kStarImageOrders);
}

bool star_lens_serves(const FarImageTable& lens, const HoleView& hole) {
  return lens.mass() == hole.mass && lens.radius() == hole.camera_radius;
}

StarFootprint star_footprint(double x, double y) {
  StarFootprint f;
  filter_axis(x, f.i0, f.wx);
  filter_axis(y, f.j0, f.wy);
  return f;
}

double star_filter_weight(double dx, double dy) {
  return filter_1d(dx) * filter_1d(dy);
}

double pixel_solid_angle(const CameraBasis& camera, int i, int j) {
  const double a0 = plane_a(camera, i), a1 = plane_a(camera, i + 1);
  const double c0 = plane_c(camera, j + 1), c1 = plane_c(camera, j);
  return corner_solid_angle(a1, c1) - corner_solid_angle(a0, c1) - corner_solid_angle(a1, c0) +
         corner_solid_angle(a0, c0);
}

void deposit_stars(std::span<const StarImage> stars, const CameraBasis& camera, int x0, int y0,
                   int width, int height, std::span<const float> sky_coverage, double weight,
                   std::span<float> rgb, int stride) {
  const int columns = lattice_size(width, stride);
  for (const StarImage& star : stars) {
    const StarFootprint f = star_footprint(star.x, star.y);
    // The corners of the footprint's pixels on the image plane, once each.
    double corner[4][4];
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a)
        corner[b][a] = corner_solid_angle(plane_a(camera, f.i0 + a), plane_c(camera, f.j0 + b));
    for (int b = 0; b < 3; ++b) {
      const int j = f.j0 + b - y0;
      if (j < 0 || j >= height) continue;
      const int row = lattice_index(j, height, stride);
      if (row < 0) continue;
      for (int a = 0; a < 3; ++a) {
        const int i = f.i0 + a - x0;
        const double w = f.wx[a] * f.wy[b];
        if (i < 0 || i >= width || w == 0) continue;
        const int column = lattice_index(i, width, stride);
        if (column < 0) continue;
        const std::size_t at = static_cast<std::size_t>(row) * columns + column;
        const double solid_angle =
            corner[b][a + 1] - corner[b][a] - corner[b + 1][a + 1] + corner[b + 1][a];
        const double k =
            w * weight * (sky_coverage.empty() ? 1.0 : sky_coverage[at]) / std::abs(solid_angle);
        rgb[3 * at] += static_cast<float>(star.flux.r * k);
        rgb[3 * at + 1] += static_cast<float>(star.flux.g * k);
        rgb[3 * at + 2] += static_cast<float>(star.flux.b * k);
      }
    }
  }
}

}  // namespace lightcone

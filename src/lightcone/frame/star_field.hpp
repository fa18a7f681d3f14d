// The stars of the sky as point sources (PHYSICS.md, "Point sources at infinity";
// docs/design/stars.md): where each star's images land in the camera's picture, the flux each
// brings, and the pixel filter that deposits that flux, the same in both renderers.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/doppler_table.hpp"
#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/schwarzschild_lens.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The flux unit: a star of V = 0 seen at rest brings a flux whose CIE Y is this (linear sRGB
// radiance times steradians: a white patch of radiance 1 and this solid angle), times 2 to the
// power sky.stars.exposure. At 1920x1080 and a 60 degree field a star of V = 0 then peaks at
// about 6 in the picture, before the render's exposure, and one of V = 6 at about 0.02.
inline constexpr double kMagnitudeZeroFlux = 1e-4;

// How bright, and what colour, each star of a sky is received: a blackbody at the temperature
// of its colour index (star_temperature) whose CIE Y at rest is its flux from V
// (magnitude_flux_ratio). Seen with shift g and with its image spread over mu times the solid
// angle it has in the sky's frame, its spectral flux is mu g^5 F_lambda(g lambda) (F'_nu(nu) =
// D F_nu(nu / D) for a moving camera, mu = 1 / D^2), under the scene's colour and searchlight
// models: with the physical ones, a blackbody at g T whose bolometric flux is g^4 mu (D^2)
// times the star's. Every temperature's colour comes from one table of the hottest star's
// blackbody against ln(g T / T_hottest), as the accretion disk's (received_thermal_colour).
class StarPhotometry {
 public:
  // `log_shift_lo/hi`: the range of ln g the stars can be seen with.
  StarPhotometry(const SkyStars& stars, const RenderSettings& settings, double log_shift_lo,
                 double log_shift_hi);

  std::size_t size() const { return stars_.size(); }
  // Whether it is the photometry of the scene's stars under its colour models and covers every
  // shift they can be seen with (a renderer keeps it from frame to frame while it does).
  bool serves(const ResolvedScene& scene) const;
  // The received flux of star k seen with shift g and solid-angle ratio mu.
  LinearRgb received(std::size_t k, double g, double mu) const;

 private:
  struct Star {
    double tau = 1;      // its temperature over the hottest's
    double scale = 0;    // the rest flux's Y over the hottest blackbody's at tau (tabulated)
    LinearRgb rest_rgb;  // its flux at rest (the non-spectral models)
  };
  const std::vector<CatalogueStar>* catalogue_ = nullptr;
  double exposure_ = 0;
  RenderSettings settings_;
  double log_shift_lo_ = 0, log_shift_hi_ = 0;
  DopplerXyzTable hottest_;  // the hottest star's blackbody seen with factor s
  std::vector<Star> stars_;
};

// One image of a star in the camera's picture.
struct StarImage {
  double x = 0, y = 0;  // image point: pixel (i, j) has its centre at (i + .5, j + .5)
  LinearRgb flux;       // received flux (StarPhotometry)
};

// The photometry of a resolved scene's stars (none without sky.stars): over every ln g its sky
// can be seen with, widened by `margin` on each side.
StarPhotometry star_photometry(const ResolvedScene& scene, double margin = 0);

// Every image of every star of the scene's sky whose pixel filter reaches into the camera's
// picture. In flat space one per star, at its exactly aberrated direction (the inverse of the
// sky lookup the camera's rays make), with g = D and the solid-angle ratio 1 / D^2. Near a black
// hole (a camera outside the horizon) the images of orders 0 to
// kStarImageOrders - 1 from the lens table of the camera's radius (star_lens_table: `lens`,
// made here when it is null or of another radius), carried into the camera's frame as locate's
// (hole_sky_image_seen), with their magnifications.
inline constexpr int kStarImageOrders = 3;
std::vector<StarImage> star_images(const ResolvedScene& scene, const StarPhotometry& photometry,
                                   const FarImageTable* lens = nullptr);
// The lens table the stars are found with: orders 0 to kStarImageOrders - 1 at 256 angles; and
// whether one is the table of this hole's mass and camera radius.
FarImageTable star_lens_table(const HoleView& hole);
bool star_lens_serves(const FarImageTable& lens, const HoleView& hole);

// The pixel filter: the quadratic B-spline, separable, three pixels wide. A point at (x, y)
// gives pixel (i0 + a, j0 + b) the weight wx[a] wy[b]; the weights sum to 1 wherever the point
// is (a partition of unity) and change continuously with it, so a star's flux is kept whole and
// does not flicker as it moves across pixels.
struct StarFootprint {
  int i0 = 0, j0 = 0;
  std::array<double, 3> wx{}, wy{};
};
StarFootprint star_footprint(double x, double y);
// The filter's weight at offset (dx, dy) from the point: B(dx) B(dy), B(t) = 3/4 - t^2 for
// |t| <= 1/2, (3/2 - |t|)^2 / 2 for |t| <= 3/2, else 0 (what each point sprite's fragment
// evaluates).
double star_filter_weight(double dx, double dy);

// The solid angle of pixel (i, j) of the pinhole camera, exactly: the rectangle's on the unit
// image plane, atan(a c / sqrt(1 + a^2 + c^2)) taken between its corners.
double pixel_solid_angle(const CameraBasis& camera, int i, int j);

// Adds the stars to a linear image of the pixels [x0, x0 + width) x [y0, y0 + height) of the
// camera's picture: each pixel gets flux times its filter weight over its solid angle, times the
// fraction of it where the sky is seen (`sky_coverage`, one per pixel; bodies and the disk hide
// the stars behind them), times `weight`. With a `stride` above 1 the image (and
// `sky_coverage`) holds that window's lattice alone (frame/pixel_lattice.hpp).
void deposit_stars(std::span<const StarImage> stars, const CameraBasis& camera, int x0, int y0,
                   int width, int height, std::span<const float> sky_coverage, double weight,
                   std::span<float> rgb, int stride = 1);

}  // namespace lightcone

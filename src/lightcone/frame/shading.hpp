// Rest-frame pattern lookups: which colour a surface point or sky direction has in its own
// rest frame (checker cells, texture and sky-image texels, grid lines).
#pragma once

#include "lightcone/frame/surface_hit.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// Bilinear lookup with texel centres at ((i + .5)/w, (j + .5)/h); u wraps, v wraps for
// textures and clamps for equirectangular skies (poles).
Rgb sample_bilinear(const Image& image, double u, double v, bool wrap_v);

// Colour index (floor(x/s) + floor(y/s) + floor(z/s)) mod 2, non-negative.
int checker_index(const Checker& checker, const Vec3& shape_point);

// The fixed colours of a material's pattern, its count as the return value: 1 for a solid
// colour; 2 for a checker, blink or clock (indexed by checker_index, blink_index, clock_index);
// 0 for textures and emission spectra.
int pattern_colours(const Material& material, Rgb colours[2]);

// Which colour of a pattern on the body's clock a point shows at the body's proper time tau:
// a blink is on (1) for the first `duty` of each period; a clock's hand and rim are 1.
int blink_index(const Blink& blink, double proper_time);
int clock_index(const Clock& clock, const std::array<double, 2>& uv, double proper_time);

Rgb texture_colour(const Texture& texture, const Hit& hit);

// The equirectangular sky image in pattern direction d: u = 0.5 + atan2(d.x, -d.z)/(2 pi),
// v = acos(d.y)/pi.
Rgb sky_image_colour(const SkyImage& sky, const Vec3& d);

// Whether pattern direction d lies on a line of the celestial grid.
bool on_grid_line(const SkyGrid& grid, const Vec3& d);

}  // namespace lightcone

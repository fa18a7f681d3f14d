// What a ray sees where it ends: the unlit radiance of a surface point or of the sky.
#pragma once

#include "lightcone/render/tracer.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// Bilinear lookup with texel centres at ((i + .5)/w, (j + .5)/h); u wraps, v wraps for
// textures and clamps for equirectangular skies (poles).
Rgb sample_bilinear(const Image& image, double u, double v, bool wrap_v);

// Rest-frame radiance of the surface of `object` at a hit.
Rgb surface_radiance(const Object& object, const Hit& hit);

// Rest-frame radiance of the sky in look direction d, given in the sky pattern's coordinates.
Rgb sky_radiance(const Sky& sky, const Vec3& d);

}  // namespace lightcone

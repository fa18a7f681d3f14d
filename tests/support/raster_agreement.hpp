// Agreement of the raster renderer with the ray tracer, through `lightcone render` with and
// without --renderer raster: the share of pixels within 4/255 off the bodies' outlines.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "lightcone/scene/scene.hpp"

namespace lightcone::test {

// The 8-bit value a PNG holds for a pixel read back as linear.
int png_level(float linear);

// The share of the pixels of a and b (PNGs of one size, read back) within 4/255 in every
// channel, off a one-pixel band along the outlines that the object ids (per pixel) mark;
// `compared` is set to the number of pixels compared. With `bodies_only`, the sky's pixels (id
// -1) are left out too.
double share_within_4_off_outlines(const Image& a, const Image& b, const std::vector<float>& object,
                                   std::size_t& compared, bool bodies_only = false);

// Two pictures of one size drawn by the raster renderer two ways that must agree (kept tables
// against fresh ones, a specialised program against the full one): how many values differ by
// more than `relative` (1 + |b|), and how many of b's are above zero (that it is not black).
struct ValueDifference {
  std::size_t differing = 0, lit = 0;
};
ValueDifference compare_values(const Image& a, const Image& b, float relative);

struct Agreement {
  double within = 0;         // fraction of the compared pixels within 4/255 in every channel
  std::size_t compared = 0;  // pixels off the silhouette band
  double bodies_within = 0;  // the same on the bodies' pixels alone (the sky's left out)
  std::size_t bodies_compared = 0;
  std::string raster_err;  // what the raster render said on stderr
  // The EV each renderer applied (its EXR's header): the scene's, or its automatic exposure.
  double trace_ev = 0, raster_ev = 0;
};

// Renders a scene (a bundled one by name, or a path) both ways at 640x360 with `samples`
// samples and the options `extra` (and `raster_extra` for the raster render alone); the ray
// tracer's object ids mark the silhouettes, and the PNGs are compared off a one-pixel band
// along them.
Agreement agreement(const std::string& scene, int samples, const std::string& extra = "",
                    const std::string& raster_extra = "");

// At least 99 % of the compared pixels within 4/255, over half the picture compared, and
// nothing the raster renderer says it draws differently; returns the agreement.
Agreement expect_agreement(const std::string& scene, const std::string& extra = "",
                           int samples = 16);

// The automatic exposure the viewer and the web page meter on their frame of `scene` (one pass
// through the pixels' centres, FloatTarget::metered_exposure), before they smooth it over time.
double metered_frame_exposure(const Scene& scene);

}  // namespace lightcone::test

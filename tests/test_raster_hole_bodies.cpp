// The raster renderer's bodies near a black hole (raster/hole_bodies.hpp): their images of
// orders 0 and 1 against the ray tracer's picture of the bundled scenes, off the outlines, and
// their vertices against locate's images of the same points. Units: G = c = 1, M = 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "lightcone/io/image_file.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/trace/aov.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

// The 8-bit value a PNG holds for a pixel read back as linear.
int level(float linear) {
  return static_cast<int>(std::lround(255 * srgb_encode(std::min(linear, 1.0f))));
}

struct Agreement {
  std::size_t body_pixels = 0, body_within = 0;  // off the outlines, on a body
  std::size_t secondary_pixels = 0;              // of those, in an image of order 1
  std::size_t other_pixels = 0, other_within = 0;
};

// Both renderers' pictures of `scene` (one sample a pixel, the exposure fixed), compared off the
// outlines: pixels whose traced ray, or a neighbour's, meets another object or image order.
Agreement compare(Scene s) {
  s.camera.samples = 1;
  s.render.auto_exposure = false;
  RenderOptions options;
  options.aovs = {Aov::kObject, Aov::kImageOrder};
  const Image traced = render_image(s, options);
  const Image rastered = render_raster(s);
  const int w = s.camera.width, h = s.camera.height;
  const auto key = [&](int x, int y) {
    const std::size_t i = static_cast<std::size_t>(y) * w + x;
    return std::pair{traced.channels[0].values[i], traced.channels[1].values[i]};
  };
  Agreement a;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          edge =
              edge || key(std::clamp(x + dx, 0, w - 1), std::clamp(y + dy, 0, h - 1)) != key(x, y);
      if (edge) continue;
      const Rgb p = traced.texel(x, y), q = rastered.texel(x, y);
      const bool within = std::abs(level(p.r) - level(q.r)) <= 4 &&
                          std::abs(level(p.g) - level(q.g)) <= 4 &&
                          std::abs(level(p.b) - level(q.b)) <= 4;
      if (key(x, y).first >= 0) {
        ++a.body_pixels;
        a.body_within += within;
        a.secondary_pixels += key(x, y).second == 1;
      } else {
        ++a.other_pixels;
        a.other_within += within;
      }
    }
  return a;
}

// A clock at rest behind the hole (its primary and flipped secondary image, which left it 9.6
// units of time apart), three clocks falling in, reddening and freezing, and a lit moon on its
// orbit (lit by a sun, directly and round the far side): both renderers agree off the outlines.
// Painted one colour, the bodies agree as the sky does (their shapes and shifts); with their
// patterns (clock faces, a checker), the hands, rims and squares are outlines the test does not
// know of, drawn within half a pixel of the tracer's, and a few percent of the pixels differ.
TEST(RasterHoleBodies, MatchTheRayTracerOffTheOutlines) {
  for (const auto& [name, width, least_secondary] : {std::tuple{"lensed-clock.json", 320, 20},
                                                     {"infall.json", 480, 0},
                                                     {"orbit.json", 480, 20}}) {
    for (const bool faces : {false, true}) {
      SCOPED_TRACE(name);
      Scene s = test::load_repository_scene(name);
      s.camera.height = s.camera.height * width / s.camera.width;
      s.camera.width = width;
      if (!faces)
        for (Object& o : s.objects) o.material.pattern = SolidColor{{1, 0.95f, 0.8f}};
      const Agreement a = compare(s);
      const double bodies = static_cast<double>(a.body_within) / a.body_pixels;
      const double others = static_cast<double>(a.other_within) / a.other_pixels;
      std::printf("%s %dx%d%s: bodies %.4f of %zu pixels (%zu of order 1), the rest %.4f of %zu\n",
                  name, s.camera.width, s.camera.height, faces ? "" : " (one colour)", bodies,
                  a.body_pixels, a.secondary_pixels, others, a.other_pixels);
      EXPECT_GT(a.body_pixels, 150u);
      EXPECT_GE(a.secondary_pixels, static_cast<std::size_t>(least_secondary));
      // (A lit body's colour is interpolated between its vertices', within 1/128 of its
      // brightest: in the dark a few levels of 255.)
      const bool lit = !s.objects.front().material.unlit;
      EXPECT_GE(bodies, faces ? 0.93 : lit ? 0.98 : 0.99);
      EXPECT_GE(others, 0.99);
    }
  }
}

}  // namespace
}  // namespace lightcone

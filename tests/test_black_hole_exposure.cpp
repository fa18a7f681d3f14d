// The automatic exposure near a black hole meters its documented subject, the bodies moving
// relative to the camera, by coverage, exactly as in flat space (frame/tone_map.hpp): the
// curved rays count the bodies they meet (and a body on a geodesic moves), in the ray tracer
// and in the raster renderer's bodies near the hole. Without it the picture near a hole was
// metered whole: terrell.json, whose floor and sky are dim so that its moving bodies set the
// exposure, came out far brighter beside a hole of no consequence.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/raster_agreement.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

// terrell.json at 320 x 180, one sample a pixel, with a hole of mass M 866 units away behind the
// camera: 1e-9 leaves every ray straight to rounding; 0.1 bends the rays through the bodies by
// about a tenth of a pixel, so they are followed as curved rays, and the picture is all but the
// flat one.
Scene terrell_beside_a_hole(double mass) {
  Scene s = test::load_repository_scene("terrell.json");
  s.camera.width = 320, s.camera.height = 180, s.camera.samples = 1;
  if (mass > 0) s.black_hole = BlackHole{{500, 500, 500}, mass, std::nullopt};
  return s;
}

struct Traced {
  Image image;
  std::vector<float> subject;
  double ev = 0;
};
Traced trace(const Scene& scene) {
  Traced t;
  RenderOptions options;
  options.subject = &t.subject;
  RenderStats stats;
  t.image = render_image(scene, options, &stats);
  t.ev = stats.exposure;
  return t;
}

// How many pixels' subject weights differ.
std::size_t weights_differing(const std::vector<float>& a, const std::vector<float>& b) {
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differ += a[i] != b[i];
  return differ;
}

std::size_t subject_pixels(const std::vector<float>& weights) {
  std::size_t n = 0;
  for (const float w : weights) n += w > 0;
  return n;
}

TEST(BlackHoleExposure, BesideAHoleOfNoConsequenceTheTracerMetersTheFlatSubject) {
  const Traced flat = trace(terrell_beside_a_hole(0));
  ASSERT_GT(subject_pixels(flat.subject), 2000u);
  for (const double mass : {1e-9, 0.1}) {
    SCOPED_TRACE(mass);
    const Traced near = trace(terrell_beside_a_hole(mass));
    std::printf("M %g: EV %+.4f, flat %+.4f; %zu of %zu subject weights differ\n", mass, near.ev,
                flat.ev, weights_differing(near.subject, flat.subject), flat.subject.size());
    EXPECT_NEAR(near.ev, flat.ev, 0.01);
    // Only where a tenth of a pixel moves an outline across a pixel's centre.
    EXPECT_LT(weights_differing(near.subject, flat.subject), 40u);
    // The negligible hole's picture is the flat one (the other's light is shifted by its depth).
    if (mass < 1e-6) {
      EXPECT_LT(test::fraction_differing(near.image, flat.image), 1e-3);
    }
  }
}

// The raster renderer's bodies near a hole are the subject where they move, as the tracer's
// curved rays find it: the same pixels but on the outlines, and so the same EV within what the
// outlines allow (test_raster_exposure's 0.04). orbit.json's moon is on a geodesic.
TEST(BlackHoleExposure, BothRenderersMeterTheSameSubjectNearAHole) {
  Scene orbit = test::load_repository_scene("orbit.json");
  orbit.camera.width = 640, orbit.camera.height = 360, orbit.camera.samples = 1;
  orbit.render.auto_exposure = true;
  for (const Scene& scene : {terrell_beside_a_hole(0.1), orbit}) {
    SCOPED_TRACE(scene.camera.width);
    const Traced traced = trace(scene);
    std::vector<float> drawn;
    RasterStats stats;
    render_raster(scene, &stats, {}, 0, RasterTessellation::kAuto, {}, &drawn);
    ASSERT_EQ(drawn.size(), traced.subject.size());
    const std::size_t subject = subject_pixels(traced.subject);
    const std::size_t differ = weights_differing(drawn, traced.subject);
    std::printf("EV %+.4f traced, %+.4f drawn; a subject of %zu pixels, %zu weighed otherwise\n",
                traced.ev, stats.exposure, subject, differ);
    EXPECT_GT(subject, 200u);
    EXPECT_LT(differ, subject / 5);
    EXPECT_NEAR(stats.exposure, traced.ev, 0.04);
  }
}

// The raster renderer beside the negligible hole (its bodies then drawn by the hole's images, their
// outlines within half a pixel of the flat ones): the flat raster picture's EV within 0.01.
TEST(BlackHoleExposure, BesideANegligibleHoleTheRasterRendererMetersTheFlatSubject) {
  Scene flat = terrell_beside_a_hole(0), near = terrell_beside_a_hole(1e-9);
  for (Scene* s : {&flat, &near}) s->camera.width = 640, s->camera.height = 360;
  RasterStats flat_stats, near_stats;
  render_raster(flat, &flat_stats);
  render_raster(near, &near_stats);
  std::printf("raster EV %+.4f beside the negligible hole, %+.4f flat\n", near_stats.exposure,
              flat_stats.exposure);
  EXPECT_NEAR(near_stats.exposure, flat_stats.exposure, 0.01);
}

// The viewer's and the web page's metering of a frame (one pixel of each 4 x 4 block, weighed by
// the bodies' alpha) beside the slight hole is the flat picture's, within what the sample allows
// (test_raster_exposure's 0.1): it metered the whole frame, 1.6 EV brighter.
TEST(BlackHoleExposure, TheViewersMeteringBesideASlightHoleIsTheFlatOnes) {
  // At 640 x 360, as test_raster_exposure meters it (a sixteenth of 320 x 180 is too few).
  const auto at_640 = [](Scene s) {
    s.camera.width = 640, s.camera.height = 360;
    return s;
  };
  const Scene flat = at_640(terrell_beside_a_hole(0));
  const double metered = test::metered_frame_exposure(at_640(terrell_beside_a_hole(0.1)));
  const double flat_metered = test::metered_frame_exposure(flat);
  std::printf("metered %+.4f beside the hole, %+.4f flat; traced flat %+.4f\n", metered,
              flat_metered, trace(flat).ev);
  EXPECT_NEAR(metered, flat_metered, 0.1);
}

}  // namespace
}  // namespace lightcone

// The ray tracer meters its automatic exposure as it writes its pixels (ExposureMeter, filled by
// each thread): the EV it applies is auto_exposure's on its own linear picture and subject
// weights, on any number of threads, and the picture it returns is that linear one scaled.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "lightcone/frame/tone_map.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

struct Exposed {
  Image image;
  double ev;
};

Exposed render_at(const Scene& scene, int threads) {
  RenderOptions options;
  options.threads = threads;
  RenderStats stats;
  Image image = render_image(scene, options, &stats);
  return {std::move(image), stats.exposure};
}

TEST(RenderExposure, IsTheRuleOnTheRendersOwnPixels) {
  // terrell.json: two moving bodies before a floor at rest; street.json: a camera in motion,
  // so that everything moves relative to it; at 2 samples, so that the subject has shares.
  for (const std::string name : {"terrell.json", "street.json"}) {
    Scene scene = test::load_repository_scene(name);
    scene.camera.width = 160, scene.camera.height = 90, scene.camera.samples = 2;
    scene.render.auto_exposure = true;  // (street.json gives a number)
    Scene fixed = scene;
    fixed.render.auto_exposure = false, fixed.render.exposure = 0;
    RenderOptions options;
    std::vector<float> subject;
    options.subject = &subject;
    const Image linear = render_image(fixed, options);
    const double rule = auto_exposure(linear, scene.render.tonemap, subject);
    EXPECT_GT(std::abs(rule), 0.1) << name;  // an EV that scaling by 1 would not hide
    for (const int threads : {1, 2, 5}) {
      const Exposed shown = render_at(scene, threads);
      EXPECT_EQ(shown.ev, rule) << name << ", " << threads << " threads";
      const auto scale = static_cast<float>(std::exp2(rule));
      ASSERT_EQ(shown.image.rgb.size(), linear.rgb.size());
      for (std::size_t v = 0; v < linear.rgb.size(); ++v)
        ASSERT_EQ(shown.image.rgb[v], linear.rgb[v] * scale) << name << ", value " << v;
    }
  }
}

}  // namespace
}  // namespace lightcone

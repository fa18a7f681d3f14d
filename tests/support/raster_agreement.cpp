#include "support/raster_agreement.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone::test {

namespace fs = std::filesystem;

int png_level(float linear) {
  return static_cast<int>(std::lround(255 * srgb_encode(linear)));
}

ValueDifference compare_values(const Image& a, const Image& b, float relative) {
  ValueDifference d;
  for (std::size_t i = 0; i < b.rgb.size(); ++i) {
    d.differing += std::abs(a.rgb[i] - b.rgb[i]) > relative * (1 + std::abs(b.rgb[i]));
    d.lit += b.rgb[i] > 0;
  }
  return d;
}

double share_within_4_off_outlines(const Image& a, const Image& b, const std::vector<float>& object,
                                   std::size_t& compared, bool bodies_only) {
  const int w = a.width, h = a.height;
  std::size_t within = 0;
  compared = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float id = object[static_cast<std::size_t>(y) * w + x];
      if (bodies_only && id < 0) continue;
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = std::clamp(x + dx, 0, w - 1), ny = std::clamp(y + dy, 0, h - 1);
          edge = edge || object[static_cast<std::size_t>(ny) * w + nx] != id;
        }
      if (edge) continue;
      ++compared;
      const Rgb p = a.texel(x, y), q = b.texel(x, y);
      within += std::abs(png_level(p.r) - png_level(q.r)) <= 4 &&
                std::abs(png_level(p.g) - png_level(q.g)) <= 4 &&
                std::abs(png_level(p.b) - png_level(q.b)) <= 4;
    }
  return static_cast<double>(within) / std::max<std::size_t>(compared, 1);
}

Agreement agreement(const std::string& scene, int samples, const std::string& extra,
                    const std::string& raster_extra) {
  const fs::path dir = test::fresh_temp_dir("agreement");
  const fs::path path = fs::path(scene).is_absolute()
                            ? fs::path(scene)
                            : fs::path(LIGHTCONE_SOURCE_DIR) / "scenes" / scene;
  const std::string source = quoted(path);
  const std::string common =
      " --width 640 --height 360 --samples " + std::to_string(samples) + " --quiet " + extra;
  const auto traced =
      test::run_lightcone("render " + source + common + " -o " + quoted(dir / "trace.png") +
                          " --exr " + quoted(dir / "trace.exr") + " --aov object");
  EXPECT_EQ(traced.status, 0) << traced.err;
  const auto rastered = test::run_lightcone("render " + source + common + " " + raster_extra +
                                            " --renderer raster -o " + quoted(dir / "raster.png") +
                                            " --exr " + quoted(dir / "raster.exr"));
  EXPECT_EQ(rastered.status, 0) << rastered.err;
  Agreement result;
  result.raster_err = rastered.err;
  if (traced.status != 0 || rastered.status != 0) return result;
  const auto a = load_image_file(dir / "trace.png"), b = load_image_file(dir / "raster.png");
  const auto exr = load_image_file(dir / "trace.exr");
  result.trace_ev = exr->exposure.value_or(NAN);
  result.raster_ev = load_image_file(dir / "raster.exr")->exposure.value_or(NAN);
  const std::vector<float>* object = nullptr;
  for (const NamedChannel& c : exr->channels)
    if (c.name == "object") object = &c.values;
  EXPECT_NE(object, nullptr);
  if (object == nullptr || a->width != b->width || a->height != b->height) return result;
  result.within = share_within_4_off_outlines(*a, *b, *object, result.compared);
  result.bodies_within = share_within_4_off_outlines(*a, *b, *object, result.bodies_compared, true);
  fs::remove_all(dir);
  return result;
}

Agreement expect_agreement(const std::string& scene, const std::string& extra, int samples) {
  const Agreement a = agreement(scene, samples, extra);
  EXPECT_GE(a.within, 0.99) << scene << extra << ": " << a.compared << " pixels compared";
  EXPECT_GT(a.compared, 640u * 360u / 2) << scene;
  EXPECT_EQ(a.raster_err, "") << scene;  // nothing this renderer shows differently
  std::printf("%s %s: %.4f of %zu pixels within 4/255\n", scene.c_str(), extra.c_str(), a.within,
              a.compared);
  return a;
}

double metered_frame_exposure(const Scene& scene) {
  const HeadlessGlContext context;
  RasterRenderer renderer;
  const FloatTarget target(scene.camera.width, scene.camera.height);
  const ResolvedScene resolved = resolve_scene(scene);
  const EmissionTable emission(resolved);
  target.bind();
  renderer.prepare(resolved, emission, {},
                   tessellate_on_gpu(RasterTessellation::kAuto, renderer.driver()));
  renderer.pass();
  return target.metered_exposure(scene.render.tonemap);
}

}  // namespace lightcone::test

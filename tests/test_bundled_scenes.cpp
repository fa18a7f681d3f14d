// The bundled scenes as a user first sees them: each is readable at its own defaults (few
// pixels the PNG holds as 255), and the README's first command renders the README's picture.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> bundled_scenes() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes"))
    if (entry.path().extension() == ".json") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// The scene at a quarter of its size (its view, samples and settings unchanged).
Image display_at_quarter_size(const std::string& name) {
  Scene s = test::load_repository_scene(name);
  s.camera.width = std::max(1, s.camera.width / 4);
  s.camera.height = std::max(1, s.camera.height / 4);
  return tone_map(render_image(s, {}), s.render.tonemap);
}

TEST(BundledScenes, EachIsReadableAtItsDefaults) {
  const std::vector<std::string> names = bundled_scenes();
  ASSERT_GE(names.size(), 10u);
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const Image image = display_at_quarter_size(name);
    std::size_t clipped = 0, lit = 0;
    const std::size_t pixels = image.rgb.size() / 3;
    // Clipped: a channel the PNG holds as 255.
    const std::vector<unsigned char> png = display_rgb8(image);
    for (std::size_t p = 0; p < pixels; ++p) {
      const float* c = &image.rgb[3 * p];
      clipped += png[3 * p] == 255 || png[3 * p + 1] == 255 || png[3 * p + 2] == 255;
      lit += std::max({c[0], c[1], c[2]}) > 0.02f;
    }
    // At most 2% of the pixels clipped in some channel, and something to see: a twentieth of
    // the picture, or of a field of point-like stars alone (each some 3x3 pixels) a 200th.
    const Scene scene = test::load_repository_scene(name);
    const bool star_field = scene.sky.stars && scene.objects.empty() && !scene.black_hole;
    EXPECT_LE(static_cast<double>(clipped) / pixels, 0.02);
    EXPECT_GE(static_cast<double>(lit) / pixels, star_field ? 0.005 : 0.05);
  }
}

// The README's first command renders scenes/terrell.json at its defaults; its picture is
// docs/images/terrell.png (made by scripts/make-doc-images.sh with that command).
TEST(BundledScenes, TheReadmesFirstCommandMakesTheReadmesPicture) {
  const auto hero = load_image_file(fs::path(LIGHTCONE_SOURCE_DIR) / "docs/images/terrell.png");
  const Scene scene = test::load_repository_scene("terrell.json");
  ASSERT_EQ(hero->width, scene.camera.width);
  ASSERT_EQ(hero->height, scene.camera.height);
  const Image small = display_at_quarter_size("terrell.json");
  // The hero reduced 4 x 4 (in linear light) against the quarter-size render, in sRGB.
  double sum = 0;
  for (int y = 0; y < small.height; ++y)
    for (int x = 0; x < small.width; ++x)
      for (int c = 0; c < 3; ++c) {
        double mean = 0;
        for (int dy = 0; dy < 4; ++dy)
          for (int dx = 0; dx < 4; ++dx)
            mean +=
                hero->rgb[3 * (static_cast<std::size_t>(4 * y + dy) * hero->width + 4 * x + dx) +
                          c];
        mean /= 16;
        const double want = srgb_encode(std::clamp(mean, 0.0, 1.0));
        const double got = srgb_encode(std::clamp<double>(
            small.rgb[3 * (static_cast<std::size_t>(y) * small.width + x) + c], 0.0, 1.0));
        sum += std::abs(got - want);
      }
  EXPECT_LT(sum / (small.width * small.height * 3), 0.02);
}

}  // namespace
}  // namespace lightcone

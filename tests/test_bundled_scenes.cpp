// The bundled scenes as a user first sees them: each is readable at its own defaults (few
// pixels the PNG holds as 255), and the README's first command renders the README's picture.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/trace/aov.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/scene_file_test.hpp"
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

// The scene-format reference's first example, the one a newcomer copies, stands beside them.
const std::string kFirstExample = "docs/scene-format.md's first example";

Scene load_named(const std::string& name) {
  if (name != kFirstExample) return test::load_repository_scene(name);
  return test::scene_from_json(test::documented_example());
}

// The scene at a quarter of its size (its view, samples and settings unchanged), and, where
// `moving` is given, which of its pixels show a body moving relative to the camera.
Image display_at_quarter_size(const std::string& name, std::vector<bool>* moving = nullptr) {
  Scene s = load_named(name);
  s.camera.width = std::max(1, s.camera.width / 4);
  s.camera.height = std::max(1, s.camera.height / 4);
  RenderOptions options;
  if (moving) options.aovs = {Aov::kObject};
  const Image linear = render_image(s, options);
  if (moving) {
    // The bodies point into the scene they were resolved in (a scene with accelerated or
    // keyframed bodies is resolved in its tangent copy), whose objects are the scene's, in order.
    const ResolvedScene resolved = resolve_scene(s);
    const std::vector<Object>& objects = resolved.scene->objects;
    std::vector<bool> object_moves(objects.size(), false);
    for (const ResolvedBody& body : resolved.bodies)
      object_moves[static_cast<std::size_t>(body.object - objects.data())] =
          body.moves_relative_to_camera();
    moving->clear();
    for (const float object : linear.channels.at(0).values)
      moving->push_back(object >= 0 && object_moves[static_cast<std::size_t>(object)]);
  }
  return tone_map(linear, s.render.tonemap);
}

// The mean of a pixel's sRGB-encoded channels, 0 to 1: its brightness in the PNG.
double png_brightness(const Image& display, std::size_t pixel) {
  double sum = 0;
  for (int c = 0; c < 3; ++c)
    sum += srgb_encode(std::clamp<double>(display.rgb[3 * pixel + c], 0.0, 1.0));
  return sum / 3;
}

TEST(BundledScenes, EachIsReadableAtItsDefaults) {
  std::vector<std::string> names = bundled_scenes();
  ASSERT_GE(names.size(), 10u);
  names.push_back(kFirstExample);
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    std::vector<bool> moving;
    const Image image = display_at_quarter_size(name, &moving);
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
    const Scene scene = load_named(name);
    const bool star_field = scene.sky.stars && scene.objects.empty() && !scene.black_hole;
    EXPECT_LE(static_cast<double>(clipped) / pixels, 0.02);
    EXPECT_GE(static_cast<double>(lit) / pixels, star_field ? 0.005 : 0.05);
    // The bodies that carry the effects are not black: their mean brightness in the PNG is at
    // least 5 % of full scale.
    double brightness = 0;
    std::size_t count = 0;
    for (std::size_t p = 0; p < pixels; ++p)
      if (moving[p]) brightness += png_brightness(image, p), ++count;
    if (count > 0) {
      EXPECT_GE(brightness / count, 0.05) << count << " pixels";
    }
  }
}

// terrell.json shows what its caption names: the crate's trailing face, turned toward the
// camera by the Terrell-Penrose rotation, and visible, not dimmed to black.
TEST(BundledScenes, TerrellShowsTheCratesTrailingFace) {
  const Scene s = test::load_repository_scene("terrell.json");
  RenderOptions options;
  options.aovs = {Aov::kObject, Aov::kNormal};
  const Image linear = render_image(s, options);
  const Image display = tone_map(linear, s.render.tonemap);
  const std::vector<float>& object = linear.channels.at(0).values;
  const std::vector<float>& normal_x = linear.channels.at(1).values;
  const std::size_t crate = 1;
  ASSERT_EQ(s.objects[crate].name, "crate");
  ASSERT_GT(s.objects[crate].world_line.velocity.x, 0);  // so its trailing face looks along -x
  std::size_t face = 0, whole = 0;
  double brightness = 0;
  for (std::size_t p = 0; p < object.size(); ++p) {
    if (object[p] != crate) continue;
    ++whole;
    if (normal_x[p] < -0.99f) ++face, brightness += png_brightness(display, p);
  }
  // Its area, in pixels of the 960 x 540 picture, and as a share of the crate's.
  RecordProperty("trailing_face_pixels", static_cast<int>(face));
  // (18,700 of the crate's 27,000 when written; none in the classical picture, where the face
  // looks away from the camera.)
  EXPECT_GE(face, 10000u);
  EXPECT_GE(static_cast<double>(face) / whole, 0.5);
  // Its checks, red and white at rest, are dark and light orange: a mean of 0.15 when written
  // (near black before the exposure followed the moving bodies).
  EXPECT_GE(brightness / face, 0.1) << face << " pixels of " << whole;
}

// infall.json shows each of its three clocks readably, the one nearest the horizon (seen at
// g = 0.31 to 0.36, some 2^-8 of the others' brightness) too: its face is the brighter lamp
// the scene's description states. (It was at 1/255 when all three were alike.)
TEST(BundledScenes, InfallShowsEveryClock) {
  Scene s = test::load_repository_scene("infall.json");
  s.camera.width /= 4;
  s.camera.height /= 4;
  s.camera.samples = 1;
  RenderOptions options;
  options.aovs = {Aov::kObject};
  const Image linear = render_image(s, options);
  const Image display = tone_map(linear, s.render.tonemap);
  const std::vector<float>& object = linear.channels.at(0).values;
  for (std::size_t clock = 0; clock < s.objects.size(); ++clock) {
    SCOPED_TRACE(s.objects[clock].name);
    double brightness = 0;
    std::size_t count = 0;
    for (std::size_t p = 0; p < object.size(); ++p)
      if (object[p] == clock) brightness += png_brightness(display, p), ++count;
    ASSERT_GT(count, 20u);
    // Its mean brightness in the PNG (hand and face): 0.74, 0.48 and 0.33 when written.
    std::printf("%s: mean brightness %.3f over %zu pixels\n", s.objects[clock].name.c_str(),
                brightness / count, count);
    EXPECT_GE(brightness / count, 0.2) << count << " pixels";
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

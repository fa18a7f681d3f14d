// How each shape maps a texture (docs/scene-format.md, "Texture coordinates"): seen from
// outside, every face of a box, a sphere's front and a plane from above show the image the
// right way round, in both renderers. The image is the bundled uv-grid.png: red top left, green
// top right, blue bottom left, yellow bottom right.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "lightcone/io/image_file.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

// The quadrant colour of uv-grid.png a linear pixel shows.
char quadrant_colour(const Image& image, int x, int y) {
  const float* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
  const float top = std::max({p[0], p[1], p[2]});
  const bool r = p[0] > 0.5f * top, g = p[1] > 0.5f * top, b = p[2] > 0.5f * top;
  if (r && g && b) return 'w';
  if (r && g) return 'Y';
  if (r) return 'R';
  if (g) return 'G';
  return b ? 'B' : '?';
}

struct View {
  const char* what;
  const char* shape;
  const char* position;  // of the camera, the body at the origin
  const char* forward;
  const char* up;
};

class TextureMapping : public test::TempDirTest {};

TEST_F(TextureMapping, EachShapeShowsTheImageTheRightWayRoundFromOutside) {
  const std::string texture = (fs::path(LIGHTCONE_SOURCE_DIR) / "scenes" / "uv-grid.png").string();
  const char* box = R"({"box": {"size": [2, 2, 2]}})";
  const View views[] = {
      {"box +x", box, "[4, 0, 0]", "[-1, 0, 0]", "[0, 1, 0]"},
      {"box -x", box, "[-4, 0, 0]", "[1, 0, 0]", "[0, 1, 0]"},
      {"box +z", box, "[0, 0, 4]", "[0, 0, -1]", "[0, 1, 0]"},
      {"box -z", box, "[0, 0, -4]", "[0, 0, 1]", "[0, 1, 0]"},
      {"box top (+y), the image's top toward -z", box, "[0, 4, 0]", "[0, -1, 0]", "[0, 0, -1]"},
      {"box bottom (-y), the image's top toward +z", box, "[0, -4, 0]", "[0, 1, 0]", "[0, 0, 1]"},
      {"sphere from +z", R"({"sphere": {"radius": 1.2}})", "[0, 0, 4]", "[0, 0, -1]", "[0, 1, 0]"},
      {"plane from above, the image's top toward -z", R"({"plane": {"size": [2, 2]}})", "[0, 3, 0]",
       "[0, -1, 0]", "[0, 0, -1]"},
  };
  for (const View& view : views) {
    for (const char* renderer : {"trace", "raster"}) {
      SCOPED_TRACE(fmt::format("{}, {} renderer", view.what, renderer));
      const fs::path scene = dir_ / "scene.json";
      // The face 3 from the camera fills a 30 degree view; the probes sit inside the quadrants,
      // clear of the grid's lines.
      test::write_text(scene, fmt::format(R"({{
  "camera": {{"position": {}, "forward": {}, "up": {}, "fov": 30, "width": 64, "height": 64,
              "samples": 1}},
  "objects": [{{"name": "body", "shape": {}, "position": [0, 0, 0],
               "material": {{"texture": {}}}}}],
  "render": {{"exposure": 0}}
}})",
                                          view.position, view.forward, view.up, view.shape,
                                          nlohmann::json(texture).dump()));
      const fs::path out = dir_ / "out.exr";
      const test::CommandResult r =
          test::run_lightcone(fmt::format("render {} -o {} --renderer {} --quiet",
                                          test::quoted(scene), test::quoted(out), renderer));
      ASSERT_EQ(r.status, 0) << r.err;
      const auto image = load_image_file(out);
      ASSERT_TRUE(image);
      const bool sphere = std::string(view.shape).find("sphere") != std::string::npos;
      const int near = sphere ? 24 : 16, far = sphere ? 40 : 48, high = sphere ? 26 : 20,
                low = sphere ? 40 : 44;
      EXPECT_EQ(quadrant_colour(*image, near, high), 'R');
      EXPECT_EQ(quadrant_colour(*image, far, high), 'G');
      EXPECT_EQ(quadrant_colour(*image, near, low), 'B');
      EXPECT_EQ(quadrant_colour(*image, far, low), 'Y');
    }
  }
}

}  // namespace
}  // namespace lightcone

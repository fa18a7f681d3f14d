// `lightcone render` through the real binary: valid renders (sizes, options, the PNG and EXR
// value contract, tone curves and exposure, --stats, the progress bar).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/image_file.hpp"
#include "support/cli_test.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using namespace test;  // the CLI fixture and helpers (support/cli_test.hpp)

// ----------------------------------------------------------------------------------------------
// Valid renders

TEST_F(CliTest, ValidRenderWritesPngAndExrOfTheRightSizeAndOneSummaryLine) {
  const fs::path scene = write_scene(kScene);
  const CommandResult r = render(scene);
  EXPECT_EQ(r.status, 0) << r.err;
  // stderr is not a terminal: no progress bar, only the summary: size, samples, time, rate,
  // the files written.
  EXPECT_EQ(line_count(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("lightcone: 64x48, 1 sample: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(" Mrays/s; wrote " + png().string() + " and " + exr().string()),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(render(scene, "--quiet").err, "");
  const auto png_image = read_png();
  const auto exr_image = read_exr();
  EXPECT_EQ(png_image->width, 64);
  EXPECT_EQ(png_image->height, 48);
  EXPECT_EQ(exr_image->width, 64);
  EXPECT_EQ(exr_image->height, 48);
  // Exactly the two images: no temporary files.
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(out_))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"image.exr", "image.png"}));
  // The ball in the middle, the blue sky in the corner.
  EXPECT_EQ(exr_image->texel(32, 24).g, 1.0f);
  EXPECT_EQ(exr_image->texel(0, 0).b, 1.0f);
  EXPECT_EQ(exr_image->texel(0, 0).g, 0.0f);
  EXPECT_EQ(png_byte(png_image->texel(32, 24).g), 255);
  EXPECT_EQ(png_byte(png_image->texel(32, 24).r), 0);
}

TEST_F(CliTest, PngOnlyWithoutExr) {
  const fs::path scene = write_scene(kScene);
  const CommandResult r = run_lightcone("render " + quoted(scene) + " -o " + quoted(png()));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(png()));
  EXPECT_FALSE(fs::exists(exr()));
}

TEST_F(CliTest, SizeAndSampleOptionsTakeEffect) {
  const fs::path scene = write_scene(kScene);
  const CommandResult r = render(scene, "--width 20 --height 10 --samples 4 --stats --quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_png()->width, 20);
  EXPECT_EQ(read_png()->height, 10);
  EXPECT_EQ(read_exr()->width, 20);
  EXPECT_EQ(read_exr()->height, 10);
  const auto stats = nlohmann::json::parse(r.err);
  EXPECT_EQ(stats.at("rays").get<std::uint64_t>(), 20u * 10u * 4u);

  // --set camera.width does the same as --width.
  const CommandResult s = render(scene, "--set camera.width=24 --set camera.height=12");
  EXPECT_EQ(s.status, 0) << s.err;
  EXPECT_EQ(read_png()->width, 24);
  EXPECT_EQ(read_png()->height, 12);
}

TEST_F(CliTest, StatsIsOneJsonLineWithSecondsRaysRateAndExposure) {
  const fs::path scene = write_scene(kScene);
  const CommandResult r = render(scene, "--samples 3 --stats --quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(line_count(r.err), 1u) << r.err;
  ASSERT_TRUE(r.err.ends_with('\n'));
  const auto stats = nlohmann::ordered_json::parse(r.err);
  ASSERT_TRUE(stats.is_object());
  std::vector<std::string> keys;
  for (const auto& item : stats.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"seconds", "rays", "mrays_per_s", "exposure"}));
  ASSERT_TRUE(stats["seconds"].is_number());
  ASSERT_TRUE(stats["rays"].is_number_integer());
  ASSERT_TRUE(stats["mrays_per_s"].is_number());
  const double seconds = stats["seconds"].get<double>();
  EXPECT_GT(seconds, 0.0);
  EXPECT_LT(seconds, 60.0);
  EXPECT_EQ(stats["rays"].get<std::uint64_t>(), 64u * 48u * 3u);
  EXPECT_EQ(stats["exposure"].get<double>(), 0.0);  // the scene's
  EXPECT_NEAR(stats["mrays_per_s"].get<double>(), 64 * 48 * 3 / seconds / 1e6,
              1e-9 * stats["mrays_per_s"].get<double>());
  EXPECT_EQ(r.out, "");
}

TEST_F(CliTest, SetSkyColourMakesTheBackgroundRed) {
  const fs::path scene = write_scene(kScene);
  ASSERT_EQ(render(scene).status, 0);
  EXPECT_EQ(read_exr()->texel(0, 0).r, 0.0f);
  const CommandResult r = render(scene, "--set 'sky.color=[1,0,0]'");
  EXPECT_EQ(r.status, 0) << r.err;
  const auto png_image = read_png();
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{63, 47}, std::pair{63, 0}}) {
    EXPECT_EQ(png_byte(png_image->texel(x, y).r), 255);
    EXPECT_EQ(png_byte(png_image->texel(x, y).g), 0);
    EXPECT_EQ(png_byte(png_image->texel(x, y).b), 0);
  }
  // The ball is still green.
  EXPECT_EQ(png_byte(png_image->texel(32, 24).g), 255);
}

// Relativity and light delay change the picture of the moving ball, and so does the camera's
// velocity.
TEST_F(CliTest, SetSwitchesChangeTheImageOfAMovingBody) {
  const fs::path scene = write_scene(moving_black_ball());
  auto ball_pixels = [&](const std::string& extra) {
    const CommandResult r = render(scene, extra);
    EXPECT_EQ(r.status, 0) << r.err;
    const auto image = read_exr();
    std::vector<int> mask;
    for (int y = 0; y < image->height; ++y)
      for (int x = 0; x < image->width; ++x) mask.push_back(image->texel(x, y).r < 0.5f);
    return mask;
  };
  auto differing = [](const std::vector<int>& a, const std::vector<int>& b) {
    int n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
    return n;
  };
  const auto relativistic = ball_pixels("");
  const auto classical = ball_pixels("--set render.relativity=false");
  const auto simultaneous = ball_pixels("--set render.light_delay=false");
  const auto flying = ball_pixels("--set 'camera.velocity=[0,0,0.5]'");
  const auto again = ball_pixels("--set render.relativity=true");
  EXPECT_GT(std::count(relativistic.begin(), relativistic.end(), 1), 100);
  EXPECT_GT(differing(relativistic, classical), 20);
  EXPECT_GT(differing(relativistic, simultaneous), 20);
  EXPECT_GT(differing(relativistic, flying), 20);
  EXPECT_EQ(differing(relativistic, again), 0);
}

// A box of colour 0.5 filling the frame, at rest before a camera at rest.
const std::string kGreyWall = R"({
  "camera": {"position": [0, 0, 0], "width": 16, "height": 12},
  "objects": [{
    "name": "wall",
    "shape": {"box": {"size": [1000, 1000, 1]}},
    "position": [0, 0, -5],
    "material": {"color": [0.5, 0.5, 0.5], "unlit": true}
  }]
}
)";

TEST_F(CliTest, PngAndExrValueContract) {
  const fs::path scene = write_scene(kGreyWall);
  struct Case {
    std::string exposure;
    float exr;
    int png;
  };
  const int expected_188 = static_cast<int>(std::lround(255 * srgb_encode(0.5)));
  ASSERT_EQ(expected_188, 188);
  const std::vector<Case> cases = {
      {"0", 0.5f, 188},
      {"1", 1.0f, 255},
      {"-1", 0.25f, static_cast<int>(std::lround(255 * srgb_encode(0.25)))},
      {"2", 2.0f, 255},  // the EXR is not clamped; the PNG is
  };
  for (const Case& c : cases) {
    SCOPED_TRACE("exposure " + c.exposure);
    const CommandResult r =
        render(scene, "--set render.exposure=" + c.exposure + " --set render.tonemap=clamp");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto png_image = read_png();
    const auto exr_image = read_exr();
    ASSERT_EQ(png_image->rgb.size(), 16u * 12u * 3u);
    ASSERT_EQ(exr_image->rgb.size(), 16u * 12u * 3u);
    for (std::size_t i = 0; i < png_image->rgb.size(); ++i) {
      ASSERT_EQ(png_byte(png_image->rgb[i]), c.png) << "value " << i;
      ASSERT_FLOAT_EQ(exr_image->rgb[i], c.exr) << "value " << i;
    }
  }
  EXPECT_EQ(static_cast<int>(std::lround(255 * srgb_encode(0.25))), 137);
}

// kGreyWall in `colour`, with the given render section.
std::string uniform_wall(const std::string& colour, const std::string& render) {
  return edited(edited(kGreyWall, "[0.5, 0.5, 0.5]", colour), "\n  }]\n}",
                "\n  }],\n  \"render\": " + render + "\n}");
}

// Every PNG value is `png` and every EXR value is `exr` (to `tolerance`).
void expect_uniform(const Image& png_image, const Image& exr_image, int png, float exr,
                    float tolerance = 0) {
  ASSERT_EQ(png_image.rgb.size(), 16u * 12u * 3u);
  ASSERT_EQ(exr_image.rgb.size(), 16u * 12u * 3u);
  for (std::size_t i = 0; i < png_image.rgb.size(); ++i) {
    ASSERT_EQ(png_byte(png_image.rgb[i]), png) << "value " << i;
    if (tolerance == 0)
      ASSERT_FLOAT_EQ(exr_image.rgb[i], exr) << "value " << i;
    else
      ASSERT_NEAR(exr_image.rgb[i], exr, tolerance) << "value " << i;
  }
}

// The tone curve shapes the PNG only; the EXR holds the linear radiance.
TEST_F(CliTest, ToneCurvesApplyToThePngOnly) {
  const std::string white = "[1, 1, 1]";
  {
    SCOPED_TRACE("clamp");
    const fs::path scene = write_scene(
        uniform_wall(white, R"({"doppler": "off", "exposure": 0, "tonemap": "clamp"})"));
    const CommandResult r = render(scene);
    ASSERT_EQ(r.status, 0) << r.err;
    expect_uniform(*read_png(), *read_exr(), 255, 1.0f);
  }
  {
    // L / (1 + Y): Y of white is 1, so 1 becomes 0.5.
    SCOPED_TRACE("reinhard");
    const int expected = static_cast<int>(std::lround(255 * srgb_encode(1.0 / (1 + 1))));
    ASSERT_EQ(expected, 188);
    const fs::path scene = write_scene(
        uniform_wall(white, R"({"doppler": "off", "exposure": 0, "tonemap": "reinhard"})"));
    const CommandResult r = render(scene);
    ASSERT_EQ(r.status, 0) << r.err;
    expect_uniform(*read_png(), *read_exr(), expected, 1.0f);
  }
  {
    SCOPED_TRACE("filmic (a scene file's default)");
    auto filmic = [](double x) { return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14); };
    const int expected = static_cast<int>(std::lround(255 * srgb_encode(filmic(1))));
    ASSERT_NE(expected, 255);
    ASSERT_NE(expected, 188);
    const fs::path scene = write_scene(uniform_wall(white, R"({"doppler": "off", "exposure": 0})"));
    const CommandResult r = render(scene);
    ASSERT_EQ(r.status, 0) << r.err;
    expect_uniform(*read_png(), *read_exr(), expected, 1.0f);
  }
}

// "exposure": "auto" (a scene file's default) brings the upper quartile of the moving bodies'
// luminance (of the whole picture's, where none moves) to 0.5, unless the brightest 2 % would
// then pass the luminance the tone curve shows as 0.9: to within the meter's half a bin of
// 1/256 of an octave (kMetered, a factor 2^0.0028).
constexpr float kMetered = 0.002f;
TEST_F(CliTest, AutomaticExposure) {
  const auto expect_exr = [](const Image& image, float value) {
    for (std::size_t i = 0; i < image.rgb.size(); ++i)
      ASSERT_NEAR(image.rgb[i], value, kMetered * value) << "value " << i;
  };
  {
    SCOPED_TRACE("uniform grey 0.2");
    const fs::path scene = write_scene(uniform_wall("[0.2, 0.2, 0.2]", R"({"doppler": "off"})"));
    const CommandResult r = render(scene);
    ASSERT_EQ(r.status, 0) << r.err;
    expect_exr(*read_exr(), 0.5f);
    // Shown through the filmic curve (the EXR's value, within the meter's precision of 0.5).
    const float shown = read_exr()->rgb[0];
    const int png = static_cast<int>(std::lround(255 * srgb_encode(filmic_curve(shown))));
    const auto picture = read_png();  // held: a range over a temporary's member would dangle
    for (const float v : picture->rgb) ASSERT_EQ(png_byte(v), png);
  }
  {
    // A few very bright pixels (2 % of 192) do not set it: they clip, and the wall is still
    // brought to 0.5.
    SCOPED_TRACE("grey 0.2 with a small bright ball");
    const std::string wall = uniform_wall("[0.2, 0.2, 0.2]", R"({"doppler": "off"})");
    const fs::path scene = write_scene(edited(wall, "\"objects\": [{",
                                              "\"objects\": [{\"name\": \"spark\", "
                                              "\"shape\": {\"sphere\": {\"radius\": 0.3}}, "
                                              "\"position\": [0, 0, -3], "
                                              "\"material\": {\"color\": [50, 50, 50]}}, {"));
    const CommandResult r = render(scene);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto exr_image = read_exr();
    int wall_pixels = 0, bright_pixels = 0;
    for (std::size_t i = 0; i < exr_image->rgb.size(); i += 3) {
      if (exr_image->rgb[i] > 1) {
        ++bright_pixels;
      } else {
        ++wall_pixels;
        EXPECT_NEAR(exr_image->rgb[i], 0.5f, kMetered * 0.5f) << "pixel " << i / 3;
      }
    }
    EXPECT_EQ(bright_pixels, 4);  // the four around the centre
    EXPECT_EQ(wall_pixels + bright_pixels, 16 * 12);
  }
  {
    // Left half 0.1, right half 0.4: the upper quartile is on the right (a median would be
    // anywhere between), so the right half goes to 0.5 and the left to 0.125.
    SCOPED_TRACE("two halves");
    const std::string wall = uniform_wall("[0.4, 0.4, 0.4]", R"({"doppler": "off"})");
    const fs::path scene = write_scene(edited(
        edited(wall, "\"position\": [0, 0, -5]", "\"position\": [500, 0, -5]"), "\"objects\": [{",
        "\"objects\": [{\"name\": \"left\", "
        "\"shape\": {\"box\": {\"size\": [1000, 1000, 1]}}, "
        "\"position\": [-500, 0, -5], \"material\": {\"color\": [0.1, 0.1, 0.1]}}, {"));
    const CommandResult r = render(scene);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto exr_image = read_exr();
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 16; ++x)
        EXPECT_NEAR(exr_image->texel(x, y).g, x < 8 ? 0.125f : 0.5f, kMetered * 0.5f)
            << x << "," << y;
  }
  {
    // The luminance is Y of linear sRGB: green 0.5 has Y = 0.7152 * 0.5.
    SCOPED_TRACE("green");
    const fs::path scene = write_scene(uniform_wall("[0, 0.5, 0]", R"({"doppler": "off"})"));
    const CommandResult r = render(scene);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto exr_image = read_exr();
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 16; ++x) {
        const Rgb c = exr_image->texel(x, y);
        EXPECT_NEAR(c.g, 0.5 / 0.7152, kMetered * 0.7) << x << "," << y;
        EXPECT_EQ(c.r, 0.0f);
        EXPECT_EQ(c.b, 0.0f);
      }
  }
  {
    // A moving ball (0.05, colours kept: Doppler and searchlight off) before a wall at rest
    // (0.02): the ball is the subject, brought to 0.5, and the wall follows to 0.2; the whole
    // picture's upper quartile would have been the wall's.
    SCOPED_TRACE("a moving ball before a wall at rest");
    const std::string wall =
        uniform_wall("[0.02, 0.02, 0.02]", R"({"doppler": "off", "searchlight": "off"})");
    const fs::path scene = write_scene(edited(wall, "\"objects\": [{",
                                              "\"objects\": [{\"name\": \"ball\", "
                                              "\"shape\": {\"sphere\": {\"radius\": 1}}, "
                                              "\"position\": [0, 0, -3], \"time\": -3, "
                                              "\"velocity\": [0.5, 0, 0], "
                                              "\"material\": {\"color\": [0.05, 0.05, 0.05]}}, {"));
    const CommandResult r = render(scene);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto exr_image = read_exr();
    float lowest = 1e9f, highest = 0;
    for (std::size_t i = 0; i < exr_image->rgb.size(); i += 3)
      lowest = std::min(lowest, exr_image->rgb[i]), highest = std::max(highest, exr_image->rgb[i]);
    EXPECT_NEAR(highest, 0.5f, kMetered * 0.5f);
    EXPECT_NEAR(lowest, 0.2f, kMetered * 0.2f);
    // Before a brighter wall (0.2), under clamp: the ball would take the wall to 2, so the
    // wall, more than 2 % of the picture, is held at 0.9 and the ball shows at 0.225.
    const fs::path bright = write_scene(
        edited(edited(bytes_of(scene), "[0.02, 0.02, 0.02]", "[0.2, 0.2, 0.2]"),
               "\"searchlight\": \"off\"", "\"searchlight\": \"off\", \"tonemap\": \"clamp\""));
    ASSERT_EQ(render(bright).status, 0);
    const auto held = read_exr();
    lowest = 1e9f, highest = 0;
    for (std::size_t i = 0; i < held->rgb.size(); i += 3)
      lowest = std::min(lowest, held->rgb[i]), highest = std::max(highest, held->rgb[i]);
    EXPECT_NEAR(highest, 0.9f, kMetered * 0.9f);
    EXPECT_NEAR(lowest, 0.225f, kMetered * 0.225f);
  }
}

TEST_F(CliTest, ThreadCountDoesNotChangeTheImage) {
  const fs::path scene = write_scene(kScene);
  ASSERT_EQ(render(scene, "--samples 4").status, 0);
  const std::vector<float> all = read_exr()->rgb;
  const CommandResult one = render(scene, "--samples 4 --threads 1");
  ASSERT_EQ(one.status, 0) << one.err;
  EXPECT_EQ(read_exr()->rgb, all);
}

TEST_F(CliTest, ProgressBarOnlyOnATerminalAndNotWithQuiet) {
  const fs::path scene = write_scene(kScene);
  const std::string args =
      "render " + quoted(scene) + " -o " + quoted(png()) + " --width 128 --height 96";
  const CommandResult shown = test::run_lightcone_on_terminal(args);
  EXPECT_EQ(shown.status, 0) << shown.err;
  EXPECT_NE(shown.err.find("rendering ["), std::string::npos) << shown.err;
  EXPECT_NE(shown.err.find("100%"), std::string::npos) << shown.err;
  EXPECT_TRUE(fs::exists(png()));

  const CommandResult quiet = test::run_lightcone_on_terminal(args + " --quiet");
  EXPECT_EQ(quiet.status, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");

  // --stats with --quiet on a terminal: only the JSON line.
  const CommandResult stats = test::run_lightcone_on_terminal(args + " --quiet --stats");
  EXPECT_EQ(stats.status, 0) << stats.err;
  EXPECT_TRUE(stats.err.starts_with("{\"seconds\":")) << stats.err;
  EXPECT_EQ(line_count(stats.err), 1u) << stats.err;
}

// Every redraw of the bar is exactly as wide as the terminal, narrow or wide, so that it neither
// wraps nor leaves the last one's end.
TEST_F(CliTest, ProgressBarFitsTheTerminalsWidthExactly) {
  const fs::path scene = write_scene(kScene);
  const std::string args =
      "render " + quoted(scene) + " -o " + quoted(png()) + " --width 128 --height 96";
  for (const int columns : {12, 40, 41, 80, 157}) {
    SCOPED_TRACE(columns);
    const CommandResult shown = test::run_lightcone_on_terminal(args, columns);
    ASSERT_EQ(shown.status, 0) << shown.err;
    // The bar's redraws, each after a "\r", up to the newline that ends them.
    const std::string bar = shown.err.substr(0, shown.err.find("\r\n"));
    std::size_t redraws = 0;
    for (std::size_t at = bar.find('\r'); at != std::string::npos; ++redraws) {
      const std::size_t next = bar.find('\r', at + 1);
      const std::string drawn =
          bar.substr(at + 1, (next == std::string::npos ? bar.size() : next) - at - 1);
      EXPECT_EQ(drawn.size(), static_cast<std::size_t>(columns)) << '"' << drawn << '"';
      EXPECT_TRUE(drawn.starts_with(std::string("rendering [").substr(0, columns))) << drawn;
      at = next;
    }
    EXPECT_GE(redraws, 1u) << shown.err;
  }
}

}  // namespace
}  // namespace lightcone

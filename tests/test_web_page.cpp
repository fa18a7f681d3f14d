// The web page (web/, built by scripts/build-web.sh), judged from what web/test/drive_page.mjs
// saw in headless Chromium (the ctest fixture WebPage.DriveThePageInChromium runs it first):
// its pictures against `lightcone render --renderer raster`, its keys, links and dropped files,
// and the spectrum table it fits.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/color/sigmoid_polynomial.hpp"
#include "lightcone/frame/request_rules.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "support/raster_agreement.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

const fs::path kSeen = LIGHTCONE_WEB_TEST_OUTPUT;

nlohmann::json results() {
  std::ifstream in(kSeen / "results.json");
  if (!in) return nullptr;
  return nlohmann::json::parse(in, nullptr, false);
}

std::shared_ptr<Image> seen(const std::string& name) {
  const fs::path file = kSeen / name;
  if (!fs::exists(file)) return nullptr;
  return load_image_file(file);
}

// The largest difference of two PNGs' 8-bit levels, over every pixel and channel.
int largest_difference(const Image& a, const Image& b) {
  int worst = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const Rgb p = a.texel(x, y), q = b.texel(x, y);
      worst = std::max({worst, std::abs(test::png_level(p.r) - test::png_level(q.r)),
                        std::abs(test::png_level(p.g) - test::png_level(q.g)),
                        std::abs(test::png_level(p.b) - test::png_level(q.b))});
    }
  return worst;
}

// The page's picture of `scene` against the native raster renderer's, at 640x360, at the
// exposure `ev` (the page's own, 0 for most): the share of pixels within 4/255 off a one-pixel
// band along the bodies' outlines (the ray tracer's object ids mark them); with
// `bodies_alone`, also on the bodies' pixels alone.
void expect_page_agrees(const fs::path& scene, const std::string& page_png,
                        bool bodies_alone = false, double ev = 0) {
  const auto page = seen(page_png);
  ASSERT_NE(page, nullptr) << page_png << ": the page's picture is missing (see the fixture)";
  const fs::path dir = test::fresh_temp_dir("web-agreement");
  const std::string common =
      " --width 640 --height 360 --samples 1 --set render.exposure=" + std::to_string(ev) +
      " --quiet";
  const auto raster =
      test::run_lightcone("render " + test::quoted(scene) + common + " --renderer raster -o " +
                          test::quoted(dir / "raster.png"));
  ASSERT_EQ(raster.status, 0) << raster.err;
  const auto traced = test::run_lightcone("render " + test::quoted(scene) + common + " -o " +
                                          test::quoted(dir / "trace.png") + " --exr " +
                                          test::quoted(dir / "trace.exr") + " --aov object");
  ASSERT_EQ(traced.status, 0) << traced.err;
  const auto native = load_image_file(dir / "raster.png");
  const auto exr = load_image_file(dir / "trace.exr");
  ASSERT_EQ(page->width, 640);
  ASSERT_EQ(page->height, 360);
  ASSERT_EQ(native->width, 640);
  const std::vector<float>* object = nullptr;
  for (const NamedChannel& c : exr->channels)
    if (c.name == "object") object = &c.values;
  ASSERT_NE(object, nullptr);
  std::size_t compared = 0;
  const double share = test::share_within_4_off_outlines(*page, *native, *object, compared);
  std::printf("%s: the page within 4/255 of `render --renderer raster` on %.4f of %zu pixels\n",
              page_png.c_str(), share, compared);
  EXPECT_GE(share, 0.99) << page_png;
  EXPECT_GT(compared, 640u * 360u / 2) << page_png;
  if (bodies_alone) {
    const double bodies =
        test::share_within_4_off_outlines(*page, *native, *object, compared, true);
    std::printf("%s: on the bodies, %.4f of %zu pixels\n", page_png.c_str(), bodies, compared);
    EXPECT_GE(bodies, 0.99) << page_png;
    EXPECT_GT(compared, 5000u) << page_png;
  }
  fs::remove_all(dir);
}

const fs::path kScenes = fs::path(LIGHTCONE_SOURCE_DIR) / "scenes";

TEST(WebPage, DrawsTerrellAsTheNativeRasterRenderer) {
  expect_page_agrees(kScenes / "terrell.json", "terrell.png");
}

TEST(WebPage, DrawsStreetAsTheNativeRasterRenderer) {
  expect_page_agrees(kScenes / "street.json", "street.png");
}

// The hole's lensed sky, disk and stars, and the star field: their stars are the catalogue the
// page carries in its data (without it the page could not open either scene).
TEST(WebPage, DrawsTheBlackHoleAsTheNativeRasterRenderer) {
  expect_page_agrees(kScenes / "black-hole.json", "black-hole.png");
}

TEST(WebPage, DrawsTheStarsAsTheNativeRasterRenderer) {
  expect_page_agrees(kScenes / "stars.json", "stars.png");
}

// Every bundled scene opens from its link (#scene=NAME), with no message of a failure; a link to
// a scene the page cannot open says so in the page, and why, and shows street.
TEST(WebPage, OpensEveryBundledSceneFromItsLink) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  ASSERT_TRUE(r.contains("opened")) << "the page's scenes are missing (see the fixture)";
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().stem().string();
    SCOPED_TRACE(name);
    ++scenes;
    const auto& opened = r["opened"].value(name, nlohmann::json::object());
    EXPECT_EQ(opened.value("scene", "(not offered)"), name);
    EXPECT_EQ(opened.value("message", "").find("cannot be opened"), std::string::npos)
        << opened.value("message", "");
  }
  EXPECT_GE(scenes, 20);
  // The hole has no classical picture: the page gives the program's reason.
  SceneLoadReport report;
  const auto refused = scene_refused(
      load_scene_file(kScenes / "black-hole.json", {"render.relativity=false"}, report));
  ASSERT_TRUE(refused);
  const std::string message = r.value("unopened_message", "");
  EXPECT_EQ(message.rfind("black-hole cannot be opened: ", 0), 0u) << message;
  // (The program names the file by its path, the page by the path in its data.)
  const std::string reason = refused->substr(refused->find("black_hole: "));
  EXPECT_NE(message.find("/scenes/black-hole.json: " + reason), std::string::npos) << message;
  EXPECT_NE(message.find("Showing street instead."), std::string::npos) << message;
  EXPECT_EQ(r.value("unopened_shows", ""), "street");
}

// At its own, automatic exposure the page meters its frame as the native viewer does
// (FloatTarget::metered_exposure, the program's rule on one pixel of each 4 x 4 block): within
// 0.03 EV of the native metering of that frame (the page's WebGL picture and the native one
// agree within 4/255, a few per cent) and within 0.1 EV of the whole picture's, which
// `lightcone render --renderer raster` applies (a sixteenth of the pixels metered: the sixteen
// ways to pick them give EVs within 0.06 of it); its picture at that EV is the native one's.
TEST(WebPage, ExposesTerrellAsTheProgramDoes) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  ASSERT_TRUE(r.contains("terrell_auto_ev")) << "the page's EV is missing (see the fixture)";
  const double page_ev = r["terrell_auto_ev"].get<double>();
  Scene scene = test::load_repository_scene("terrell.json");
  scene.camera.width = 640, scene.camera.height = 360, scene.camera.samples = 1;
  ASSERT_TRUE(scene.render.auto_exposure);
  RasterStats whole;
  render_raster(scene, &whole);
  const double native = test::metered_frame_exposure(scene);
  std::printf("terrell's EV: the page %+.4f, the native viewer %+.4f, render %+.4f\n", page_ev,
              native, whole.exposure);
  EXPECT_NEAR(page_ev, native, 0.03);
  EXPECT_NEAR(page_ev, whole.exposure, 0.1);
  expect_page_agrees(kScenes / "terrell.json", "terrell-auto.png", false, page_ev);
}

// Lit by its lamps, with their shadows: the lit bodies' surfaces, then the lighting pass.
TEST(WebPage, DrawsStreetLitAsTheNativeRasterRenderer) {
  expect_page_agrees(kScenes / "street-lit.json", "street-lit.png");
}

// A scene of the user's own, chosen in the file dialog with the image it names.
TEST(WebPage, DrawsAUsersSceneAndItsImageAsTheNativeRasterRenderer) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  EXPECT_EQ(r.value("user_message", "?"), "");
  expect_page_agrees(kScenes / "texture-mapping.json", "texture-mapping.png");
}

// The same textures lit by a lamp under the spectral model: each sample fits its texel to a
// reflectance, from the columns of the coefficient table the page fitted for the texture.
TEST(WebPage, DrawsALitTextureUnderTheSpectralModelAsTheNativeRasterRenderer) {
  expect_page_agrees(kSeen / "lit-texture-mapping.json", "lit-texture-mapping.png");
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  EXPECT_EQ(r.value("lit_texture_message", "?"), "");  // no difference to warn of
}

// Shadows near a black hole: the page has no ray tracer, and meets the bodies along the curved
// shadow paths directly (DirectBodySegments), as the native program does through Embree.
TEST(WebPage, CastsShadowsNearABlackHoleAsTheNativeRasterRenderer) {
  expect_page_agrees(fs::path(LIGHTCONE_SOURCE_DIR) / "tests/data/hole-shadows.json",
                     "hole-shadows.png", true);
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  EXPECT_EQ(r.value("hole_shadows_message", "?"), "");  // no difference to warn of
  std::printf("the page's first frame of it: %.0f ms after the file was chosen\n",
              r.value("hole_shadows_ms", 0.0));
}

// The screenshot button downloads the canvas as a PNG named after the scene.
TEST(WebPage, TheScreenshotButtonDownloadsThePicture) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  EXPECT_EQ(r.value("screenshot_name", ""), "lightcone-terrell.png");
  const auto a = seen("screenshot-button.png"), b = seen("screenshot-canvas.png");
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->width, 640);
  EXPECT_EQ(largest_difference(*a, *b), 0);
}

TEST(WebPage, TheWKeyRaisesTheSpeedAndChangesThePicture) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  const double before = r.value("beta_before_key", 0.0), after = r.value("beta_after_key", 0.0);
  EXPECT_NEAR(before, 0.8, 1e-9);  // street.json's camera
  // One step of the native viewer's W: a tenth of rapidity more.
  EXPECT_NEAR(after, std::tanh(std::atanh(0.8) + 0.1), 1e-9);
  const auto a = seen("key-before.png"), b = seen("key-after.png");
  ASSERT_TRUE(a && b);
  EXPECT_GT(largest_difference(*a, *b), 20);
}

// A drag to the left by 100 pixels turns the view by 0.4 radians to the left (as the native
// viewer's drag), and the link says so; a finger holding the joystick up speeds the camera up.
// R, as in the native viewer: after a boost and a turn, the scene's camera again, and its picture.
TEST(WebPage, RGoesBackToTheScenesCamera) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  // street's camera moves at 0.8c; W took it faster.
  EXPECT_GT(r.value("beta_before_reset", -1.0), r.value("beta_before_key", 2.0));
  EXPECT_EQ(r.value("beta_after_reset", -1.0), r.value("beta_before_key", 2.0));
  const std::string hash = r.value("hash_after_reset", "");
  EXPECT_NE(hash.find("yaw=0.0000"), std::string::npos) << hash;
  EXPECT_EQ(hash.find("beta="), std::string::npos) << hash;
  const auto reset = seen("reset.png"), street = seen("street.png");
  ASSERT_TRUE(reset && street);
  EXPECT_EQ(largest_difference(*reset, *street), 0);
}

// Near a hole the page's clock is the native viewer's (viewer/flight.hpp's default_time_scale):
// infall's clocks fall in 10 s, not in over half a minute. The proper time shown runs that much
// faster than the frames' time (each frame's step is at most 0.1 s, so not faster than the wall).
TEST(WebPage, NearAHoleTheClockRunsAtTheViewersScale) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  ASSERT_TRUE(r.contains("infall_clock"));
  const auto& clock = r["infall_clock"];
  // The clocks' fall from rest at 10M, (pi/2) sqrt(10^3 / 2) of their own time, in 10 s.
  const double scale = std::numbers::pi / 2 * std::sqrt(1000.0 / 2) / 10;
  EXPECT_NEAR(clock.value("time_scale", 0.0), scale, 1e-9);
  std::printf("infall in the page: %.2f of proper time in %.2f s\n",
              clock.value("proper_time", 0.0), clock.value("wall_seconds", 0.0));
  EXPECT_GT(clock.value("proper_time", 0.0), 0);
  EXPECT_LE(clock.value("proper_time", 0.0), scale * clock.value("wall_seconds", 0.0) * 1.01);
}

// The page's probes are the program's: each is what `lightcone locate --pixel` says of that
// pixel of the same picture (640 x 360); a link keeps them, the readouts are text in the page
// with the ruler between two, a click adds one, X clears them.
TEST(WebPage, ProbesAPixelAsLocateDoes) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  ASSERT_TRUE(r.contains("probes")) << "the probes are missing (see the fixture)";
  const auto& from_link = r["probes"]["from_link"];
  const auto& clicked = r["probes"]["clicked"];
  ASSERT_EQ(from_link["probes"].size(), 2u);
  ASSERT_EQ(clicked["probes"].size(), 1u);
  EXPECT_EQ(from_link["probe"], "466.5,171.5;289.5,180.5");
  EXPECT_EQ(from_link["marks"], 2);
  const std::string text = from_link["text"];
  EXPECT_NE(text.find("1: crate at ("), std::string::npos) << text;
  EXPECT_NE(text.find("2: ball at ("), std::string::npos) << text;
  EXPECT_NE(text.find("degrees apart"), std::string::npos) << text;
  EXPECT_EQ(clicked["probes"][0]["meets"], "sky");
  EXPECT_EQ(clicked["probe"], "100.5,20.5");
  EXPECT_EQ(r["probes"]["cleared"]["text"], "");
  EXPECT_TRUE(r["probes"]["cleared"]["probe"].is_null());
  EXPECT_EQ(r["probes"]["cleared"]["marks"], 0);
  std::vector<nlohmann::json> all(from_link["probes"].begin(), from_link["probes"].end());
  all.push_back(clicked["probes"][0]);
  for (const nlohmann::json& probe : all) {
    const double x = probe["pixel"][0], y = probe["pixel"][1];
    const auto cli = test::run_lightcone(
        fmt::format("locate '{}' --pixel {},{} --set camera.width=640 --set camera.height=360",
                    (kScenes / "terrell.json").string(), x, y));
    ASSERT_EQ(cli.status, 0) << cli.err;
    const auto native = nlohmann::json::parse(cli.out);
    ASSERT_EQ(native.size(), probe.size());
    for (const auto& [key, value] : native.items()) {
      SCOPED_TRACE(fmt::format("pixel {}, {}: {}", x, y, key));
      const auto near = [](double a, double b) { EXPECT_NEAR(a, b, 1e-9 * (1 + std::abs(b))); };
      if (value.is_number()) {
        near(probe[key].get<double>(), value.get<double>());
      } else if (value.is_array()) {
        for (std::size_t k = 0; k < value.size(); ++k)
          near(probe[key][k].get<double>(), value[k].get<double>());
      } else if (value.is_object()) {
        for (std::size_t k = 0; k < 3; ++k)
          near(probe[key]["direction"][k].get<double>(), value["direction"][k].get<double>());
      } else {
        EXPECT_EQ(probe[key], value);
      }
    }
  }
}

TEST(WebPage, ADragTurnsTheViewAndTheJoystickSpeedsUp) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  EXPECT_NEAR(r.value("yaw_after_drag", 0.0), 0.4, 1e-3);
  const auto a = seen("key-before.png"), b = seen("dragged.png");
  ASSERT_TRUE(a && b);
  EXPECT_GT(largest_difference(*a, *b), 20);
  EXPECT_TRUE(r.value("joystick_shown", false));  // on a touch screen
  ASSERT_TRUE(r.contains("joystick_beta"));
  EXPECT_GT(r["joystick_beta"][1].get<double>(), r["joystick_beta"][0].get<double>() + 0.01);
}

TEST(WebPage, APresetLinkGivesThePictureOfItsSwitchesSetByHand) {
  const auto a = seen("preset.png"), b = seen("by-hand.png");
  ASSERT_TRUE(a && b);
  EXPECT_EQ(largest_difference(*a, *b), 0);
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  const std::string hash = r.value("hash_by_hand", "");
  EXPECT_NE(hash.find("doppler=off"), std::string::npos) << hash;
  EXPECT_NE(hash.find("beta=0.9"), std::string::npos) << hash;
  // And the switches make a difference: street without colour shift at 0.9c is not street.
  const auto street = seen("street.png");
  ASSERT_TRUE(street);
  EXPECT_GT(largest_difference(*a, *street), 20);
}

TEST(WebPage, ADroppedSceneWithAnErrorSaysWhereAndKeepsThePreviousScene) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  const std::string message = r.value("drop_message", "");
  EXPECT_EQ(message.rfind("bad.json:3: objectz: unknown key", 0), 0u) << message;
  const auto a = seen("drop-before.png"), b = seen("drop-after.png");
  ASSERT_TRUE(a && b);
  EXPECT_EQ(largest_difference(*a, *b), 0);
}

// The page is a door to the library's rules (frame/request_rules.hpp): each scene they refuse
// is refused there with the program's message (tests/test_request_rules.cpp), the dropped file
// named as the program names its file.
TEST(WebPage, RefusesTheScenesTheProgramRefusesWithItsMessage) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  ASSERT_TRUE(r.contains("refusals"));
  std::ifstream in(fs::path(LIGHTCONE_SOURCE_DIR) / "tests/data/refused-requests.json");
  const nlohmann::json cases = nlohmann::json::parse(in)["cases"];
  int scenes = 0;
  for (const auto& c : cases) {
    if (c.contains("render") || c.contains("locate")) continue;
    const std::string name = c["name"];
    SCOPED_TRACE(name);
    ++scenes;
    EXPECT_EQ(r["refusals"].value(name, "(not dropped)"),
              name + ".json: " + c["refusal"].get<std::string>());
  }
  EXPECT_GE(scenes, 3);
}

// The page fits the RGB-to-spectrum table's columns as it needs them, with the same fit as the
// native build's table: the same coefficients, but for WebAssembly's libm and sums (relative
// 1e-5; a colour's spectrum then differs by far less than a level of 8 bits).
TEST(WebPage, FitsTheNativeSpectrumTable) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  ASSERT_TRUE(r.contains("columns"));
  constexpr int res = kRgbToSpectrumRes;
  double worst = 0;
  for (const auto& [key, values] : r["columns"].items()) {
    int l = 0, j = 0, i = 0;
    ASSERT_EQ(std::sscanf(key.c_str(), "%d,%d,%d", &l, &j, &i), 3);
    ASSERT_EQ(values.size(), 3u * res);
    const float* table = detail::rgb_to_spectrum_table(l, j, i);
    for (int k = 0; k < res; ++k)
      for (int n = 0; n < 3; ++n) {
        const double native = table[rgb_to_spectrum_cell(l, k, j, i, res) + n];
        const double page = values[3 * k + n].get<double>();
        worst = std::max(worst, std::abs(page - native) / std::max(1.0, std::abs(native)));
      }
  }
  std::printf("the page's table columns: largest relative difference %.3g\n", worst);
  EXPECT_LT(worst, 1e-5);
}

TEST(WebPage, ReportsItsFrameRateAndLoadTimeWithNoConsoleError) {
  const auto r = results();
  ASSERT_TRUE(r.is_object());
  const double fps = r.value("fps", 0.0);
  std::printf(
      "the page on street.json at 640x360 (SwiftShader): %.1f fps; first frame after "
      "%.0f ms (terrell %.0f ms)\n",
      fps, r["load_ms"].value("street", 0.0), r["load_ms"].value("terrell", 0.0));
  EXPECT_GT(fps, 0.5);
  // `lightcone view scenes/street.json --benchmark 100 --width 640 --height 360`'s flight.
  const auto& benchmark = r["benchmark"];
  ASSERT_TRUE(benchmark.is_object()) << r.dump(1);
  std::printf("its --benchmark 100 flight: %.1f fps (%zu triangles a frame)\n",
              benchmark.value("fps", 0.0), benchmark.value("triangles", std::size_t{0}));
  EXPECT_GT(benchmark.value("triangles", std::size_t{0}), 1000u);
  EXPECT_TRUE(r["console"].empty()) << r["console"].dump(1);
}

}  // namespace
}  // namespace lightcone

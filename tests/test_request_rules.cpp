// The library's rules for what may be asked of a scene (frame/request_rules.hpp), and the
// program's door to them: each case of tests/data/refused-requests.json is refused by the rule
// with its message, and `lightcone` prints that message, exits with 2 and writes nothing. The
// Python module (python/tests/test_lightcone.py) and the web page (tests/test_web_page.cpp) are
// held to the same cases and messages.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lightcone/frame/request_rules.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/locate_json.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

nlohmann::json refused_cases() {
  std::ifstream in(fs::path(LIGHTCONE_SOURCE_DIR) / "tests/data/refused-requests.json");
  return nlohmann::json::parse(in)["cases"];
}

// The case's scene written to DIR/NAME.json.
fs::path written(const nlohmann::json& c, const fs::path& dir) {
  const fs::path file = dir / (c["name"].get<std::string>() + ".json");
  test::write_text(file, c["scene"].dump(1));
  return file;
}

std::vector<Aov> aovs_of(const nlohmann::json& c) {
  std::vector<Aov> aovs;
  if (c.contains("render"))
    for (const auto& name : c["render"]["aovs"])
      aovs.push_back(*aov_from_name(name.get<std::string>()));
  return aovs;
}

bool raster(const nlohmann::json& c) {
  return c.contains("render") && c["render"].value("renderer", "trace") == "raster";
}

Scene loaded(const fs::path& file) {
  SceneLoadReport report;
  return load_scene_file(file, {}, report);
}

TEST(RequestRules, EachCaseIsRefusedByItsRuleWithItsMessage) {
  const fs::path dir = test::fresh_temp_dir("request-rules");
  const nlohmann::json cases = refused_cases();
  ASSERT_GE(cases.size(), 5u);
  for (const auto& c : cases) {
    SCOPED_TRACE(c["name"].get<std::string>());
    const fs::path file = written(c, dir);
    const Scene scene = loaded(file);
    const std::string expected = file.string() + ": " + c["refusal"].get<std::string>();
    if (c.contains("locate")) {
      LocateQuery query;
      query.kind = LocateQuery::Kind::WorldPoint;
      const auto& p = c["locate"]["world_point"];
      query.value = {p[0].get<double>(), p[1].get<double>(), p[2].get<double>()};
      EXPECT_EQ(locate_refused(scene, query).value_or("(accepted)"), expected);
      EXPECT_EQ(render_refused(scene, {}), std::nullopt);  // the scene itself may be drawn
    } else {
      EXPECT_EQ(render_refused(scene, {.aovs = aovs_of(c)}).value_or("(accepted)"), expected);
      // The ray tracer itself refuses it too: no picture of it ever leaves the library (the
      // raster renderer is asked for no output variables, and refuses the scenes alike).
      if (!raster(c)) {
        RenderOptions options;
        options.aovs = aovs_of(c);
        EXPECT_THROW(render_image(scene, options), std::invalid_argument);
      }
    }
  }
}

TEST(RequestRules, TheProgramShowsTheRulesMessageAndWritesNothing) {
  const fs::path dir = test::fresh_temp_dir("request-rules-cli");
  for (const auto& c : refused_cases()) {
    SCOPED_TRACE(c["name"].get<std::string>());
    const fs::path file = written(c, dir);
    std::string arguments;
    const fs::path out = dir / "out.exr";
    if (c.contains("locate")) {
      const auto& p = c["locate"]["world_point"];
      arguments = "locate " + test::quoted(file) + " --world-point " + p[0].dump() + "," +
                  p[1].dump() + "," + p[2].dump();
    } else {
      arguments = "render " + test::quoted(file) + " -o " + test::quoted(out);
      for (const auto& name :
           c.value("render", nlohmann::json::object()).value("aovs", nlohmann::json::array()))
        arguments += " --aov " + name.get<std::string>();
      if (raster(c)) arguments += " --renderer raster";
    }
    const std::string message =
        "lightcone: " + file.string() + ": " + c["refusal"].get<std::string>() + "\n";
    const test::CommandResult r = test::run_lightcone(arguments);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, message);
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(fs::exists(out));
    // `check` says ok only of a scene the renderers draw.
    if (!c.contains("render") && !c.contains("locate")) {
      const test::CommandResult checked = test::run_lightcone("check " + test::quoted(file));
      EXPECT_EQ(checked.status, 2);
      EXPECT_EQ(checked.err, message);
    }
  }
}

// The names a render request takes are the library's too: the program refuses another with the
// rule's message (the Python module too: python/tests/test_request_rules.py).
TEST(RequestRules, TheRendererAndTessellationNamesAreTheLibrarys) {
  for (const char* name : {"trace", "raster"}) EXPECT_EQ(renderer_refused(name), std::nullopt);
  for (const char* name : {"cpu", "gpu", "auto"})
    EXPECT_EQ(tessellation_refused(name), std::nullopt);
  EXPECT_EQ(tessellation_named("cpu"), RasterTessellation::kCpu);
  EXPECT_EQ(tessellation_named("gpu"), RasterTessellation::kGpu);
  EXPECT_EQ(tessellation_named("auto"), RasterTessellation::kAuto);
  const std::string scene = test::quoted(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes/terrell.json");
  const fs::path out = test::fresh_temp_dir("request-rules-names") / "out.png";
  const struct {
    std::string arguments, message;
  } cases[] = {{" --renderer bogus", *renderer_refused("bogus")},
               {" --renderer raster --tessellation nope", *tessellation_refused("nope")}};
  for (const auto& c : cases) {
    const test::CommandResult r =
        test::run_lightcone("render " + scene + " -o " + test::quoted(out) + c.arguments);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

// The horizon rule holds at every mass the kernels take (they work in units of M): a point
// outside the horizon of a hole of 1e-300 is located, one inside a hole of 1e300 refused.
TEST(RequestRules, TheHorizonRuleIsScaleFree) {
  for (const double mass : {1e-300, 1.0, 1e300}) {
    SCOPED_TRACE(mass);
    Scene scene;
    scene.black_hole = BlackHole{};
    scene.black_hole->mass = mass;
    scene.black_hole->position = {mass, 0, 0};
    LocateQuery query;
    query.kind = LocateQuery::Kind::WorldPoint;
    query.value = {mass, 2.5 * mass, 0};
    EXPECT_EQ(locate_refused(scene, query), std::nullopt);
    query.value = {mass, 1.5 * mass, 0};
    EXPECT_NE(locate_refused(scene, query).value_or("").find("inside its horizon"),
              std::string::npos);
  }
}

// What the scene format's loader refuses, a scene changed in code is refused for by the same
// limits: no renderer is handed a camera it cannot draw (0 samples gave an all-NaN picture).
TEST(RequestRules, ASceneChangedInCodeIsHeldToTheCamerasLimits) {
  const fs::path dir = test::fresh_temp_dir("request-rules-camera");
  const fs::path file = dir / "ball.json";
  test::write_text(file, R"({"camera": {"position": [0, 0, 0], "width": 8, "height": 6},
    "objects": [{"name": "ball", "shape": {"sphere": {"radius": 1}}, "position": [0, 0, -5]}]})");
  Scene scene = loaded(file);
  EXPECT_EQ(scene_refused(scene), std::nullopt);
  for (const int samples : {0, -1, kMaxCameraSamples + 1}) {
    Scene changed = scene;
    changed.camera.samples = samples;
    EXPECT_EQ(scene_refused(changed).value_or("(accepted)"),
              file.string() + ": camera.samples: must be an integer from 1 to 65536, got " +
                  std::to_string(samples));
    EXPECT_THROW(render_image(changed, {}), std::invalid_argument);
  }
  Scene wide = scene;
  wide.camera.width = kMaxCameraSide + 1;
  EXPECT_NE(
      scene_refused(wide).value_or("").find("camera.width: must be an integer from 1 to 16384"),
      std::string::npos);
  Scene in_code;  // built in code: no source to name
  in_code.camera.samples = 0;
  EXPECT_EQ(scene_refused(in_code).value_or("").rfind("the scene: camera.samples: ", 0), 0u);
}

// A picture with a value beyond a float's range is refused by the library, not handed out.
TEST(RequestRules, NoNonFinitePictureLeavesTheLibrary) {
  const fs::path dir = test::fresh_temp_dir("request-rules-picture");
  const fs::path file = dir / "ball.json";
  test::write_text(file, R"({"camera": {"position": [0, 0, 0], "width": 8, "height": 6},
    "objects": [{"name": "ball", "shape": {"sphere": {"radius": 1}}, "position": [0, 0, -5],
                 "material": {"color": [1, 1, 1]}}],
    "render": {"exposure": 1000}})");
  const Scene scene = loaded(file);
  try {
    render_image(scene, {});
    ADD_FAILURE() << "a picture of radiance times 2^1000 was handed out";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(file.string() + ": the render has ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("non-finite values"), std::string::npos) << e.what();
  }
  Image image;
  image.width = 2, image.height = 1;
  image.rgb = {0, 1, 2, 3, 4, std::numeric_limits<float>::quiet_NaN()};
  // (expose counts the values not finite as it scales; at EV 0 it only counts)
  EXPECT_NE(
      picture_refused(scene, expose(image, 0), 0).value_or("").find("has 1 non-finite value (NaN"),
      std::string::npos);
  image.rgb.back() = 5;
  EXPECT_EQ(picture_refused(scene, expose(image, 0), 0), std::nullopt);
}

// Near a black hole, a point no light leaves for the camera has no image: locate then gives no
// direction and no shift rather than made-up ones ([0, 0, 0] and 1 were printed).
TEST(RequestRules, APointWithNoImageHasNoDirectionNorShift) {
  Scene scene;
  scene.black_hole = BlackHole{};
  const auto json = nlohmann::json::parse(locate_json(LocateResult{}, scene));
  EXPECT_TRUE(json["direction"].is_null());
  EXPECT_TRUE(json["doppler"].is_null());
  EXPECT_TRUE(json["pixel"].is_null());
  EXPECT_TRUE(json["images"].empty());
  scene.black_hole.reset();  // flat space: every point has its one image
  EXPECT_FALSE(nlohmann::json::parse(locate_json(LocateResult{}, scene))["direction"].is_null());
}

}  // namespace
}  // namespace lightcone

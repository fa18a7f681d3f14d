// Tests of the JSON scene format (docs/scene-format.md): how a file maps onto the scene model,
// --set overrides, and that every kind of bad input is an InputError whose message names the
// file, the line and the JSON path ("FILE:LINE: PATH: what is wrong").
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "../fuzz/fuzz_support.hpp"  // how the fuzzer splits its inputs
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/json_locator.hpp"
#include "lightcone/io/scene_file.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

// A single triangle, and the same with one degenerate (repeated-vertex) triangle added.
constexpr const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
constexpr const char* kTriangleObjWithDegenerate = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 2\n";

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class SceneFileTest : public ::testing::Test {
 protected:
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) {
    const fs::path file = dir_ / name;
    fs::create_directories(file.parent_path());
    test::write_text(file, text);
    return file;
  }

  // A 2 x 1 PNG of the two linear colours `rgb` holds, beside the scene.
  void write_two_texel_png(const std::string& name, std::vector<float> rgb) {
    Image image;
    image.width = 2;
    image.height = 1;
    image.rgb = std::move(rgb);
    write_images(image, dir_ / name, std::nullopt);
  }

  Scene load(const std::string& text, const std::vector<std::string>& overrides = {}) {
    report_ = {};
    return load_scene_file(write("scene.json", text), overrides, report_);
  }

  // The message of the InputError that loading `text` throws, or "" when it loads.
  std::string error(const std::string& text, const std::vector<std::string>& overrides = {}) {
    try {
      load(text, overrides);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  // Expects "DIR/scene.json:LINE: PATH: ..." with `fragment` somewhere in the description.
  void expect_error(const std::string& text, int line, const std::string& path,
                    const std::string& fragment = "") {
    const std::string message = error(text);
    const std::string prefix =
        fmt::format("{}:{}: {}: ", (dir_ / "scene.json").string(), line, path);
    EXPECT_EQ(message.substr(0, prefix.size()), prefix) << message;
    EXPECT_NE(message.find(fragment, prefix.size()), std::string::npos) << message;
  }

  // Expects "--set PATH: ..." with `fragment` in the description.
  void expect_set_error(const std::string& text, const std::vector<std::string>& overrides,
                        const std::string& path, const std::string& fragment = "") {
    const std::string message = error(text, overrides);
    const std::string prefix = "--set " + path + ": ";
    EXPECT_EQ(message.substr(0, prefix.size()), prefix) << message;
    EXPECT_NE(message.find(fragment, prefix.size()), std::string::npos) << message;
  }

  fs::path dir_ = test::fresh_temp_dir("scene-file");
  SceneLoadReport report_;
};

// Wraps one object (given on the third line) in a valid scene.
std::string with_object(const std::string& object) {
  return "{\n  \"camera\": {\"position\": [0, 0, 5]},\n  \"objects\": [" + object + "]\n}";
}

void expect_rgb(const Rgb& c, float r, float g, float b) {
  EXPECT_FLOAT_EQ(c.r, r);
  EXPECT_FLOAT_EQ(c.g, g);
  EXPECT_FLOAT_EQ(c.b, b);
}

void expect_vec(const Vec3& v, double x, double y, double z, double tolerance = 1e-12) {
  EXPECT_NEAR(v.x, x, tolerance);
  EXPECT_NEAR(v.y, y, tolerance);
  EXPECT_NEAR(v.z, z, tolerance);
}

// ---------------------------------------------------------------------------------------------
// Valid scenes

TEST_F(SceneFileTest, FullSceneMapsOntoTheModel) {
  const Scene s = load(R"({
    "$schema": "../schema/scene.schema.json",
    "camera": {"position": [1, 2, 3], "time": 4, "velocity": [0, 0, -0.5],
               "forward": [0, 0, -2], "up": [0, 3, 0], "fov": 75, "width": 320,
               "height": 200, "samples": 4},
    "objects": [
      {"name": "ball", "shape": {"sphere": {"radius": 2}}, "position": [0, 1, -10],
       "time": -1, "velocity": [0.6, 0, 0], "material": {"color": [1, 0.5, 0.25], "unlit": true}},
      {"name": "crate", "shape": {"box": {"size": [1, 2, 3]}}, "scale": 2,
       "rotation": {"axis": [0, 0, 2], "degrees": 90},
       "material": {"checker": {"size": 0.5, "colors": [[1, 1, 1], [0, 0, 0.5]]}}},
      {"name": "floor", "shape": {"plane": {"size": [10, 20]}}, "scale": [1, 2, 3]}
    ],
    "sky": {"grid": {"spacing": 30, "line_width": 1, "color": [1, 0, 0],
                     "background": [0, 0, 0.1]},
            "velocity": [0, 0.3, 0], "rotation": {"axis": [1, 0, 0], "degrees": 180}},
    "render": {"relativity": false, "light_delay": false, "exposure": -1.5}
  })");

  const Camera& c = s.camera;
  expect_vec(c.world_line.position, 1, 2, 3);
  EXPECT_EQ(c.world_line.time, 4);
  expect_vec(c.world_line.velocity, 0, 0, -0.5);
  expect_vec(c.forward, 0, 0, -1);  // directions are normalized
  expect_vec(c.up, 0, 1, 0);
  EXPECT_EQ(c.fov_degrees, 75);
  EXPECT_EQ(c.width, 320);
  EXPECT_EQ(c.height, 200);
  EXPECT_EQ(c.samples, 4);

  ASSERT_EQ(s.objects.size(), 3u);
  const Object& ball = s.objects[0];
  EXPECT_EQ(ball.name, "ball");
  EXPECT_EQ(std::get<Sphere>(ball.shape).radius, 2);
  expect_vec(ball.world_line.position, 0, 1, -10);
  EXPECT_EQ(ball.world_line.time, -1);
  expect_vec(ball.world_line.velocity, 0.6, 0, 0);
  expect_rgb(std::get<SolidColor>(ball.material.pattern).color, 1, 0.5f, 0.25f);
  EXPECT_TRUE(ball.material.unlit);

  const Object& crate = s.objects[1];
  expect_vec(std::get<Box>(crate.shape).size, 1, 2, 3);
  expect_vec(crate.scale, 2, 2, 2);
  // 90 degrees about +z, right-handed: x -> y, y -> -x.
  expect_vec(crate.rotation * Vec3{1, 0, 0}, 0, 1, 0);
  expect_vec(crate.rotation * Vec3{0, 1, 0}, -1, 0, 0);
  const Checker& checker = std::get<Checker>(crate.material.pattern);
  EXPECT_EQ(checker.size, 0.5);
  expect_rgb(checker.colors[0], 1, 1, 1);
  expect_rgb(checker.colors[1], 0, 0, 0.5f);

  const Object& floor = s.objects[2];
  EXPECT_EQ(std::get<Plane>(floor.shape).size_x, 10);
  EXPECT_EQ(std::get<Plane>(floor.shape).size_z, 20);
  expect_vec(floor.scale, 1, 2, 3);

  const SkyGrid& grid = std::get<SkyGrid>(s.sky.pattern);
  EXPECT_EQ(grid.spacing_degrees, 30);
  EXPECT_EQ(grid.line_width_degrees, 1);
  expect_rgb(grid.line_color, 1, 0, 0);
  expect_rgb(grid.background, 0, 0, 0.1f);
  expect_vec(s.sky.velocity, 0, 0.3, 0);
  expect_vec(s.sky.rotation * Vec3{0, 1, 0}, 0, -1, 0);

  EXPECT_FALSE(s.render.relativity);
  EXPECT_FALSE(s.render.light_delay);
  EXPECT_EQ(s.render.exposure, -1.5);
  EXPECT_TRUE(report_.warnings.empty());
}

// A scene given as text (the Python module's Scene.from_dict): the same scene as from its file,
// relative paths beside the name it is given, and errors located in that name.
TEST_F(SceneFileTest, SceneTextLoadsAsItsFileWould) {
  write_two_texel_png("sky.png", {1, 0, 0, 0, 0, 1});
  const std::string text = R"({
  "camera": {"position": [0, 0, 0], "velocity": [0, 0, -0.5]},
  "sky": {"image": "sky.png"}
})";
  const Scene from_file = load(text);
  SceneLoadReport report;
  const Scene from_text =
      load_scene_text(text, dir_ / "made-in-code.json", {"camera.fov=50"}, report);
  EXPECT_EQ(from_text.camera.world_line.velocity.z, from_file.camera.world_line.velocity.z);
  EXPECT_EQ(from_text.camera.fov_degrees, 50);
  ASSERT_TRUE(std::holds_alternative<SkyImage>(from_text.sky.pattern));
  try {
    load_scene_text("{\n  \"camera\": {\"position\": [0, 0, 0], \"fov\": 200}\n}",
                    dir_ / "made-in-code.json", {}, report);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "made-in-code.json").string() +
                                         ":2: camera.fov: must be between 0 and 180"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(SceneFileTest, CameraMotionAndProperTimeSelectTheObservation) {
  // From rest, proper acceleration 0.5 along -z for 2 units of proper time, observed at proper
  // time 1.5: t = sinh(0.75) / 0.5, z = -(cosh(0.75) - 1) / 0.5, speed tanh(0.75).
  const Scene accelerated = load(R"({
  "camera": {"position": [1, 2, 3], "time": 4,
             "motion": {"phases": [{"duration": 2, "acceleration": [0, 0, -0.5]}]},
             "proper_time": 1.5},
  "objects": []
})");
  const WorldLine& w = accelerated.camera.world_line;
  EXPECT_NEAR(w.time, 4 + std::sinh(0.75) / 0.5, 1e-12);
  EXPECT_NEAR(w.position.x, 1, 1e-12);
  EXPECT_NEAR(w.position.z, 3 - (std::cosh(0.75) - 1) / 0.5, 1e-12);
  EXPECT_NEAR(w.velocity.z, -std::tanh(0.75), 1e-14);
  EXPECT_EQ(accelerated.camera.motion.phases.size(), 1u);
  EXPECT_EQ(accelerated.camera.motion.proper_time, 1.5);
  // Inertial, with a proper time: gamma tau later, gamma v tau further.
  const Scene inertial = load(R"({
  "camera": {"position": [0, 0, 0], "time": 1, "velocity": [0.6, 0, 0], "proper_time": 2},
  "objects": []
})");
  EXPECT_NEAR(inertial.camera.world_line.time, 1 + 1.25 * 2, 1e-12);
  EXPECT_NEAR(inertial.camera.world_line.position.x, 0.6 * 1.25 * 2, 1e-12);
  EXPECT_NEAR(inertial.camera.world_line.velocity.x, 0.6, 1e-15);
}

TEST_F(SceneFileTest, BadCameraMotionIsLocated) {
  const auto with_motion = [](const std::string& motion) {
    return "{\n  \"camera\": {\"position\": [0, 0, 0],\n    \"motion\": " + motion +
           "},\n  \"objects\": []\n}";
  };
  expect_error(with_motion(R"({"phases": [{"duration": 1, "acceleration": [0, 0, 0]}]})"), 3,
               "camera.motion.phases[0].acceleration", "must not be zero");
  expect_error(with_motion(R"({"phases": [{"duration": -1, "acceleration": [1, 0, 0]}]})"), 3,
               "camera.motion.phases[0].duration", "greater than 0");
  expect_error(with_motion(R"({"phases": [{"acceleration": [1, 0, 0]}]})"), 3,
               "camera.motion.phases[0]", "needs \"duration\"");
  expect_error(
      with_motion(R"({"phases": [{"duration": 1, "acceleration": [1, 0, 0], "jerk": 1}]})"), 3,
      "camera.motion.phases[0].jerk", "unknown key");
  expect_error(with_motion(R"({"keyframes": []})"), 3, "camera.motion.keyframes",
               "must be a non-empty array");
  expect_error(with_motion(R"({"phases": 3})"), 3, "camera.motion.phases", "must be an array");
  // So fast by the phase's end that double precision cannot hold it: tanh(100) rounds to 1.
  // (The whole world-line is held to the limit, not only the observation.)
  expect_error(with_motion(R"({"phases": [{"duration": 100, "acceleration": [1, 0, 0]}]},
    "proper_time": 50)"),
               3, "camera.motion.phases[0]", "too close to the speed of light");
  expect_error(
      "{\n  \"camera\": {\"position\": [0, 0, 0],\n    \"proper_time\": \"soon\"},\n"
      "  \"objects\": []\n}",
      3, "camera.proper_time", "must be a number");
}

TEST_F(SceneFileTest, KeyframedCameraObservesAtItsProperTime) {
  // Two keys make uniform motion at 0.6: proper time 2 is world time 2.5, at x = 1.5.
  const Scene s = load(R"({
  "camera": {"motion": {"keyframes": [{"time": 1, "position": [0, 0, 0]},
                                      {"time": 6, "position": [3, 0, 0]}]},
             "proper_time": 2},
  "objects": []
})");
  EXPECT_NEAR(s.camera.world_line.time, 1 + 2.5, 1e-12);
  EXPECT_NEAR(s.camera.world_line.position.x, 1.5, 1e-12);
  EXPECT_NEAR(s.camera.world_line.velocity.x, 0.6, 1e-12);
  expect_error(R"({
  "camera": {"position": [0, 0, 0],
    "motion": {"keyframes": [{"time": 1, "position": [0, 0, 0]}]}},
  "objects": []
})",
               2, "camera.position", "must not be given with motion.keyframes");
}

TEST_F(SceneFileTest, BodyMotionAndSpinAreReadAndBadOnesLocated) {
  const Scene s = load(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "position": [1, 0, 0], "velocity": [0.5, 0, 0],
    "motion": {"phases": [{"duration": 2, "acceleration": [0, 0.1, 0]}]},
    "spin": {"axis": [0, 2, 0], "rate": 18}})"));
  ASSERT_EQ(s.objects[0].motion.phases.size(), 1u);
  expect_vec(s.objects[0].motion.phases[0].acceleration, 0, 0.1, 0);
  ASSERT_TRUE(s.objects[0].spin);
  expect_vec(s.objects[0].spin->axis, 0, 1, 0);
  EXPECT_NEAR(s.objects[0].spin->rate, std::numbers::pi / 10, 1e-15);

  const auto object = [](const std::string& extra) {
    return with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    )" + extra + "}");
  };
  expect_error(object(R"("motion": {"phases": [{"duration": 1, "acceleration": [0, 0, 0]}]})"), 4,
               "objects[0].motion.phases[0].acceleration", "must not be zero");
  expect_error(object(R"("motion": {"phases": [{"duration": -2, "acceleration": [1, 0, 0]}]})"), 4,
               "objects[0].motion.phases[0].duration", "greater than 0");
  expect_error(object(R"("motion": {})"), 4, "objects[0].motion",
               "exactly one of: phases, keyframes");
  expect_error(object(R"("motion": {"keyframes": [{"time": 2, "position": [0, 0, 0]},
      {"time": 1, "position": [1, 0, 0]}]})"),
               5, "objects[0].motion.keyframes[1]", "keyframe times must increase");
  expect_error(object(R"("motion": {"keyframes": [{"time": 0, "position": [0, 0, 0]},
      {"time": 1, "position": [0.3, 0, 0]},
      {"time": 2, "position": [1.6, 0, 0]}]})"),
               6, "objects[0].motion.keyframes[2]", "between keyframes 1 and 2 reaches speed");
  expect_error(object(R"("position": [1, 0, 0],
      "motion": {"keyframes": [{"time": 0, "position": [0, 0, 0]}]})"),
               4, "objects[0].position", "must not be given with motion.keyframes");
  expect_error(object(R"("motion": {"keyframes": [{"time": 0}]})"), 4,
               "objects[0].motion.keyframes[0]", "needs \"position\"");
  // A rim at the speed of light, or past it: rate 90 degrees = pi/2 per unit time, radius 1.
  expect_error(object(R"("spin": {"axis": [0, 1, 0], "rate": 60})"), 4, "objects[0].spin.rate",
               "the rim speed 1.047 (rate times the shape's radius 1 about the origin) must be "
               "below the speed of light (1)");
  expect_error(object(R"("spin": {"axis": [0, 0, 0], "rate": 10})"), 4, "objects[0].spin.axis",
               "must not be the zero vector");
  expect_error(object(R"("spin": {"axis": [0, 1, 0]})"), 4, "objects[0].spin", "needs \"rate\"");
  expect_error(object(R"("material": {"blink": {"period": 0}})"), 4,
               "objects[0].material.blink.period", "greater than 0");
  expect_error(object(R"("material": {"blink": {"period": 1, "duty": 1.5}})"), 4,
               "objects[0].material.blink.duty", "at most 1");
  expect_error(object(R"("material": {"clock": {"period": 1, "duty": 0.5}})"), 4,
               "objects[0].material.clock.duty", "unknown key");
  expect_error(R"({
  "camera": {"position": [0, 0, 5]},
  "lights": [{"name": "sun", "type": "directional",
    "motion": {"phases": [{"duration": 1, "acceleration": [1, 0, 0]}]}}]
})",
               4, "lights[0].motion", "a directional light is at infinity");
}

TEST_F(SceneFileTest, SpeedOfLightConvertsAtTheEdgeAndBoundsSpeeds) {
  // c = 10: speeds are in units of c / 10, times tenfold in the engine's units, accelerations a
  // hundredth.
  const Scene s = load(R"({
  "speed_of_light": 10,
  "camera": {"position": [0, 0, 5], "time": 2, "velocity": [3, 0, 0]},
  "objects": [{"name": "a", "shape": {"sphere": {"radius": 1}}, "time": 1, "velocity": [0, 6, 0],
               "motion": {"phases": [{"duration": 0.5, "acceleration": [20, 0, 0]}]},
               "spin": {"axis": [0, 0, 1], "rate": 180},
               "material": {"blink": {"period": 0.25}}}]
})");
  EXPECT_EQ(s.speed_of_light, 10);
  EXPECT_NEAR(s.camera.world_line.time, 20, 1e-12);
  expect_vec(s.camera.world_line.velocity, 0.3, 0, 0);
  EXPECT_NEAR(s.objects[0].world_line.time, 10, 1e-12);
  expect_vec(s.objects[0].world_line.velocity, 0, 0.6, 0);
  EXPECT_NEAR(s.objects[0].motion.phases[0].duration, 5, 1e-12);
  expect_vec(s.objects[0].motion.phases[0].acceleration, 0.2, 0, 0);
  EXPECT_NEAR(s.objects[0].spin->rate, std::numbers::pi / 10, 1e-15);
  EXPECT_NEAR(std::get<Blink>(s.objects[0].material.pattern).period, 2.5, 1e-12);

  expect_error(R"({
  "speed_of_light": 10,
  "camera": {"position": [0, 0, 5], "velocity": [0, 0, 12]},
  "objects": []
})",
               3, "camera.velocity", "speed 12 must be below the speed of light (10)");
  expect_error("{\n  \"speed_of_light\": 0,\n  \"camera\": {\"position\": [0, 0, 5]}\n}", 2,
               "speed_of_light", "greater than 0");
  expect_error("{\n  \"speed_of_light\": -3,\n  \"camera\": {\"position\": [0, 0, 5]}\n}", 2,
               "speed_of_light", "greater than 0");
}

TEST_F(SceneFileTest, DefaultsAreTheDocumentedOnes) {
  const Scene s = load(R"({"camera": {"position": [0, 0, 0]},
                           "objects": [{"name": "a", "shape": {"sphere": {"radius": 1}}}]})");
  const Camera& c = s.camera;
  EXPECT_EQ(c.world_line.time, 0);
  expect_vec(c.world_line.velocity, 0, 0, 0);
  expect_vec(c.forward, 0, 0, -1);
  expect_vec(c.up, 0, 1, 0);
  EXPECT_EQ(c.fov_degrees, 60);
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 360);
  EXPECT_EQ(c.samples, 1);

  const Object& a = s.objects.at(0);
  expect_vec(a.world_line.position, 0, 0, 0);
  EXPECT_EQ(a.world_line.time, 0);
  expect_vec(a.world_line.velocity, 0, 0, 0);
  expect_vec(a.rotation * Vec3{1, 2, 3}, 1, 2, 3);
  expect_vec(a.scale, 1, 1, 1);
  expect_rgb(std::get<SolidColor>(a.material.pattern).color, 1, 1, 1);
  EXPECT_TRUE(a.material.unlit);

  expect_rgb(std::get<SolidColor>(s.sky.pattern).color, 0, 0, 0);
  expect_vec(s.sky.velocity, 0, 0, 0);
  EXPECT_TRUE(s.render.relativity);
  EXPECT_TRUE(s.render.light_delay);
  // A scene file's picture is exposed for its moving bodies and shown through the filmic curve;
  // a scene built in code keeps its radiance as it is.
  EXPECT_TRUE(s.render.auto_exposure);
  EXPECT_EQ(s.render.doppler, DopplerModel::kSpectral);
  EXPECT_EQ(s.render.searchlight, SearchlightModel::kPhysical);
  EXPECT_FALSE(s.render.hue_loop);
  EXPECT_EQ(s.render.tonemap, ToneMap::kFilmic);
  EXPECT_FALSE(RenderSettings{}.auto_exposure);
  EXPECT_EQ(RenderSettings{}.exposure, 0);
  EXPECT_EQ(RenderSettings{}.tonemap, ToneMap::kClamp);
  // Those defaults hold with a render section that does not name them, and a number given
  // turns the automatic exposure off.
  const Scene partial =
      load(R"({"camera": {"position": [0, 0, 0]}, "render": {"shadows": false}})");
  EXPECT_TRUE(partial.render.auto_exposure);
  EXPECT_EQ(partial.render.tonemap, ToneMap::kFilmic);
  const Scene fixed = load(R"({"camera": {"position": [0, 0, 0]}, "render": {"exposure": -1}})");
  EXPECT_FALSE(fixed.render.auto_exposure);
  EXPECT_EQ(fixed.render.exposure, -1);
}

TEST_F(SceneFileTest, SkyGridDefaultsAndSkyColour) {
  const Scene grid = load(R"({"camera": {"position": [0, 0, 0]}, "sky": {"grid": {}}})");
  const SkyGrid& g = std::get<SkyGrid>(grid.sky.pattern);
  EXPECT_EQ(g.spacing_degrees, 15);
  EXPECT_EQ(g.line_width_degrees, 0.4);
  expect_rgb(g.line_color, 1, 1, 1);
  expect_rgb(g.background, 0.02f, 0.02f, 0.05f);

  const Scene plain = load(R"({"camera": {"position": [0, 0, 0]}, "sky": {"color": [0, 0.5, 1]}})");
  expect_rgb(std::get<SolidColor>(plain.sky.pattern).color, 0, 0.5f, 1);
}

// sky.stars: the bundled catalogue, alone (a black sky) or over a pattern, cut at the magnitude
// limit; false is none.
TEST_F(SceneFileTest, SkyStarsReadTheCatalogueBrighterThanTheLimit) {
  const Scene all = load(R"({"camera": {"position": [0, 0, 0]}, "sky": {"stars": true}})");
  ASSERT_TRUE(all.sky.stars && all.sky.stars->stars);
  EXPECT_GT(all.sky.stars->stars->size(), 8000u);
  EXPECT_EQ(all.sky.stars->exposure, 0);
  expect_rgb(std::get<SolidColor>(all.sky.pattern).color, 0, 0, 0);

  const Scene bright = load(R"({"camera": {"position": [0, 0, 0]}, "sky": {"grid": {},
      "stars": {"catalogue": "bright", "magnitude_limit": 2, "exposure": 1.5}}})");
  ASSERT_TRUE(bright.sky.stars && bright.sky.stars->stars);
  EXPECT_TRUE(std::holds_alternative<SkyGrid>(bright.sky.pattern));
  EXPECT_EQ(bright.sky.stars->exposure, 1.5);
  EXPECT_GT(bright.sky.stars->stars->size(), 30u);
  EXPECT_LT(bright.sky.stars->stars->size(), 100u);
  for (const CatalogueStar& star : *bright.sky.stars->stars) EXPECT_LT(star.magnitude, 2);

  const Scene none = load(R"({"camera": {"position": [0, 0, 0]},
      "sky": {"color": [0, 0, 1], "stars": false}})");
  EXPECT_FALSE(none.sky.stars);
  const Scene set = load(R"({"camera": {"position": [0, 0, 0]}, "sky": {"color": [0, 0, 1]}})",
                         {"sky.stars=true"});
  EXPECT_TRUE(set.sky.stars && set.sky.stars->stars);
}

TEST_F(SceneFileTest, BadSkyStarsAreLocated) {
  const std::string head = R"({"camera": {"position": [0, 0, 0]},
  "sky": )";
  expect_error(head + R"({"stars": {"catalogue": "hipparcos"}}})", 2, "sky.stars.catalogue",
               "unknown catalogue 'hipparcos'");
  // JSON has no infinities or NaN: a limit beyond the doubles is refused where it is written.
  expect_error(head + R"({"stars": {"magnitude_limit": 1e999}}})", 2, "(syntax)",
               "number overflow");
  expect_error(head + R"({"stars": {"magnitude_limit": "6"}}})", 2, "sky.stars.magnitude_limit",
               "must be a number");
  expect_error(head + R"({"stars": {"exposure": null}}})", 2, "sky.stars.exposure",
               "must be a number");
  expect_error(head + R"({"stars": {"limit": 6}}})", 2, "sky.stars.limit", "unknown key");
  expect_error(head + R"({"stars": 1}})", 2, "sky.stars", "must be");
  expect_error(head + R"({"stars": true, "color": [0, 0, 0], "grid": {}}})", 2, "sky",
               "exactly one of");
}

TEST_F(SceneFileTest, BlackbodyAndSpectrumMaterials) {
  const Scene s = load(with_object(R"(
    {"name": "sun", "shape": {"sphere": {"radius": 1}},
     "material": {"blackbody": {"temperature": 5762, "luminance": 2.5}}},
    {"name": "star", "shape": {"sphere": {"radius": 1}},
     "material": {"blackbody": {"temperature": 3000.5}, "unlit": true}},
    {"name": "dark", "shape": {"sphere": {"radius": 1}},
     "material": {"blackbody": {"temperature": 1e-3, "luminance": 0}}},
    {"name": "lamp", "shape": {"sphere": {"radius": 1}},
     "material": {"spectrum": {"wavelengths": [300, 450.5, 1200], "values": [0, 2, 0.25]}}},
    {"name": "flat", "shape": {"sphere": {"radius": 1}},
     "material": {"spectrum": {"wavelengths": [1e-3, 1e6], "values": [1, 1]}}})"));
  ASSERT_EQ(s.objects.size(), 5u);

  const Blackbody& sun = std::get<Blackbody>(s.objects[0].material.pattern);
  EXPECT_EQ(sun.temperature_k, 5762);
  EXPECT_EQ(sun.luminance, 2.5);
  const Blackbody& star = std::get<Blackbody>(s.objects[1].material.pattern);
  EXPECT_EQ(star.temperature_k, 3000.5);
  EXPECT_EQ(star.luminance, 1);  // the default
  EXPECT_TRUE(s.objects[1].material.unlit);
  const Blackbody& dark = std::get<Blackbody>(s.objects[2].material.pattern);
  EXPECT_EQ(dark.temperature_k, 1e-3);  // any temperature above 0
  EXPECT_EQ(dark.luminance, 0);         // luminance 0 is allowed

  const EmissionSpectrum& lamp = std::get<EmissionSpectrum>(s.objects[3].material.pattern);
  EXPECT_EQ(lamp.wavelengths_nm, (std::vector<double>{300, 450.5, 1200}));
  EXPECT_EQ(lamp.values, (std::vector<double>{0, 2, 0.25}));
  EXPECT_TRUE(s.objects[3].material.unlit);
  const EmissionSpectrum& flat = std::get<EmissionSpectrum>(s.objects[4].material.pattern);
  EXPECT_EQ(flat.wavelengths_nm, (std::vector<double>{1e-3, 1e6}));
  EXPECT_EQ(flat.values, (std::vector<double>{1, 1}));
}

TEST_F(SceneFileTest, ColourRenderSettings) {
  auto render = [&](const std::string& settings) {
    return load(R"({"camera": {"position": [0, 0, 0]}, "render": )" + settings + "}").render;
  };
  const std::pair<const char*, DopplerModel> dopplers[] = {{"spectral", DopplerModel::kSpectral},
                                                           {"rgb3", DopplerModel::kRgb3},
                                                           {"hue", DopplerModel::kHue},
                                                           {"off", DopplerModel::kOff}};
  for (const auto& [name, model] : dopplers) {
    SCOPED_TRACE(name);
    EXPECT_EQ(render(fmt::format(R"({{"doppler": "{}"}})", name)).doppler, model);
  }
  const std::pair<const char*, SearchlightModel> searchlights[] = {
      {"physical", SearchlightModel::kPhysical},
      {"chang1996", SearchlightModel::kChang1996},
      {"off", SearchlightModel::kOff}};
  for (const auto& [name, model] : searchlights) {
    SCOPED_TRACE(name);
    EXPECT_EQ(render(fmt::format(R"({{"searchlight": "{}"}})", name)).searchlight, model);
  }
  const std::pair<const char*, ToneMap> curves[] = {
      {"clamp", ToneMap::kClamp}, {"reinhard", ToneMap::kReinhard}, {"filmic", ToneMap::kFilmic}};
  for (const auto& [name, curve] : curves) {
    SCOPED_TRACE(name);
    EXPECT_EQ(render(fmt::format(R"({{"tonemap": "{}"}})", name)).tonemap, curve);
  }

  EXPECT_TRUE(render(R"({"hue": {"loop": true}})").hue_loop);
  EXPECT_FALSE(render(R"({"hue": {"loop": false}})").hue_loop);
  EXPECT_FALSE(render(R"({"hue": {}})").hue_loop);

  const RenderSettings automatic = render(R"({"exposure": "auto"})");
  EXPECT_TRUE(automatic.auto_exposure);
  EXPECT_EQ(automatic.exposure, 0);
  const RenderSettings fixed = render(R"({"exposure": 1.5})");
  EXPECT_FALSE(fixed.auto_exposure);
  EXPECT_EQ(fixed.exposure, 1.5);

  // All at once, and the other keys keep their defaults.
  const RenderSettings all = render(R"({"doppler": "hue", "searchlight": "chang1996",
      "hue": {"loop": true}, "exposure": "auto", "tonemap": "filmic"})");
  EXPECT_EQ(all.doppler, DopplerModel::kHue);
  EXPECT_EQ(all.searchlight, SearchlightModel::kChang1996);
  EXPECT_TRUE(all.hue_loop);
  EXPECT_TRUE(all.auto_exposure);
  EXPECT_EQ(all.tonemap, ToneMap::kFilmic);
  EXPECT_TRUE(all.relativity);
  EXPECT_TRUE(all.light_delay);
}

TEST_F(SceneFileTest, LightsOfEachTypeMapOntoTheModel) {
  const Scene s = load(R"({
    "camera": {"position": [0, 0, 5]},
    "lights": [
      {"name": "bulb", "type": "point", "position": [1, 2, 3], "time": -2,
       "velocity": [0.5, 0, 0], "color": [1, 0.5, 2], "intensity": 10},
      {"name": "torch", "type": "spot", "position": [0, 5, 0], "direction": [0, -2, 0],
       "cone": 40, "falloff": 20, "intensity": 3, "blackbody": {"temperature": 3000}},
      {"name": "sun", "type": "directional", "position": [9, 9, 9], "direction": [1, -1, 0],
       "irradiance": 2.5, "velocity": [0, 0, 0.3], "color": [1, 0.9, 0.8]},
      {"name": "globe", "type": "sphere", "position": [0, 0, -4], "radius": 0.5,
       "intensity": 0}
    ]
  })");
  ASSERT_EQ(s.lights.size(), 4u);

  const Light& bulb = s.lights[0];
  EXPECT_EQ(bulb.name, "bulb");
  EXPECT_TRUE(std::holds_alternative<PointLight>(bulb.kind));
  expect_vec(bulb.world_line.position, 1, 2, 3);
  EXPECT_EQ(bulb.world_line.time, -2);
  expect_vec(bulb.world_line.velocity, 0.5, 0, 0);
  expect_rgb(std::get<Rgb>(bulb.spectrum.emission), 1, 0.5f, 2);  // above 1 is allowed
  EXPECT_EQ(bulb.intensity, 10);

  const Light& torch = s.lights[1];
  const SpotLight& spot = std::get<SpotLight>(torch.kind);
  expect_vec(spot.direction, 0, -1, 0);  // normalized
  EXPECT_EQ(spot.cone_degrees, 40);
  EXPECT_EQ(spot.falloff_degrees, 20);  // up to half the cone
  EXPECT_EQ(std::get<Blackbody>(torch.spectrum.emission).temperature_k, 3000);
  EXPECT_EQ(torch.intensity, 3);
  expect_vec(torch.world_line.position, 0, 5, 0);

  const Light& sun = s.lights[2];
  const DirectionalLight& directional = std::get<DirectionalLight>(sun.kind);
  expect_vec(directional.direction, std::sqrt(0.5), -std::sqrt(0.5), 0);
  EXPECT_EQ(directional.irradiance, 2.5);
  expect_vec(sun.world_line.velocity, 0, 0, 0.3);
  expect_vec(sun.world_line.position, 9, 9, 9);  // allowed, and ignored by the renderer
  expect_rgb(std::get<Rgb>(sun.spectrum.emission), 1, 0.9f, 0.8f);

  const Light& globe = s.lights[3];
  EXPECT_EQ(std::get<SphereLight>(globe.kind).radius, 0.5);
  EXPECT_EQ(globe.intensity, 0);  // a light may be off
  expect_vec(globe.world_line.position, 0, 0, -4);
}

TEST_F(SceneFileTest, LightDefaultsAreTheDocumentedOnes) {
  const Scene s = load(R"({
    "camera": {"position": [0, 0, 5]},
    "lights": [
      {"name": "p", "type": "point"},
      {"name": "s", "type": "spot"},
      {"name": "d", "type": "directional"},
      {"name": "b", "type": "sphere", "radius": 2},
      {"name": "narrow", "type": "spot", "cone": 6},
      {"name": "hard", "type": "spot", "cone": 6, "falloff": 0}
    ]
  })");
  ASSERT_EQ(s.lights.size(), 6u);
  for (const Light& l : s.lights) {
    SCOPED_TRACE(l.name);
    expect_vec(l.world_line.position, 0, 0, 0);
    EXPECT_EQ(l.world_line.time, 0);
    expect_vec(l.world_line.velocity, 0, 0, 0);
    expect_rgb(std::get<Rgb>(l.spectrum.emission), 1, 1, 1);
    EXPECT_EQ(l.intensity, 1);
  }
  EXPECT_TRUE(std::holds_alternative<PointLight>(s.lights[0].kind));
  const SpotLight& spot = std::get<SpotLight>(s.lights[1].kind);
  expect_vec(spot.direction, 0, 0, -1);
  EXPECT_EQ(spot.cone_degrees, 60);
  EXPECT_EQ(spot.falloff_degrees, 5);
  const DirectionalLight& directional = std::get<DirectionalLight>(s.lights[2].kind);
  expect_vec(directional.direction, 0, -1, 0);
  EXPECT_EQ(directional.irradiance, 1);
  EXPECT_EQ(std::get<SphereLight>(s.lights[3].kind).radius, 2);
  // The default soft edge (5 degrees) shrinks to half of a cone narrower than 10 degrees.
  EXPECT_EQ(std::get<SpotLight>(s.lights[4].kind).falloff_degrees, 3);
  EXPECT_EQ(std::get<SpotLight>(s.lights[5].kind).falloff_degrees, 0);

  // No "lights": no lights; an empty list is allowed too.
  EXPECT_TRUE(load(R"({"camera": {"position": [0, 0, 5]}})").lights.empty());
  EXPECT_TRUE(load(R"({"camera": {"position": [0, 0, 5]}, "lights": []})").lights.empty());
}

TEST_F(SceneFileTest, LitMaterials) {
  write_two_texel_png("albedo.png", {1, 0, 0, 0, 0, 0.5f});
  const Scene s = load(with_object(R"(
    {"name": "matte", "shape": {"sphere": {"radius": 1}},
     "material": {"color": [0.5, 0.25, 1], "unlit": false}},
    {"name": "tiles", "shape": {"plane": {"size": [4, 4]}},
     "material": {"checker": {"size": 1, "colors": [[1, 1, 1], [0, 0, 0]]}, "unlit": false,
                  "glossy": {}}},
    {"name": "chrome", "shape": {"sphere": {"radius": 1}},
     "material": {"color": [0, 0, 0], "unlit": false,
                  "glossy": {"roughness": 1, "specular": 0}}},
    {"name": "shiny", "shape": {"sphere": {"radius": 1}},
     "material": {"unlit": false, "glossy": {"roughness": 0.05, "specular": 1},
                  "texture": "albedo.png"}},
    {"name": "lamp", "shape": {"sphere": {"radius": 1}},
     "material": {"color": [2, 2, 2], "unlit": true}})"));
  ASSERT_EQ(s.objects.size(), 5u);

  const Material& matte = s.objects[0].material;
  EXPECT_FALSE(matte.unlit);
  EXPECT_FALSE(matte.glossy.has_value());
  expect_rgb(std::get<SolidColor>(matte.pattern).color, 0.5f, 0.25f, 1);

  const Material& tiles = s.objects[1].material;
  EXPECT_FALSE(tiles.unlit);
  ASSERT_TRUE(tiles.glossy.has_value());
  EXPECT_EQ(tiles.glossy->roughness, 0.3);  // the defaults
  EXPECT_EQ(tiles.glossy->specular, 0.04);
  expect_rgb(std::get<Checker>(tiles.pattern).colors[0], 1, 1, 1);

  const Material& chrome = s.objects[2].material;
  ASSERT_TRUE(chrome.glossy.has_value());
  EXPECT_EQ(chrome.glossy->roughness, 1);
  EXPECT_EQ(chrome.glossy->specular, 0);

  const Material& shiny = s.objects[3].material;
  EXPECT_FALSE(shiny.unlit);
  ASSERT_TRUE(shiny.glossy.has_value());
  EXPECT_EQ(shiny.glossy->roughness, 0.05);
  EXPECT_EQ(shiny.glossy->specular, 1);
  ASSERT_NE(std::get<Texture>(shiny.pattern).image, nullptr);

  // Unlit colours are radiance and may exceed 1.
  EXPECT_TRUE(s.objects[4].material.unlit);
  expect_rgb(std::get<SolidColor>(s.objects[4].material.pattern).color, 2, 2, 2);
}

TEST_F(SceneFileTest, LightRenderSettings) {
  auto render = [&](const std::string& settings) {
    return load(R"({"camera": {"position": [0, 0, 0]}, "render": )" + settings + "}").render;
  };
  const RenderSettings defaults = render("{}");
  EXPECT_EQ(defaults.light_source_delay, LightSourceDelay::kSurface);
  EXPECT_TRUE(defaults.shadows);
  const std::pair<const char*, LightSourceDelay> modes[] = {{"surface", LightSourceDelay::kSurface},
                                                            {"camera", LightSourceDelay::kCamera},
                                                            {"none", LightSourceDelay::kNone}};
  for (const auto& [name, mode] : modes) {
    SCOPED_TRACE(name);
    EXPECT_EQ(render(fmt::format(R"({{"light_source_delay": "{}"}})", name)).light_source_delay,
              mode);
  }
  EXPECT_FALSE(render(R"({"shadows": false})").shadows);
  EXPECT_TRUE(render(R"({"shadows": true})").shadows);

  const RenderSettings all = render(R"({"light_source_delay": "none", "shadows": false,
                                        "tonemap": "filmic"})");
  EXPECT_EQ(all.light_source_delay, LightSourceDelay::kNone);
  EXPECT_FALSE(all.shadows);
  EXPECT_EQ(all.tonemap, ToneMap::kFilmic);
  EXPECT_TRUE(all.light_delay);
}

TEST_F(SceneFileTest, CommentsAreAllowedAndDoNotShiftLines) {
  const std::string text = R"(// a scene { with "braces" and quotes
{
  /* block comment spanning
     two lines: "camera": { */
  "camera": {"position": [0, 0, 5]}, // trailing
  "objects": [{"name": "a // not a comment", "shape": {"sphere": {"radius": 1}}}]
})";
  const Scene s = load(text);
  EXPECT_EQ(s.objects.at(0).name, "a // not a comment");

  // An error after the comments is still reported on the right line.
  expect_error(R"({
  /* one
     two */ "camera": {"position": [0, 0, 5]},
  // "sky": {
  "sky": {"color": [0, 0, -1]}
})",
               5, "sky.color[2]", ">= 0");
}

TEST_F(SceneFileTest, IntegralFloatsAreIntegers) {
  EXPECT_EQ(load(R"({"camera": {"position": [0, 0, 0], "width": 32.0}})").camera.width, 32);
}

// ---------------------------------------------------------------------------------------------
// Overrides

constexpr const char* kOverrideScene = R"({
  "camera": {"position": [0, 0, 5], "velocity": [0, 0, 0.1]},
  "objects": [{"name": "a", "shape": {"sphere": {"radius": 1}}}],
  "render": {"relativity": true}
})";

TEST_F(SceneFileTest, OverridesReplaceValues) {
  const Scene s = load(kOverrideScene, {"render.relativity=false", "camera.velocity=[0,0,0.5]",
                                        "camera.width=320", "objects.0.velocity=[0.5,0,0]",
                                        "objects[0].position=[1, 2, 3]", "objects.0.name=renamed"});
  EXPECT_FALSE(s.render.relativity);
  expect_vec(s.camera.world_line.velocity, 0, 0, 0.5);
  EXPECT_EQ(s.camera.width, 320);
  expect_vec(s.objects.at(0).world_line.velocity, 0.5, 0, 0);
  expect_vec(s.objects.at(0).world_line.position, 1, 2, 3);
  EXPECT_EQ(s.objects.at(0).name, "renamed");  // not JSON, so taken as a string
}

// Numbers separated by commas are an array, as locate's --direction x,y,z; other text that is
// not JSON stays a string.
TEST_F(SceneFileTest, OverridesReadCommaSeparatedNumbersAsArrays) {
  const Scene s = load(kOverrideScene, {"camera.velocity=0,0,-0.99", "objects.0.position=1, 2,3e-1",
                                        "objects.0.name=a,b"});
  expect_vec(s.camera.world_line.velocity, 0, 0, -0.99);
  expect_vec(s.objects.at(0).world_line.position, 1, 2, 0.3);
  EXPECT_EQ(s.objects.at(0).name, "a,b");
  expect_set_error(kOverrideScene, {"camera.velocity=0,0,x"}, "camera.velocity",
                   "string \"0,0,x\"");
}

TEST_F(SceneFileTest, OverridesCreateMissingObjectsAndAppendElements) {
  const Scene s =
      load(kOverrideScene, {"sky.grid.spacing=10", "render.exposure=2",
                            R"(objects.1={"name":"b","shape":{"box":{"size":[1,1,1]}}})"});
  EXPECT_EQ(std::get<SkyGrid>(s.sky.pattern).spacing_degrees, 10);
  EXPECT_EQ(s.render.exposure, 2);
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[1].name, "b");
}

TEST_F(SceneFileTest, OverridesPrecedeValidation) {
  expect_set_error(kOverrideScene, {"camera.velocity=[0,0,1.2]"}, "camera.velocity",
                   "speed 1.2 must be below the speed of light (1)");
  expect_set_error(kOverrideScene, {"objects[0].shape.sphere.radius=-1"},
                   "objects[0].shape.sphere.radius", "greater than 0");
  expect_set_error(kOverrideScene, {"camera.colour=[1,1,1]"}, "camera.colour", "unknown key");
  expect_set_error(kOverrideScene, {"camera.width=big"}, "camera.width", "string \"big\"");
  // An override that makes the file's own value invalid is blamed on the override.
  expect_set_error(kOverrideScene, {"objects.0.shape.box={\"size\":[1,1,1]}"}, "objects[0].shape",
                   "exactly one of");
  // A value the override did not touch is still reported against the file.
  expect_error(R"({
  "camera": {"position": [0, 0, 5]},
  "render": {"exposure": "bright"}
})",
               3, "render.exposure", "must be a number");
  EXPECT_NE(error(R"({"camera": {"position": [0, 0, 5]}, "render": {"exposure": "x"}})",
                  {"camera.width=10"})
                .find(":1: render.exposure: "),
            std::string::npos);
}

TEST_F(SceneFileTest, MalformedOverrides) {
  expect_set_error(kOverrideScene, {"render.relativity"}, "render.relativity", "key.path=value");
  expect_set_error(kOverrideScene, {"camera.position.x.y=1"}, "camera.position.x.y",
                   "camera.position is an array");
  expect_set_error(kOverrideScene, {"objects.5.name=x"}, "objects.5.name", "not an index");
  expect_set_error(kOverrideScene, {"render.relativity.x=1"}, "render.relativity.x",
                   "render.relativity is a boolean, not an object or array");
  expect_set_error(kOverrideScene, {"camera..width=1"}, "camera..width", "empty component");
  // `"stars": false` stands for no table to open, unlike `true`.
  expect_set_error(R"({"camera": {"position": [0, 0, 0]}, "sky": {"stars": false}})",
                   {"sky.stars.exposure=1"}, "sky.stars.exposure",
                   "sky.stars is a boolean, not an object or array");
}

// `"stars": true` stands for the stars' defaults: a path through it opens them.
TEST_F(SceneFileTest, OverridesOpenTheStarsDefaults) {
  const Scene s = load(R"({"camera": {"position": [0, 0, 0]}, "sky": {"stars": true}})",
                       {"sky.stars.magnitude_limit=3"});
  const Scene all = load(R"({"camera": {"position": [0, 0, 0]}, "sky": {"stars": true}})");
  ASSERT_TRUE(s.sky.stars && all.sky.stars && s.sky.stars->stars && all.sky.stars->stars);
  EXPECT_EQ(s.sky.stars->magnitude_limit, 3);
  EXPECT_GT(s.sky.stars->stars->size(), 0u);
  EXPECT_LT(s.sky.stars->stars->size(), all.sky.stars->stars->size() / 10);
}

TEST_F(SceneFileTest, ColourRenderSettingsFromOverrides) {
  // "auto" and the model names are not JSON, so --set takes them as strings.
  const Scene s =
      load(kOverrideScene, {"render.exposure=auto", "render.doppler=rgb3", "render.searchlight=off",
                            "render.hue.loop=true", "render.tonemap=reinhard"});
  EXPECT_TRUE(s.render.auto_exposure);
  EXPECT_EQ(s.render.doppler, DopplerModel::kRgb3);
  EXPECT_EQ(s.render.searchlight, SearchlightModel::kOff);
  EXPECT_TRUE(s.render.hue_loop);
  EXPECT_EQ(s.render.tonemap, ToneMap::kReinhard);
  expect_set_error(kOverrideScene, {"render.doppler=rgb"}, "render.doppler",
                   "unknown model \"rgb\"");
  expect_set_error(kOverrideScene, {"render.exposure=bright"}, "render.exposure",
                   "must be a number (EV) or \"auto\"");
  expect_set_error(kOverrideScene, {"objects.0.material.blackbody.temperature=0"},
                   "objects[0].material.blackbody.temperature", "greater than 0");
}

TEST_F(SceneFileTest, LightsFromOverrides) {
  const Scene s = load(kOverrideScene,
                       {R"(lights=[{"name":"sun","type":"directional"}])", "lights.0.irradiance=3",
                        "render.light_source_delay=camera", "render.shadows=false",
                        R"(objects.0.material={"color":[0.5,0.5,0.5],"unlit":false})"});
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(std::get<DirectionalLight>(s.lights[0].kind).irradiance, 3);
  EXPECT_EQ(s.render.light_source_delay, LightSourceDelay::kCamera);
  EXPECT_FALSE(s.render.shadows);
  EXPECT_FALSE(s.objects.at(0).material.unlit);
  expect_set_error(kOverrideScene,
                   {R"(lights=[{"name":"lamp","type":"point"}])", "lights.0.intensity=-1"},
                   "lights[0].intensity", "must be >= 0, got -1");
  expect_set_error(kOverrideScene, {"render.light_source_delay=retarded"},
                   "render.light_source_delay", "unknown mode \"retarded\"");
}

// ---------------------------------------------------------------------------------------------
// Bad input: each error names the file, the line and the path

TEST_F(SceneFileTest, MissingOrUnreadableFile) {
  const fs::path missing = dir_ / "nope.json";
  SceneLoadReport report;
  try {
    load_scene_file(missing, {}, report);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(missing.string() + ": cannot read scene file: ", 0), 0u)
        << e.what();
  }
  EXPECT_THROW(load_scene_file(dir_, {}, report), InputError);  // a directory
}

TEST_F(SceneFileTest, DeeplyNestedJsonIsRefusedAsItIsRead) {
  const fs::path file = write("deep.json", "{\"camera\": " + std::string(100000, '[') + "0" +
                                               std::string(100000, ']') + "}");
  SceneLoadReport report;
  try {
    load_scene_file(file, {}, report);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nested more than 64 levels deep"), std::string::npos)
        << e.what();
  }
}

// Found by the fuzzer: comments holding NUL bytes and override lines before the scene made the
// line map's scanner loop forever, recording array elements until memory ran out.
TEST_F(SceneFileTest, TheLineMapScannerAlwaysMovesOn) {
  const fuzz::SceneInput input = fuzz::split_scene_input(
      read_file(fs::path(LIGHTCONE_SOURCE_DIR) / "tests" / "data" / "scanner-loop.fuzz"));
  ASSERT_FALSE(input.overrides.empty());
  const fs::path file = write("scene.json", input.scene);
  SceneLoadReport report;
  EXPECT_THROW(load_scene_file(file, {}, report), InputError);
}

// Inputs found by the fuzzer (fuzz/fuzz_scene.cpp: override lines, "---", the scene): each may
// only end in a clear error, never in another exception.
//   scanner-bad-escape: a key the scanner read with an escape the parser never saw threw the
//     parser's own exception out of the line map;
//   invalid-utf8-override: a --set value of invalid UTF-8 threw while being quoted in the
//     error message.
TEST_F(SceneFileTest, FuzzerFindingsEndInClearErrors) {
  for (const char* name : {"scanner-bad-escape.fuzz", "invalid-utf8-override.fuzz"}) {
    SCOPED_TRACE(name);
    const fuzz::SceneInput input = fuzz::split_scene_input(
        read_file(fs::path(LIGHTCONE_SOURCE_DIR) / "tests" / "data" / name));
    const fs::path file = write("scene.json", input.scene);
    SceneLoadReport report;
    try {
      load_scene_file(file, input.overrides, report);
    } catch (const InputError&) {
    }  // any other exception fails the test
  }
}

TEST_F(SceneFileTest, SyntaxErrors) {
  expect_error("{\n  \"camera\": {\"position\": [0, 0, 5]},\n}\n", 3, "(syntax)",
               "a comma after the last member");
  expect_error("{\n  \"camera\": {\"position\": [0, 0, NaN]}\n}", 2, "(syntax)", "invalid literal");
  expect_error("{\n  \"camera\":\n {\"position\": [0, 0, 1e400]}\n}", 3, "(syntax)",
               "number overflow");
  expect_error("", 1, "(syntax)", "unexpected end of input");
  expect_error("{\"camera\": {\"position\": [0, 0, 5]}}\n\n  x", 3, "(syntax)", "invalid literal");
  // No "[json.exception..." or nlohmann's own line and column.
  EXPECT_EQ(error("{\n,").find("json.exception"), std::string::npos);
  EXPECT_EQ(error("{\n,").find("column"), std::string::npos);
}

TEST_F(SceneFileTest, UnknownKeys) {
  expect_error("{\n  \"camera\": {\"position\": [0, 0, 5]},\n  \"light\": []\n}", 3, "light",
               "unknown key \"light\" (did you mean \"lights\"? expected one of: $schema, "
               "speed_of_light, camera, objects, lights, sky, render, black_hole)");
  expect_error("{\n  \"camera\": {\"position\": [0, 0, 5],\n    \"fovy\": 60}\n}", 3, "camera.fovy",
               "(did you mean \"fov\"? expected one of: position, time");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "colour": [1, 0, 0]})"),
               4, "objects[0].colour", "unknown key \"colour\" (expected one of");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1, "segments": 3}}})"),
               3, "objects[0].shape.sphere.segments", "unknown key");
  expect_error(with_object(R"({"name": "a", "shape": {"box": {"size": [1, 1, 1]}},
    "material": {"color": [1, 1, 1], "shiny": true}})"),
               4, "objects[0].material.shiny", "unknown key");
  expect_error("{\"camera\": {\"position\": [0, 0, 5]},\n \"render\": {\"\\u0066oo\": 1}}", 2,
               "render.foo", "unknown key \"foo\" (expected one of");  // nothing near enough
  expect_error(with_object(R"({"name": "a", "shape": {"box": {"size": [1, 1, 1]}},
    "material": {"colro": [1, 1, 1]}})"),
               4, "objects[0].material.colro", "(did you mean \"color\"? expected one of");
}

// JSON has no trailing commas: one is named as such, on the line of the '}' or ']' after it.
TEST_F(SceneFileTest, TrailingCommasAreNamed) {
  const auto syntax = [&](const std::string& text, int line) {
    return fmt::format("{}:{}: (syntax): ", (dir_ / "scene.json").string(), line);
  };
  EXPECT_EQ(error("{\"camera\": {\"position\": [0, 0, 5],\n  }\n}"),
            syntax("", 2) + "a comma after the last member, before '}' (JSON allows none there)");
  EXPECT_EQ(error("{\"camera\": {\"position\": [0, 0, 5,]}}"),
            syntax("", 1) + "a comma after the last element, before ']' (JSON allows none there)");
  // A ']' where a value must come but after no comma is the parser's own message.
  EXPECT_EQ(error("{\"camera\": {\"position\": ]}}").find("comma"), std::string::npos);
}

TEST_F(SceneFileTest, DuplicateKeys) {
  expect_error("{\n  \"camera\": {\"position\": [0, 0, 5],\n  \"position\": [0, 0, 1]}\n}", 3,
               "camera.position", "duplicate key");
}

TEST_F(SceneFileTest, MissingRequiredValues) {
  expect_error("{\n  \"objects\": []\n}", 1, "camera", "required");
  expect_error("{\n  \"camera\":\n    {\"fov\": 60}\n}", 3, "camera.position", "required");
  expect_error(with_object(R"({"shape": {"sphere": {"radius": 1}}})"), 3, "objects[0].name",
               "required");
  expect_error(with_object(R"({"name": "a"})"), 3, "objects[0].shape", "required");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {}}})"), 3,
               "objects[0].shape.sphere.radius", "required");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "rotation": {"axis": [0, 1, 0]}})"),
               4, "objects[0].rotation.degrees", "required");
}

TEST_F(SceneFileTest, SpeedsMustBeBelowLight) {
  expect_error("{\n  \"camera\": {\"position\": [0, 0, 5],\n    \"velocity\": [0, 0, 1.5]}\n}", 3,
               "camera.velocity", "speed 1.5 must be below the speed of light (1)");
  expect_error("{\n  \"camera\": {\"position\": [0, 0, 5], \"velocity\": [-1, 0, 0]}\n}", 2,
               "camera.velocity", "speed 1 must be below the speed of light (1)");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "velocity": [0.8, 0.8, 0]})"),
               4, "objects[0].velocity", "below the speed of light");
  expect_error(
      "{\n  \"camera\": {\"position\": [0, 0, 5]},\n  \"sky\": {\"color\": [0, 0, 0],\n"
      "    \"velocity\": [0, 1, 0]}\n}",
      4, "sky.velocity", "speed 1 must be below the speed of light (1)");
}

TEST_F(SceneFileTest, VectorsAndNumbers) {
  expect_error("{\n  \"camera\": {\"position\": [0, 5]}\n}", 2, "camera.position",
               "array of 3 numbers, got an array of 2 elements");
  expect_error("{\n  \"camera\": {\"position\": [0, 0, 5, 1]}\n}", 2, "camera.position",
               "array of 3 numbers");
  expect_error("{\n  \"camera\": {\"position\": 5}\n}", 2, "camera.position", "array of 3 numbers");
  expect_error("{\n  \"camera\": {\"position\": [0,\n \"5\", 0]}\n}", 3, "camera.position[1]",
               "must be a number, got string \"5\"");
  expect_error("{\n  \"camera\": {\"position\": [0, 0, 0], \"time\": null}\n}", 2, "camera.time",
               "must be a number, got null");
  expect_error("{\n  \"camera\": {\"position\": [0, 0, 0], \"time\": true}\n}", 2, "camera.time",
               "must be a number");
  expect_error("{\n  \"camera\": {\"position\": [0, 0, 0]},\n  \"render\": {\"relativity\": 1}\n}",
               3, "render.relativity", "true or false");
  expect_error("{\n  \"camera\": [0, 0, 0]\n}", 2, "camera", "must be an object");
  expect_error("[1, 2]", 1, "(top level)", "must be an object");
  expect_error("{\"camera\": {\"position\": [0, 0, 0]},\n \"objects\": {}}", 2, "objects",
               "must be an array");
}

TEST_F(SceneFileTest, SizesMustBePositive) {
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": -1}}})"), 3,
               "objects[0].shape.sphere.radius", "greater than 0, got -1");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 0}}})"), 3,
               "objects[0].shape.sphere.radius", "greater than 0");
  expect_error(with_object(R"({"name": "a", "shape": {"box": {"size": [1, 0, 1]}}})"), 3,
               "objects[0].shape.box.size[1]", "greater than 0");
  expect_error(with_object(R"({"name": "a", "shape": {"plane": {"size": [1, 1, 1]}}})"), 3,
               "objects[0].shape.plane.size", "array of 2 numbers");
  expect_error(with_object(R"({"name": "a", "shape": {"plane": {"size": [-2, 1]}}})"), 3,
               "objects[0].shape.plane.size[0]", "greater than 0");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "scale": -2})"),
               4, "objects[0].scale", "greater than 0");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "scale": [1, 1, 0]})"),
               4, "objects[0].scale[2]", "greater than 0");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "material": {"checker": {"size": 0, "colors": [[1, 1, 1], [0, 0, 0]]}}})"),
               4, "objects[0].material.checker.size", "greater than 0");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "material": {"checker": {"size": 1, "colors": [[1, 1, 1]]}}})"),
               4, "objects[0].material.checker.colors", "array of 2 colours");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "material": {"color": [1, -0.5, 1]}})"),
               4, "objects[0].material.color[1]", ">= 0");
}

TEST_F(SceneFileTest, CameraLimits) {
  auto camera = [](const std::string& extra) {
    return "{\n  \"camera\": {\"position\": [0, 0, 5],\n    " + extra + "}\n}";
  };
  expect_error(camera("\"fov\": 0"), 3, "camera.fov", "between 0 and 180");
  expect_error(camera("\"fov\": 180"), 3, "camera.fov", "between 0 and 180");
  expect_error(camera("\"fov\": -5"), 3, "camera.fov", "got -5");
  expect_error(camera("\"width\": 0"), 3, "camera.width", "integer from 1 to 16384, got 0");
  expect_error(camera("\"width\": 100000"), 3, "camera.width", "got 100000");
  expect_error(camera("\"height\": 2.5"), 3, "camera.height", "integer");
  expect_error(camera("\"width\": 16384, \"height\": 16384"), 3, "camera.width", "2^27");
  expect_error(camera("\"samples\": 0"), 3, "camera.samples", "from 1 to 65536");
  expect_error(camera("\"forward\": [0, 0, 0]"), 3, "camera.forward", "zero vector");
  expect_error(camera("\"forward\": [0, 0, -1], \"up\": [0, 0, 2]"), 3, "camera.up", "parallel");
  // The default up is parallel to this forward; the error names up and the camera's line.
  expect_error(camera("\"forward\": [0, -1, 0]"), 2, "camera.up", "defaults to");
}

// A texture or a clock's dial on a mesh is read at the mesh's texture coordinates: a mesh
// without them is refused at the pattern, naming the mesh (it would show one texel everywhere).
TEST_F(SceneFileTest, TexturesAndClocksOnAMeshNeedItsTextureCoordinates) {
  write("bare.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write("mapped.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  fs::copy_file(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes" / "uv-grid.png", dir_ / "uv-grid.png");
  const auto object = [](const std::string& shape, const std::string& material) {
    return "{\"name\": \"m\", \"shape\": " + shape + ",\n \"material\": " + material + "}";
  };
  const std::string bare = R"({"mesh": {"file": "bare.obj"}})";
  const std::string mapped = R"({"mesh": {"file": "mapped.obj"}})";
  const std::string texture = R"({"texture": "uv-grid.png"})";
  const std::string clock = R"({"clock": {"period": 2}})";
  const std::string bare_file = "\"" + (dir_ / "bare.obj").string() + "\" has none";
  expect_error(with_object(object(bare, texture)), 4, "objects[0].material.texture", bare_file);
  expect_error(with_object(object(bare, clock)), 4, "objects[0].material.clock", bare_file);
  EXPECT_EQ(error(with_object(object(mapped, texture))), "");
  EXPECT_EQ(error(with_object(object(mapped, clock))), "");
  EXPECT_EQ(error(with_object(object(bare, R"({"color": [1, 0, 0]})"))), "");
  EXPECT_EQ(error(with_object(object(R"({"box": {"size": [1, 1, 1]}})", texture))), "");
}

TEST_F(SceneFileTest, ObjectNamesAndShapes) {
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}}},
    {"name": "a", "shape": {"sphere": {"radius": 1}}})"),
               4, "objects[1].name", "duplicate object name \"a\" (also used by objects[0])");
  expect_error(with_object(R"({"name": "", "shape": {"sphere": {"radius": 1}}})"), 3,
               "objects[0].name", "must not be empty");
  expect_error(with_object(R"({"name": "a", "shape": {"cone": {"radius": 1}}})"), 3,
               "objects[0].shape.cone", "unknown key \"cone\" (expected one of: sphere, box");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1},
    "box": {"size": [1, 1, 1]}}})"),
               3, "objects[0].shape",
               "exactly one of: sphere, box, plane, mesh (found sphere, box)");
  expect_error(with_object(R"({"name": "a", "shape": {}})"), 3, "objects[0].shape", "found none");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "rotation": {"axis": [0, 0, 0], "degrees": 10}})"),
               4, "objects[0].rotation.axis", "zero vector");
}

TEST_F(SceneFileTest, MaterialsAndSky) {
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "material": {"color": [1, 1, 1],
      "unlit": "no"}})"),
               5, "objects[0].material.unlit", "must be true or false, got string \"no\"");
  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "material": {"unlit": true}})"),
               4, "objects[0].material", "exactly one of: color, checker, texture");
  const std::string camera = "{\n  \"camera\": {\"position\": [0, 0, 5]},\n";
  expect_error(camera + "  \"sky\": {\"color\": [0, 0, 0], \"grid\": {}}\n}", 3, "sky",
               "exactly one of: color, image, grid");
  expect_error(camera + "  \"sky\": {\"grid\": {\"spacing\": 0}}\n}", 3, "sky.grid.spacing",
               "at most 90");
  expect_error(camera + "  \"sky\": {\"grid\": {\n\"spacing\": 91}}\n}", 4, "sky.grid.spacing",
               "at most 90");
  expect_error(camera + "  \"sky\": {\"grid\": {\"line_width\": 0}}\n}", 3, "sky.grid.line_width",
               "greater than 0");
  expect_error(camera + "  \"sky\": {\"image\": \"\"}\n}", 3, "sky.image", "must not be empty");
}

// A sphere with the given material, whose first line is line 4 of the scene.
std::string with_material(const std::string& material) {
  return with_object(
      "{\"name\": \"a\", \"shape\": {\"sphere\": {\"radius\": 1}},\n"
      "    \"material\": " +
      material + "}");
}

TEST_F(SceneFileTest, BadBlackbodies) {
  const std::string temperature = "objects[0].material.blackbody.temperature";
  expect_error(with_material(R"({"blackbody": {"temperature": 0}})"), 4, temperature,
               "must be greater than 0, got 0");
  expect_error(with_material(R"({"blackbody": {"temperature": -300}})"), 4, temperature,
               "must be greater than 0, got -300");
  expect_error(with_material(R"({"blackbody":
      {"luminance": 1,
       "temperature": -1e-9}})"),
               6, temperature, "must be greater than 0");
  expect_error(with_material(R"({"blackbody": {"temperature": "hot"}})"), 4, temperature,
               "must be a number, got string \"hot\"");
  // A missing key is reported where the object that lacks it starts.
  expect_error(with_material(R"({"blackbody":
      {"luminance": 1}})"),
               5, temperature, "required key is missing");
  expect_error(with_material(R"({"blackbody": {"temperature": 5000,
      "luminance": -1}})"),
               5, "objects[0].material.blackbody.luminance", "must be >= 0, got -1");
  expect_error(with_material(R"({"blackbody": {"temperature": 5000, "luminance": null}})"), 4,
               "objects[0].material.blackbody.luminance", "must be a number, got null");
  expect_error(with_material(R"({"blackbody": {"temperature": 5000,
      "color": [1, 1, 1]}})"),
               5, "objects[0].material.blackbody.color",
               "unknown key \"color\" (expected one of: temperature, luminance)");
  expect_error(with_material(R"({"blackbody": 5000})"), 4, "objects[0].material.blackbody",
               "must be an object");
  expect_error(with_material(R"({"color": [1, 1, 1], "blackbody": {"temperature": 5000}})"), 4,
               "objects[0].material",
               "exactly one of: color, checker, texture, blackbody, spectrum, blink, clock "
               "(found color, blackbody)");
}

TEST_F(SceneFileTest, BadSpectra) {
  const std::string spectrum = "objects[0].material.spectrum";
  // Each element on its own line, so that the line tells which one is blamed.
  expect_error(with_material(R"({"spectrum": {"wavelengths": [400,
      600,
      500], "values": [1, 1, 1]}})"),
               6, spectrum + ".wavelengths[2]", "strictly increasing (500 after 600)");
  expect_error(with_material(R"({"spectrum": {"wavelengths": [400,
      500,
      500, 700], "values": [1, 1, 1, 1]}})"),
               6, spectrum + ".wavelengths[2]", "strictly increasing (500 after 500)");
  expect_error(with_material(R"({"spectrum": {"values": [1, 1],
      "wavelengths": [0,
      500]}})"),
               5, spectrum + ".wavelengths[0]", "greater than 0 nm, got 0");
  expect_error(with_material(R"({"spectrum": {"wavelengths": [-400,
      500], "values": [1, 1]}})"),
               4, spectrum + ".wavelengths[0]", "greater than 0 nm, got -400");
  expect_error(with_material(R"({"spectrum": {"wavelengths": [400, 500, 600],
      "values": [1, 1]}})"),
               5, spectrum + ".values", "as many entries as wavelengths (3), got 2");
  expect_error(with_material(R"({"spectrum": {"wavelengths": [400, 500],
      "values": [1, 1, 1]}})"),
               5, spectrum + ".values", "as many entries as wavelengths (2), got 3");
  expect_error(with_material(R"({"spectrum": {"values": [1],
      "wavelengths": [500]}})"),
               5, spectrum + ".wavelengths", "at least 2 numbers, got an array of 1 elements");
  expect_error(with_material(R"({"spectrum": {"wavelengths": [400, 500],
      "values": [1]}})"),
               5, spectrum + ".values", "at least 2 numbers, got an array of 1 elements");
  expect_error(with_material(R"({"spectrum": {"wavelengths": [],
      "values": []}})"),
               4, spectrum + ".wavelengths", "at least 2 numbers, got an array of 0 elements");
  expect_error(with_material(R"({"spectrum": {"wavelengths": 500, "values": 1}})"), 4,
               spectrum + ".wavelengths", "at least 2 numbers, got number 500");
  expect_error(with_material(R"({"spectrum": {"wavelengths": [400, 500], "values": [1,
      -0.5]}})"),
               5, spectrum + ".values[1]", "must be >= 0, got -0.5");
  expect_error(with_material(R"({"spectrum": {"wavelengths": [400, 500], "values": [1,
      "x"]}})"),
               5, spectrum + ".values[1]", "must be a number, got string \"x\"");
  expect_error(
      with_material(R"({"spectrum": {"wavelengths": [400, 500],
      "value": [1, 1]}})"),
      5, spectrum + ".value",
      "unknown key \"value\" (did you mean \"values\"? expected one of: wavelengths, values)");
  expect_error(with_material(R"({"spectrum":
      {"wavelengths": [400, 500]}})"),
               5, spectrum + ".values", "required key is missing");
}

// A render section whose first line is line 3 of the scene.
std::string with_render(const std::string& render) {
  return "{\n  \"camera\": {\"position\": [0, 0, 5]},\n  \"render\": " + render + "\n}";
}

TEST_F(SceneFileTest, BadColourRenderSettings) {
  expect_error(with_render(R"({"doppler": "rgb"})"), 3, "render.doppler",
               "unknown model \"rgb\" (expected one of: spectral, rgb3, hue, off)");
  expect_error(with_render(R"({"relativity": true,
    "doppler": "Spectral"})"),
               4, "render.doppler", "unknown model \"Spectral\"");  // names are case-sensitive
  expect_error(with_render(R"({"doppler": 3})"), 3, "render.doppler",
               "must be a string, got number 3");
  expect_error(with_render(R"({
    "searchlight": "chang"})"),
               4, "render.searchlight",
               "unknown model \"chang\" (expected one of: physical, chang1996, off)");
  expect_error(with_render(R"({"searchlight": true})"), 3, "render.searchlight",
               "must be a string");
  expect_error(with_render(R"({"tonemap":
    "aces"})"),
               4, "render.tonemap",
               "unknown model \"aces\" (expected one of: clamp, reinhard, filmic)");
  expect_error(with_render(R"({"exposure": "bright"})"), 3, "render.exposure",
               "must be a number (EV) or \"auto\"");
  expect_error(with_render(R"({"exposure": "AUTO"})"), 3, "render.exposure",
               "must be a number (EV) or \"auto\"");
  expect_error(with_render(R"({"exposure": true})"), 3, "render.exposure", "must be a number");
  expect_error(with_render(R"({"hue": {"loop": true,
    "lop": true}})"),
               4, "render.hue.lop",
               "unknown key \"lop\" (did you mean \"loop\"? expected one of: loop)");
  expect_error(with_render(R"({"hue": {"loop": 1}})"), 3, "render.hue.loop", "true or false");
  expect_error(with_render(R"({"hue": true})"), 3, "render.hue", "must be an object");
  expect_error(with_render(R"({"tonemapping": "filmic"})"), 3, "render.tonemapping",
               "unknown key \"tonemapping\" (expected one of: relativity, light_delay, "
               "exposure, doppler, searchlight, hue, tonemap, light_source_delay, shadows)");
}

// A lights array whose first element starts on line 3 of the scene.
std::string with_light(const std::string& lights) {
  return "{\n  \"camera\": {\"position\": [0, 0, 5]},\n  \"lights\": [" + lights + "]\n}";
}

TEST_F(SceneFileTest, BadLightPowerAndSize) {
  expect_error(with_light(R"({"name": "a", "type": "point", "intensity": -1})"), 3,
               "lights[0].intensity", "must be >= 0, got -1");
  expect_error(with_light(R"({"name": "a", "type": "spot", "intensity": -0.5})"), 3,
               "lights[0].intensity", "must be >= 0, got -0.5");
  expect_error(with_light(R"({"name": "a", "type": "sphere", "radius": 1, "intensity": -2})"), 3,
               "lights[0].intensity", "must be >= 0, got -2");
  expect_error(with_light(R"({"name": "a", "type": "directional", "irradiance": -3})"), 3,
               "lights[0].irradiance", "must be >= 0, got -3");
  expect_error(with_light(R"({"name": "a", "type": "point", "intensity": "bright"})"), 3,
               "lights[0].intensity", "must be a number, got string \"bright\"");
  // The second light, on its own line, is the one blamed.
  expect_error(with_light(R"({"name": "a", "type": "point"},
    {"name": "b", "type": "sphere", "radius": -1})"),
               4, "lights[1].radius", "must be greater than 0, got -1");
  expect_error(with_light(R"({"name": "a", "type": "sphere", "radius": 0})"), 3, "lights[0].radius",
               "must be greater than 0, got 0");
  expect_error(with_light(R"({"name": "a",
    "type": "sphere"})"),
               3, "lights[0].radius", "required key is missing");
}

TEST_F(SceneFileTest, BadSpotAngles) {
  for (const char* cone : {"0", "180", "200", "-10"}) {
    SCOPED_TRACE(cone);
    expect_error(with_light(fmt::format(R"({{"name": "a", "type": "spot", "cone": {}}})", cone)), 3,
                 "lights[0].cone",
                 fmt::format("must be between 0 and 180 degrees (both excluded), got {}", cone));
  }
  expect_error(with_light(R"({"name": "a", "type": "spot", "cone": 40,
    "falloff": 25})"),
               4, "lights[0].falloff", "must be from 0 to half the cone (20 degrees), got 25");
  expect_error(with_light(R"({"name": "a", "type": "spot", "falloff": 31})"), 3,
               "lights[0].falloff", "half the cone (30 degrees), got 31");
  expect_error(with_light(R"({"name": "a", "type": "spot", "falloff": -1})"), 3,
               "lights[0].falloff", "got -1");
  expect_error(with_light(R"({"name": "a", "type": "spot", "direction": [0, 0, 0]})"), 3,
               "lights[0].direction", "must not be the zero vector");
  expect_error(with_light(R"({"name": "a", "type": "directional", "direction": [0, 0, 0]})"), 3,
               "lights[0].direction", "must not be the zero vector");
}

TEST_F(SceneFileTest, BadLightMotion) {
  expect_error(with_light(R"({"name": "a", "type": "point",
    "velocity": [0, 0, 1]})"),
               4, "lights[0].velocity", "speed 1 must be below the speed of light (1)");
  expect_error(with_light(R"({"name": "a", "type": "directional", "velocity": [0.8, 0.8, 0]})"), 3,
               "lights[0].velocity", "must be below the speed of light");
  expect_error(with_light(R"({"name": "a", "type": "sphere", "radius": 1, "velocity": [2, 0, 0]})"),
               3, "lights[0].velocity", "speed 2 must be below the speed of light (1)");
  expect_error(with_light(R"({"name": "a", "type": "point", "position": [0, 0]})"), 3,
               "lights[0].position", "array of 3 numbers");
  expect_error(with_light(R"({"name": "a", "type": "point", "time": null})"), 3, "lights[0].time",
               "must be a number, got null");
}

TEST_F(SceneFileTest, BadLightTypesNamesAndKeys) {
  expect_error(with_light(R"({"name": "a", "type": "laser"})"), 3, "lights[0].type",
               "unknown light type \"laser\" (expected one of: point, spot, directional, sphere)");
  expect_error(with_light(R"({"name": "a", "type": "Point"})"), 3, "lights[0].type",
               "unknown light type \"Point\"");
  expect_error(with_light(R"({"name": "a", "type": 1})"), 3, "lights[0].type",
               "must be a string, got number 1");
  expect_error(with_light(R"({"name": "a"})"), 3, "lights[0].type", "required key is missing");
  expect_error(with_light(R"({"type": "point"})"), 3, "lights[0].name", "required key is missing");
  expect_error(with_light(R"({"name": "", "type": "point"})"), 3, "lights[0].name",
               "must not be empty");
  expect_error(with_light(R"({"name": "a", "type": "point"},
    {"name": "a", "type": "spot"})"),
               4, "lights[1].name", "duplicate light name \"a\" (also used by lights[0])");
  // A light may share its name with an object.
  EXPECT_EQ(error(R"({"camera": {"position": [0, 0, 5]},
    "objects": [{"name": "a", "shape": {"sphere": {"radius": 1}}}],
    "lights": [{"name": "a", "type": "point"}]})"),
            "");

  expect_error(with_light(R"({"name": "a", "type": "point",
    "radius": 1})"),
               4, "lights[0].radius",
               "unknown key \"radius\" for a point light (expected one of: name, type, position, "
               "time, velocity, motion, color, blackbody, intensity)");
  expect_error(with_light(R"({"name": "a", "type": "directional", "intensity": 1})"), 3,
               "lights[0].intensity", "unknown key \"intensity\" for a directional light");
  expect_error(with_light(R"({"name": "a", "type": "spot", "irradiance": 1})"), 3,
               "lights[0].irradiance", "unknown key \"irradiance\" for a spot light");
  expect_error(with_light(R"({"name": "a", "type": "sphere", "radius": 1, "cone": 30})"), 3,
               "lights[0].cone", "unknown key \"cone\" for a sphere light");
  expect_error(with_light(R"({"name": "a", "type": "point", "direction": [0, 0, -1]})"), 3,
               "lights[0].direction", "unknown key \"direction\" for a point light");
  expect_error(with_light(R"({"name": "a", "type": "point", "colour": [1, 1, 1]})"), 3,
               "lights[0].colour", "unknown key \"colour\"");

  expect_error(with_light(R"({"name": "a", "type": "point", "color": [1, 1, 1],
    "blackbody": {"temperature": 3000}})"),
               3, "lights[0]", "at most one of: color, blackbody (found color, blackbody)");
  expect_error(with_light(R"({"name": "a", "type": "point", "color": [1, -1, 1]})"), 3,
               "lights[0].color[1]", "must be >= 0, got -1");
  expect_error(with_light(R"({"name": "a", "type": "point", "blackbody": {"temperature": 0}})"), 3,
               "lights[0].blackbody.temperature", "must be greater than 0, got 0");
  expect_error(with_light(R"({"name": "a", "type": "point", "blackbody": {}})"), 3,
               "lights[0].blackbody.temperature", "required key is missing");
  expect_error(
      with_light(
          R"({"name": "a", "type": "point", "blackbody": {"temperature": 3000, "luminance": 2}})"),
      3, "lights[0].blackbody.luminance",
      "unknown key \"luminance\" (expected one of: temperature)");

  expect_error("{\n  \"camera\": {\"position\": [0, 0, 5]},\n  \"lights\": {}\n}", 3, "lights",
               "must be an array of lights, got an object");
  expect_error(with_light("1"), 3, "lights[0]", "must be an object, got number 1");
}

TEST_F(SceneFileTest, BadLitMaterials) {
  expect_error(with_material(R"({"blackbody": {"temperature": 5000},
      "unlit": false})"),
               5, "objects[0].material.unlit",
               "a blackbody material is an emitter and cannot be lit");
  expect_error(with_material(R"({"unlit": false,
      "spectrum": {"wavelengths": [400, 700], "values": [1, 1]}})"),
               4, "objects[0].material.unlit", "a spectrum material is an emitter");
  expect_error(with_material(R"({"color": [1,
      1.5, 0.5], "unlit": false})"),
               5, "objects[0].material.color[1]",
               "must be at most 1 for a lit material (an albedo), got 1.5");
  expect_error(with_material(R"({"unlit": false, "checker": {"size": 1,
      "colors": [[1, 1, 1], [2, 0, 0]]}})"),
               5, "objects[0].material.checker.colors[1][0]", "must be at most 1");
  expect_error(with_material(R"({"color": [0.5, -0.5, 0.5], "unlit": false})"), 4,
               "objects[0].material.color[1]", "must be >= 0, got -0.5");
  expect_error(with_material(R"({"color": [1, 1, 1],
      "glossy": {}})"),
               5, "objects[0].material.glossy",
               "a glossy layer needs a lit material (\"unlit\": false)");
  expect_error(with_material(R"({"color": [1, 1, 1], "unlit": true, "glossy": {}})"), 4,
               "objects[0].material.glossy", "needs a lit material");
  const std::string glossy = "objects[0].material.glossy";
  expect_error(with_material(R"({"color": [1, 1, 1], "unlit": false,
      "glossy": {"roughness": 0}})"),
               5, glossy + ".roughness", "must be greater than 0 and at most 1, got 0");
  expect_error(with_material(R"({"color": [1, 1, 1], "unlit": false,
      "glossy": {"roughness": 1.5}})"),
               5, glossy + ".roughness", "got 1.5");
  expect_error(with_material(R"({"color": [1, 1, 1], "unlit": false,
      "glossy": {"specular": -0.1}})"),
               5, glossy + ".specular", "must be at least 0 and at most 1, got -0.1");
  expect_error(with_material(R"({"color": [1, 1, 1], "unlit": false,
      "glossy": {"specular": 2}})"),
               5, glossy + ".specular", "got 2");
  expect_error(with_material(R"({"color": [1, 1, 1], "unlit": false,
      "glossy": {"shine": 2}})"),
               5, glossy + ".shine",
               "unknown key \"shine\" (expected one of: roughness, specular)");
  expect_error(with_material(R"({"color": [1, 1, 1], "unlit": false, "glossy": true})"), 4, glossy,
               "must be an object");

  // An EXR albedo with values above 1 is found when the texture loads; unlit, it is radiance.
  Image bright;
  bright.width = 1;
  bright.height = 1;
  bright.rgb = {0.5f, 2, 0.5f};
  write_images(bright, std::nullopt, dir_ / "bright.exr");
  expect_error(with_material(R"({"unlit": false,
      "texture": "bright.exr"})"),
               5, "objects[0].material.texture", "must have values from 0 to 1, found 0.5 to 2");
  EXPECT_EQ(error(with_material(R"({"texture": "bright.exr"})")), "");
}

TEST_F(SceneFileTest, BadLightRenderSettings) {
  expect_error(with_render(R"({"light_source_delay": "retarded"})"), 3, "render.light_source_delay",
               "unknown mode \"retarded\" (expected one of: surface, camera, none)");
  expect_error(with_render(R"({"shadows": true,
    "light_source_delay": "Surface"})"),
               4, "render.light_source_delay", "unknown mode \"Surface\"");
  expect_error(with_render(R"({"light_source_delay": false})"), 3, "render.light_source_delay",
               "must be a string, got boolean false");
  expect_error(with_render(R"({"shadows": "yes"})"), 3, "render.shadows",
               "must be true or false, got string \"yes\"");
}

// ---------------------------------------------------------------------------------------------
// Meshes and images

TEST_F(SceneFileTest, MeshFilesAreResolvedAndLoadedOnce) {
  write("meshes/tri.obj", kTriangleObj);
  const Scene s = load(R"({
    "camera": {"position": [0, 0, 5]},
    "objects": [
      {"name": "a", "shape": {"mesh": {"file": "meshes/tri.obj"}}},
      {"name": "b", "shape": {"mesh": {"file": "./meshes/../meshes/tri.obj"}}},
      {"name": "c", "shape": {"mesh": {"file": ")" +
                       (dir_ / "meshes" / "tri.obj").string() + R"("}}}
    ]
  })");
  const auto& a = std::get<MeshShape>(s.objects.at(0).shape).mesh;
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->triangles.size(), 1u);
  EXPECT_EQ(std::get<MeshShape>(s.objects.at(1).shape).mesh, a);
  EXPECT_EQ(std::get<MeshShape>(s.objects.at(2).shape).mesh, a);
  EXPECT_TRUE(report_.warnings.empty());
}

TEST_F(SceneFileTest, DroppedDegenerateTrianglesAreReportedOnce) {
  write("tri.obj", kTriangleObjWithDegenerate);
  load(with_object(R"({"name": "a", "shape": {"mesh": {"file": "tri.obj"}}},
                      {"name": "b", "shape": {"mesh": {"file": "tri.obj"}}})"));
  ASSERT_EQ(report_.warnings.size(), 1u);
  EXPECT_EQ(report_.warnings[0], (dir_ / "tri.obj").string() + ": 1 degenerate triangles dropped");
}

TEST_F(SceneFileTest, MeshErrorsAreLocatedInTheScene) {
  write("tri.obj", kTriangleObj);
  const std::string text = with_object(R"({"name": "a", "shape": {"mesh": {"file": "tri.obj"}}},
    {"name": "b", "shape": {"mesh":
      {"file": "missing.obj"}}})");
  expect_error(text, 5, "objects[1].shape.mesh.file", "missing.obj");
  expect_error(with_object(R"({"name": "a", "shape": {"mesh": {"file": 3}}})"), 3,
               "objects[0].shape.mesh.file", "must be a string");
  // Every other error is found before any file is loaded.
  expect_error(with_object(R"({"name": "a", "shape": {"mesh": {"file": "missing.obj"}}},
    {"name": "b", "shape": {"sphere": {"radius": -1}}})"),
               4, "objects[1].shape.sphere.radius", "greater than 0");
}

TEST_F(SceneFileTest, TexturesAndSkyImagesAreSharedAndLocated) {
  write_two_texel_png("tex.png", {1, 0, 0, 0, 0, 1});
  const Scene s = load(R"({
    "camera": {"position": [0, 0, 5]},
    "objects": [
      {"name": "a", "shape": {"sphere": {"radius": 1}}, "material": {"texture": "tex.png"}},
      {"name": "b", "shape": {"sphere": {"radius": 1}}, "material": {"texture": "./tex.png"}}
    ],
    "sky": {"image": "tex.png"}
  })");
  const auto& a = std::get<Texture>(s.objects.at(0).material.pattern).image;
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->width, 2);
  EXPECT_EQ(std::get<Texture>(s.objects.at(1).material.pattern).image, a);
  EXPECT_EQ(std::get<SkyImage>(s.sky.pattern).image, a);

  expect_error(with_object(R"({"name": "a", "shape": {"sphere": {"radius": 1}},
    "material": {"texture": "nope.png"}})"),
               4, "objects[0].material.texture", "nope.png");
  expect_error(
      "{\n  \"camera\": {\"position\": [0, 0, 5]},\n  \"sky\": {\"image\": \"nope.exr\"}\n}", 3,
      "sky.image", "nope.exr");
}

// ---------------------------------------------------------------------------------------------
// The documentation and the schema

std::string read_source_file(const std::string& relative) {
  std::ifstream in(fs::path(LIGHTCONE_SOURCE_DIR) / relative, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The lit example in the section on lights is a whole scene, and loads.
TEST_F(SceneFileTest, DocumentedLightsExampleLoads) {
  const std::string doc = read_source_file("docs/scene-format.md");
  const std::size_t section = doc.find("## `lights[]`");
  ASSERT_NE(section, std::string::npos);
  const std::size_t start = doc.find("```jsonc\n", section);
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = doc.find("```", start + 9);
  const Scene s = load(doc.substr(start + 9, end - start - 9));
  EXPECT_EQ(s.lights.size(), 4u);
  EXPECT_FALSE(s.objects.at(0).material.unlit);
}

TEST_F(SceneFileTest, DocumentedExampleLoads) {
  const std::string doc = read_source_file("docs/scene-format.md");
  const std::size_t start = doc.find("```jsonc\n");
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = doc.find("```", start + 9);
  const Scene s = load(doc.substr(start + 9, end - start - 9));
  EXPECT_EQ(s.objects.size(), 3u);
  expect_vec(s.camera.world_line.velocity, 0, 0, -0.6);
}

// Every object in the schema that lists properties forbids others, like the loader.
void expect_closed(const nlohmann::json& node, const std::string& where) {
  if (node.is_object()) {
    if (node.contains("properties")) {
      EXPECT_EQ(node.value("additionalProperties", nlohmann::json()), false) << where;
    }
    for (const auto& item : node.items()) expect_closed(item.value(), where + "/" + item.key());
  } else if (node.is_array()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      expect_closed(node[i], where + "/" + std::to_string(i));
  }
}

TEST(SceneSchema, IsClosedEverywhere) {
  const auto schema = nlohmann::json::parse(read_source_file("schema/scene.schema.json"));
  EXPECT_EQ(schema.at("$schema"), "https://json-schema.org/draft/2020-12/schema");
  expect_closed(schema, "");
}

std::vector<std::string> keys_of(const nlohmann::json& object) {
  std::vector<std::string> keys;
  for (const auto& item : object.items()) keys.push_back(item.key());
  std::sort(keys.begin(), keys.end());
  return keys;
}

// The schema's sky.stars: a boolean or the loader's three keys, its one catalogue.
TEST(SceneSchema, ListsTheSkysStars) {
  const auto schema = nlohmann::json::parse(read_source_file("schema/scene.schema.json"));
  const auto& stars = schema.at("$defs").at("sky").at("properties").at("stars").at("oneOf");
  EXPECT_EQ(stars.at(0).at("type"), "boolean");
  EXPECT_EQ(keys_of(stars.at(1).at("properties")),
            (std::vector<std::string>{"catalogue", "exposure", "magnitude_limit"}));
  EXPECT_EQ(stars.at(1).at("properties").at("catalogue").at("enum"),
            nlohmann::json::parse(R"(["bright"])"));
}

// The schema names the same colour keys and model names as the loader accepts.
TEST(SceneSchema, ListsTheColourKeysAndModels) {
  const auto schema = nlohmann::json::parse(read_source_file("schema/scene.schema.json"));
  const auto& defs = schema.at("$defs");
  const auto& render = defs.at("render").at("properties");
  EXPECT_EQ(keys_of(render), (std::vector<std::string>{"doppler", "exposure", "hue", "light_delay",
                                                       "light_source_delay", "relativity",
                                                       "searchlight", "shadows", "tonemap"}));
  EXPECT_EQ(render.at("doppler").at("enum"),
            nlohmann::json::parse(R"(["spectral", "rgb3", "hue", "off"])"));
  EXPECT_EQ(render.at("doppler").at("default"), "spectral");
  EXPECT_EQ(render.at("searchlight").at("enum"),
            nlohmann::json::parse(R"(["physical", "chang1996", "off"])"));
  EXPECT_EQ(render.at("searchlight").at("default"), "physical");
  EXPECT_EQ(render.at("tonemap").at("enum"),
            nlohmann::json::parse(R"(["clamp", "reinhard", "filmic"])"));
  EXPECT_EQ(render.at("tonemap").at("default"), "filmic");
  EXPECT_EQ(render.at("exposure").at("default"), "auto");
  EXPECT_EQ(keys_of(render.at("hue").at("properties")), (std::vector<std::string>{"loop"}));
  EXPECT_NE(render.at("exposure").dump().find(R"({"const":"auto"})"), std::string::npos);

  const auto& material = defs.at("unlitMaterial").at("properties");
  EXPECT_EQ(keys_of(material), (std::vector<std::string>{"blackbody", "blink", "checker", "clock",
                                                         "color", "spectrum", "texture", "unlit"}));
  EXPECT_EQ(keys_of(material.at("blackbody").at("properties")),
            (std::vector<std::string>{"luminance", "temperature"}));
  EXPECT_EQ(material.at("blackbody").at("required"), nlohmann::json::parse(R"(["temperature"])"));
  EXPECT_EQ(keys_of(material.at("spectrum").at("properties")),
            (std::vector<std::string>{"values", "wavelengths"}));
  EXPECT_EQ(defs.at("unlitMaterial").at("oneOf").size(), 7u);

  // And the format reference documents every one of them.
  const std::string doc = read_source_file("docs/scene-format.md");
  for (const char* word :
       {"`doppler`", "`searchlight`", "`hue`", "`tonemap`", "`\"auto\"`", "`blackbody`",
        "`spectrum`", "`temperature`", "`luminance`", "`wavelengths`", "`values`", "`chang1996`",
        "`rgb3`", "`reinhard`", "`filmic`", "design/colour.md"})
    EXPECT_NE(doc.find(word), std::string::npos) << word;
}

// The schema names the same light types, light keys, lit-material keys and modes as the loader.
TEST(SceneSchema, ListsTheLightKeysAndModes) {
  const auto schema = nlohmann::json::parse(read_source_file("schema/scene.schema.json"));
  const auto& defs = schema.at("$defs");
  EXPECT_EQ(schema.at("properties").at("lights").at("items").at("$ref"), "#/$defs/light");
  const std::vector<std::string> common = {"blackbody", "color", "name",    "position",
                                           "time",      "type",  "velocity"};
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.end(), common.begin(), common.end());
    std::sort(extra.begin(), extra.end());
    return extra;
  };
  const std::pair<const char*, std::vector<std::string>> types[] = {
      {"point", with({"intensity", "motion"})},
      {"spot", with({"intensity", "direction", "cone", "falloff", "motion"})},
      {"directional", with({"irradiance", "direction"})},
      {"sphere", with({"intensity", "radius", "motion"})}};
  const auto& one_of = defs.at("light").at("oneOf");
  ASSERT_EQ(one_of.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& [type, keys] = types[i];
    SCOPED_TRACE(type);
    const std::string ref = one_of[i].at("$ref");
    const auto& light = defs.at(ref.substr(ref.rfind('/') + 1));
    EXPECT_EQ(keys_of(light.at("properties")), keys);
    EXPECT_EQ(light.at("properties").at("type").at("const"), type);
  }
  EXPECT_EQ(defs.at("sphereLight").at("required"),
            nlohmann::json::parse(R"(["name", "type", "radius"])"));

  const auto& lit = defs.at("litMaterial").at("properties");
  EXPECT_EQ(keys_of(lit), (std::vector<std::string>{"blink", "checker", "clock", "color", "glossy",
                                                    "texture", "unlit"}));
  EXPECT_EQ(keys_of(lit.at("glossy").at("properties")),
            (std::vector<std::string>{"roughness", "specular"}));
  EXPECT_EQ(defs.at("material").at("oneOf").size(), 2u);

  const auto& render = defs.at("render").at("properties");
  EXPECT_EQ(render.at("light_source_delay").at("enum"),
            nlohmann::json::parse(R"(["surface", "camera", "none"])"));
  EXPECT_EQ(render.at("light_source_delay").at("default"), "surface");
  EXPECT_EQ(render.at("shadows").at("default"), true);

  const std::string doc = read_source_file("docs/scene-format.md");
  for (const char* word :
       {"`lights[]`", "`point`", "`spot`", "`directional`", "`sphere`", "`intensity`",
        "`irradiance`", "`cone`", "`falloff`", "`radius`", "`glossy`", "`roughness`", "`specular`",
        "`light_source_delay`", "`shadows`", "`surface`", "`camera`", "`none`",
        "design/light-transport.md"})
    EXPECT_NE(doc.find(word), std::string::npos) << word;
}

// The schema names the motion keys the loader accepts, and the reference documents them.
TEST(SceneSchema, ListsTheMotionKeys) {
  const auto schema = nlohmann::json::parse(read_source_file("schema/scene.schema.json"));
  const auto& defs = schema.at("$defs");
  EXPECT_TRUE(schema.at("properties").contains("speed_of_light"));
  EXPECT_EQ(keys_of(defs.at("motion").at("properties")),
            (std::vector<std::string>{"keyframes", "phases"}));
  for (const char* owner : {"pointLight", "spotLight", "sphereLight"})
    EXPECT_EQ(defs.at(owner).at("properties").at("motion").at("$ref"), "#/$defs/motion") << owner;
  // The camera's and an object's: these, or near a black hole geodesics
  // (test_black_hole_motion.cpp).
  for (const char* owner : {"camera", "object"})
    EXPECT_EQ(defs.at(owner).at("properties").at("motion").at("$ref"), "#/$defs/bodyMotion")
        << owner;
  EXPECT_EQ(
      defs.at("bodyMotion").at("oneOf"),
      nlohmann::json::parse(R"([{"$ref": "#/$defs/motion"}, {"$ref": "#/$defs/geodesicMotion"}])"));
  EXPECT_EQ(keys_of(defs.at("object").at("properties").at("spin").at("properties")),
            (std::vector<std::string>{"axis", "rate"}));
  const std::string doc = read_source_file("docs/scene-format.md");
  for (const char* word :
       {"`speed_of_light`", "`phases`", "`keyframes`", "`spin`", "`blink`", "`clock`", "`duty`",
        "`period`", "design/accelerated-bodies.md", "design/spinning-bodies.md"})
    EXPECT_NE(doc.find(word), std::string::npos) << word;
}

// ---------------------------------------------------------------------------------------------
// The line locator on its own

TEST(JsonLineMap, RecordsValueAndKeyLines) {
  const JsonLineMap lines(R"({
  "a": {"b": [1,
              {"c": "x\"}{[" }],
    "d"
      : /* { */ 2},
  // "e": 1,
  "e":
    [[3]]
})");
  EXPECT_EQ(lines.value_line(""), 1);
  EXPECT_EQ(lines.value_line("a"), 2);
  EXPECT_EQ(lines.value_line("a.b"), 2);
  EXPECT_EQ(lines.value_line("a.b[0]"), 2);
  EXPECT_EQ(lines.value_line("a.b[1]"), 3);
  EXPECT_EQ(lines.value_line("a.b[1].c"), 3);
  EXPECT_EQ(lines.key_line("a.d"), 4);
  EXPECT_EQ(lines.value_line("a.d"), 5);
  EXPECT_EQ(lines.key_line("e"), 7);
  EXPECT_EQ(lines.value_line("e"), 8);
  EXPECT_EQ(lines.value_line("e[0][0]"), 8);
  // Paths not in the text fall back to their nearest ancestor.
  EXPECT_EQ(lines.value_line("a.b[1].missing"), 3);
  EXPECT_EQ(lines.value_line("a.d.x[4]"), 5);
  EXPECT_EQ(lines.key_line("a.nope"), 2);
  EXPECT_EQ(lines.value_line("zzz"), 1);
  EXPECT_TRUE(lines.duplicate_keys().empty());
}

TEST(JsonLineMap, FindsDuplicateKeysAndSurvivesDeepNesting) {
  const JsonLineMap dup("{\"a\": 1,\n \"b\": {\"c\": 1, \"c\": 2},\n \"a\": 3}");
  ASSERT_EQ(dup.duplicate_keys().size(), 2u);
  EXPECT_EQ(dup.duplicate_keys()[0].path, "b.c");
  EXPECT_EQ(dup.duplicate_keys()[0].line, 2);
  EXPECT_EQ(dup.duplicate_keys()[1].path, "a");
  EXPECT_EQ(dup.duplicate_keys()[1].line, 3);

  const std::string deep =
      "{\"a\":" + std::string(100000, '[') + std::string(100000, ']') + ",\n\"b\": 1}";
  const JsonLineMap lines(deep);
  EXPECT_EQ(lines.value_line("b"), 2);
}

TEST(JsonLineMap, ElementLinesComeFromRunsAndMemoryFollowsKeysAndLines) {
  // Elements on lines of their own, elements sharing a line, and a nested array over lines.
  const JsonLineMap lines(R"({"v": [1,
  2, 3,
  4,
  [5,
   6]],
  "w": [7, 8]})");
  EXPECT_EQ(lines.value_line("v[0]"), 1);
  EXPECT_EQ(lines.value_line("v[1]"), 2);
  EXPECT_EQ(lines.value_line("v[2]"), 2);
  EXPECT_EQ(lines.value_line("v[3]"), 3);
  EXPECT_EQ(lines.value_line("v[4]"), 4);
  EXPECT_EQ(lines.value_line("v[4][0]"), 4);
  EXPECT_EQ(lines.value_line("v[4][1]"), 5);
  EXPECT_EQ(lines.key_line("v[3]"), 3);
  EXPECT_EQ(lines.value_line("w[1]"), 6);
  EXPECT_EQ(lines.value_line("v[99]"), 4);  // past the end: the last run
  EXPECT_EQ(lines.recorded_paths(), 3u);    // the root, v and w; runs for v and v[4]

  // A million numbers on one line and a thousand on lines of their own: nothing per element on
  // one line, one run per line otherwise.
  std::string many = "{\"a\": [0";
  for (int i = 1; i < 1000000; ++i) many += ",0";
  many += "],\n\"b\": [0";
  for (int i = 1; i < 1000; ++i) many += ",\n0";
  many += "]}";
  const JsonLineMap big(many);
  EXPECT_EQ(big.recorded_paths(), 3u);
  EXPECT_EQ(big.recorded_runs(), 1000u);
  EXPECT_EQ(big.value_line("a[999999]"), 1);
  EXPECT_EQ(big.value_line("b[0]"), 2);
  EXPECT_EQ(big.value_line("b[999]"), 1001);
}

}  // namespace
}  // namespace lightcone

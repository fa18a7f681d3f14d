// Tests of the JSON scene format (docs/scene-format.md): how a valid file maps onto the scene
// model, its defaults, and its meshes and images. (Overrides: test_scene_overrides.cpp; bad
// input: test_scene_file_errors.cpp; the schema and the line locator: test_scene_schema.cpp.)
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/scene_file.hpp"
#include "support/scene_file_test.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using namespace test;  // the scene-file fixture and helpers (support/scene_file_test.hpp)

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
  expect_vec(c.world_line.position, {1, 2, 3});
  EXPECT_EQ(c.world_line.time, 4);
  expect_vec(c.world_line.velocity, {0, 0, -0.5});
  expect_vec(c.forward, {0, 0, -1});  // directions are normalized
  expect_vec(c.up, {0, 1, 0});
  EXPECT_EQ(c.fov_degrees, 75);
  EXPECT_EQ(c.width, 320);
  EXPECT_EQ(c.height, 200);
  EXPECT_EQ(c.samples, 4);

  ASSERT_EQ(s.objects.size(), 3u);
  const Object& ball = s.objects[0];
  EXPECT_EQ(ball.name, "ball");
  EXPECT_EQ(std::get<Sphere>(ball.shape).radius, 2);
  expect_vec(ball.world_line.position, {0, 1, -10});
  EXPECT_EQ(ball.world_line.time, -1);
  expect_vec(ball.world_line.velocity, {0.6, 0, 0});
  expect_rgb(std::get<SolidColor>(ball.material.pattern).color, 1, 0.5f, 0.25f);
  EXPECT_TRUE(ball.material.unlit);

  const Object& crate = s.objects[1];
  expect_vec(std::get<Box>(crate.shape).size, {1, 2, 3});
  expect_vec(crate.scale, {2, 2, 2});
  // 90 degrees about +z, right-handed: x -> y, y -> -x.
  expect_vec(crate.rotation * Vec3{1, 0, 0}, {0, 1, 0});
  expect_vec(crate.rotation * Vec3{0, 1, 0}, {-1, 0, 0});
  const Checker& checker = std::get<Checker>(crate.material.pattern);
  EXPECT_EQ(checker.size, 0.5);
  expect_rgb(checker.colors[0], 1, 1, 1);
  expect_rgb(checker.colors[1], 0, 0, 0.5f);

  const Object& floor = s.objects[2];
  EXPECT_EQ(std::get<Plane>(floor.shape).size_x, 10);
  EXPECT_EQ(std::get<Plane>(floor.shape).size_z, 20);
  expect_vec(floor.scale, {1, 2, 3});

  const SkyGrid& grid = std::get<SkyGrid>(s.sky.pattern);
  EXPECT_EQ(grid.spacing_degrees, 30);
  EXPECT_EQ(grid.line_width_degrees, 1);
  expect_rgb(grid.line_color, 1, 0, 0);
  expect_rgb(grid.background, 0, 0, 0.1f);
  expect_vec(s.sky.velocity, {0, 0.3, 0});
  expect_vec(s.sky.rotation * Vec3{0, 1, 0}, {0, -1, 0});

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
  expect_vec(s.objects[0].motion.phases[0].acceleration, {0, 0.1, 0});
  ASSERT_TRUE(s.objects[0].spin);
  expect_vec(s.objects[0].spin->axis, {0, 1, 0});
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
  expect_vec(s.camera.world_line.velocity, {0.3, 0, 0});
  EXPECT_NEAR(s.objects[0].world_line.time, 10, 1e-12);
  expect_vec(s.objects[0].world_line.velocity, {0, 0.6, 0});
  EXPECT_NEAR(s.objects[0].motion.phases[0].duration, 5, 1e-12);
  expect_vec(s.objects[0].motion.phases[0].acceleration, {0.2, 0, 0});
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
  expect_vec(c.world_line.velocity, {0, 0, 0});
  expect_vec(c.forward, {0, 0, -1});
  expect_vec(c.up, {0, 1, 0});
  EXPECT_EQ(c.fov_degrees, 60);
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 360);
  EXPECT_EQ(c.samples, 1);

  const Object& a = s.objects.at(0);
  expect_vec(a.world_line.position, {0, 0, 0});
  EXPECT_EQ(a.world_line.time, 0);
  expect_vec(a.world_line.velocity, {0, 0, 0});
  expect_vec(a.rotation * Vec3{1, 2, 3}, {1, 2, 3});
  expect_vec(a.scale, {1, 1, 1});
  expect_rgb(std::get<SolidColor>(a.material.pattern).color, 1, 1, 1);
  EXPECT_TRUE(a.material.unlit);

  expect_rgb(std::get<SolidColor>(s.sky.pattern).color, 0, 0, 0);
  expect_vec(s.sky.velocity, {0, 0, 0});
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
  expect_vec(bulb.world_line.position, {1, 2, 3});
  EXPECT_EQ(bulb.world_line.time, -2);
  expect_vec(bulb.world_line.velocity, {0.5, 0, 0});
  expect_rgb(std::get<Rgb>(bulb.spectrum.emission), 1, 0.5f, 2);  // above 1 is allowed
  EXPECT_EQ(bulb.intensity, 10);

  const Light& torch = s.lights[1];
  const SpotLight& spot = std::get<SpotLight>(torch.kind);
  expect_vec(spot.direction, {0, -1, 0});  // normalized
  EXPECT_EQ(spot.cone_degrees, 40);
  EXPECT_EQ(spot.falloff_degrees, 20);  // up to half the cone
  EXPECT_EQ(std::get<Blackbody>(torch.spectrum.emission).temperature_k, 3000);
  EXPECT_EQ(torch.intensity, 3);
  expect_vec(torch.world_line.position, {0, 5, 0});

  const Light& sun = s.lights[2];
  const DirectionalLight& directional = std::get<DirectionalLight>(sun.kind);
  expect_vec(directional.direction, {std::sqrt(0.5), -std::sqrt(0.5), 0});
  EXPECT_EQ(directional.irradiance, 2.5);
  expect_vec(sun.world_line.velocity, {0, 0, 0.3});
  expect_vec(sun.world_line.position, {9, 9, 9});  // allowed, and ignored by the renderer
  expect_rgb(std::get<Rgb>(sun.spectrum.emission), 1, 0.9f, 0.8f);

  const Light& globe = s.lights[3];
  EXPECT_EQ(std::get<SphereLight>(globe.kind).radius, 0.5);
  EXPECT_EQ(globe.intensity, 0);  // a light may be off
  expect_vec(globe.world_line.position, {0, 0, -4});
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
    expect_vec(l.world_line.position, {0, 0, 0});
    EXPECT_EQ(l.world_line.time, 0);
    expect_vec(l.world_line.velocity, {0, 0, 0});
    expect_rgb(std::get<Rgb>(l.spectrum.emission), 1, 1, 1);
    EXPECT_EQ(l.intensity, 1);
  }
  EXPECT_TRUE(std::holds_alternative<PointLight>(s.lights[0].kind));
  const SpotLight& spot = std::get<SpotLight>(s.lights[1].kind);
  expect_vec(spot.direction, {0, 0, -1});
  EXPECT_EQ(spot.cone_degrees, 60);
  EXPECT_EQ(spot.falloff_degrees, 5);
  const DirectionalLight& directional = std::get<DirectionalLight>(s.lights[2].kind);
  expect_vec(directional.direction, {0, -1, 0});
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

}  // namespace
}  // namespace lightcone

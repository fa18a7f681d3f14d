// The "black_hole" key of the scene format (docs/scene-format.md, "black_hole"): how it maps
// onto the scene model, what a hole asks of the camera, objects and lights, and that every
// refusal names the file, the line and the JSON path, and through the `lightcone` command exits
// with status 2 and writes nothing.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/physics/schwarzschild_motion.hpp"
#include "support/scene_file_test.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

using BlackHoleScene = test::SceneFileTest;

// A scene with the hole `hole` (on line 3) and, from line 4 on, `rest` (keys after the camera).
std::string with_hole(const std::string& hole,
                      const std::string& camera = "\"position\": [0, 0, 50]",
                      const std::string& rest = "") {
  return "{\n  \"camera\": {" + camera + "},\n  \"black_hole\": " + hole +
         (rest.empty() ? "" : ",\n") + rest + "\n}";
}

// A hole of mass 1 at the origin and one object (on line 4).
std::string with_object(const std::string& keys) {
  return with_hole(
      R"({"mass": 1})", "\"position\": [0, 0, 50]",
      R"(  "objects": [{"name": "a", "shape": {"sphere": {"radius": 0.1}}, )" + keys + "}]");
}

// A hole of mass 1 at the origin and one point light (on line 4).
std::string with_light(const std::string& keys) {
  return with_hole(R"({"mass": 1})", "\"position\": [0, 0, 50]",
                   std::string(R"(  "lights": [{"name": "l", "type": "point")") +
                       (keys.empty() ? "" : ", ") + keys + "}]");
}

// ---------------------------------------------------------------------------------------------
// Valid scenes

TEST_F(BlackHoleScene, MapsOntoTheModelWithTheDiskInLengths) {
  const Scene s = load(with_hole(R"({"position": [1, 2, 3], "mass": 2,
    "disk": {"inner": 8, "outer": 30, "normal": [0, 0, 2], "temperature": 20000,
             "luminance": 3}})"));
  ASSERT_TRUE(s.black_hole);
  const BlackHole& h = *s.black_hole;
  EXPECT_EQ(h.position, (Vec3{1, 2, 3}));
  EXPECT_EQ(h.mass, 2);
  ASSERT_TRUE(h.disk);
  EXPECT_EQ(h.disk->inner, 16);  // 8 M
  EXPECT_EQ(h.disk->outer, 60);  // 30 M
  EXPECT_EQ(h.disk->normal, (Vec3{0, 0, 1}));
  EXPECT_EQ(h.disk->temperature_k, 20000);
  EXPECT_EQ(h.disk->luminance, 3);
}

TEST_F(BlackHoleScene, Defaults) {
  const Scene bare = load(with_hole(R"({"mass": 1.5})"));
  ASSERT_TRUE(bare.black_hole);
  EXPECT_EQ(bare.black_hole->position, (Vec3{0, 0, 0}));
  EXPECT_EQ(bare.black_hole->mass, 1.5);
  EXPECT_FALSE(bare.black_hole->disk);

  const Scene disk = load(with_hole(R"({"mass": 1.5, "disk": {}})"));
  ASSERT_TRUE(disk.black_hole->disk);
  const AccretionDisk& d = *disk.black_hole->disk;
  EXPECT_EQ(d.inner, 9);   // 6 M
  EXPECT_EQ(d.outer, 30);  // 20 M
  EXPECT_EQ(d.normal, (Vec3{0, 1, 0}));
  EXPECT_EQ(d.temperature_k, 10000);
  EXPECT_EQ(d.luminance, 1);

  EXPECT_FALSE(load("{\"camera\": {\"position\": [0, 0, 5]}}").black_hole);
}

TEST_F(BlackHoleScene, SpeedOfLightLeavesLengthsAlone) {
  const Scene s = load(R"({
  "speed_of_light": 10,
  "camera": {"position": [0, 0, 50], "time": 2, "velocity": [3, 0, 0]},
  "black_hole": {"position": [0, 1, 0], "mass": 2, "disk": {"inner": 7, "outer": 12}},
  "objects": [{"name": "a", "shape": {"sphere": {"radius": 1}}, "position": [40, 0, 0],
               "time": 1, "velocity": [0, 3, 0]}]
})");
  EXPECT_EQ(s.black_hole->mass, 2);
  EXPECT_EQ(s.black_hole->position, (Vec3{0, 1, 0}));
  EXPECT_EQ(s.black_hole->disk->inner, 14);
  EXPECT_EQ(s.black_hole->disk->outer, 24);
  EXPECT_NEAR(s.camera.world_line.time, 20, 1e-12);
  EXPECT_NEAR(s.camera.world_line.velocity.x, 0.3, 1e-15);
  EXPECT_NEAR(s.objects[0].world_line.velocity.y, 0.3, 1e-15);
}

TEST_F(BlackHoleScene, BodiesOutsideTheHorizonLoad) {
  const Scene s = load(R"({
  "camera": {"position": [0, 0, 2.5], "velocity": [0.9, 0, 0], "proper_time": 0, "shutter": 0},
  "black_hole": {"mass": 1},
  "objects": [{"name": "at rest", "shape": {"sphere": {"radius": 0.1}}, "position": [2.01, 0, 0]},
              {"name": "passing", "shape": {"sphere": {"radius": 0.1}}, "position": [-100, 20, 0],
               "velocity": [0.5, 0, 0], "material": {"color": [1, 0, 0]}}],
  "lights": [{"name": "lamp", "type": "point", "position": [0, 3, 0]},
             {"name": "sun", "type": "directional", "velocity": [0.5, 0, 0]}]
})");
  EXPECT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.lights.size(), 2u);
  EXPECT_NEAR(s.camera.world_line.velocity.x, 0.9, 1e-15);
}

// The flat limit relative to the camera (a camera and a body each at gamma 1000, head on) does
// not apply near a hole, where the camera's velocity is its local static observer's measure.
TEST_F(BlackHoleScene, SpeedsRelativeToTheCameraAreNotFlatOnesNearAHole) {
  const std::string bodies = R"(
  "objects": [{"name": "a", "shape": {"sphere": {"radius": 1}}, "position": [0, 1e9, 0],
               "velocity": [-0.9999995, 0, 0]}])";
  const std::string flat =
      "{\n  \"camera\": {\"position\": [0, 0, 1e9], \"velocity\": "
      "[0.9999995, 0, 0]}," +
      bodies + "\n}";
  EXPECT_NE(error(flat).find("relative to the camera is too close to the speed of light"),
            std::string::npos)
      << error(flat);
  const std::string curved = "{\n  \"black_hole\": {\"mass\": 1},\n" + flat.substr(2);
  EXPECT_EQ(error(curved), "");
}

TEST_F(BlackHoleScene, OverridesReachTheHole) {
  const Scene s = load(with_hole(R"({"mass": 1})"), {"black_hole.disk.outer=40"});
  EXPECT_EQ(s.black_hole->disk->outer, 40);
  const std::string message = error(with_hole(R"({"mass": 1})"), {"black_hole.mass=-1"});
  EXPECT_EQ(message.rfind("--set black_hole.mass: must be greater than 0", 0), 0u) << message;
}

// ---------------------------------------------------------------------------------------------
// Refusals

TEST_F(BlackHoleScene, TheHoleItself) {
  for (const char* mass : {"0", "-1", "-1e-300"})
    expect_error(with_hole(fmt::format("{{\n    \"mass\": {}}}", mass)), 4, "black_hole.mass",
                 "must be greater than 0 (the gravitational radius GM/c^2, a length)");
  expect_error(with_hole("{\"mass\": 1e308}"), 3, "black_hole.mass", "too large");
  expect_error(with_hole("{\"position\": [0, 0, 0]}"), 3, "black_hole.mass",
               "required key is missing");
  expect_error(with_hole("{\"mass\": \"1\"}"), 3, "black_hole.mass", "must be a number");
  expect_error(with_hole(R"([{"mass": 1}, {"mass": 1, "position": [10, 0, 0]}])"), 3, "black_hole",
               "a scene holds one black hole at most (two holes are not an exact solution: no "
               "closed-form spacetime holds two)");
  expect_error(with_hole(R"([{"mass": 1}])"), 3, "black_hole", "one black hole at most");
  expect_error(with_hole("3"), 3, "black_hole", "must be an object");
  expect_error(with_hole("{\"mass\": 1,\n  \"spin\": 0.5}"), 4, "black_hole.spin",
               "unknown key \"spin\" (expected one of: position, mass, disk)");
  expect_error(with_hole("{\"mass\": 1, \"position\": [0, 0]}"), 3, "black_hole.position",
               "must be an array of 3 numbers");
}

TEST_F(BlackHoleScene, TheDisk) {
  const auto disk = [](const std::string& keys) {
    return with_hole("{\"mass\": 1,\n    \"disk\": {\n      " + keys + "}}");
  };
  expect_error(disk("\"inner\": 5.9"), 5, "black_hole.disk.inner",
               "5.9 is below the innermost stable circular orbit, 6M");
  expect_error(disk("\"inner\": 8, \"outer\": 8"), 5, "black_hole.disk.outer",
               "the outer radius 8 must be greater than the inner radius 8");
  expect_error(disk("\"outer\": 3"), 5, "black_hole.disk.outer",
               "must be greater than the inner radius 6");
  // The default outer radius, 20, inside a larger inner one: blamed on the disk's line.
  expect_error(disk("\"inner\": 25"), 4, "black_hole.disk.outer",
               "the outer radius 20 (the default) must be greater than the inner radius 25");
  for (const char* t : {"0", "-100"})
    expect_error(disk(fmt::format("\"temperature\": {}", t)), 5, "black_hole.disk.temperature",
                 "must be greater than 0 kelvin");
  expect_error(disk("\"luminance\": 0"), 5, "black_hole.disk.luminance", "greater than 0");
  expect_error(disk("\"normal\": [0, 0, 0]"), 5, "black_hole.disk.normal",
               "must not be the zero vector");
  expect_error(disk("\"radius\": 3"), 5, "black_hole.disk.radius", "unknown key");
  expect_error(with_hole("{\"mass\": 1e300, \"disk\": {\"outer\": 1e10}}"), 3,
               "black_hole.disk.outer", "too large");
}

TEST_F(BlackHoleScene, TheCamera) {
  // Inside or on the horizon, at rest or moving.
  for (const char* camera : {"\"position\": [0, 0, 2]", "\"position\": [1, 1, 0]",
                             "\"position\": [0, 0, 0.5], \"velocity\": [0, 0, 0.9]"})
    expect_error(with_hole(R"({"mass": 1})", camera), 2, "camera.position",
                 "inside its horizon r = 2M = 2: its velocity is measured by the local static "
                 "observer, and there is none inside the horizon");
  // Measured from the hole's position.
  expect_error(with_hole(R"({"mass": 1, "position": [0, 0, 49]})"), 2, "camera.position",
               "the camera is at r = 1 from the black hole");
  expect_error(with_hole(R"({"mass": 1})", R"("position": [0, 0, 50],
    "motion": {"phases": [{"duration": 1, "acceleration": [1, 0, 0]}]})"),
               3, "camera.motion",
               "motion (phases or keyframes) of the camera is not yet supported near a black hole");
  expect_error(with_hole(R"({"mass": 1})", R"("motion": {"keyframes": [
      {"time": 0, "position": [0, 0, 50]}, {"time": 1, "position": [0, 0.5, 50]}]})"),
               2, "camera.motion", "is not yet supported near a black hole");
  expect_error(with_hole(R"({"mass": 1})", R"("position": [0, 0, 50],
    "shutter": 0.1)"),
               3, "camera.shutter", "is not yet supported near a black hole");
  expect_error(with_hole(R"({"mass": 1})", R"("position": [0, 0, 50],
    "proper_time": 2)"),
               3, "camera.proper_time", "is not yet supported near a black hole");
}

TEST_F(BlackHoleScene, BodiesAtRestInsideTheHorizon) {
  for (const char* at : {R"("position": [0, 1.5, 0])", R"("position": [2, 0, 0])"})
    expect_error(with_object(at), 4, "objects[0].position", "the object is at rest at r = ");
  // No position: at [0, 0, 0], where the hole is.
  expect_error(with_object(R"("velocity": [0, 0, 0])"), 4, "objects[0].position",
               "the object is at rest at r = 0 from the black hole, inside its horizon r = 2M = "
               "2: nothing stays at rest there (there are no static observers inside the "
               "horizon)");
  expect_error(with_light(R"("position": [0.5, 0, 0])"), 4, "lights[0].position",
               "the light is at rest at r = 0.5");
  expect_error(with_light(""), 4, "lights[0].position", "the light is at rest at r = 0");
  // A directional light is at infinity.
  EXPECT_EQ(error(with_hole(R"({"mass": 1})", "\"position\": [0, 0, 50]",
                            R"(  "lights": [{"name": "sun", "type": "directional"}])")),
            "");
}

TEST_F(BlackHoleScene, BodiesOnGeodesics) {
  // An orbit, and a fall held at rest at r0 until it is let go at its time.
  const Scene orbit = load(with_object(R"("motion": {"orbit": {"radius": 8, "phase": 90}})"));
  ASSERT_TRUE(orbit.objects[0].motion.geodesic);
  EXPECT_NEAR(length(orbit.objects[0].world_line.position), 8, 1e-12);
  const Scene fall =
      load(with_object(R"("motion": {"fall": {"from": 10, "direction": [0, 2, 0], "time": 5}})"));
  EXPECT_NEAR(fall.objects[0].world_line.position.y, 10, 1e-12);
  EXPECT_EQ(fall.objects[0].world_line.velocity, Vec3{});
  expect_error(with_object(R"("scale": 12, "motion": {"orbit": {"radius": 3.1}})"), 4,
               "objects[0].motion.orbit.radius",
               "the object reaches 1.2 from its origin, so on an orbit at r = 3.1 it crosses "
               "the horizon r = 2M = 2: an orbit's radius must exceed 2M plus the object's reach");
  expect_error(with_object(R"("position": [0, 0, 9], "motion": {"orbit": {"radius": 8}})"), 4,
               "objects[0].position", "must not be given with motion.orbit");
  expect_error(with_object(R"("velocity": [0, 0, 0.1], "motion": {"fall": {"from": 9}})"), 4,
               "objects[0].velocity", "must not be given with motion.fall");
  expect_error(with_object(R"("motion": {"fall": {"from": 1.5}})"), 4,
               "objects[0].motion.fall.from", "");
  // Without a hole, orbits and falls mean nothing.
  expect_error(R"({
  "camera": {"position": [0, 0, 50]},
  "objects": [{"name": "a", "shape": {"sphere": {"radius": 0.1}}, "motion": {"orbit": {"radius": 8}}}]
})",
               3, "objects[0].motion.orbit",
               "a circular orbit about a black hole needs a black hole");
}

TEST_F(BlackHoleScene, MovingBodiesWhoseLinesReachTheHorizon) {
  expect_error(with_object(R"("position": [-100, 1.9, 0], "velocity": [0.5, 0, 0])"), 4,
               "objects[0].velocity",
               "the object's coordinate line position + velocity (t - time) comes within r = 1.9");
  // Radially outward from far away: its line came out of the hole in the past.
  expect_error(with_object(R"("position": [0, 0, 1000], "time": 5, "velocity": [0, 0, 0.1])"), 4,
               "objects[0].velocity", "comes within r = 0 of the black hole");
  expect_error(with_light(R"("position": [0, 2, -30], "velocity": [0, 0, 0.5])"), 4,
               "lights[0].velocity", "the light's coordinate line");
}

TEST_F(BlackHoleScene, MovingBodiesWhoseLocalSpeedReachesTheSpeedOfLight) {
  // Closest approach 3M at 0.6: sqrt(3) 0.6 > 1 already there.
  const std::string fast = R"("position": [50, 3, 0], "velocity": [-0.6, 0, 0])";
  ASSERT_GE(peak_static_observer_speed(1, {50, 3, 0}, {-0.6, 0, 0}).speed, 1);
  expect_error(with_object(fast), 4, "objects[0].velocity",
               "along the object's coordinate line position + velocity (t - time), the speed "
               "measured by the local static observers reaches ");
  expect_error(with_object(fast), 4, "objects[0].velocity",
               "must stay below the speed of light (1)");
  expect_error(with_light(fast), 4, "lights[0].velocity", "along the light's coordinate line");
  // With speed_of_light, in the scene's units.
  const std::string scaled =
      "{\n  \"speed_of_light\": 10," +
      with_object(R"("position": [50, 3, 0], "velocity": [-6, 0, 0])").substr(1);
  expect_error(scaled, 5, "objects[0].velocity", "must stay below the speed of light (10)");
  // Below 1 everywhere, but within 5e-13 of it somewhere: the one limit on gamma.
  const double b = 1.5e12, v = 1 - 1e-12;
  const LineSpeedPeak peak = peak_static_observer_speed(1, {0, b, 0}, {v, 0, 0});
  ASSERT_LT(peak.speed, 1);
  ASSERT_GT(1 / std::sqrt((1 - peak.speed) * (1 + peak.speed)), 1e6);
  expect_error(
      with_object(fmt::format(R"("position": [0, {}, 0], "velocity": [{:.17g}, 0, 0])", b, v)), 4,
      "objects[0].velocity",
      "measured by the local static observer is too close to the speed of light");
  // The same line slower is fine.
  EXPECT_EQ(
      error(with_object(fmt::format(R"("position": [0, {}, 0], "velocity": [0.99, 0, 0])", b))),
      "");
}

TEST_F(BlackHoleScene, MotionAndSpinAreNotYetSupported) {
  expect_error(with_object(R"("position": [0, 0, 30],
    "motion": {"phases": [{"duration": 1, "acceleration": [1, 0, 0]}]})"),
               5, "objects[0].motion",
               "motion (phases or keyframes) of an object is not yet supported near a black hole");
  expect_error(with_object(R"("motion": {"keyframes": [{"time": 0, "position": [0, 0, 30]},
    {"time": 1, "position": [0, 0.5, 30]}]})"),
               4, "objects[0].motion", "is not yet supported near a black hole");
  expect_error(with_object(R"("position": [0, 0, 30],
    "spin": {"axis": [0, 1, 0], "rate": 10})"),
               5, "objects[0].spin", "spin is not yet supported near a black hole");
  expect_error(with_light(R"("position": [0, 0, 30],
    "motion": {"phases": [{"duration": 1, "acceleration": [1, 0, 0]}]})"),
               5, "lights[0].motion",
               "motion (phases or keyframes) of a light is not yet supported near a black hole");
}

// Through the command: one line naming the place, status 2, no image.
TEST_F(BlackHoleScene, TheCommandRefusesWithStatus2AndWritesNothing) {
  struct Case {
    std::string scene, where;
  };
  const std::vector<Case> cases = {
      {with_hole("{\n    \"mass\": -1}"), ":4: black_hole.mass: "},
      {with_hole(R"([{"mass": 1}, {"mass": 2}])"), ":3: black_hole: "},
      {with_hole("{\"mass\": 1,\n    \"disk\": {\"inner\": 4}}"), ":4: black_hole.disk.inner: "},
      {with_hole("{\"mass\": 1,\n    \"disk\": {\"outer\": 5}}"), ":4: black_hole.disk.outer: "},
      {with_hole("{\"mass\": 1,\n    \"disk\": {\"temperature\": 0}}"),
       ":4: black_hole.disk.temperature: "},
      {with_hole("{\"mass\": 1,\n    \"disk\": {\"luminance\": -1}}"),
       ":4: black_hole.disk.luminance: "},
      {with_hole(R"({"mass": 1})", "\"position\": [0, 1, 0]"), ":2: camera.position: "},
      {with_hole(R"({"mass": 1})", "\"position\": [0, 0, 50], \"shutter\": 1"),
       ":2: camera.shutter: "},
      {with_object(R"("position": [1, 0, 0])"), ":4: objects[0].position: "},
      {with_object(R"("position": [-50, 1, 0], "velocity": [0.5, 0, 0])"),
       ":4: objects[0].velocity: "},
      {with_object(R"("position": [50, 3, 0], "velocity": [-0.6, 0, 0])"),
       ":4: objects[0].velocity: "},
      {with_object(R"("spin": {"axis": [0, 1, 0], "rate": 1}, "position": [0, 0, 30])"),
       ":4: objects[0].spin: "},
      {with_light(R"("position": [0, 0, 1])"), ":4: lights[0].position: "},
  };
  for (const Case& c : cases) {
    const fs::path scene = write("bad.json", c.scene), out = dir_ / "out.png";
    const test::CommandResult r =
        test::run_lightcone("render " + test::quoted(scene) + " -o " + test::quoted(out));
    EXPECT_EQ(r.status, 2) << c.where << ": " << r.err;
    EXPECT_EQ(r.err.rfind("lightcone: " + scene.string() + c.where, 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.where;
  }
}

// ---------------------------------------------------------------------------------------------
// The documentation and the schema

TEST_F(BlackHoleScene, TheDocumentedExampleLoads) {
  const Scene s = load(test::documented_example("## `black_hole`"));
  ASSERT_TRUE(s.black_hole);
  EXPECT_TRUE(s.black_hole->disk);
}

TEST(BlackHoleSchema, ListsTheKeysTheLoaderReads) {
  const auto schema = nlohmann::json::parse(test::read_source_file("schema/scene.schema.json"));
  const auto& defs = schema.at("$defs");
  EXPECT_EQ(schema.at("properties").at("black_hole").at("$ref"), "#/$defs/blackHole");
  const auto& hole = defs.at("blackHole");
  EXPECT_EQ(hole.at("type"), "object");
  EXPECT_EQ(hole.at("required"), nlohmann::json::parse(R"(["mass"])"));
  EXPECT_EQ(hole.at("additionalProperties"), false);
  std::vector<std::string> keys, disk_keys;
  for (const auto& item : hole.at("properties").items()) keys.push_back(item.key());
  for (const auto& item : defs.at("accretionDisk").at("properties").items())
    disk_keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"disk", "mass", "position"}));
  EXPECT_EQ(disk_keys,
            (std::vector<std::string>{"inner", "luminance", "normal", "outer", "temperature"}));
  const auto& disk = defs.at("accretionDisk").at("properties");
  EXPECT_EQ(disk.at("inner").at("minimum"), 6);
  EXPECT_EQ(disk.at("inner").at("default"), 6);
  EXPECT_EQ(disk.at("outer").at("default"), 20);
  EXPECT_EQ(disk.at("temperature").at("default"), 10000);
  EXPECT_EQ(disk.at("luminance").at("default"), 1);

  const std::string doc = test::read_source_file("docs/scene-format.md");
  for (const char* word :
       {"`black_hole`", "`mass`", "`disk`", "`inner`", "`outer`", "`normal`", "`temperature`",
        "`luminance`", "GM/c^2", "Schwarzschild coordinate time", "static observer",
        "not yet supported near a black hole", "one black hole at most"})
    EXPECT_NE(doc.find(word), std::string::npos) << word;
}

}  // namespace
}  // namespace lightcone

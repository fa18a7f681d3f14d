// The scene format's --set overrides: values replaced, numbers read as arrays, objects made and
// elements appended, all before validation, and malformed ones named.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "lightcone/io/scene_file.hpp"
#include "support/scene_file_test.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using namespace test;  // the scene-file fixture and helpers (support/scene_file_test.hpp)

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
  expect_vec(s.camera.world_line.velocity, {0, 0, 0.5});
  EXPECT_EQ(s.camera.width, 320);
  expect_vec(s.objects.at(0).world_line.velocity, {0.5, 0, 0});
  expect_vec(s.objects.at(0).world_line.position, {1, 2, 3});
  EXPECT_EQ(s.objects.at(0).name, "renamed");  // not JSON, so taken as a string
}

// Numbers separated by commas are an array, as locate's --direction x,y,z; other text that is
// not JSON stays a string.
TEST_F(SceneFileTest, OverridesReadCommaSeparatedNumbersAsArrays) {
  const Scene s = load(kOverrideScene, {"camera.velocity=0,0,-0.99", "objects.0.position=1, 2,3e-1",
                                        "objects.0.name=a,b"});
  expect_vec(s.camera.world_line.velocity, {0, 0, -0.99});
  expect_vec(s.objects.at(0).world_line.position, {1, 2, 0.3});
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

}  // namespace
}  // namespace lightcone

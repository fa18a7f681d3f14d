// Bad scene files: every kind of bad input is an InputError whose message names the file, the
// line and the JSON path ("FILE:LINE: PATH: what is wrong").
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "../fuzz/fuzz_support.hpp"  // how the fuzzer splits its inputs
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/json_locator.hpp"
#include "lightcone/io/scene_file.hpp"
#include "support/scene_file_test.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using namespace test;  // the scene-file fixture and helpers (support/scene_file_test.hpp)

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
      bytes_of(fs::path(LIGHTCONE_SOURCE_DIR) / "tests" / "data" / "scanner-loop.fuzz"));
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
    const fuzz::SceneInput input =
        fuzz::split_scene_input(bytes_of(fs::path(LIGHTCONE_SOURCE_DIR) / "tests" / "data" / name));
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

}  // namespace
}  // namespace lightcone

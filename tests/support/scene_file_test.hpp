// The scene-file tests' fixture (tests/test_scene_*.cpp, and the black hole's scene tests): scenes
// written to a fresh folder and loaded, the checks that an InputError names the file, the line
// and the JSON path, and small scene-building helpers.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/scene_file.hpp"
#include "support/test_support.hpp"

namespace lightcone::test {

// A single triangle, and the same with one degenerate (repeated-vertex) triangle added.
inline constexpr const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
inline constexpr const char* kTriangleObjWithDegenerate =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 2\n";

// A fixture that loads scene text written to DIR/scene.json, and checks the InputError that bad
// text throws.
class SceneFileTest : public TempDirTest {
 protected:
  // A 2 x 1 PNG of the two linear colours `rgb` holds, beside the scene.
  void write_two_texel_png(const std::string& name, std::vector<float> rgb) const;
  // Loads `text`; report_ holds what the loader reported.
  Scene load(const std::string& text, const std::vector<std::string>& overrides = {});
  // The message of the InputError that loading `text` throws, or "" when it loads.
  std::string error(const std::string& text, const std::vector<std::string>& overrides = {});
  // Expects "DIR/scene.json:LINE: PATH: ..." with `fragment` somewhere in the description.
  void expect_error(const std::string& text, int line, const std::string& path,
                    const std::string& fragment = "");
  // Expects "--set PATH: ..." with `fragment` in the description.
  void expect_set_error(const std::string& text, const std::vector<std::string>& overrides,
                        const std::string& path, const std::string& fragment = "");

  SceneLoadReport report_;
};

// A file of the repository (docs/scene-format.md, schema/scene.schema.json), as text.
std::string read_source_file(const std::string& relative);
// The first ```jsonc example of docs/scene-format.md after the line `heading` (from the top when
// empty); a test failure and "" where there is none.
std::string documented_example(const std::string& heading = "");
// A JSON object's keys, sorted.
std::vector<std::string> keys_of(const nlohmann::json& object);

// Wraps one object (given on the third line) in a valid scene.
std::string with_object(const std::string& object);

void expect_rgb(const Rgb& c, float r, float g, float b);

}  // namespace lightcone::test

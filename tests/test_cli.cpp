// The `lightcone` command through the real binary: bad input (exit status 2, one message that
// names the file, line and JSON path, nothing written), valid renders (sizes, options, the PNG
// and EXR value contract, --stats, the progress bar), `locate` and --help.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/physics/aberration.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using test::CommandResult;
using test::quoted;
using test::run_lightcone;

// One key per line, so that every value has a known line:
//  1 {                                    11 "name": "ball"
//  2   "camera": {                        12 "shape"
//  3     "position"                       13 "position"
//  4     "velocity"                       14 "velocity"
//  5     "fov"                            15 "material"
//  6     "width"                          16 }
//  7     "height"                         17 ],
//  8   },                                 18 "sky"
//  9   "objects": [                       19 "render"
// 10     {                                20 }
// A green ball of radius 2 at rest 10 ahead of a camera at rest, on a blue sky.
const std::string kScene = R"({
  "camera": {
    "position": [0, 0, 0],
    "velocity": [0, 0, 0],
    "fov": 30,
    "width": 64,
    "height": 48
  },
  "objects": [
    {
      "name": "ball",
      "shape": {"sphere": {"radius": 2}},
      "position": [0, 0, -10],
      "velocity": [0, 0, 0],
      "material": {"color": [0, 1, 0]}
    }
  ],
  "sky": {"color": [0, 0, 1]},
  "render": {"exposure": 0, "tonemap": "clamp"}
}
)";

// `text` with the one occurrence of `from` replaced by `to`.
std::string edited(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "no '" << from << "' in the scene";
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "'" << from << "' is not unique";
  if (at == std::string::npos) return text;
  return text.substr(0, at) + to + text.substr(at + from.size());
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t line_count(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// The 8-bit value the PNG holds for a pixel read back as linear (load_image_file decodes sRGB).
int png_byte(float linear) {
  for (int i = 0; i < 256; ++i)
    if (static_cast<float>(srgb_decode(i / 255.0)) == linear) return i;
  return -1;
}

Rgb pixel(const Image& image, int x, int y) {
  return image.texel(x, y);
}

class CliTest : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::fresh_temp_dir("cli");
    out_ = dir_ / "out";
    fs::create_directories(out_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write_scene(const std::string& json, const std::string& name = "scene.json") {
    const fs::path file = dir_ / name;
    test::write_text(file, json);
    return file;
  }

  fs::path png() const { return out_ / "image.png"; }
  fs::path exr() const { return out_ / "image.exr"; }

  // `lightcone render SCENE -o out/image.png --exr out/image.exr EXTRA`.
  CommandResult render(const fs::path& scene, const std::string& extra = "") const {
    return run_lightcone("render " + quoted(scene) + " -o " + quoted(png()) + " --exr " +
                         quoted(exr()) + " " + extra);
  }
  CommandResult locate(const fs::path& scene, const std::string& extra) const {
    return run_lightcone("locate " + quoted(scene) + " " + extra);
  }

  std::shared_ptr<Image> read_png() const { return load_image_file(png()); }
  std::shared_ptr<Image> read_exr() const { return load_image_file(exr()); }

  // Nothing in the output folder: no PNG, no EXR, no temporary file; and no temporary file
  // anywhere else in the test's folder.
  void expect_nothing_written() const {
    EXPECT_FALSE(fs::exists(png()));
    EXPECT_FALSE(fs::exists(exr()));
    for (const auto& entry : fs::recursive_directory_iterator(dir_)) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
          << "temporary file left behind: " << entry.path();
      EXPECT_NE(entry.path().parent_path(), out_) << "file written: " << entry.path();
    }
  }

  // Exit status 2, exactly one line on stderr that starts with "lightcone: " + `start` and
  // contains every one of `parts`, nothing on stdout, nothing written.
  void expect_rejected(const CommandResult& r, const std::string& start,
                       const std::vector<std::string>& parts = {}) const {
    EXPECT_TRUE(r.err.starts_with("lightcone: " + start))
        << "expected 'lightcone: " << start << "...', got: " << r.err;
    expect_rejected_command_line(r, parts);
  }

  // The same for a command line that the option parser rejects: the message need not start
  // with the program's name.
  void expect_rejected_command_line(const CommandResult& r,
                                    const std::vector<std::string>& parts) const {
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(line_count(r.err), 1u) << "stderr is not one line:\n" << r.err;
    EXPECT_TRUE(r.err.ends_with('\n')) << r.err;
    for (const std::string& part : parts)
      EXPECT_NE(r.err.find(part), std::string::npos) << "no '" << part << "' in: " << r.err;
    EXPECT_EQ(r.out, "");
    expect_nothing_written();
  }

  fs::path dir_, out_;
};

// ----------------------------------------------------------------------------------------------
// Bad scene values: FILE:LINE: PATH: what

struct BadValue {
  std::string name, from, to;
  int line;
  std::string path, what;
};

TEST_F(CliTest, BadSceneValuesNameFileLineAndPathAndWriteNothing) {
  const std::vector<BadValue> cases = {
      {"camera at the speed of light", "\n    \"velocity\": [0, 0, 0]",
       "\n    \"velocity\": [0, 0, 1]", 4, "camera.velocity",
       "speed 1 must be below the speed of light"},
      {"object faster than light", "\n      \"velocity\": [0, 0, 0]",
       "\n      \"velocity\": [0.8, 0.8, 0]", 14, "objects[0].velocity",
       "must be below the speed of light"},
      // |beta|^2 = 1 - 2.2e-16: once a frame of NaN pixels.
      {"camera a rounding error below c", "\n    \"velocity\": [0, 0, 0]",
       "\n    \"velocity\": [0.7071067811865475, 0.7071067811865475, 0]", 4, "camera.velocity",
       "is too close to the speed of light (gamma 6.71e+07; at most 1e+06)"},

      {"unknown camera key", "\"fov\": 30", "\"fovy\": 30", 5, "camera.fovy",
       "unknown key \"fovy\""},
      {"unknown render key", "\"exposure\": 0", "\"exposur\": 0", 19, "render.exposur",
       "unknown key \"exposur\""},
      {"fov 0", "\"fov\": 30", "\"fov\": 0", 5, "camera.fov", "between 0 and 180"},
      {"fov 180", "\"fov\": 30", "\"fov\": 180", 5, "camera.fov", "between 0 and 180"},
      {"fov negative", "\"fov\": 30", "\"fov\": -10", 5, "camera.fov", "between 0 and 180"},
      {"negative radius", "\"radius\": 2", "\"radius\": -2", 12, "objects[0].shape.sphere.radius",
       "must be greater than 0"},
      {"negative box size", "{\"sphere\": {\"radius\": 2}}", "{\"box\": {\"size\": [1, -2, 1]}}",
       12, "objects[0].shape.box.size[1]", "must be greater than 0"},
      {"zero width", "\"width\": 64", "\"width\": 0", 6, "camera.width",
       "must be an integer from 1 to 16384"},
      {"absurd width", "\"width\": 64", "\"width\": 100000", 6, "camera.width",
       "must be an integer from 1 to 16384"},
      {"fractional width", "\"width\": 64", "\"width\": 64.5", 6, "camera.width",
       "must be an integer"},
      {"negative height", "\"height\": 48", "\"height\": -48", 7, "camera.height",
       "must be an integer from 1 to 16384"},
      {"too many pixels", "\"width\": 64,\n    \"height\": 48",
       "\"width\": 16384,\n    \"height\": 16384", 6, "camera.width", "more than the limit"},
      {"negative colour", "[0, 1, 0]", "[0, -1, 0]", 15, "objects[0].material.color[1]",
       "must be >= 0"},
      {"two sky patterns", "\"sky\": {\"color\": [0, 0, 1]}",
       "\"sky\": {\"color\": [0, 0, 1], \"grid\": {}}", 18, "sky", "exactly one of"},
      {"missing camera position", "\n    \"position\": [0, 0, 0],", "", 2, "camera.position",
       "required key is missing"},
      {"duplicate key", "\"fov\": 30,", "\"fov\": 30,\n    \"fov\": 40,", 6, "camera.fov",
       "duplicate key"},
      {"lit blackbody", "{\"color\": [0, 1, 0]}",
       "{\"blackbody\": {\"temperature\": 5000}, \"unlit\": false}", 15,
       "objects[0].material.unlit", "cannot be lit"},
  };
  for (const BadValue& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path scene = write_scene(edited(kScene, c.from, c.to));
    const std::string where = scene.string() + ":" + std::to_string(c.line) + ": " + c.path + ": ";
    expect_rejected(render(scene), where, {c.what});
    // locate reads the scene the same way.
    expect_rejected(locate(scene, "--world-point 0,0,-10"), where, {c.what});
  }
}

// The colour keys: emitter materials (line 15) and model names (line 19).
TEST_F(CliTest, BadColourValuesNameFileLineAndPathAndWriteNothing) {
  const std::string material = "{\"color\": [0, 1, 0]}";
  const std::string render_line = "\"exposure\": 0";
  const std::vector<BadValue> cases = {
      {"blackbody at 0 K", material, "{\"blackbody\": {\"temperature\": 0}}", 15,
       "objects[0].material.blackbody.temperature", "must be greater than 0, got 0"},
      {"blackbody below 0 K", material, "{\"blackbody\": {\"temperature\": -5762}}", 15,
       "objects[0].material.blackbody.temperature", "must be greater than 0, got -5762"},
      {"negative luminance", material,
       "{\"blackbody\": {\"temperature\": 5762, \"luminance\": -1}}", 15,
       "objects[0].material.blackbody.luminance", "must be >= 0, got -1"},
      {"unsorted wavelengths", material,
       "{\"spectrum\": {\"wavelengths\": [400, 700, 600], \"values\": [1, 1, 1]}}", 15,
       "objects[0].material.spectrum.wavelengths[2]", "strictly increasing (600 after 700)"},
      {"unknown Doppler model", render_line, "\"doppler\": \"rgb\"", 19, "render.doppler",
       "unknown model \"rgb\""},
      {"unknown searchlight model", render_line, "\"searchlight\": \"chang\"", 19,
       "render.searchlight", "unknown model \"chang\""},
      {"unknown tone curve", "\"tonemap\": \"clamp\"", "\"tonemap\": \"aces\"", 19,
       "render.tonemap", "unknown model \"aces\""},
      {"exposure neither a number nor auto", render_line, "\"exposure\": \"bright\"", 19,
       "render.exposure", "must be a number (EV) or \"auto\""},
  };
  for (const BadValue& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path scene = write_scene(edited(kScene, c.from, c.to));
    const std::string where = scene.string() + ":" + std::to_string(c.line) + ": " + c.path + ": ";
    expect_rejected(render(scene), where, {c.what});
    expect_rejected(locate(scene, "--world-point 0,0,-10"), where, {c.what});
  }
}

// Negative power or radius, spot angles outside (0, 180), a light faster than light, an unknown
// light type or mode, and lit materials that are not albedos. The scene gets a lights array
// whose one light is on line 19 (the sky moves to line 21, the render settings to 22).
TEST_F(CliTest, BadLightValuesNameFileLineAndPathAndWriteNothing) {
  const std::string lamp =
      R"({"name": "lamp", "type": "point", "position": [0, 5, 0], "intensity": 10})";
  const std::string lit =
      edited(kScene, "  ],\n  \"sky\"", "  ],\n  \"lights\": [\n    " + lamp + "\n  ],\n  \"sky\"");
  const std::string material = "{\"color\": [0, 1, 0]}";
  const std::string render_line = "\"exposure\": 0";
  auto light = [&](const std::string& json) { return std::make_pair(lamp, json); };
  struct Case {
    std::string name;
    std::pair<std::string, std::string> edit;
    int line;
    std::string path, what;
  };
  const std::vector<Case> cases = {
      {"negative intensity",
       light(R"({"name": "lamp", "type": "point", "position": [0, 5, 0], "intensity": -10})"), 19,
       "lights[0].intensity", "must be >= 0, got -10"},
      {"negative irradiance", light(R"({"name": "lamp", "type": "directional", "irradiance": -1})"),
       19, "lights[0].irradiance", "must be >= 0, got -1"},
      {"negative radius", light(R"({"name": "lamp", "type": "sphere", "radius": -0.5})"), 19,
       "lights[0].radius", "must be greater than 0, got -0.5"},
      {"zero radius", light(R"({"name": "lamp", "type": "sphere", "radius": 0})"), 19,
       "lights[0].radius", "must be greater than 0, got 0"},
      {"spot cone 0", light(R"({"name": "lamp", "type": "spot", "cone": 0})"), 19, "lights[0].cone",
       "between 0 and 180 degrees"},
      {"spot cone 180", light(R"({"name": "lamp", "type": "spot", "cone": 180})"), 19,
       "lights[0].cone", "between 0 and 180 degrees"},
      {"spot cone 200", light(R"({"name": "lamp", "type": "spot", "cone": 200})"), 19,
       "lights[0].cone", "got 200"},
      {"falloff wider than half the cone",
       light(R"({"name": "lamp", "type": "spot", "cone": 40, "falloff": 25})"), 19,
       "lights[0].falloff", "half the cone (20 degrees), got 25"},
      {"light at the speed of light",
       light(R"({"name": "lamp", "type": "point", "velocity": [0, 0, 1]})"), 19,
       "lights[0].velocity", "speed 1 must be below the speed of light"},
      {"light faster than light",
       light(R"({"name": "lamp", "type": "point", "velocity": [0.8, 0.8, 0]})"), 19,
       "lights[0].velocity", "must be below the speed of light"},
      {"unknown light type", light(R"({"name": "lamp", "type": "laser"})"), 19, "lights[0].type",
       "unknown light type \"laser\" (expected one of: point, spot, directional, sphere)"},
      {"radius on a point light", light(R"({"name": "lamp", "type": "point", "radius": 1})"), 19,
       "lights[0].radius", "unknown key \"radius\" for a point light"},
      {"duplicate light name", light(lamp + ",\n    " + lamp), 20, "lights[1].name",
       "duplicate light name \"lamp\" (also used by lights[0])"},
      {"unknown light source delay mode",
       {render_line, "\"light_source_delay\": \"retarded\""},
       22,
       "render.light_source_delay",
       "unknown mode \"retarded\" (expected one of: surface, camera, none)"},
      {"albedo above 1",
       {material, "{\"color\": [0, 1.5, 0], \"unlit\": false}"},
       15,
       "objects[0].material.color[1]",
       "must be at most 1 for a lit material"},
      {"glossy on an unlit material",
       {material, "{\"color\": [0, 1, 0], \"glossy\": {}}"},
       15,
       "objects[0].material.glossy",
       "needs a lit material"},
      {"roughness 0",
       {material, "{\"color\": [0, 1, 0], \"unlit\": false, \"glossy\": {\"roughness\": 0}}"},
       15,
       "objects[0].material.glossy.roughness",
       "must be greater than 0 and at most 1, got 0"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path scene = write_scene(edited(lit, c.edit.first, c.edit.second));
    const std::string where = scene.string() + ":" + std::to_string(c.line) + ": " + c.path + ": ";
    expect_rejected(render(scene), where, {c.what});
    expect_rejected(locate(scene, "--world-point 0,0,-10"), where, {c.what});
  }
  // Through --set, the message names the setting.
  const fs::path scene = write_scene(lit);
  expect_rejected(render(scene, "--set lights.0.intensity=-1"),
                  "--set lights[0].intensity: ", {"must be >= 0, got -1"});
  expect_rejected(render(scene, "--set render.light_source_delay=later"),
                  "--set render.light_source_delay: ", {"unknown mode \"later\""});
}

// A program without its star catalogue beside it or installed (here a copy of it elsewhere)
// says which file is missing, where the scene asks for it, and which package provides it.
TEST_F(CliTest, AMissingStarCatalogueIsNamedWithItsPackage) {
  const fs::path program = dir_ / "bin" / "lightcone";
  fs::create_directories(program.parent_path());
  fs::copy_file(LIGHTCONE_BINARY, program);
  const fs::path scene =
      write_scene("{\"camera\": {\"position\": [0, 0, 0]},\n \"sky\": {\"stars\": true}}");
  const CommandResult r = test::run_command("'" + program.string() + "' render '" + scene.string() +
                                            "' -o '" + png().string() + "'");
  expect_rejected(r, scene.string() + ":2: sky.stars: ",
                  {(dir_ / "bin" / "data" / "stars-bright.lcstars").string(), "kstars-data"});
}

TEST_F(CliTest, ExampleFromTheBriefCameraVelocityOnLineFour) {
  const fs::path scene = write_scene(
      edited(kScene, "\n    \"velocity\": [0, 0, 0]", "\n    \"velocity\": [0, 0, 1.5]"));
  const CommandResult r = render(scene);
  expect_rejected(r, scene.string() + ":4: camera.velocity: ");
  EXPECT_EQ(r.err, "lightcone: " + scene.string() +
                       ":4: camera.velocity: speed 1.5 must be below the speed of light (1)\n");
}

TEST_F(CliTest, SyntaxErrorsNameTheLine) {
  struct Case {
    std::string name, from, to;
    int line;
    std::string what;
  };
  const std::vector<Case> cases = {
      {"NaN", "\"fov\": 30", "\"fov\": NaN", 5, "invalid literal"},
      {"Infinity", "\"exposure\": 0", "\"exposure\": Infinity", 19, "invalid literal"},
      {"number too large for a double", "\"position\": [0, 0, 0]", "\"position\": [0, 0, 1e400]", 3,
       "1e400"},
      {"two numbers", "\"fov\": 30", "\"fov\": 3 0", 5, "syntax error"},
      {"trailing comma", "\"height\": 48", "\"height\": 48,", 8, "a comma after the last member"},
      {"unterminated string", "\"name\": \"ball\",", "\"name\": \"ball,", 11, "syntax error"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path scene = write_scene(edited(kScene, c.from, c.to));
    expect_rejected(render(scene),
                    scene.string() + ":" + std::to_string(c.line) + ": (syntax): ", {c.what});
  }
  SCOPED_TRACE("truncated file");
  const std::string whole = kScene;
  const fs::path truncated = write_scene(whole.substr(0, whole.find("  \"objects\"")));
  expect_rejected(render(truncated), truncated.string() + ":9: (syntax): ", {"end of input"});
}

TEST_F(CliTest, MissingOrUnreadableSceneFile) {
  const fs::path missing = dir_ / "no-such-scene.json";
  expect_rejected(render(missing),
                  missing.string() + ": cannot read scene file: ", {"No such file or directory"});
  expect_rejected(locate(missing, "--direction 0,0,-1"),
                  missing.string() + ": cannot read scene file: ");

  const fs::path folder = dir_ / "folder.json";
  fs::create_directories(folder);
  expect_rejected(render(folder),
                  folder.string() + ": cannot read scene file: ", {"it is a directory"});

  if (geteuid() != 0) {  // root reads any file
    const fs::path locked = write_scene(kScene, "locked.json");
    fs::permissions(locked, fs::perms::none);
    expect_rejected(render(locked),
                    locked.string() + ": cannot read scene file: ", {"Permission denied"});
  }

  const fs::path empty = write_scene("", "empty.json");
  expect_rejected(render(empty), empty.string() + ":1: (syntax): ");
}

TEST_F(CliTest, BadOverridesNameTheSetting) {
  const fs::path scene = write_scene(kScene);
  expect_rejected(render(scene, "--set 'camera.velocity=[0,0,1.5]'"),
                  "--set camera.velocity: ", {"speed 1.5 must be below the speed of light"});
  expect_rejected(render(scene, "--set camera.fov=NaN"),
                  "--set camera.fov: ", {"must be a number"});
  expect_rejected(render(scene, "--set camera.fov=200"),
                  "--set camera.fov: ", {"between 0 and 180"});
  for (const char* setting : {"camera=null", "camera.fov=null"}) {
    const CommandResult r = render(scene, std::string("--set ") + setting);
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(r.err.ends_with(", got null\n")) << r.err;
  }
  expect_rejected(render(scene, "--set camera.fov"), "--set camera.fov: ", {"key.path=value"});
  expect_rejected(render(scene, "--set camera.fovy=40"),
                  "--set camera.fovy: ", {"unknown key \"fovy\""});
  expect_rejected(render(scene, "--set objects.3.velocity=[0,0,0]"), "--set objects");
  expect_rejected(render(scene, "--samples 0"),
                  "--samples: ", {"must be an integer from 1 to 65536"});
}

// --width and friends are overrides of camera.width; the message names the option typed.
TEST_F(CliTest, AbsurdImageSizeOptions) {
  const fs::path scene = write_scene(kScene);
  for (const auto& [option, prefix] :
       {std::pair{"--width 100000", "--width: "}, std::pair{"--width 0", "--width: "},
        std::pair{"--height -5", "--height: "}}) {
    SCOPED_TRACE(option);
    expect_rejected(render(scene, option), prefix, {"must be an integer from 1 to 16384"});
  }
  const CommandResult both = render(scene, "--width 16384 --height 16384");
  expect_rejected(both, "--width: ", {"more than the limit"});
}

// ----------------------------------------------------------------------------------------------
// Broken meshes and images: FILE:LINE: PATH: <the loader's message>

std::string binary_ply_triangle() {
  std::string data =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  data.append(reinterpret_cast<const char*>(v), sizeof v);
  data.push_back(3);
  const std::int32_t f[3] = {0, 1, 2};
  data.append(reinterpret_cast<const char*>(f), sizeof f);
  return data;
}

TEST_F(CliTest, BrokenMeshesAndMissingTextures) {
  const std::string mesh_scene =
      edited(kScene, "{\"sphere\": {\"radius\": 2}}", "{\"mesh\": {\"file\": \"MESH\"}}");
  auto scene_with_mesh = [&](const std::string& file) {
    return write_scene(edited(mesh_scene, "MESH", file));
  };
  const std::string where_mesh = ":12: objects[0].shape.mesh.file: ";

  {
    SCOPED_TRACE("OBJ index out of range");
    test::write_text(dir_ / "broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n");
    const fs::path scene = scene_with_mesh("broken.obj");
    expect_rejected(render(scene), scene.string() + where_mesh,
                    {(dir_ / "broken.obj").string() + ":5: vertex index 9 out of range"});
  }
  {
    SCOPED_TRACE("truncated binary PLY");
    std::string data = binary_ply_triangle();
    test::write_text(dir_ / "whole.ply", data);
    data.resize(data.size() - 6);
    test::write_text(dir_ / "truncated.ply", data);
    // The whole file renders (so it is the truncation that is rejected).
    const CommandResult ok = render(scene_with_mesh("whole.ply"));
    EXPECT_EQ(ok.status, 0) << ok.err;
    fs::remove(png());
    fs::remove(exr());
    const fs::path scene = scene_with_mesh("truncated.ply");
    expect_rejected(render(scene), scene.string() + where_mesh,
                    {(dir_ / "truncated.ply").string() + ": unexpected end of file"});
  }
  {
    SCOPED_TRACE("missing mesh file");
    const fs::path scene = scene_with_mesh("nowhere.obj");
    expect_rejected(
        render(scene), scene.string() + where_mesh,
        {(dir_ / "nowhere.obj").string() + ": cannot read mesh file: No such file or directory"});
  }
  {
    SCOPED_TRACE("unknown mesh format");
    test::write_text(dir_ / "mesh.stl", "solid x\n");
    const fs::path scene = scene_with_mesh("mesh.stl");
    expect_rejected(render(scene), scene.string() + where_mesh, {"unsupported mesh format"});
  }
  {
    SCOPED_TRACE("missing texture");
    const fs::path scene =
        write_scene(edited(kScene, "{\"color\": [0, 1, 0]}", "{\"texture\": \"missing.png\"}"));
    expect_rejected(
        render(scene), scene.string() + ":15: objects[0].material.texture: ",
        {(dir_ / "missing.png").string() + ": cannot read image: No such file or directory"});
  }
  {
    SCOPED_TRACE("texture that is not an image");
    test::write_text(dir_ / "garbage.png", "this is not a PNG");
    const fs::path scene =
        write_scene(edited(kScene, "{\"color\": [0, 1, 0]}", "{\"texture\": \"garbage.png\"}"));
    expect_rejected(render(scene), scene.string() + ":15: objects[0].material.texture: ",
                    {(dir_ / "garbage.png").string() + ": "});
  }
  {
    SCOPED_TRACE("missing sky image");
    const fs::path scene = write_scene(
        edited(kScene, "\"sky\": {\"color\": [0, 0, 1]}", "\"sky\": {\"image\": \"sky.exr\"}"));
    expect_rejected(
        render(scene), scene.string() + ":18: sky.image: ",
        {(dir_ / "sky.exr").string() + ": cannot read image: No such file or directory"});
  }
}

// A shell prefix that limits the command's address space to 1 GB; none under AddressSanitizer,
// which reserves terabytes of address space for its shadow memory.
#if defined(__SANITIZE_ADDRESS__)
constexpr const char* kOneGigabyteLimit = "";
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr const char* kOneGigabyteLimit = "";
#else
constexpr const char* kOneGigabyteLimit = "ulimit -v 1048576;";
#endif
#else
constexpr const char* kOneGigabyteLimit = "ulimit -v 1048576;";
#endif

TEST_F(CliTest, HostileImagesAreRefusedQuicklyAndSmall) {
  // What stb_image once did with them: a 9-byte JPEG wrote past a table, a PNM's size
  // overflowed, a 10-byte GIF allocated 532 MB. Each is now a located error, through the real
  // command, within 5 s and 1 GB (a ulimit on the command's address space).
  const std::pair<const char*, std::string> images[] = {
      {"tiny.jpg", std::string("\xff\xd8\xff\xdb\x00\x43\x00\x01\x02", 9)},
      {"huge.pgm", std::string("P5\n4294967295 4294967295\n255\n")},
      {"bomb.gif", std::string("GIF89a\xff\xff\xff\xff", 10)},
      {"truncated.png",
       std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\x20\0\0\0\x20\0\x08\x02", 26)}};
  for (const auto& [name, bytes] : images) {
    SCOPED_TRACE(name);
    test::write_text(dir_ / name, bytes);
    const fs::path scene = write_scene(
        edited(kScene, "{\"color\": [0, 1, 0]}", std::string("{\"texture\": \"") + name + "\"}"));
    const auto start = std::chrono::steady_clock::now();
    const CommandResult r = run_lightcone(
        "render " + quoted(scene) + " -o " + quoted(png()) + " --exr " + quoted(exr()),
        kOneGigabyteLimit);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(scene.string() +
                         ":15: objects[0].material.texture: " + (dir_ / name).string() + ": "),
              std::string::npos)
        << r.err;
    EXPECT_LT(seconds, 5.0);
    expect_nothing_written();
  }
}

TEST_F(CliTest, DegenerateTrianglesAreDroppedWithAWarning) {
  // A quad (two good triangles), a repeated index and a zero-area triangle.
  test::write_text(dir_ / "quad.obj",
                   "v -50 -50 0\nv 50 -50 0\nv 50 50 0\nv -50 50 0\nv 0 0 0\n"
                   "f 1 2 3 4\nf 1 1 2\nf 1 5 3\n");
  const fs::path scene = write_scene(
      edited(kScene, "{\"sphere\": {\"radius\": 2}}", "{\"mesh\": {\"file\": \"quad.obj\"}}"));
  const CommandResult r = render(scene);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(
      r.err.substr(0, r.err.find('\n') + 1),
      "lightcone: warning: " + (dir_ / "quad.obj").string() + ": 2 degenerate triangles dropped\n");
  EXPECT_EQ(line_count(r.err), 2u) << r.err;  // and the summary line
  ASSERT_TRUE(fs::exists(png()));
  // The remaining quad fills the frame with the mesh's green.
  const auto image = read_exr();
  EXPECT_EQ(pixel(*image, 0, 0).g, 1.0f);
  EXPECT_EQ(pixel(*image, 0, 0).b, 0.0f);
}

// ----------------------------------------------------------------------------------------------
// Bad command lines

TEST_F(CliTest, UnknownSubcommandOrOptionAndMissingArguments) {
  const fs::path scene = write_scene(kScene);
  // The message names what is wrong: the unknown subcommand or option, the missing argument.
  expect_rejected_command_line(run_lightcone("frobnicate " + quoted(scene)), {"frobnicate"});
  expect_rejected_command_line(run_lightcone(""), {"subcommand"});
  expect_rejected_command_line(render(scene, "--bogus"), {"--bogus"});
  expect_rejected_command_line(run_lightcone("render " + quoted(scene)), {"--output"});
  expect_rejected_command_line(run_lightcone("render -o " + quoted(png())), {"scene"});
  expect_rejected_command_line(render(scene, "--width abc"), {"--width", "abc"});
  expect_rejected_command_line(render(scene, "--threads -1"), {"--threads"});
  expect_rejected_command_line(locate(scene, "--world-point 0,0,-10 --bogus"), {"--bogus"});
  // The nearest command or option, where one is near.
  expect_rejected_command_line(run_lightcone("rendr " + quoted(scene)),
                               {"unknown command 'rendr' (did you mean 'render'?"});
  expect_rejected_command_line(render(scene, "--sample 4"),
                               {"(did you mean --samples for --sample?)"});
  expect_rejected_command_line(render(scene, "--widht=64"),
                               {"(did you mean --width for --widht?)"});
  EXPECT_EQ(render(scene, "--bogus").err.find("did you mean"), std::string::npos);
}

// A missing output folder is made, with its parents; one that cannot be made (a file holds its
// name) is bad input, and nothing is written.
TEST_F(CliTest, OutputFoldersAreMadeWhenMissing) {
  const fs::path scene = write_scene(kScene);
  const fs::path nowhere = dir_ / "nowhere" / "deeper";
  const CommandResult r =
      run_lightcone("render " + quoted(scene) + " -o " + quoted(nowhere / "image.png") + " --exr " +
                    quoted(nowhere / "image.exr") + " --quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(nowhere / "image.png"));
  EXPECT_TRUE(fs::is_regular_file(nowhere / "image.exr"));

  const fs::path blocked = dir_ / "blocked";
  std::ofstream(blocked) << "a file, not a folder";
  const CommandResult e = run_lightcone("render " + quoted(scene) + " -o " + quoted(png()) +
                                        " --exr " + quoted(blocked / "image.exr"));
  expect_rejected(e, "--exr ", {blocked.string(), "does not exist and cannot be made"});
  EXPECT_FALSE(fs::exists(png()));
}

// An output path that names a folder is bad input too; the images are written nowhere and no
// temporary file is left beside the target.
TEST_F(CliTest, OutputThatIsAFolder) {
  const fs::path scene = write_scene(kScene);
  const fs::path folder = out_ / "image.png";
  fs::create_directories(folder);
  const CommandResult r = run_lightcone("render " + quoted(scene) + " -o " + quoted(folder) +
                                        " --exr " + quoted(exr()));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(line_count(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find(folder.string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(exr()));
  EXPECT_TRUE(fs::is_empty(folder));
  for (const auto& entry : fs::directory_iterator(out_))
    EXPECT_EQ(entry.path(), folder) << "left behind: " << entry.path();
}

TEST_F(CliTest, LocateRejectsBadQueries) {
  const fs::path scene = write_scene(kScene);
  for (const char* bad : {"1,2", "1,2,x", "1,2,3,4", "1,,3", "1,2,nan", "1,2,inf", "'1 2 3'"}) {
    SCOPED_TRACE(bad);
    expect_rejected(locate(scene, std::string("--object ball --point ") + bad), "--point ",
                    {"expected three numbers x,y,z"});
  }
  expect_rejected(locate(scene, "--world-point 0,0"), "--world-point ", {"expected three numbers"});
  expect_rejected(locate(scene, "--direction 0,0,0"), "--direction: ", {"zero"});
  expect_rejected(locate(scene, "--object nosuch --point 0,0,0"),
                  scene.string() + ": --object: ", {"no object named 'nosuch'"});
  expect_rejected(locate(scene, "--point 0,0,0"), "locate: ", {"--object"});
  expect_rejected(locate(scene, ""), "locate: ", {"exactly one of"});
  expect_rejected(locate(scene, "--world-point 0,0,-10 --direction 0,0,-1"),
                  "locate: ", {"exactly one of"});
  // Points whose light path overflows double precision: an error, not a line of nulls.
  for (const char* far : {"1e308,0,0", "0,0,-1e300"}) {
    expect_rejected(locate(scene, std::string("--world-point ") + far),
                    std::string("--world-point ") + far + ": ", {"too far from the camera"});
    expect_rejected(locate(scene, std::string("--object ball --point ") + far),
                    std::string("--point ") + far + ": ", {"too far from the camera"});
  }
}

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
  EXPECT_EQ(pixel(*exr_image, 32, 24).g, 1.0f);
  EXPECT_EQ(pixel(*exr_image, 0, 0).b, 1.0f);
  EXPECT_EQ(pixel(*exr_image, 0, 0).g, 0.0f);
  EXPECT_EQ(png_byte(pixel(*png_image, 32, 24).g), 255);
  EXPECT_EQ(png_byte(pixel(*png_image, 32, 24).r), 0);
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

TEST_F(CliTest, StatsIsOneJsonLineWithSecondsRaysAndRate) {
  const fs::path scene = write_scene(kScene);
  const CommandResult r = render(scene, "--samples 3 --stats --quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(line_count(r.err), 1u) << r.err;
  ASSERT_TRUE(r.err.ends_with('\n'));
  const auto stats = nlohmann::ordered_json::parse(r.err);
  ASSERT_TRUE(stats.is_object());
  std::vector<std::string> keys;
  for (const auto& item : stats.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"seconds", "rays", "mrays_per_s"}));
  ASSERT_TRUE(stats["seconds"].is_number());
  ASSERT_TRUE(stats["rays"].is_number_integer());
  ASSERT_TRUE(stats["mrays_per_s"].is_number());
  const double seconds = stats["seconds"].get<double>();
  EXPECT_GT(seconds, 0.0);
  EXPECT_LT(seconds, 60.0);
  EXPECT_EQ(stats["rays"].get<std::uint64_t>(), 64u * 48u * 3u);
  EXPECT_NEAR(stats["mrays_per_s"].get<double>(), 64 * 48 * 3 / seconds / 1e6,
              1e-9 * stats["mrays_per_s"].get<double>());
  EXPECT_EQ(r.out, "");
}

TEST_F(CliTest, SetSkyColourMakesTheBackgroundRed) {
  const fs::path scene = write_scene(kScene);
  ASSERT_EQ(render(scene).status, 0);
  EXPECT_EQ(pixel(*read_exr(), 0, 0).r, 0.0f);
  const CommandResult r = render(scene, "--set 'sky.color=[1,0,0]'");
  EXPECT_EQ(r.status, 0) << r.err;
  const auto png_image = read_png();
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{63, 47}, std::pair{63, 0}}) {
    EXPECT_EQ(png_byte(pixel(*png_image, x, y).r), 255);
    EXPECT_EQ(png_byte(pixel(*png_image, x, y).g), 0);
    EXPECT_EQ(png_byte(pixel(*png_image, x, y).b), 0);
  }
  // The ball is still green.
  EXPECT_EQ(png_byte(pixel(*png_image, 32, 24).g), 255);
}

// The ball of kScene crossing the view at 0.8c, placed so that the light from its centre that
// reaches the camera left it at t = -10 straight ahead. It is black on a red sky at rest: black
// stays black and the sky stays red whatever the Doppler shift, so a pixel tells which it is.
std::string moving_black_ball() {
  const std::string moving = edited(kScene, "\n      \"velocity\": [0, 0, 0]",
                                    "\n      \"velocity\": [0.8, 0, 0],\n      \"time\": -10");
  return edited(edited(moving, "\"color\": [0, 0, 1]", "\"color\": [1, 0, 0]"),
                "\"color\": [0, 1, 0]", "\"color\": [0, 0, 0]");
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
      for (int x = 0; x < image->width; ++x) mask.push_back(pixel(*image, x, y).r < 0.5f);
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
// then pass the luminance the tone curve shows as 0.9.
TEST_F(CliTest, AutomaticExposure) {
  const auto expect_exr = [](const Image& image, float value) {
    for (std::size_t i = 0; i < image.rgb.size(); ++i)
      ASSERT_NEAR(image.rgb[i], value, 1e-6f) << "value " << i;
  };
  {
    SCOPED_TRACE("uniform grey 0.2");
    const fs::path scene = write_scene(uniform_wall("[0.2, 0.2, 0.2]", R"({"doppler": "off"})"));
    const CommandResult r = render(scene);
    ASSERT_EQ(r.status, 0) << r.err;
    expect_exr(*read_exr(), 0.5f);
    // Shown through the filmic curve.
    const int png = static_cast<int>(std::lround(255 * srgb_encode(filmic_curve(0.5))));
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
        EXPECT_NEAR(exr_image->rgb[i], 0.5f, 1e-6f) << "pixel " << i / 3;
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
        EXPECT_NEAR(pixel(*exr_image, x, y).g, x < 8 ? 0.125f : 0.5f, 1e-6f) << x << "," << y;
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
        const Rgb c = pixel(*exr_image, x, y);
        EXPECT_NEAR(c.g, 0.5 / 0.7152, 1e-6) << x << "," << y;
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
    EXPECT_NEAR(highest, 0.5f, 1e-5f);
    EXPECT_NEAR(lowest, 0.2f, 1e-5f);
    // Before a brighter wall (0.2), under clamp: the ball would take the wall to 2, so the
    // wall, more than 2 % of the picture, is held at 0.9 and the ball shows at 0.225.
    const fs::path bright = write_scene(
        edited(edited(read_text(scene), "[0.02, 0.02, 0.02]", "[0.2, 0.2, 0.2]"),
               "\"searchlight\": \"off\"", "\"searchlight\": \"off\", \"tonemap\": \"clamp\""));
    ASSERT_EQ(render(bright).status, 0);
    const auto held = read_exr();
    lowest = 1e9f, highest = 0;
    for (std::size_t i = 0; i < held->rgb.size(); i += 3)
      lowest = std::min(lowest, held->rgb[i]), highest = std::max(highest, held->rgb[i]);
    EXPECT_NEAR(highest, 0.9f, 1e-5f);
    EXPECT_NEAR(lowest, 0.225f, 1e-5f);
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

// ----------------------------------------------------------------------------------------------
// --help

TEST_F(CliTest, HelpForTheProgramAndEachSubcommand) {
  const CommandResult program = run_lightcone("--help");
  EXPECT_EQ(program.status, 0) << program.err;
  for (const char* word : {"render", "locate"})
    EXPECT_NE(program.out.find(word), std::string::npos) << word << " in\n" << program.out;

  const CommandResult render_help = run_lightcone("render --help");
  EXPECT_EQ(render_help.status, 0) << render_help.err;
  for (const char* option : {"-o", "--output", "--exr", "--width", "--height", "--samples",
                             "--threads", "--set", "--stats", "--quiet"})
    EXPECT_NE(render_help.out.find(option), std::string::npos) << option << " in\n"
                                                               << render_help.out;

  const CommandResult locate_help = run_lightcone("locate --help");
  EXPECT_EQ(locate_help.status, 0) << locate_help.err;
  for (const char* option : {"--object", "--point", "--world-point", "--direction", "--set"})
    EXPECT_NE(locate_help.out.find(option), std::string::npos) << option << " in\n"
                                                               << locate_help.out;
  EXPECT_EQ(locate_help.out.find("--exr"), std::string::npos);

  EXPECT_EQ(run_lightcone("render -h").status, 0);
}

// ----------------------------------------------------------------------------------------------
// locate

// Parses locate's stdout: one line, one JSON object with exactly the contract's keys in order.
nlohmann::ordered_json locate_output(const CommandResult& r) {
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(line_count(r.out), 1u) << r.out;
  const auto out = nlohmann::ordered_json::parse(r.out, nullptr, false);
  EXPECT_TRUE(out.is_object()) << r.out;
  if (!out.is_object()) return nlohmann::ordered_json::object();
  std::vector<std::string> keys;
  for (const auto& item : out.items()) keys.push_back(item.key());
  EXPECT_EQ(keys,
            (std::vector<std::string>{"pixel", "direction", "emission_time", "emission_position",
                                      "emission_proper_time", "distance", "in_view", "doppler"}));
  // A pixel where the point is in view, null where it is behind the camera or off the image.
  if (out["in_view"].get<bool>())
    EXPECT_TRUE(out["pixel"].is_array() && out["pixel"].size() == 2) << r.out;
  else
    EXPECT_TRUE(out["pixel"].is_null()) << r.out;
  EXPECT_TRUE(out["doppler"].is_number() && out["doppler"].get<double>() > 0) << r.out;
  EXPECT_TRUE(out["direction"].is_array() && out["direction"].size() == 3) << r.out;
  EXPECT_TRUE(out["in_view"].is_boolean()) << r.out;
  return out;
}

double at(const nlohmann::ordered_json& j, const char* key, std::size_t i) {
  return j.at(key).at(i).get<double>();
}

// Near a black hole, --object gives every image of a body's point with its clock reading: the
// clock let go last in infall.json, seen held at rest (clock negative) in its secondary and
// third images, falling in its primary; their emission times in the order of the images.
TEST_F(CliTest, LocateAnObjectNearABlackHole) {
  const CommandResult r = locate(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes/infall.json",
                                 "--object late --point 0,0,0.8");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto out = nlohmann::ordered_json::parse(r.out);
  const auto& images = out.at("images");
  ASSERT_EQ(images.size(), 3u);
  EXPECT_GT(images[0]["emission_proper_time"].get<double>(), 0);
  EXPECT_LT(images[1]["emission_proper_time"].get<double>(), 0);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(images[k]["order"].get<int>(), k);
  EXPECT_GT(images[0]["emission_time"].get<double>(), images[1]["emission_time"].get<double>());
  EXPECT_GT(images[1]["emission_time"].get<double>(), images[2]["emission_time"].get<double>());
  EXPECT_EQ(out["emission_proper_time"], images[0]["emission_proper_time"]);
}

TEST_F(CliTest, LocateWorldPointKnownValues) {
  const fs::path scene = write_scene(kScene);
  // Camera at rest at the origin: a point 10 ahead is in the image centre, 10 away, emitted at
  // t = -10 where it is.
  const auto still = locate_output(locate(scene, "--world-point 0,0,-10"));
  ASSERT_FALSE(still.empty());
  EXPECT_NEAR(at(still, "pixel", 0), 32, 1e-9);
  EXPECT_NEAR(at(still, "pixel", 1), 24, 1e-9);
  EXPECT_NEAR(at(still, "direction", 0), 0, 1e-12);
  EXPECT_NEAR(at(still, "direction", 1), 0, 1e-12);
  EXPECT_NEAR(at(still, "direction", 2), -1, 1e-12);
  EXPECT_NEAR(still["emission_time"].get<double>(), -10, 1e-9);
  EXPECT_NEAR(at(still, "emission_position", 2), -10, 1e-9);
  EXPECT_NEAR(still["distance"].get<double>(), 10, 1e-9);
  EXPECT_TRUE(still["in_view"].get<bool>());

  // The camera flying at 0.6c toward it: same emission event, but in the camera's frame the
  // light travelled gamma (1 + beta) 10 = 20.
  const auto flying =
      locate_output(locate(scene, "--world-point 0,0,-10 --set 'camera.velocity=[0,0,-0.6]'"));
  ASSERT_FALSE(flying.empty());
  EXPECT_NEAR(at(flying, "pixel", 0), 32, 1e-9);
  EXPECT_NEAR(at(flying, "pixel", 1), 24, 1e-9);
  EXPECT_NEAR(flying["emission_time"].get<double>(), -10, 1e-9);
  EXPECT_NEAR(at(flying, "emission_position", 0), 0, 1e-9);
  EXPECT_NEAR(at(flying, "emission_position", 2), -10, 1e-9);
  EXPECT_NEAR(flying["distance"].get<double>(), 20, 1e-9);

  // Off axis, above and to the right: x grows to the right, y downwards. fov 30 over 48 rows:
  // focal length 24 / tan(15 deg) pixels.
  const double focal = 24 / std::tan(15 * std::acos(-1.0) / 180);
  const auto off = locate_output(locate(scene, "--world-point 1,0.5,-10"));
  ASSERT_FALSE(off.empty());
  EXPECT_NEAR(at(off, "pixel", 0), 32 + focal * 0.1, 1e-9);
  EXPECT_NEAR(at(off, "pixel", 1), 24 - focal * 0.05, 1e-9);
  EXPECT_NEAR(off["distance"].get<double>(), std::sqrt(1 + 0.25 + 100), 1e-9);

  // Behind the camera.
  const auto behind = locate_output(locate(scene, "--world-point 0,0,10"));
  ASSERT_FALSE(behind.empty());
  EXPECT_FALSE(behind["in_view"].get<bool>());
  // Far to the side, in front.
  const auto aside = locate_output(locate(scene, "--world-point 100,0,-10"));
  ASSERT_FALSE(aside.empty());
  EXPECT_FALSE(aside["in_view"].get<bool>());
}

TEST_F(CliTest, LocateDirectionHasNoEmissionEvent) {
  const fs::path scene = write_scene(kScene);
  const auto ahead = locate_output(locate(scene, "--direction 0,0,-3"));
  ASSERT_FALSE(ahead.empty());
  EXPECT_NEAR(at(ahead, "pixel", 0), 32, 1e-9);
  EXPECT_NEAR(at(ahead, "pixel", 1), 24, 1e-9);
  EXPECT_NEAR(at(ahead, "direction", 2), -1, 1e-12);
  EXPECT_TRUE(ahead["emission_time"].is_null());
  EXPECT_TRUE(ahead["emission_position"].is_null());
  EXPECT_TRUE(ahead["distance"].is_null());
  EXPECT_TRUE(ahead["in_view"].get<bool>());

  // A camera flying along +x at 0.6c sees the direction perpendicular to its motion tilted
  // forward: the apparent direction is (beta, 0, -1/gamma) = (0.6, 0, -0.8).
  const auto tilted =
      locate_output(locate(scene, "--direction 0,0,-1 --set 'camera.velocity=[0.6,0,0]'"));
  ASSERT_FALSE(tilted.empty());
  EXPECT_NEAR(at(tilted, "direction", 0), 0.6, 1e-12);
  EXPECT_NEAR(at(tilted, "direction", 1), 0, 1e-12);
  EXPECT_NEAR(at(tilted, "direction", 2), -0.8, 1e-12);
  EXPECT_FALSE(tilted["in_view"].get<bool>());  // 37 degrees off axis, the half-width is ~21

  // Directions are scaled before they are normalised: huge and tiny components work alike.
  for (const char* direction : {"0,0,-1e300", "0,0,-1e-300"}) {
    const auto scaled = locate_output(locate(scene, std::string("--direction ") + direction));
    ASSERT_FALSE(scaled.empty()) << direction;
    EXPECT_NEAR(at(scaled, "pixel", 0), 32, 1e-9) << direction;
    EXPECT_NEAR(at(scaled, "direction", 2), -1, 1e-12) << direction;
  }
}

// locate's "doppler" is D = nu_camera / nu_emitter (PHYSICS.md, "Doppler factor").
TEST_F(CliTest, LocateDopplerFactor) {
  const fs::path scene = write_scene(kScene);
  auto doppler = [&](const std::string& query) {
    const auto out = locate_output(locate(scene, query));
    return out.empty() ? -1.0 : out["doppler"].get<double>();
  };
  // Camera and point at rest: no shift at all.
  EXPECT_EQ(doppler("--world-point 0,0,-10"), 1.0);
  EXPECT_EQ(doppler("--world-point 3,-2,-10"), 1.0);
  EXPECT_EQ(doppler("--object ball --point 0,0,2"), 1.0);
  // The camera flying at 0.6c straight toward the point: sqrt((1 + 0.6) / (1 - 0.6)) = 2.
  const std::string toward = " --set 'camera.velocity=[0,0,-0.6]'";
  EXPECT_NEAR(doppler("--world-point 0,0,-10" + toward), std::sqrt(1.6 / 0.4), 1e-9);
  EXPECT_NEAR(doppler("--world-point 0,0,-10" + toward), 2, 1e-9);
  // Flying away: 1/2. Across the light's path in W (n . beta = 0): gamma = 1.25, the
  // transverse Doppler effect.
  EXPECT_NEAR(doppler("--world-point 0,0,-10 --set 'camera.velocity=[0,0,0.6]'"), 0.5, 1e-9);
  EXPECT_NEAR(doppler("--world-point 0,0,-10 --set 'camera.velocity=[0.6,0,0]'"), 1.25, 1e-9);
  // The emitter approaching a camera at rest at 0.6c: 1 / (gamma (1 - 0.6)) = 2 as well.
  EXPECT_NEAR(doppler("--object ball --point 0,0,0 --set 'objects[0].velocity=[0,0,0.6]'"), 2,
              1e-9);
  // Without relativity there is no Doppler shift.
  EXPECT_EQ(doppler("--world-point 0,0,-10" + toward + " --set render.relativity=false"), 1.0);
  EXPECT_EQ(doppler("--object ball --point 0,0,0 --set 'objects[0].velocity=[0,0,0.6]'"
                    " --set render.relativity=false"),
            1.0);
}

// For --direction, "doppler" is the factor of the sky's light from that direction.
TEST_F(CliTest, LocateDopplerOfTheSkysLight) {
  const fs::path scene = write_scene(kScene);
  auto doppler = [&](const std::string& query) {
    const auto out = locate_output(locate(scene, query));
    return out.empty() ? -1.0 : out["doppler"].get<double>();
  };
  EXPECT_EQ(doppler("--direction 0,0,-1"), 1.0);
  // The camera flying at 0.6c toward the sky it looks at: 2; away from it: 1/2.
  EXPECT_NEAR(doppler("--direction 0,0,-1 --set 'camera.velocity=[0,0,-0.6]'"), 2, 1e-9);
  EXPECT_NEAR(doppler("--direction 0,0,-1 --set 'camera.velocity=[0,0,0.6]'"), 0.5, 1e-9);
  // Light crossing the camera's motion at a right angle in W: gamma = 1.25.
  EXPECT_NEAR(doppler("--direction 0,0,-1 --set 'camera.velocity=[0.6,0,0]'"), 1.25, 1e-9);
  // The sky itself approaching a camera at rest at 0.6c: 1 / (gamma (1 - 0.6)) = 2.
  EXPECT_NEAR(doppler("--direction 0,0,-1 --set 'sky.velocity=[0,0,0.6]'"), 2, 1e-9);
  EXPECT_EQ(doppler("--direction 0,0,-1 --set 'camera.velocity=[0,0,-0.6]'"
                    " --set render.relativity=false"),
            1.0);
}

// Visible points of the ball crossing at 0.8c are located on pixels drawn in the ball's colour.
TEST_F(CliTest, LocateObjectPointLandsOnTheRenderedBall) {
  const fs::path scene = write_scene(moving_black_ball());
  const CommandResult r = render(scene);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto image = read_png();
  EXPECT_EQ(png_byte(pixel(*image, 0, 0).r), 255);  // the sky

  for (const char* point : {"0,0,2", "-2,0,0", "-1.2,0,1.6", "-1.6,1.2,0"}) {
    SCOPED_TRACE(point);
    const auto where = locate_output(locate(scene, std::string("--object ball --point ") + point));
    ASSERT_FALSE(where.empty());
    EXPECT_TRUE(where["in_view"].get<bool>());
    const int x = static_cast<int>(std::floor(at(where, "pixel", 0)));
    const int y = static_cast<int>(std::floor(at(where, "pixel", 1)));
    ASSERT_TRUE(x >= 0 && x < 64 && y >= 0 && y < 48) << x << "," << y;
    const Rgb c = pixel(*image, x, y);
    EXPECT_EQ(png_byte(c.r), 0) << x << "," << y;
    EXPECT_EQ(png_byte(c.g), 0) << x << "," << y;
    EXPECT_EQ(png_byte(c.b), 0) << x << "," << y;
    // The emission event lies on the camera's past light cone: |x| = -t.
    const double t = where["emission_time"].get<double>();
    const double d =
        std::hypot(at(where, "emission_position", 0), at(where, "emission_position", 1),
                   at(where, "emission_position", 2));
    EXPECT_NEAR(d, -t, 1e-9);
    EXPECT_NEAR(where["distance"].get<double>(), -t, 1e-9);  // the camera is at rest in W
  }
  // The front point's emission event is on its world-line: it left z = -8 when the ball's
  // centre was at x = 0.8 (t + 10). Light delay shows it well to the right of the image centre.
  const auto front = locate_output(locate(scene, "--object ball --point 0,0,2"));
  ASSERT_FALSE(front.empty());
  const double t = front["emission_time"].get<double>();
  EXPECT_NEAR(at(front, "emission_position", 0), 0.8 * (t + 10), 1e-9);
  EXPECT_NEAR(at(front, "emission_position", 1), 0, 1e-9);
  EXPECT_NEAR(at(front, "emission_position", 2), -8, 1e-9);
  EXPECT_GT(at(front, "pixel", 0), 42);
  // The centre's light left it at t = -10 from straight ahead.
  const auto centre = locate_output(locate(scene, "--object ball --point 0,0,0"));
  ASSERT_FALSE(centre.empty());
  EXPECT_NEAR(centre["emission_time"].get<double>(), -10, 1e-9);
  EXPECT_NEAR(at(centre, "pixel", 0), 32, 1e-9);
  EXPECT_NEAR(at(centre, "pixel", 1), 24, 1e-9);
}

// A big sphere at rest 1e7 away in direction d and the direction d itself land on the same
// pixel for a camera at 0.9c.
TEST_F(CliTest, LocateFarBodyAndDirectionAgree) {
  const double d[3] = {0.3, 0.1, -1};
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  char position[200];
  std::snprintf(position, sizeof position, "[%.17g, %.17g, %.17g]", 1e7 * d[0] / n, 1e7 * d[1] / n,
                1e7 * d[2] / n);
  const std::string far = edited(
      edited(edited(kScene, "{\"sphere\": {\"radius\": 2}}", "{\"sphere\": {\"radius\": 1000}}"),
             "\"position\": [0, 0, -10]", std::string("\"position\": ") + position),
      "\"name\": \"ball\"", "\"name\": \"far\"");
  // 0.9c along (0.2, 0.1, -1), so that the aberrated direction stays in view.
  const double v[3] = {0.2, 0.1, -1};
  const double k = 0.9 / std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  char velocity[200];
  std::snprintf(velocity, sizeof velocity, "[%.17g, %.17g, %.17g]", k * v[0], k * v[1], k * v[2]);
  const fs::path scene = write_scene(
      edited(far, "\n    \"velocity\": [0, 0, 0]", std::string("\n    \"velocity\": ") + velocity));
  const auto body = locate_output(locate(scene, "--object far --point 0,0,0"));
  const auto sky = locate_output(locate(scene, "--direction 0.3,0.1,-1"));
  ASSERT_FALSE(body.empty());
  ASSERT_FALSE(sky.empty());
  EXPECT_TRUE(sky["in_view"].get<bool>());
  EXPECT_EQ(body["in_view"], sky["in_view"]);
  EXPECT_NEAR(at(body, "pixel", 0), at(sky, "pixel", 0), 1e-3);
  EXPECT_NEAR(at(body, "pixel", 1), at(sky, "pixel", 1), 1e-3);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(at(body, "direction", i), at(sky, "direction", i), 1e-9);
  // Aberration moved it: at rest, the same direction is elsewhere in the image.
  const auto still =
      locate_output(locate(scene, "--direction 0.3,0.1,-1 --set 'camera.velocity=[0,0,0]'"));
  ASSERT_FALSE(still.empty());
  EXPECT_GT(std::abs(at(still, "pixel", 0) - at(sky, "pixel", 0)), 1.0);
}

// ----------------------------------------------------------------------------------------------
// Output formats, crops, seeds, check, info, the interrupt

// A moving checkered ball over a sky, with 4 samples: different seeds give different pixels.
const std::string kMovingScene = edited(
    edited(kScene, "\"material\": {\"color\": [0, 1, 0]}",
           "\"material\": {\"checker\": {\"size\": 0.3, \"colors\": [[1, 1, 1], [0, 0, 0]]}}"),
    "\"height\": 48", "\"height\": 48, \"samples\": 4");

TEST_F(CliTest, OutputFormatFollowsTheExtension) {
  const fs::path scene = write_scene(kScene);
  for (const char* name : {"a.png", "b.PNG", "c.jpg", "d.jpeg", "e.exr"}) {
    const fs::path out = out_ / name;
    const CommandResult r = run_lightcone("render " + quoted(scene) + " -o " + quoted(out));
    EXPECT_EQ(r.status, 0) << name << ": " << r.err;
    std::ifstream in(out, std::ios::binary);
    std::string magic(4, '\0');
    in.read(magic.data(), 4);
    const std::string ext = image_format_of(out) == ImageFormat::kExr    ? "exr"
                            : image_format_of(out) == ImageFormat::kJpeg ? "jpg"
                                                                         : "png";
    if (ext == "png") {
      EXPECT_EQ(magic.substr(1, 3), "PNG") << name;
    }
    if (ext == "jpg") {
      EXPECT_EQ(static_cast<unsigned char>(magic[0]), 0xFF) << name;
    }
    if (ext == "exr") {
      EXPECT_EQ(magic, std::string("\x76\x2f\x31\x01", 4)) << name;
    }
    // Every format decodes to the same picture (the EXR holds the linear radiance: green 1).
    const auto image = load_image_file(out);
    ASSERT_EQ(image->width, 64);
    const Rgb centre = pixel(*image, 32, 24);
    EXPECT_NEAR(centre.g, 1.0, 0.02) << name;
    EXPECT_NEAR(centre.r, 0.0, 0.02) << name;
  }
}

TEST_F(CliTest, BadOutputRequestsAreErrorsBeforeRendering) {
  const fs::path scene = write_scene(kScene);
  const struct {
    std::string args, message;
  } cases[] = {
      {"-o " + quoted(out_ / "x.tif"),
       "-o " + (out_ / "x.tif").string() + ": unknown image format"},
      {"-o " + quoted(out_ / "noext"), "unknown image format"},
      {"-o " + quoted(png()) + " --exr " + quoted(png()),
       "--exr " + png().string() + ": the name must end in .exr"},
      {"-o " + quoted(exr()) + " --exr " + quoted(exr()), ": is the same file as -o"},
      {"-o ''", "-o: the output file name is empty"},
      {"-o " + quoted(png()) + " --crop 0,0,0,10", "--crop 0,0,0,10: the window must be non-empty"},
      {"-o " + quoted(png()) + " --crop 0,0,65,10", "inside the 64x48 image"},
      {"-o " + quoted(png()) + " --crop 1,2,3", "expected four integers"},
      {"-o " + quoted(png()) + " --seed 1.5", "--seed"},
      {"-o " + quoted(png()) + " --seed x", "--seed"},
      {"-o " + quoted(exr()) + " --aov doppler,speed",
       "--aov doppler,speed: unknown output variable 'speed'"},
      {"-o " + quoted(png()) + " --aov doppler",
       "--aov: the output variables go into an OpenEXR file"},
      {"-o " + quoted(exr()) + " --aov ''", "--aov"},
      {"-o " + quoted(png()) + " --map normal", "--map normal: unknown quantity"},
      {"-o " + quoted(exr()) + " --map doppler", "--map: the map is a picture"},
  };
  for (const auto& c : cases) {
    const CommandResult r = run_lightcone("render " + quoted(scene) + " " + c.args);
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_EQ(line_count(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    expect_nothing_written();
  }
}

TEST_F(CliTest, BodiesMovingApartTooFastForDoublePrecisionAreErrors) {
  // Each at gamma 2236, but 1e7 relative to each other: once a frame of NaN pixels.
  const fs::path scene = write_scene(edited(
      edited(kScene, "\n    \"velocity\": [0, 0, 0]", "\n    \"velocity\": [0, 0, 0.9999999]"),
      "\n      \"velocity\": [0, 0, 0]", "\n      \"velocity\": [0, 0, -0.9999999]"));
  const CommandResult r = render(scene);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(scene.string() + ":14: objects[0].velocity: speed 0.9999999 relative to "
                                        "the camera is too close to the speed of light"),
            std::string::npos)
      << r.err;
  expect_nothing_written();
}

TEST_F(CliTest, OnlyRegularFilesAreReplacedAndLinksAreKept) {
  const fs::path scene = write_scene(kScene);
  // A FIFO and (where the test may create one) a character device named like images.
  const fs::path fifo = out_ / "fifo.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const fs::path device = out_ / "device.png";
  const bool have_device = ::mknod(device.c_str(), S_IFCHR | 0644, makedev(1, 3)) == 0;
  for (const fs::path& special : {fifo, device}) {
    if (special == device && !have_device) continue;
    const CommandResult r = run_lightcone("render " + quoted(scene) + " -o " + quoted(special));
    EXPECT_EQ(r.status, 2) << special;
    EXPECT_NE(r.err.find("is not a regular file"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::is_regular_file(special)) << special << " was replaced";
  }
  // A symbolic link to a regular file: the file is written, the link stays a link.
  const fs::path real = out_ / "real.png", link = out_ / "link.png";
  test::write_text(real, "old");
  fs::create_symlink(real, link);
  const CommandResult r = run_lightcone("render " + quoted(scene) + " -o " + quoted(link));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(load_image_file(real)->width, 64);
  // A name of 250 characters: the temporary name beside it stays short.
  const fs::path long_name = out_ / (std::string(246, 'n') + ".png");
  const CommandResult l = run_lightcone("render " + quoted(scene) + " -o " + quoted(long_name));
  EXPECT_EQ(l.status, 0) << l.err;
  EXPECT_TRUE(fs::is_regular_file(long_name));
}

TEST_F(CliTest, AFullDiskLeavesThePreviousImagesAndExitsOne) {
  const fs::path scene = write_scene(kScene);
  // The sizes of the two files, from a render where the disk has room.
  const fs::path roomy = dir_ / "roomy";
  fs::create_directories(roomy);
  ASSERT_EQ(run_lightcone("render " + quoted(scene) + " -o " + quoted(roomy / "a.png") + " --exr " +
                          quoted(roomy / "a.exr"))
                .status,
            0);
  const auto png_bytes = static_cast<long long>(fs::file_size(roomy / "a.png"));
  const auto exr_bytes = static_cast<long long>(fs::file_size(roomy / "a.exr"));
  // Full at once; full in the middle of the PNG; full in the middle of the EXR (the PNG, written
  // first, fits).
  for (long long budget : {0LL, png_bytes / 2, png_bytes + exr_bytes / 2}) {
    test::write_text(png(), "previous PNG");
    test::write_text(exr(), "previous EXR");
    const std::string environment = "LD_PRELOAD=" + quoted(LIGHTCONE_FULL_DISK_LIBRARY) +
                                    " LIGHTCONE_FULL_DISK_BYTES=" + std::to_string(budget) +
                                    " ASAN_OPTIONS=verify_asan_link_order=0";
    const CommandResult r = run_lightcone(
        "render " + quoted(scene) + " -o " + quoted(png()) + " --exr " + quoted(exr()),
        environment);
    EXPECT_EQ(r.status, 1) << budget << ": " << r.err;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    EXPECT_EQ(read_text(png()), "previous PNG") << budget;
    EXPECT_EQ(read_text(exr()), "previous EXR") << budget;
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(out_))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"image.exr", "image.png"})) << budget;
  }
}

TEST_F(CliTest, AnAcceleratingCameraSeesWithItsVelocityAtItsProperTime) {
  // From rest, 0.5 along -z for 2 units of proper time, observed at proper time 1.5: the same
  // pictures and located directions as a camera at that event with that velocity
  // (tanh(0.75) = 0.63515) given directly.
  const std::string tail = R"(
  "objects": [{"name": "ball", "shape": {"sphere": {"radius": 1}}, "position": [2, 0, -8],
               "velocity": [0.3, 0, 0],
               "material": {"checker": {"size": 0.3, "colors": [[1, 0.5, 0], [0, 0.3, 1]]}}}],
  "sky": {"grid": {"spacing": 15}}
})";
  const fs::path accelerated = write_scene(R"({
  "camera": {"position": [0, 0, 0], "width": 96, "height": 64,
             "motion": {"phases": [{"duration": 2, "acceleration": [0, 0, -0.5]}]},
             "proper_time": 1.5},)" + tail,
                                           "accelerated.json");
  const double t = std::sinh(0.75) / 0.5, z = -(std::cosh(0.75) - 1) / 0.5;
  const fs::path inertial = write_scene(fmt::format(R"({{
  "camera": {{"position": [0, 0, {:.17g}], "time": {:.17g}, "velocity": [0, 0, {:.17g}],
             "width": 96, "height": 64}},)",
                                                    z, t, -std::tanh(0.75)) +
                                            tail,
                                        "inertial.json");
  for (const char* query :
       {"--direction 1,0.3,-1", "--direction -0.2,0.1,-1", "--object ball --point 0,1,0"}) {
    const auto a = locate_output(locate(accelerated, query));
    const auto b = locate_output(locate(inertial, query));
    ASSERT_FALSE(a.empty()) << query;
    for (const char* key : {"pixel", "direction"})
      for (std::size_t k = 0; k < a[key].size(); ++k)
        EXPECT_NEAR(a[key][k].get<double>(), b[key][k].get<double>(), 1e-9) << query << key;
    EXPECT_NEAR(a["doppler"].get<double>(), b["doppler"].get<double>(), 1e-12) << query;
  }
  // And the sky's direction is where the aberration formula puts it for the 4-velocity at that
  // proper time, (0, 0, -sinh(0.75)) / cosh(0.75).
  const Vec3 sky = normalize(Vec3{1, 0.3, -1});
  const Vec3 seen = aberrate_into_moving_frame(sky, {0, 0, -std::tanh(0.75)});
  const auto located = locate_output(locate(accelerated, "--direction 1,0.3,-1"));
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(located["direction"][k].get<double>(), seen[k], 1e-12) << k;
  const fs::path a_png = out_ / "a.exr", b_png = out_ / "b.exr";
  ASSERT_EQ(run_lightcone("render " + quoted(accelerated) + " -o " + quoted(a_png)).status, 0);
  ASSERT_EQ(run_lightcone("render " + quoted(inertial) + " -o " + quoted(b_png)).status, 0);
  EXPECT_LT(test::fraction_differing(*load_image_file(a_png), *load_image_file(b_png)), 0.001);
}

TEST_F(CliTest, DevicesAndFifosAreNotReadAsInputs) {
  // /dev/zero never ends and a FIFO blocks: both are refused before they are opened.
  const fs::path fifo = dir_ / "fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  for (const std::string& scene : {std::string("/dev/zero"), fifo.string()}) {
    const CommandResult r = run_lightcone("render '" + scene + "' -o " + quoted(png()));
    EXPECT_EQ(r.status, 2) << scene;
    EXPECT_NE(r.err.find(scene + ": cannot read scene file: it is not a regular file"),
              std::string::npos)
        << r.err;
  }
  fs::create_symlink("/dev/zero", dir_ / "zero.obj");  // a mesh name that leads to /dev/zero
  const fs::path mesh_scene = write_scene(
      edited(kScene, "{\"sphere\": {\"radius\": 2}}", "{\"mesh\": {\"file\": \"zero.obj\"}}"));
  const CommandResult r = render(mesh_scene);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("zero.obj: cannot read mesh file: it is not a regular file"),
            std::string::npos)
      << r.err;
  expect_nothing_written();
}

TEST_F(CliTest, MessagesAreCutAndShowControlCharacters) {
  const fs::path big = write_scene(
      edited(kScene, "\"fov\": 30", "\"" + std::string(1000000, 'k') + "\": 1, \"fov\": 30"),
      "big.json");
  const CommandResult r = run_lightcone("check " + quoted(big));
  EXPECT_EQ(r.status, 2);
  EXPECT_LT(r.err.size(), 600u) << r.err.substr(0, 600);
  EXPECT_NE(r.err.find(std::string(70, 'k') + "..."), std::string::npos);
  const fs::path control = write_scene(
      edited(kScene, "\"fov\": 30", "\"a\\u0000\\u001b[31m\": 1, \"fov\": 30"), "control.json");
  const CommandResult c = run_lightcone("check " + quoted(control));
  EXPECT_EQ(c.status, 2);
  EXPECT_NE(c.err.find("camera.a\\x00\\x1b[31m: unknown key"), std::string::npos) << c.err;
  EXPECT_EQ(c.err.find('\x1b'), std::string::npos);
}

TEST_F(CliTest, NonFiniteRendersAreErrorsAndWriteNothing) {
  const fs::path scene = write_scene(kScene);
  const CommandResult r = render(scene, "--set render.exposure=1e308");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("non-finite values"), std::string::npos) << r.err;
  expect_nothing_written();
}

TEST_F(CliTest, DashWritesThePngToStandardOutput) {
  const fs::path scene = write_scene(kScene);
  const CommandResult r = run_lightcone("render " + quoted(scene) + " -o - --quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  ASSERT_GT(r.out.size(), 8u);
  EXPECT_EQ(r.out.substr(1, 3), "PNG");
  test::write_text(out_ / "stdout.png", r.out);
  const auto image = load_image_file(out_ / "stdout.png");
  EXPECT_EQ(image->width, 64);
  EXPECT_NEAR(pixel(*image, 32, 24).g, 1.0, 1e-6);
}

TEST_F(CliTest, VersionNamesTheVersionAndCommit) {
  const CommandResult r = run_lightcone("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("lightcone 0.", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("(commit "), std::string::npos) << r.out;
}

TEST_F(CliTest, CropIsTheSameRegionOfTheFullRenderPixelForPixel) {
  const fs::path scene = write_scene(kMovingScene);
  ASSERT_EQ(render(scene, "--quiet").status, 0);
  const auto full = read_exr();
  const fs::path crop = out_ / "crop.exr";
  const CommandResult r =
      run_lightcone("render " + quoted(scene) + " -o " + quoted(crop) + " --crop 13,7,45,30");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto part = load_image_file(crop);
  ASSERT_EQ(part->width, 32);
  ASSERT_EQ(part->height, 23);
  int differing = 0;
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 32; ++x) {
      const Rgb a = pixel(*part, x, y), b = pixel(*full, x + 13, y + 7);
      differing += a.r != b.r || a.g != b.g || a.b != b.b;
    }
  EXPECT_EQ(differing, 0);
}

TEST_F(CliTest, SeedsChangeTheSamplePatternDeterministically) {
  const fs::path scene = write_scene(kMovingScene);
  const auto run = [&](const std::string& seed) {
    EXPECT_EQ(render(scene, "--quiet " + seed).status, 0);
    return read_exr()->rgb;
  };
  const auto a = run(""), b = run("--seed 0"), c = run("--seed 7"), d = run("--seed 7");
  EXPECT_EQ(a, b);  // 0 is the default
  EXPECT_EQ(c, d);
  EXPECT_NE(a, c);
}

// A seed that is not a whole number from 0 to 2^64 - 1 is refused, saying what a seed is, for
// render and animate alike; no file is written.
TEST_F(CliTest, SeedsOutsideTheirRangeAreRefusedWithTheRange) {
  const fs::path scene = write_scene(kScene);
  for (const char* seed : {"''", "abc", "-1", "18446744073709551616", "1.5", "' 7'"}) {
    SCOPED_TRACE(seed);
    expect_rejected(render(scene, std::string("--seed ") + seed),
                    "--seed: ", {"a seed is a whole number from 0 to 18446744073709551615"});
    EXPECT_FALSE(fs::exists(png()));
    const CommandResult animated =
        run_lightcone("animate " + quoted(scene) + " -o " + quoted(dir_ / "f-%d.png") +
                      " --frames 0-0 --seed " + seed);
    expect_rejected(animated, "--seed: ", {"whole number from 0 to 18446744073709551615"});
  }
  EXPECT_EQ(render(scene, "--quiet --seed 18446744073709551615").status, 0);
}

TEST_F(CliTest, PreviewIsAQuarterSizeOneSampleTheScenesExposure) {
  const fs::path scene = write_scene(kMovingScene);
  const CommandResult r = render(scene, "--preview --stats --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto preview = read_png();
  EXPECT_EQ(preview->width, 16);
  EXPECT_EQ(preview->height, 12);
  EXPECT_EQ(nlohmann::json::parse(r.err).at("rays").get<int>(), 16 * 12);
  // The same picture as a quarter-size render with one sample: the scene's exposure, not auto.
  ASSERT_EQ(render(scene, "--scale 0.25 --samples 1 --quiet").status, 0);
  EXPECT_EQ(test::fraction_differing(*preview, *read_png()), 0.0);
}

// --width and --height keep the scene's field both ways: a narrower picture keeps the
// horizontal field (two balls 40 degrees either side stay in view, where the vertical field
// alone would have lost them), a wider one the vertical field; stderr says which.
TEST_F(CliTest, ASizeOfAnotherAspectKeepsTheScenesField) {
  const fs::path scene = write_scene(R"({
  "camera": {"position": [0, 0, 0], "fov": 40, "width": 96, "height": 36},
  "objects": [
    {"name": "left", "shape": {"sphere": {"radius": 0.2}}, "position": [-6.4279, 0, -7.6604],
     "material": {"color": [1, 1, 1]}},
    {"name": "right", "shape": {"sphere": {"radius": 0.2}}, "position": [6.4279, 0, -7.6604],
     "material": {"color": [1, 1, 1]}}],
  "render": {"exposure": 0}
})");
  // The brightest column of a picture's left or right half.
  const auto brightest_column = [&](bool right) {
    const auto image = read_exr();
    int best = -1;
    float most = 0;
    for (int x = right ? image->width / 2 : 0; x < (right ? image->width : image->width / 2); ++x)
      for (int y = 0; y < image->height; ++y)
        if (const float v = image->rgb[3 * (y * image->width + x) + 1]; v > most) {
          most = v;
          best = x;
        }
    return best;
  };
  // tan 40 over the scene's horizontal half-tangent, tan 20 * 96 / 36, of the half-width.
  const double from_centre =
      std::tan(40 * std::numbers::pi / 180) / (std::tan(20 * std::numbers::pi / 180) * 96 / 36);
  CommandResult r = render(scene, "--width 48 --height 27");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("48x27 is narrower than the scene: its horizontal field of 88.29 degrees "
                       "is kept, the vertical one widens from 40 to 57.27"),
            std::string::npos)
      << r.err;
  EXPECT_NEAR(brightest_column(true), 24 + 24 * from_centre - 0.5, 1.0);
  EXPECT_NEAR(brightest_column(false), 24 - 24 * from_centre - 0.5, 1.0);
  r = render(scene, "--width 200");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("200x36 is wider than the scene: its vertical field of 40 degrees is "
                       "kept, the horizontal one widens from 88.29 to 127.4"),
            std::string::npos)
      << r.err;
  const double wider = from_centre * 96 / 200;  // the same vertical field, 200 / 36 wide
  EXPECT_NEAR(brightest_column(true), 100 + 100 * wider - 0.5, 1.0);
  // At the scene's aspect nothing is said.
  r = render(scene, "--width 192 --height 72");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("field"), std::string::npos) << r.err;
}

// --scale keeps the picture: half the size, with four times the samples, is the full-size
// render averaged over 2x2 blocks, within the sampling noise of the checker's edges.
TEST_F(CliTest, ScaleKeepsThePicture) {
  const fs::path scene = write_scene(kMovingScene);
  ASSERT_EQ(render(scene, "--width 128 --height 96 --samples 4 --quiet").status, 0);
  const auto full = load_image_file(exr());
  ASSERT_EQ(render(scene, "--width 128 --height 96 --scale 0.5 --samples 16 --quiet").status, 0);
  const auto half = load_image_file(exr());
  ASSERT_EQ(half->width, 64);
  ASSERT_EQ(half->height, 48);
  // The mean difference from the blocks `shift` full-size pixels to the right, over their mean.
  const auto difference = [&](int shift) {
    double sum = 0, level = 0;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 63; ++x)
        for (int c = 0; c < 3; ++c) {
          double block = 0;
          for (int k = 0; k < 4; ++k)
            block += full->rgb[3 * ((2 * y + k / 2) * 128 + 2 * x + shift + k % 2) + c] / 4;
          sum += std::abs(half->rgb[3 * (y * 64 + x) + c] - block);
          level += block;
        }
    return sum / level;
  };
  std::printf("--scale 0.5 against 2x2 blocks: %.4f; one pixel over: %.4f\n", difference(0),
              difference(1));
  EXPECT_LT(difference(0), 0.05);
  EXPECT_GT(difference(1), 2 * difference(0));  // the comparison sees a picture moved
  fs::remove(png());
  fs::remove(exr());
  expect_rejected(render(scene, "--scale 0"), "--scale 0: ", {"must be above 0"});
}

TEST_F(CliTest, CheckValidatesWithoutRendering) {
  const fs::path good = write_scene(kScene);
  const CommandResult ok = run_lightcone("check " + quoted(good));
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_NE(ok.out.find(": ok"), std::string::npos) << ok.out;
  const fs::path bad = write_scene(edited(kScene, "\"fov\": 30", "\"fov\": -30"), "bad.json");
  const CommandResult no = run_lightcone("check " + quoted(bad));
  EXPECT_EQ(no.status, 2);
  EXPECT_NE(no.err.find("bad.json:"), std::string::npos) << no.err;
  EXPECT_NE(no.err.find("camera.fov"), std::string::npos) << no.err;
  EXPECT_EQ(std::distance(fs::directory_iterator(out_), fs::directory_iterator()), 0);
}

TEST_F(CliTest, InfoJsonReportsSpeedsGammaDopplerAndTimeWindow) {
  const fs::path scene = write_scene(edited(kScene, "\"velocity\": [0, 0, 0],\n    \"fov\"",
                                            "\"velocity\": [0, 0, -0.6],\n    \"fov\""));
  const CommandResult r = run_lightcone("info " + quoted(scene) + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out);
  EXPECT_EQ(info.at("image").at("width").get<int>(), 64);
  const auto& camera = info.at("bodies").at(0);
  EXPECT_EQ(camera.at("kind"), "camera");
  EXPECT_NEAR(camera.at("speed").get<double>(), 0.6, 1e-12);
  EXPECT_NEAR(camera.at("gamma").get<double>(), 1.25, 1e-12);
  // Flying at 0.6c toward a ball and sky at rest: D = 1 / (gamma (1 - beta cos theta)), theta
  // the camera-frame angle from straight ahead: 2 there, 1.769 at the corners (24.1 degrees).
  EXPECT_NEAR(info.at("doppler").at(1).get<double>(), 2.0, 1e-6);
  EXPECT_NEAR(info.at("doppler").at(0).get<double>(), 1.769, 0.002);
  // Straight ahead the ball's near point, 8 away and at rest in W, sent its light at t = -8;
  // points toward its rim sent it earlier.
  EXPECT_NEAR(info.at("emission_time").at(1).get<double>(), -8.0, 0.05);
  EXPECT_LT(info.at("emission_time").at(0).get<double>(), -8.0);
  EXPECT_GT(info.at("memory_bytes").get<double>(), 64 * 48 * 12);
  const CommandResult text = run_lightcone("info " + quoted(scene));
  EXPECT_EQ(text.status, 0);
  EXPECT_NE(text.out.find("gamma 1.25"), std::string::npos) << text.out;
}

// The stars a scene draws: how many, from which catalogue, to which magnitude.
TEST_F(CliTest, InfoCountsTheStars) {
  const CommandResult r =
      run_lightcone("info " + quoted(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes/stars.json") +
                    " --json --set sky.stars.magnitude_limit=3");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto stars = nlohmann::json::parse(r.out).at("stars");
  EXPECT_EQ(stars.at("catalogue"), "bright");
  EXPECT_EQ(stars.at("magnitude_limit").get<double>(), 3);
  // The Bright Star Catalogue has some 170 stars brighter than V = 3.
  EXPECT_GT(stars.at("count").get<int>(), 150);
  EXPECT_LT(stars.at("count").get<int>(), 190);
}

TEST_F(CliTest, LocateBehindTheCameraHasNoPixel) {
  const fs::path scene = write_scene(kScene);
  const auto behind = locate_output(locate(scene, "--world-point 0,0,10"));
  EXPECT_TRUE(behind["pixel"].is_null());
  EXPECT_FALSE(behind["in_view"].get<bool>());
  const auto aside = locate_output(locate(scene, "--world-point 100,0,-10"));
  EXPECT_TRUE(aside["pixel"].is_null());
}

TEST_F(CliTest, AStoppedRenderWritesItsTilesBesideAnUntouchedTarget) {
  // A render that takes seconds, stopped after a moment by Ctrl-C, `timeout`/`scancel`
  // (SIGTERM) or a closed terminal (SIGHUP): the tiles finished go to out.partial.png and
  // .partial.exr, the finished image already there is untouched, and the status is the
  // shell's for that signal.
  const fs::path scene = write_scene(edited(kMovingScene, "\"samples\": 4", "\"samples\": 4096"));
  for (const auto& [signal, status_expected] :
       {std::pair{"INT", 130}, std::pair{"TERM", 143}, std::pair{"HUP", 129}}) {
    test::write_text(png(), "a finished image");
    const fs::path exr = this->exr();
    fs::remove(exr);
    const std::string command = std::string("'") + LIGHTCONE_BINARY + "' render " + quoted(scene) +
                                " -o " + quoted(png()) + " --exr " + quoted(exr) +
                                " --threads 1 2>" + quoted(out_ / "err.txt") +
                                " & pid=$!; sleep 1; kill -" + signal +
                                " $pid; wait $pid; echo $? > " + quoted(out_ / "status.txt");
    test::write_text(dir_ / "interrupt.sh", command + "\n");
    ASSERT_EQ(std::system(("bash " + quoted(dir_ / "interrupt.sh")).c_str()), 0);
    std::ifstream status_file(out_ / "status.txt");
    int status = -1;
    status_file >> status;
    EXPECT_EQ(status, status_expected) << signal;
    std::ifstream err_file(out_ / "err.txt");
    const std::string err((std::istreambuf_iterator<char>(err_file)), {});
    EXPECT_NE(err.find(std::string("stopped by SIG") + signal + " with "), std::string::npos)
        << err;
    EXPECT_NE(err.find(" tiles done: wrote them to "), std::string::npos) << err;
    std::ifstream target(png());
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(target)), {}), "a finished image");
    EXPECT_FALSE(fs::exists(exr)) << signal;
    const auto image = load_image_file(out_ / "image.partial.png");  // a PNG that decodes
    EXPECT_EQ(image->width, 64);
    EXPECT_EQ(load_image_file(out_ / "image.partial.exr")->width, 64);
    for (const fs::directory_entry& e : fs::directory_iterator(out_))
      EXPECT_EQ(e.path().filename().string().find(".lightcone-"), std::string::npos)
          << "a temporary file left: " << e.path();
  }
}

TEST_F(CliTest, AovChannelsGoIntoTheExrByName) {
  const fs::path scene = write_scene(kScene);
  const CommandResult r =
      render(scene, "--quiet --aov doppler,emission_time,distance,object,depth,normal");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto image = read_exr();
  std::vector<std::string> names;
  for (const NamedChannel& c : image->channels) names.push_back(c.name);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"depth", "distance", "doppler", "emission_time",
                                             "normal.X", "normal.Y", "normal.Z", "object"}));
  // The ball at rest 10 ahead, radius 2: its near point is 8 away and sent its light at t = -8.
  for (const NamedChannel& c : image->channels) {
    const float centre = c.values[24 * 64 + 32];
    if (c.name == "distance") {
      EXPECT_NEAR(centre, 8.0, 5e-3);
    }  // half a pixel off the axis
    if (c.name == "emission_time") {
      EXPECT_NEAR(centre, -8.0, 5e-3);
    }
    if (c.name == "doppler") {
      EXPECT_EQ(centre, 1.0f);
    }
    if (c.name == "object") {
      EXPECT_EQ(centre, 0.0f);
    }
    if (c.name == "object") {
      EXPECT_EQ(c.values[0], -1.0f);
    }  // the sky in the corner
  }
}

TEST_F(CliTest, MapWritesAColourMappedPictureWithAScaleBar) {
  const fs::path scene = write_scene(edited(kScene, "\"velocity\": [0, 0, 0],\n    \"fov\"",
                                            "\"velocity\": [0, 0, -0.6],\n    \"fov\""));
  const CommandResult r = render(scene, "--quiet --map doppler");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto picture = read_png();
  EXPECT_EQ(picture->width, 64);
  EXPECT_EQ(picture->height, 48);     // the render's size, the legend inside
  const auto exr_image = read_exr();  // the EXR keeps the render and the mapped channel
  ASSERT_EQ(exr_image->channels.size(), 1u);
  EXPECT_EQ(exr_image->channels[0].name, "doppler");
  EXPECT_NEAR(exr_image->channels[0].values[24 * 64 + 32], 2.0, 1e-3);
}

}  // namespace
}  // namespace lightcone

// The `lightcone` command through the real binary, given bad input: bad scene values, syntax
// errors, missing files, bad overrides and sizes, broken meshes and images, bad command lines
// (exit status 2, one message that names the file, line and JSON path, nothing written); and
// --help.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <fstream>
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
  const CommandResult r =
      test::run_command(quoted(program) + " render " + quoted(scene) + " -o " + quoted(png()));
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
  EXPECT_EQ(image->texel(0, 0).g, 1.0f);
  EXPECT_EQ(image->texel(0, 0).b, 0.0f);
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

}  // namespace
}  // namespace lightcone

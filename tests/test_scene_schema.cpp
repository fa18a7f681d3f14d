// The scene format's documentation and schema against the loader (the documented examples load;
// the schema is closed and names the loader's keys), and the JSON line locator on its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "lightcone/io/json_locator.hpp"
#include "lightcone/io/scene_file.hpp"
#include "support/scene_file_test.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using namespace test;  // the scene-file fixture and helpers (support/scene_file_test.hpp)

// ---------------------------------------------------------------------------------------------
// The documentation and the schema

// The lit example in the section on lights is a whole scene, and loads.
TEST_F(SceneFileTest, DocumentedLightsExampleLoads) {
  const Scene s = load(documented_example("## `lights[]`"));
  EXPECT_EQ(s.lights.size(), 4u);
  EXPECT_FALSE(s.objects.at(0).material.unlit);
}

TEST_F(SceneFileTest, DocumentedExampleLoads) {
  const Scene s = load(documented_example());
  EXPECT_EQ(s.objects.size(), 3u);
  expect_vec(s.camera.world_line.velocity, {0, 0, -0.6});
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

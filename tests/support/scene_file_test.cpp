#include "support/scene_file_test.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"

namespace lightcone::test {

std::string read_source_file(const std::string& relative) {
  return bytes_of(std::filesystem::path(LIGHTCONE_SOURCE_DIR) / relative);
}

std::string documented_example(const std::string& heading) {
  const std::string doc = read_source_file("docs/scene-format.md");
  const std::size_t section = heading.empty() ? 0 : doc.find(heading);
  const std::size_t start =
      section == std::string::npos ? section : doc.find("```jsonc\n", section);
  EXPECT_NE(start, std::string::npos) << "no example under '" << heading << "'";
  if (start == std::string::npos) return "";
  const std::size_t end = doc.find("```", start + 9);
  return doc.substr(start + 9, end - start - 9);
}

std::vector<std::string> keys_of(const nlohmann::json& object) {
  std::vector<std::string> keys;
  for (const auto& item : object.items()) keys.push_back(item.key());
  std::sort(keys.begin(), keys.end());
  return keys;
}

std::string with_object(const std::string& object) {
  return "{\n  \"camera\": {\"position\": [0, 0, 5]},\n  \"objects\": [" + object + "]\n}";
}

void expect_rgb(const Rgb& c, float r, float g, float b) {
  EXPECT_FLOAT_EQ(c.r, r);
  EXPECT_FLOAT_EQ(c.g, g);
  EXPECT_FLOAT_EQ(c.b, b);
}

void SceneFileTest::write_two_texel_png(const std::string& name, std::vector<float> rgb) const {
  Image image;
  image.width = 2;
  image.height = 1;
  image.rgb = std::move(rgb);
  write_images(image, dir_ / name, std::nullopt);
}

Scene SceneFileTest::load(const std::string& text, const std::vector<std::string>& overrides) {
  report_ = {};
  return load_scene_file(write("scene.json", text), overrides, report_);
}

std::string SceneFileTest::error(const std::string& text,
                                 const std::vector<std::string>& overrides) {
  try {
    load(text, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void SceneFileTest::expect_error(const std::string& text, int line, const std::string& path,
                                 const std::string& fragment) {
  const std::string message = error(text);
  const std::string prefix = fmt::format("{}:{}: {}: ", (dir_ / "scene.json").string(), line, path);
  EXPECT_EQ(message.substr(0, prefix.size()), prefix) << message;
  EXPECT_NE(message.find(fragment, prefix.size()), std::string::npos) << message;
}

void SceneFileTest::expect_set_error(const std::string& text,
                                     const std::vector<std::string>& overrides,
                                     const std::string& path, const std::string& fragment) {
  const std::string message = error(text, overrides);
  const std::string prefix = "--set " + path + ": ";
  EXPECT_EQ(message.substr(0, prefix.size()), prefix) << message;
  EXPECT_NE(message.find(fragment, prefix.size()), std::string::npos) << message;
}

}  // namespace lightcone::test

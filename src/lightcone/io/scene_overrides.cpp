#include "lightcone/io/scene_overrides.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <string_view>
#include <vector>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/json_locator.hpp"

namespace lightcone {

namespace {

// Values where `true` stands for a table of defaults (docs/scene-format.md): a path through one
// opens it as that table.
constexpr std::string_view kTrueForDefaults[] = {"sky.stars"};

}  // namespace

std::string apply_scene_override(SceneJson& document, const std::string& override_text) {
  const std::size_t equals = override_text.find('=');
  if (equals == std::string::npos)
    throw InputError(fmt::format("--set {}: expected key.path=value", override_text));
  const std::string spec = override_text.substr(0, equals);
  const std::string text = override_text.substr(equals + 1);
  auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("--set {}: {}", spec, what));
  };

  // "objects[0].velocity" is read as "objects.0.velocity".
  std::vector<std::string> parts(1);
  for (const char c : spec) {
    if (c == '.' || c == '[')
      parts.emplace_back();
    else if (c != ']')
      parts.back() += c;
  }
  if (std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
    fail("empty component in the key path");

  SceneJson value = SceneJson::parse(text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) {
    // "0,0,-0.99" is the array [0, 0, -0.99] (as locate's --direction x,y,z); other text that is
    // not JSON is a string.
    SceneJson list = SceneJson::parse("[" + text + "]", nullptr, /*allow_exceptions=*/false);
    const bool numbers =
        !list.is_discarded() && list.size() > 1 &&
        std::all_of(list.begin(), list.end(), [](const SceneJson& v) { return v.is_number(); });
    value = numbers ? std::move(list) : SceneJson(text);
  }

  SceneJson* node = &document;
  std::string path;
  auto where = [&] { return path.empty() ? std::string("the scene") : path; };
  for (const std::string& part : parts) {
    const bool defaults = node->is_boolean() && node->get<bool>() &&
                          std::find(std::begin(kTrueForDefaults), std::end(kTrueForDefaults),
                                    path) != std::end(kTrueForDefaults);
    if (node->is_null() || defaults) *node = SceneJson::object();
    if (node->is_object()) {
      path = json_member_path(path, part);
      node = &(*node)[part];
    } else if (node->is_array()) {
      const bool digits =
          std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; });
      const std::size_t size = node->size();
      if (!digits || part.size() > 9 || std::stoul(part) > size)
        fail(fmt::format("{} is an array of {} elements; \"{}\" is not an index from 0 to {}",
                         where(), size, part, size));
      const std::size_t index = std::stoul(part);
      if (index == size) node->push_back(nullptr);
      path = json_element_path(path, index);
      node = &(*node)[index];
    } else {
      fail(fmt::format("{} is a {}, not an object or array", where(), node->type_name()));
    }
  }
  *node = std::move(value);
  return path;
}

}  // namespace lightcone

#include "lightcone/io/scene_parse.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/input_file.hpp"
#include "lightcone/io/scene_file.hpp"

namespace lightcone {
namespace {

using json = SceneJson;
namespace fs = std::filesystem;

// Builds nlohmann's DOM from the events of its parser, as its own json_sax_dom_parser does, and
// records the position of the first error: parsing through this hook, rather than catching
// json::parse_error, also gives a position to errors that nlohmann throws without one (a number
// too large for a double, 1e400, is an out_of_range error). It also notes whether a key repeats
// within an object, which the DOM hides (it keeps the last one), so that the slower scan that
// names the repeats runs only then.
class DomBuilder {
 public:
  explicit DomBuilder(json& root) : root_(root) {}

  bool null() { return add(nullptr); }
  bool boolean(bool b) { return add(b); }
  bool number_integer(json::number_integer_t i) { return add(i); }
  bool number_unsigned(json::number_unsigned_t u) { return add(u); }
  bool number_float(json::number_float_t d, const std::string& /*text*/) { return add(d); }
  bool string(std::string& s) { return add(std::move(s)); }
  bool binary(json::binary_t& b) { return add(std::move(b)); }

  // Nesting deeper than any scene needs is refused as it is read (each level costs memory
  // and stack in the DOM and the line map).
  bool start_object(std::size_t /*elements*/) { return open(json::value_t::object); }
  bool start_array(std::size_t /*elements*/) { return open(json::value_t::array); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(std::string& k) {
    const auto [it, added] = open_.back()->get_ref<json::object_t&>().try_emplace(std::move(k));
    repeated_key |= !added;
    member_ = &it->second;
    return true;
  }

  template <class Exception>
  bool parse_error(std::size_t byte, const std::string& /*token*/, const Exception& e) {
    error_byte = byte;
    // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error while
    // parsing ...": the line is reported our way, so keep only the description.
    error = e.what();
    if (const std::size_t tag = error.find("] "); tag != std::string::npos) error.erase(0, tag + 2);
    if (error.rfind("parse error", 0) == 0) error.erase(0, error.find(": ") + 2);
    return false;
  }

  std::size_t error_byte = 0;  // 1-based offset of the last character read
  std::string error;
  bool repeated_key = false;

 private:
  // Places a value: the root, the next element of the open array, or the member just keyed.
  template <class Value>
  json* place(Value&& v) {
    if (open_.empty()) {
      root_ = json(std::forward<Value>(v));
      return &root_;
    }
    if (json& parent = *open_.back(); parent.is_array()) {
      auto& array = parent.get_ref<json::array_t&>();
      array.emplace_back(std::forward<Value>(v));
      return &array.back();
    }
    *member_ = json(std::forward<Value>(v));
    return member_;
  }
  template <class Value>
  bool add(Value&& v) {
    place(std::forward<Value>(v));
    return true;
  }
  bool open(json::value_t type) {
    if (open_.size() >= kMaxSceneNesting) {
      error = fmt::format("nested more than {} levels deep", kMaxSceneNesting);
      return false;
    }
    json* value = place(type);
    // Most arrays of a scene are vectors and colours: room for 3 at once, not for 1, 2 and 4 in
    // turn (the arena keeps what a vector outgrows).
    if (type == json::value_t::array) value->get_ref<json::array_t&>().reserve(3);
    open_.push_back(value);
    return true;
  }
  bool close() {
    open_.pop_back();
    return true;
  }

  json& root_;
  std::vector<json*> open_;  // the arrays and objects being read, innermost last
  json* member_ = nullptr;   // the value of the key just read
};

// A '}' or ']' just after a comma (whitespace between): JSON has no trailing commas, and the
// parser's own words for it ("unexpected '}'; expected string literal") do not say so.
std::optional<std::string> trailing_comma(const std::string& text, std::size_t at) {
  if (at >= text.size() || (text[at] != '}' && text[at] != ']')) return std::nullopt;
  std::size_t k = at;
  while (k > 0 && std::isspace(static_cast<unsigned char>(text[k - 1]))) --k;
  if (k == 0 || text[k - 1] != ',') return std::nullopt;
  return fmt::format("a comma after the last {}, before '{}' (JSON allows none there)",
                     text[at] == '}' ? "member" : "element", text[at]);
}

}  // namespace

std::string read_scene_text(const fs::path& file) {
  std::string text = read_input_file(file, "scene file", kMaxSceneFileBytes);
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos)
    throw InputError(fmt::format("{}:{}: (syntax): a NUL byte: this is not a text file",
                                 file.string(),
                                 1 + std::count(text.begin(), text.begin() + nul, '\n')));
  return text;
}

json parse_scene_document(const fs::path& file, const std::string& text, bool& repeated_key,
                          bool line_numbers) {
  json document;
  DomBuilder builder(document);
  if (json::sax_parse(text, &builder, json::input_format_t::json, /*strict=*/true,
                      /*ignore_comments=*/true)) {
    repeated_key = builder.repeated_key;
    return document;
  }
  const std::size_t end =
      std::min(builder.error_byte > 0 ? builder.error_byte - 1 : 0, text.size());
  const std::string what = trailing_comma(text, end).value_or(builder.error);
  if (!line_numbers) throw InputError(fmt::format("{}: (syntax): {}", file.string(), what));
  const auto line = 1 + std::count(text.begin(), text.begin() + end, '\n');
  throw InputError(fmt::format("{}:{}: (syntax): {}", file.string(), line, what));
}

}  // namespace lightcone

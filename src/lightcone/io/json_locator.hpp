// Line numbers for the values of a JSON text. nlohmann::json keeps no source positions, so the
// text is scanned once more, and only when asked: for repeated keys, or for lines (which only
// messages want). For every object member, the line where its key and its value start is
// remembered under its readable path: `camera.velocity`, `objects[2].shape.sphere.radius`; the
// root is "". Array elements are kept as runs of elements per line of their array, so that memory
// follows the keys and lines, not the elements.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace lightcone {

// The readable path of an object member or an array element. Shared by the locator and its users
// so that the paths they build always agree.
std::string json_member_path(const std::string& parent, std::string_view key);
std::string json_element_path(const std::string& parent, std::size_t index);

class JsonLineMap {
 public:
  struct DuplicateKey {
    std::string path;
    int line = 0;
  };

  // `text` must be a JSON document that nlohmann::json accepted (comments allowed); it is kept.
  explicit JsonLineMap(std::string text) : text_(std::move(text)) {}

  // 1-based line where the value at `path` starts. A path that is not in the text (a missing
  // key) gets the line of its nearest ancestor that is.
  int value_line(const std::string& path) const;
  // Line of the key of the member at `path`; the value's line for array elements and the root.
  int key_line(const std::string& path) const;
  // Keys repeated within one object (every occurrence after the first), in text order.
  // nlohmann::json silently keeps the last one, which hides typos, so callers reject them.
  // Scanned for on the first call (not thread-safe).
  const std::vector<DuplicateKey>& duplicate_keys() const;

  // What the map holds: one path per object member (and the root), one run per line of an array
  // that spans lines.
  std::size_t recorded_paths() const {
    build();
    return lines_.size();
  }
  std::size_t recorded_runs() const;

 private:
  friend class JsonScanner;

 public:
  struct Lines {
    int key = 1, value = 1;
  };
  // Elements from `first_index` on (up to the next run) start on `line`.
  struct ElementRun {
    std::size_t first_index = 0;
    int line = 1;
  };

 private:
  Lines find(std::string path) const;
  // Scans the text for the lines, once (a cache filled by the first question; not thread-safe).
  void build() const;

  std::string text_;
  mutable bool built_ = false;
  // Lines of the root and of every object member, by path.
  mutable std::unordered_map<std::string, Lines> lines_;
  // Lines of the elements of every array that spans lines, by the array's path.
  mutable std::unordered_map<std::string, std::vector<ElementRun>> element_runs_;
  mutable bool duplicates_found_ = false;
  mutable std::vector<DuplicateKey> duplicates_;
};

}  // namespace lightcone

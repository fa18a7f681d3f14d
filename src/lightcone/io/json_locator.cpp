#include "lightcone/io/json_locator.hpp"

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <nlohmann/json.hpp>

namespace lightcone {

std::string json_member_path(const std::string& parent, std::string_view key) {
  // Control characters in a key (a NUL, an escape sequence) are shown, not passed on.
  std::string shown;
  for (const char ch : key) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) {
      static constexpr char kHex[] = "0123456789abcdef";
      shown += "\\x";
      shown += kHex[c >> 4];
      shown += kHex[c & 15];
    } else {
      shown += ch;
    }
  }
  return parent.empty() ? shown : parent + "." + shown;
}

std::string json_element_path(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

// A recursive-descent walk over text that is already known to be valid JSON, so it checks
// nothing and only keeps track of lines and paths.
class JsonScanner {
 public:
  // Records lines into `lines` and `runs`, or (when they are null) only finds repeated keys
  // into `duplicates`.
  JsonScanner(std::string_view text, std::unordered_map<std::string, JsonLineMap::Lines>* lines,
              std::unordered_map<std::string, std::vector<JsonLineMap::ElementRun>>* runs,
              std::vector<JsonLineMap::DuplicateKey>* duplicates)
      : s_(text), lines_(lines), runs_(runs), duplicates_(duplicates) {}

  void run() {
    if (s_.substr(0, 3) == "\xEF\xBB\xBF") i_ = 3;  // nlohmann skips a UTF-8 byte order mark
    value(Path{}, 0, 0, true);
  }

 private:
  // Nothing the scene format reads is nested this deep. Deeper values are skipped without being
  // recorded so that a hostile file cannot exhaust the stack or fill memory with long paths.
  static constexpr int kMaxDepth = 32;

  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  void advance() {
    if (i_ >= s_.size()) return;
    if (s_[i_] == '\n') ++line_;
    ++i_;
  }

  // Whitespace and both comment styles that nlohmann accepts with ignore_comments.
  void skip_space() {
    while (i_ < s_.size()) {
      const char c = s_[i_], next = i_ + 1 < s_.size() ? s_[i_ + 1] : '\0';
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
        advance();
      } else if (c == '/' && next == '/') {
        while (i_ < s_.size() && s_[i_] != '\n') advance();
      } else if (c == '/' && next == '*') {
        advance(), advance();
        while (i_ < s_.size() && !(s_[i_] == '*' && peek_at(1) == '/')) advance();
        advance(), advance();
      } else {
        return;
      }
    }
  }
  char peek_at(std::size_t k) const { return i_ + k < s_.size() ? s_[i_ + k] : '\0'; }

  // Returns the raw token, quotes and escapes included.
  std::string_view string_token() {
    const std::size_t start = i_;
    advance();
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\\') advance();
      advance();
    }
    advance();
    return s_.substr(start, i_ - start);
  }

  static std::string decode_key(std::string_view token) {
    if (token.find('\\') == std::string_view::npos)
      return std::string(token.substr(1, token.size() - 2));
    // The parser knows every escape; a token it does not take (the scanner is simpler than the
    // parser, and may read text the parser skipped) is recorded as written.
    const nlohmann::json key = nlohmann::json::parse(std::string(token), nullptr, false);
    if (key.is_string()) return key.get<std::string>();
    return std::string(token.size() >= 2 ? token.substr(1, token.size() - 2) : token);
  }

  // Where a value is: its parent's place and its key (a member's raw token) or index. Spelled
  // out only when a path is wanted, so that finding repeated keys builds no strings.
  struct Path {
    const Path* parent = nullptr;
    std::string_view key;  // the raw token, quotes included; empty for an element or the root
    std::size_t index = 0;
    bool element = false;

    std::string spelled() const {
      if (!parent) return "";
      const std::string up = parent->spelled();
      return element ? json_element_path(up, index) : json_member_path(up, decode_key(key));
    }
  };

  // Two raw key tokens that name the same key.
  static bool same_key(std::string_view a, std::string_view b) {
    if (a.find('\\') == std::string_view::npos && b.find('\\') == std::string_view::npos)
      return a == b;
    return decode_key(a) == decode_key(b);
  }

  // Scans the value at `path`; `record` says whether it is an object member or the root (an
  // array element's line is kept in its array's runs instead, so that memory grows with the keys
  // and the lines of the text, not with the elements).
  void value(const Path& path, int key_line, int depth, bool record) {
    skip_space();
    if (record && lines_) (*lines_)[path.spelled()] = {key_line > 0 ? key_line : line_, line_};
    const char c = peek();
    if (depth >= kMaxDepth && (c == '{' || c == '[')) return skip_values(0);
    if (c == '{') {
      advance();
      std::vector<std::string_view> seen;  // the members' raw keys (objects are small)
      for (skip_space(); peek() == '"'; skip_space()) {
        const int line = line_;
        const std::string_view token = string_token();
        const Path member{&path, token};
        if (duplicates_ && std::any_of(seen.begin(), seen.end(),
                                       [&](std::string_view k) { return same_key(k, token); }))
          duplicates_->push_back({member.spelled(), line});
        seen.push_back(token);
        skip_space();
        advance();  // ':'
        value(member, line, depth + 1, true);
        skip_space();
        if (peek() == ',') advance();
      }
      advance();  // '}'
    } else if (c == '[') {
      const int array_line = line_;
      advance();
      skip_space();
      std::vector<JsonLineMap::ElementRun> runs;
      for (std::size_t index = 0; peek() != ']' && i_ < s_.size(); ++index) {
        const std::size_t before = i_;
        if (runs_ && (runs.empty() ? line_ != array_line : line_ != runs.back().line))
          runs.push_back({index, line_});
        value(Path{&path, {}, index, true}, 0, depth + 1, false);
        skip_space();
        if (peek() == ',') advance();
        skip_space();
        // Text the scanner does not understand (the parser accepted it, the scanner is simpler)
        // must not make it loop: stop recording this array.
        if (i_ == before) {
          skip_values(1);
          break;
        }
      }
      if (i_ < s_.size() && peek() == ']') advance();
      // An array on one line needs no runs: its elements share its line.
      if (!runs.empty()) {
        if (runs.front().first_index != 0) runs.insert(runs.begin(), {0, array_line});
        runs.shrink_to_fit();
        (*runs_)[path.spelled()] = std::move(runs);
      }
    } else if (c == '"') {
      string_token();
    } else {  // number, true, false, null
      while (i_ < s_.size() &&
             std::string_view(" \t\r\n,]}/").find(s_[i_]) == std::string_view::npos)
        advance();
    }
  }

  // Skips values until `open` more brackets have closed than opened: skip_values(0) at a '{'
  // or '[' skips that object or array, skip_values(1) inside an array moves past its ']'.
  // Iterative, so no nesting can exhaust the stack.
  void skip_values(int open) {
    do {
      skip_space();
      const char c = peek();
      if (c == '"') {
        string_token();
        continue;
      }
      if (c == '{' || c == '[') ++open;
      if (c == '}' || c == ']') --open;
      advance();
    } while (open > 0 && i_ < s_.size());
  }

  std::string_view s_;
  std::unordered_map<std::string, JsonLineMap::Lines>* lines_;
  std::unordered_map<std::string, std::vector<JsonLineMap::ElementRun>>* runs_;
  std::vector<JsonLineMap::DuplicateKey>* duplicates_;
  std::size_t i_ = 0;
  int line_ = 1;
};

const std::vector<JsonLineMap::DuplicateKey>& JsonLineMap::duplicate_keys() const {
  if (!duplicates_found_) JsonScanner(text_, nullptr, nullptr, &duplicates_).run();
  duplicates_found_ = true;
  return duplicates_;
}

void JsonLineMap::build() const {
  if (built_) return;
  JsonScanner(text_, &lines_, &element_runs_, nullptr).run();
  built_ = true;
}

JsonLineMap::Lines JsonLineMap::find(std::string path) const {
  build();
  for (;;) {
    if (auto it = lines_.find(path); it != lines_.end()) return it->second;
    if (path.empty()) return {};
    // Drop the last component: "[i]" or ".key" (or the whole path when it has a single key).
    const bool element = path.back() == ']';
    const std::size_t cut = element ? path.rfind('[') : path.rfind('.');
    if (element && cut != std::string::npos) {
      // An element: its line is in its array's runs (the last run starting at or before it).
      const std::string array = path.substr(0, cut);
      if (auto it = element_runs_.find(array); it != element_runs_.end()) {
        const std::size_t index = std::strtoull(path.c_str() + cut + 1, nullptr, 10);
        const auto run =
            std::upper_bound(it->second.begin(), it->second.end(), index,
                             [](std::size_t i, const ElementRun& r) { return i < r.first_index; });
        const int line = std::prev(run)->line;
        return {line, line};
      }
    }
    path.resize(cut == std::string::npos ? 0 : cut);
  }
}

std::size_t JsonLineMap::recorded_runs() const {
  build();
  std::size_t runs = 0;
  for (const auto& [path, array_runs] : element_runs_) runs += array_runs.size();
  return runs;
}

int JsonLineMap::value_line(const std::string& path) const {
  return find(path).value;
}

int JsonLineMap::key_line(const std::string& path) const {
  // A key that is not in the text has no key line of its own; its parent's value line is nearer
  // than the parent's key.
  build();
  if (auto it = lines_.find(path); it != lines_.end()) return it->second.key;
  return find(path).value;
}

}  // namespace lightcone

// The typed values of a scene document, inside src/lightcone/io: where a value is (Node), the
// checks of each type (in the scene's units, within the one speed limit), and the messages that
// name the value's path and line, or blame the --set override it came from. SceneReader reads
// the document's sections with these.
#pragma once

#include <fmt/format.h>

#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lightcone/io/json_locator.hpp"
#include "lightcone/io/scene_document.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone::scene_io {

using json = SceneJson;

// A value in the document and where it is: its parent and its key or index. The readable path
// is spelled out only for a message, so that reading a valid file builds no path strings. `value`
// is null when the key is absent, so optional keys keep the scene model's defaults (which are the
// format's defaults). A node refers to its parent and its key: both must outlive it.
struct Node {
  const json* value;
  const Node* parent = nullptr;  // null for the root
  std::string_view key = {};     // of a member
  std::size_t index = 0;         // of an element
  bool element = false;

  std::string path() const {
    if (!parent) return "";
    const std::string up = parent->path();
    return element ? json_element_path(up, index) : json_member_path(up, key);
  }
};

Node member(const Node& object, std::string_view key);
Node element(const Node& array, std::size_t index);

// A value as a message shows it: its type, and its text cut to 40 characters.
std::string describe(const json& v);

// Key names, from a braced list or a vector, without copying them.
struct Names : std::span<const std::string_view> {
  using span::span;
  Names(std::initializer_list<std::string_view> names) : span(names.begin(), names.size()) {}
};

// "a, b, c": the names in `words`, then those in `more`.
std::string join(Names words, Names more = {});

// Reads and checks single values; every failure is an InputError "FILE:LINE: PATH: what is
// wrong" (or "--set PATH: what is wrong"; without `line_numbers`, "FILE: PATH: what is wrong").
class SceneValueReader {
 protected:
  // Relative paths are read from `folder`, or where none is given from `file`'s folder.
  SceneValueReader(const std::filesystem::path& file, const JsonLineMap& lines,
                   std::vector<std::string> overridden, bool line_numbers = true,
                   std::optional<std::filesystem::path> folder = std::nullopt)
      : lines_(lines),
        file_(file),
        overridden_(std::move(overridden)),
        line_numbers_(line_numbers),
        folder_(folder ? std::move(*folder) : file.parent_path()) {}

  // The one speed limit: every speed a body can reach (the camera, objects, lights, the sky, a
  // spinning body's points), in W and relative to the camera, has gamma at most this; beyond
  // it double precision cannot hold the physics (1 - v is below 5e-13).

  // An observer a speed is checked against; `relative` is how a message names it.
  struct Observer {
    Vec4 four_velocity;
    std::string relative;
  };

  // --- Messages ---------------------------------------------------------------------------

  [[noreturn]] void fail_at(const std::string& path, int line, const std::string& what) const;
  [[noreturn]] void fail(const Node& n, const std::string& what) const;

  // The one wording of the speed limit: "SUBJECT[ relative to the camera] is too close to the
  // speed of light (gamma G; at most 1e+06)".
  void limit_gamma(const Node& n, double gamma, const std::string& subject,
                   const Observer& observer) const;

  // --- Typed values -----------------------------------------------------------------------

  const json& need(const Node& n) const;

  // Checks that `n` is an object whose keys are all in `allowed` or `more`; `context` (" for a
  // point light") qualifies the message about an unknown key.
  void object(const Node& n, Names allowed, Names more = {}, std::string_view context = "") const;

  // An object with exactly one of `choices` (plus any of `others`); returns the chosen key.
  std::string_view one_of(const Node& n, Names choices, Names others = {}) const;

  double number(const Node& n) const;
  double non_negative(const Node& n) const;
  double positive(const Node& n) const;
  int integer(const Node& n, int lo, int hi) const;
  bool boolean(const Node& n) const;
  std::string string(const Node& n) const;

  // Checks that `n` is an array of `count` finite numbers.
  void numbers(const Node& n, std::size_t count) const;

  Vec3 vec3(const Node& n) const;
  Vec3 positive_vec3(const Node& n) const;

  // A unit direction. Scaled by its largest component before normalizing, so that tiny or huge
  // (but finite) vectors neither underflow to zero nor overflow to infinity.
  Vec3 direction(const Node& n) const;

  // Below the speed of light, and not so close to it, in W or relative to the camera, that
  // double precision cannot hold the physics: gamma at most kMaxLorentzFactor.
  Vec3 velocity(const Node& n) const;

  Rgb color(const Node& n) const;

  // The colour of a lit surface: the fraction of the light it reflects, each component in
  // [0, 1].
  Rgb albedo(const Node& n) const;

  // A number in [lo, hi], or in (lo, hi] when `open_below`.
  double in_range(const Node& n, double lo, double hi, bool open_below = false) const;

  Mat3 rotation(const Node& n) const;

  // A file named in the scene; a relative path is relative to the scene file's folder (or the
  // folder the load's options give).
  std::filesystem::path file_path(const Node& n) const;

  // A time in the scene's units, in the engine's.
  double time(const Node& n) const;

  // One of a fixed set of names; `noun` names what they are in the message.
  template <class T>
  T choice(const Node& n, const std::vector<std::pair<std::string, T>>& names,
           const char* noun = "model") const {
    const std::string given = string(n);
    std::vector<std::string_view> known;
    for (const auto& [name, value] : names) {
      if (name == given) return value;
      known.push_back(name);
    }
    fail(n, fmt::format("unknown {} \"{}\" (expected one of: {})", noun, given, join(known)));
  }

  const JsonLineMap& lines_;
  double c_ = 1;  // the scene's speed of light, in its units
  // The observers every speed is checked against: W, and once the camera is read, the camera
  // at its observation and over its shutter.
  std::vector<Observer> observers_{{Vec4{1, {}}, ""}};

 private:
  // An error inside (or around) a value that came from --set is the override's fault, not the
  // file's; the line of the file would point at the value that was replaced.
  bool overridden(const std::string& path) const;

  const std::filesystem::path& file_;
  std::vector<std::string> overridden_;  // readable paths that --set replaced
  bool line_numbers_;
  std::filesystem::path folder_;  // where relative paths are read from
};

}  // namespace lightcone::scene_io

#include "lightcone/io/scene_value_reader.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/spelling.hpp"

namespace lightcone::scene_io {

Node member(const Node& object, std::string_view key) {
  const auto it = object.value->find(key);
  return {it == object.value->end() ? nullptr : &*it, &object, key};
}

Node element(const Node& array, std::size_t index) {
  return {&(*array.value)[index], &array, {}, index, true};
}

std::string describe(const json& v) {
  if (v.is_object()) return "an object";
  if (v.is_array()) return fmt::format("an array of {} elements", v.size());
  if (v.is_null()) return "null";
  // Invalid UTF-8 (from a --set value) is shown replaced, not thrown.
  std::string text = v.dump(-1, ' ', false, json::error_handler_t::replace);
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return fmt::format("{} {}", v.type_name(), text);
}

std::string join(Names words, Names more) {
  std::string out;
  for (const Names list : {words, more})
    for (const std::string_view w : list) {
      if (!out.empty()) out += ", ";
      out += w;
    }
  return out;
}

bool SceneValueReader::overridden(const std::string& path) const {
  auto within = [](const std::string& inner, const std::string& outer) {
    return inner.size() > outer.size() && inner.compare(0, outer.size(), outer) == 0 &&
           (inner[outer.size()] == '.' || inner[outer.size()] == '[');
  };
  return std::any_of(overridden_.begin(), overridden_.end(), [&](const std::string& o) {
    return o == path || within(path, o) || within(o, path);
  });
}

void SceneValueReader::fail_at(const std::string& path, int line, const std::string& what) const {
  const std::string shown = path.empty() ? "(top level)" : path;
  if (overridden(path)) throw InputError(fmt::format("--set {}: {}", shown, what));
  if (!line_numbers_) throw InputError(fmt::format("{}: {}: {}", file_.string(), shown, what));
  throw InputError(fmt::format("{}:{}: {}: {}", file_.string(), line, shown, what));
}

void SceneValueReader::fail(const Node& n, const std::string& what) const {
  const std::string path = n.path();
  fail_at(path, line_numbers_ ? lines_.value_line(path) : 0, what);
}

void SceneValueReader::limit_gamma(const Node& n, double gamma, const std::string& subject,
                                   const Observer& observer) const {
  if (!(gamma <= kMaxLorentzFactor))
    fail(n, fmt::format("{}{} is too close to the speed of light (gamma {:.3g}; at most {:g})",
                        subject, observer.relative, gamma, kMaxLorentzFactor));
}

const json& SceneValueReader::need(const Node& n) const {
  if (!n.value) fail(n, "required key is missing");
  return *n.value;
}

void SceneValueReader::object(const Node& n, Names allowed, Names more,
                              std::string_view context) const {
  const json& v = need(n);
  if (!v.is_object()) fail(n, fmt::format("must be an object, got {}", describe(v)));
  for (const auto& [key, value] : v.get_ref<const json::object_t&>()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end() ||
        std::find(more.begin(), more.end(), key) != more.end())
      continue;
    const std::string path = json_member_path(n.path(), key);
    std::vector<std::string_view> names(allowed.begin(), allowed.end());
    names.insert(names.end(), more.begin(), more.end());
    const std::optional<std::string_view> near = nearest_name(key, names);
    fail_at(path, line_numbers_ ? lines_.key_line(path) : 0,
            fmt::format("unknown key \"{}\"{} ({}expected one of: {})", json_member_path("", key),
                        context, near ? fmt::format("did you mean \"{}\"? ", *near) : "",
                        join(allowed, more)));
  }
}

std::string_view SceneValueReader::one_of(const Node& n, Names choices, Names others) const {
  object(n, choices, others);
  const auto has = [&](std::string_view c) { return n.value->contains(c); };
  if (std::count_if(choices.begin(), choices.end(), has) != 1) {
    std::vector<std::string_view> present;
    std::copy_if(choices.begin(), choices.end(), std::back_inserter(present), has);
    fail(n, fmt::format("must have exactly one of: {} (found {})", join(choices),
                        present.empty() ? "none" : join(present)));
  }
  return *std::find_if(choices.begin(), choices.end(), has);
}

double SceneValueReader::number(const Node& n) const {
  const json& v = need(n);
  if (!v.is_number()) fail(n, fmt::format("must be a number, got {}", describe(v)));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(n, "must be a finite number");
  return d;
}

double SceneValueReader::non_negative(const Node& n) const {
  const double d = number(n);
  if (!(d >= 0)) fail(n, fmt::format("must be >= 0, got {}", d));
  return d;
}

double SceneValueReader::positive(const Node& n) const {
  const double d = number(n);
  if (!(d > 0)) fail(n, fmt::format("must be greater than 0, got {}", d));
  return d;
}

int SceneValueReader::integer(const Node& n, int lo, int hi) const {
  const double d = number(n);
  if (d != std::floor(d) || d < lo || d > hi)
    fail(n, fmt::format("must be an integer from {} to {}, got {}", lo, hi, n.value->dump()));
  return static_cast<int>(d);
}

bool SceneValueReader::boolean(const Node& n) const {
  const json& v = need(n);
  if (!v.is_boolean()) fail(n, fmt::format("must be true or false, got {}", describe(v)));
  return v.get<bool>();
}

std::string SceneValueReader::string(const Node& n) const {
  const json& v = need(n);
  if (!v.is_string()) fail(n, fmt::format("must be a string, got {}", describe(v)));
  return v.get<std::string>();
}

void SceneValueReader::numbers(const Node& n, std::size_t count) const {
  const json& v = need(n);
  if (!v.is_array() || v.size() != count)
    fail(n, fmt::format("must be an array of {} numbers, got {}", count, describe(v)));
  for (std::size_t i = 0; i < count; ++i) number(element(n, i));
}

Vec3 SceneValueReader::vec3(const Node& n) const {
  numbers(n, 3);
  const json& v = *n.value;
  return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
}

Vec3 SceneValueReader::positive_vec3(const Node& n) const {
  vec3(n);  // shape and types first, so that the messages below are about values
  return {positive(element(n, 0)), positive(element(n, 1)), positive(element(n, 2))};
}

Vec3 SceneValueReader::direction(const Node& n) const {
  const Vec3 v = vec3(n);
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (largest == 0) fail(n, "must not be the zero vector");
  return normalize(v / largest);
}

Vec3 SceneValueReader::velocity(const Node& n) const {
  const Vec3 v = vec3(n);
  const Vec3 beta = v / c_;
  if (!(dot(beta, beta) < 1))
    fail(n, fmt::format("speed {} must be below the speed of light ({})", length(v), c_));
  const double speed = length(beta);
  // (1 - v)(1 + v), not 1 - v^2: no cancellation near v = 1.
  const double gamma = 1 / std::sqrt((1 - speed) * (1 + speed));
  const Vec4 u{gamma, beta * gamma};
  for (const Observer& o : observers_)
    limit_gamma(n, o.relative.empty() ? gamma : relative_gamma(o.four_velocity, u),
                fmt::format("speed {}", length(v)), o);
  return beta;
}

Rgb SceneValueReader::color(const Node& n) const {
  vec3(n);
  float c[3];
  for (std::size_t i = 0; i < 3; ++i) {
    const Node component = element(n, i);
    const double d = number(component);
    c[i] = static_cast<float>(d);
    if (d < 0) fail(component, fmt::format("must be >= 0, got {}", d));
    if (!std::isfinite(c[i])) fail(component, fmt::format("is too large for a colour, got {}", d));
  }
  return {c[0], c[1], c[2]};
}

Rgb SceneValueReader::albedo(const Node& n) const {
  const Rgb c = color(n);
  for (std::size_t i = 0; i < 3; ++i) {
    const Node component = element(n, i);
    if (const double d = number(component); d > 1)
      fail(component, fmt::format("must be at most 1 for a lit material (an albedo), got {}", d));
  }
  return c;
}

double SceneValueReader::in_range(const Node& n, double lo, double hi, bool open_below) const {
  const double d = number(n);
  if (open_below ? !(d > lo && d <= hi) : !(d >= lo && d <= hi))
    fail(n, fmt::format("must be {} {} and at most {}, got {}",
                        open_below ? "greater than" : "at least", lo, hi, d));
  return d;
}

Mat3 SceneValueReader::rotation(const Node& n) const {
  object(n, {"axis", "degrees"});
  const Vec3 axis = direction(member(n, "axis"));
  return Mat3::rotation(axis, number(member(n, "degrees")) * std::numbers::pi / 180);
}

std::filesystem::path SceneValueReader::file_path(const Node& n) const {
  const std::string text = string(n);
  if (text.empty()) fail(n, "must not be empty");
  const std::filesystem::path p(text);
  return p.is_relative() ? folder_ / p : p;
}

double SceneValueReader::time(const Node& n) const {
  return number(n) * c_;
}

}  // namespace lightcone::scene_io

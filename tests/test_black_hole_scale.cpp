// Scale-freedom near a black hole (docs/design/black-hole.md, "Scale"): G = c = 1 leaves no
// length of its own, so a scene whose every length and time is multiplied by k (the mass, the
// camera's and bodies' positions, sizes, times and clock periods; radii the file gives in units
// of M stay) is the same picture, and locate's answers are the same directions and shifts at k
// times the times and positions. What cannot be represented in double precision is refused by
// the loader, naming the field, and no library's message reaches the user.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "lightcone/frame/locate.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/scene_file_test.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

// "key=[k v_1, k v_2, ...]" (one value: "key=k v").
std::string scaled(const std::string& key, double k, const std::vector<double>& values) {
  std::vector<std::string> parts;
  for (const double v : values) parts.push_back(fmt::format("{:.17g}", k * v));
  const std::string joined = fmt::format("{}", fmt::join(parts, ","));
  return key + "=" + (values.size() > 1 ? "[" + joined + "]" : joined);
}

// The overrides that multiply every length and time of a bundled scene by k.
std::vector<std::string> black_hole_at(double k) {
  return {scaled("black_hole.mass", k, {1}), scaled("camera.position", k, {0, 10.4189, 59.0885})};
}
std::vector<std::string> orbit_at(double k) {
  return {scaled("black_hole.mass", k, {1}), scaled("camera.position", k, {0, 5.2, 39.7}),
          scaled("objects[0].shape.sphere.radius", k, {1.2}),
          scaled("objects[0].material.checker.size", k, {0.6})};
}
std::vector<std::string> lensed_clock_at(double k) {
  return {scaled("black_hole.mass", k, {1}), scaled("camera.position", k, {0, 0, 30}),
          scaled("objects[0].shape.box.size", k, {4, 4, 4}),
          scaled("objects[0].position", k, {7, 1, -12}),
          scaled("objects[0].material.clock.period", k, {36})};
}
std::vector<std::string> infall_at(double k) {
  std::vector<std::string> o = {scaled("black_hole.mass", k, {1}),
                                scaled("camera.position", k, {0, 0, 30})};
  const double let_go[3] = {-40, -66, -76};
  for (int i = 0; i < 3; ++i) {
    const std::string object = fmt::format("objects[{}].", i);
    o.push_back(scaled(object + "shape.box.size", k, {1.6, 1.6, 1.6}));
    o.push_back(scaled(object + "motion.fall.time", k, {let_go[i]}));
    o.push_back(scaled(object + "material.clock.period", k, {10}));
  }
  return o;
}

// A bundled scene with `overrides`, small, one sample, exposure 0.
Scene bundled(const std::string& name, std::vector<std::string> overrides) {
  for (const char* small :
       {"camera.width=64", "camera.height=36", "camera.samples=1", "render.exposure=0"})
    overrides.emplace_back(small);
  SceneLoadReport report;
  return load_scene_file(std::filesystem::path(LIGHTCONE_SOURCE_DIR) / "scenes" / name, overrides,
                         report);
}

// The same picture: every value within 1e-6 of the other, relatively.
void expect_same_picture(const Image& expected, const Image& actual) {
  ASSERT_EQ(actual.rgb.size(), expected.rgb.size());
  std::size_t differing = 0, first = 0;
  for (std::size_t i = 0; i < expected.rgb.size(); ++i) {
    const double a = expected.rgb[i], b = actual.rgb[i];
    if (std::abs(a - b) <= 1e-6 * std::max(std::abs(a), std::abs(b))) continue;
    if (differing++ == 0) first = i;
  }
  EXPECT_EQ(differing, 0u) << "first at value " << first << ": " << expected.rgb[first]
                           << " against " << actual.rgb[first];
}

TEST(BlackHoleScale, TheSkyTheDiskAndTheStarsAreTheSameAtEveryScale) {
  const Image unit = render_image(bundled("black-hole.json", black_hole_at(1)), {});
  double sum = 0;
  for (const float v : unit.rgb) sum += v;
  ASSERT_GT(sum, 0);
  for (const double k : {1e-300, 1e-100, 1e-3, 1e6, 1e100, 1e150, 1e300}) {
    SCOPED_TRACE(k);
    expect_same_picture(unit, render_image(bundled("black-hole.json", black_hole_at(k)), {}));
  }
}

// A moon on an orbit, lit by a sun (its shadows cast); clocks falling; a clock at rest.
TEST(BlackHoleScale, BodiesAreTheSameAtEveryScale) {
  struct Case {
    const char* name;
    std::vector<std::string> (*at)(double);
  };
  for (const Case& c : {Case{"orbit.json", orbit_at}, Case{"infall.json", infall_at},
                        Case{"lensed-clock.json", lensed_clock_at}}) {
    SCOPED_TRACE(c.name);
    const Image unit = render_image(bundled(c.name, c.at(1)), {});
    for (const double k : {1e-300, 1e-100, 1e-3, 1e6, 1e100, 1e150, 1e300}) {
      SCOPED_TRACE(k);
      expect_same_picture(unit, render_image(bundled(c.name, c.at(k)), {}));
    }
  }
}

// locate's answers at scale k against k = 1: the same images, directions and shifts, at k times
// the emission times, positions and clock readings.
void expect_scaled(const LocateResult& unit, const LocateResult& at_k, double k) {
  ASSERT_EQ(at_k.images.size(), unit.images.size());
  ASSERT_FALSE(unit.images.empty());
  const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(a); };
  for (std::size_t i = 0; i < unit.images.size(); ++i) {
    const LocateImage &a = unit.images[i], &b = at_k.images[i];
    SCOPED_TRACE(a.order);
    EXPECT_EQ(b.order, a.order);
    test::expect_vec(b.direction, a.direction, 1e-9);
    EXPECT_PRED2(near, a.shift, b.shift);
    ASSERT_EQ(b.emission_time.has_value(), a.emission_time.has_value());
    if (a.emission_time) {
      EXPECT_PRED2(near, *a.emission_time, *b.emission_time / k);
    }
    ASSERT_EQ(b.emission_position.has_value(), a.emission_position.has_value());
    if (a.emission_position) {
      test::expect_vec(*b.emission_position / k, *a.emission_position,
                       1e-9 * length(*a.emission_position));
    }
    ASSERT_EQ(b.emission_proper_time.has_value(), a.emission_proper_time.has_value());
    if (a.emission_proper_time) {
      EXPECT_PRED2(near, *a.emission_proper_time, *b.emission_proper_time / k);
    }
  }
}

TEST(BlackHoleScale, LocateAnswersScale) {
  struct Query {
    const char* scene;
    std::vector<std::string> (*at)(double);
    LocateQuery::Kind kind;
    const char* object;
    Vec3 value;  // at k = 1; a point scales with k, a direction does not
  };
  using Kind = LocateQuery::Kind;
  for (const Query& q :
       {Query{"orbit.json", orbit_at, Kind::ObjectPoint, "moon", {0, 0.5, 0}},
        Query{"infall.json", infall_at, Kind::ObjectPoint, "late", {0.8, 0, 0}},
        Query{"black-hole.json", black_hole_at, Kind::WorldPoint, "", {4, 0, -14}},
        Query{"black-hole.json", black_hole_at, Kind::SkyDirection, "", {0.3, 0.2, -1}}}) {
    SCOPED_TRACE(std::string(q.scene) + " " + q.object);
    const LocateResult unit = locate(bundled(q.scene, q.at(1)), {q.kind, q.object, q.value});
    for (const double k : {1e-300, 1e-100, 1e-3, 1e6, 1e100, 1e150, 1e300}) {
      SCOPED_TRACE(k);
      const Vec3 value = q.kind == Kind::SkyDirection ? q.value : q.value * k;
      expect_scaled(unit, locate(bundled(q.scene, q.at(k)), {q.kind, q.object, value}), k);
    }
  }
}

using BlackHoleScaleFile = test::SceneFileTest;

// A hole of mass `mass` at the origin seen from `camera` (line 2), with `rest` from line 4 on.
std::string hole_scene(const std::string& mass, const std::string& camera,
                       const std::string& rest = "") {
  return "{\n  \"camera\": {\"position\": " + camera + "},\n  \"black_hole\": {\"mass\": " + mass +
         "}" + (rest.empty() ? "" : ",\n" + rest) + "\n}";
}

// One sphere (line 4) with `keys` about a hole of mass `mass`, seen from 10 away.
std::string with_sphere(const std::string& mass, const std::string& keys) {
  return hole_scene(
      mass, "[0, 0, 10]",
      R"(  "objects": [{"name": "a", "shape": {"sphere": {"radius": 1}}, )" + keys + "}]");
}

TEST_F(BlackHoleScaleFile, WhatDoublesCannotHoldIsRefusedByName) {
  // A horizon beyond the largest double.
  expect_error(hole_scene("1e308", "[0, 0, 1e300]"), 3, "black_hole.mass", "not a finite number");
  // A camera whose distance, or its distance in units of M, is beyond it.
  expect_error(hole_scene("1", "[1.5e308, 1.5e308, 0]"), 2, "camera.position",
               "not a finite number");
  expect_error(hole_scene("1e-300", "[0, 0, 1e10]"), 2, "camera.position", "not a finite number");
  // An object or a light there.
  expect_error(with_sphere("1e-300", R"("position": [0, 1e10, 0])"), 4, "objects[0].position",
               "not a finite number");
  expect_error(
      hole_scene("1e-300", "[0, 0, 10]",
                 R"(  "lights": [{"name": "l", "type": "point", "position": [1e10, 0, 0]}])"),
      4, "lights[0].position", "not a finite number");
  // Bodies so far away in units of M that the chords that meet them square no double.
  expect_error(with_sphere("1e-300", R"("position": [0, 1e-140, 0])"), 4, "objects[0].position",
               "drawn within 1e+150 M");
  expect_error(with_sphere("1", R"("motion": {"orbit": {"radius": 1e200}})"), 4,
               "objects[0].motion.orbit.radius", "drawn within 1e+150 M");
}

// Boost's messages name its functions ("boost::math::ellint_rf<double>(double,double,double)");
// none may reach the user.
bool names_boost(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text.find("boost") != std::string::npos;
}

TEST_F(BlackHoleScaleFile, EveryScaleRendersThroughTheProgramWithoutALibrarysMessage) {
  const std::string scene =
      test::quoted(std::filesystem::path(LIGHTCONE_SOURCE_DIR) / "scenes" / "black-hole.json");
  const std::string out = test::quoted(dir_ / "out.png");
  for (const double k : {1e-300, 1e153, 1e300}) {
    SCOPED_TRACE(k);
    std::string sets = " --width 32 --height 18 --samples 1";
    for (const std::string& s : black_hole_at(k)) sets += " --set " + test::quoted(s);
    const test::CommandResult rendered =
        test::run_lightcone("render " + scene + " -o " + out + sets);
    EXPECT_EQ(rendered.status, 0) << rendered.err;
    EXPECT_FALSE(names_boost(rendered.err)) << rendered.err;
    const test::CommandResult located =
        test::run_lightcone("locate " + scene + " --world-point " +
                            fmt::format("{:.17g},0,{:.17g}", 4 * k, -14 * k) + sets);
    EXPECT_FALSE(names_boost(located.err + located.out)) << located.err;
  }
  // Refused: inside the horizon at every scale.
  const test::CommandResult refused =
      test::run_lightcone("render " + scene + " -o " + out +
                          " --set black_hole.mass=1e300 --set camera.position=[0,0,1e300]");
  EXPECT_EQ(refused.status, 2);
  EXPECT_FALSE(names_boost(refused.err)) << refused.err;
}

}  // namespace
}  // namespace lightcone

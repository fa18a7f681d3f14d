// The one speed limit (gamma at most 10^6) holds wherever a speed can arise: a body's velocity,
// relative to a moving camera, phases (at their end and mid-way), keyframes, a spinning rim
// (alone, with the body's velocity, relative to the camera), the camera's velocity, phases and
// keyframes, and the camera's shutter. Just past the limit the loader names the file, line and
// field; just inside it accepts; the CLI exits with status 2 and writes nothing; a rim just
// inside the limit renders finite, non-negative radiance.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/physics/keyframe_world_line.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using test::CommandResult;
using test::quoted;
using test::run_lightcone;

constexpr double kLimit = 1e6;
constexpr double kPast = 1.1 * kLimit, kInside = 0.9 * kLimit;

// The speed whose gamma is `gamma`, as JSON text that reads back to the nearest double.
std::string speed(double gamma) {
  return fmt::format("{:.17g}", std::sqrt(1 - 1 / (gamma * gamma)));
}
std::string number(double x) {
  return fmt::format("{:.17g}", x);
}
// The spin rate in degrees per unit time of a rim of radius 1 whose gamma is `gamma`.
std::string rim_rate(double gamma) {
  return number(std::sqrt(1 - 1 / (gamma * gamma)) * 180 / std::numbers::pi);
}

// A scene: the camera's members, then the objects' (the ball's members are on line 4).
std::string scene(const std::string& camera, const std::string& ball,
                  const std::string& more = "") {
  return "{\n  \"camera\": {\"width\": 32, \"height\": 24" + camera +
         "},\n  \"objects\": [\n    {\"name\": \"ball\", \"shape\": {\"sphere\": {\"radius\": 1}}" +
         ball + "}\n  ]" + more + "\n}\n";
}

class SpeedLimitTest : public test::TempDirTest {
 protected:
  // The loader's message for `text`, or "" when it loads.
  std::string error(const std::string& text) {
    const fs::path file = write("scene.json", text);
    try {
      SceneLoadReport report;
      load_scene_file(file, {}, report);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  // Refused at FILE:LINE: PATH, with the one wording of the limit and `fragment`.
  void expect_refused(const std::string& text, int line, const std::string& path,
                      const std::string& fragment = "") {
    const std::string message = error(text);
    const std::string prefix =
        fmt::format("{}:{}: {}: ", (dir_ / "scene.json").string(), line, path);
    EXPECT_EQ(message.substr(0, prefix.size()), prefix) << message;
    EXPECT_NE(message.find("is too close to the speed of light (gamma "), std::string::npos)
        << message;
    EXPECT_NE(message.find("; at most 1e+06)"), std::string::npos) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
  void expect_accepted(const std::string& text) { EXPECT_EQ(error(text), "") << text; }
};

TEST_F(SpeedLimitTest, BodyVelocity) {
  const auto with = [](double g) {
    return scene(", \"position\": [0, 0, 10]",
                 ", \"position\": [0, 0, 0],\n      \"velocity\": [" + speed(g) + ", 0, 0]");
  };
  expect_refused(with(kPast), 5, "objects[0].velocity", "gamma 1.1e+06");
  expect_accepted(with(kInside));
}

TEST_F(SpeedLimitTest, BodyVelocityRelativeToAMovingCamera) {
  // Each well inside the limit in W; relative gamma 2 g_c g_b.
  const auto with = [](double g) {
    return scene(", \"position\": [0, 0, 10], \"velocity\": [" + speed(1000) + ", 0, 0]",
                 ",\n      \"velocity\": [-" + speed(g) + ", 0, 0]");
  };
  expect_refused(with(550), 5, "objects[0].velocity", "relative to the camera");
  expect_accepted(with(450));
}

TEST_F(SpeedLimitTest, PhasesAtTheEnd) {
  const auto with = [](double g) {
    return scene(", \"position\": [0, 0, 10]",
                 ",\n      \"motion\": {\"phases\": [\n        {\"duration\": " +
                     number(std::acosh(g)) + ", \"acceleration\": [1, 0, 0]}]}");
  };
  expect_refused(with(kPast), 6, "objects[0].motion.phases[0]", "at the end of phase 0");
  expect_accepted(with(kInside));
}

TEST_F(SpeedLimitTest, PhasesMidWay) {
  // Up to g and back to rest: the end is slow, the middle is not.
  const auto there_and_back = [](double g) {
    const std::string d = number(std::acosh(g));
    return scene(", \"position\": [0, 0, 10]",
                 ",\n      \"motion\": {\"phases\": [\n        {\"duration\": " + d +
                     ", \"acceleration\": [1, 0, 0]},\n        {\"duration\": " + d +
                     ", \"acceleration\": [-1, 0, 0]}]}");
  };
  expect_refused(there_and_back(kPast), 6, "objects[0].motion.phases[0]");
  expect_accepted(there_and_back(kInside));

  // A phase that turns a body moving at gamma 1000 (acceleration across its velocity), then
  // one that brings it to rest along its velocity at the turn's end.
  const auto turn = [](double g) {
    const double g0 = 1000, b0 = std::sqrt(1 - 1 / (g0 * g0)), eta = std::acosh(g / g0);
    // U(eta) = cosh(eta) U0 + sinh(eta) N: gamma g, spatial (g0 b0 cosh, sinh, 0).
    const double ux = g0 * b0 * std::cosh(eta), uy = std::sinh(eta), u = std::hypot(ux, uy);
    return scene(
        ", \"position\": [0, 0, 10]",
        ", \"velocity\": [" + speed(g0) +
            ", 0, 0],\n      \"motion\": {\"phases\": [{\"duration\": " + number(eta) +
            ", \"acceleration\": [0, 1, 0]},\n        {\"duration\": " + number(std::acosh(g)) +
            ", \"acceleration\": [" + number(-ux / u) + ", " + number(-uy / u) + ", 0]}]}");
  };
  expect_refused(turn(kPast), 5, "objects[0].motion.phases[0]", "at the end of phase 0");
  expect_accepted(turn(kInside));
}

TEST_F(SpeedLimitTest, PhasesRelativeToAMovingCamera) {
  const auto with = [](double g) {
    return scene(", \"position\": [0, 0, 10], \"velocity\": [" + speed(1000) + ", 0, 0]",
                 ",\n      \"motion\": {\"phases\": [\n        {\"duration\": " +
                     number(std::acosh(g)) + ", \"acceleration\": [-1, 0, 0]}]}");
  };
  expect_refused(with(550), 6, "objects[0].motion.phases[0]", "relative to the camera");
  expect_accepted(with(450));
}

TEST_F(SpeedLimitTest, Keyframes) {
  const auto with = [](double g) {
    return scene(", \"position\": [0, 0, 10]",
                 ",\n      \"motion\": {\"keyframes\": [{\"time\": 0, \"position\": [0, 0, 0]},\n"
                 "        {\"time\": 1, \"position\": [" +
                     speed(g) + ", 0, 0]}]}");
  };
  expect_refused(with(kPast), 6, "objects[0].motion.keyframes[1]", "between keyframes 0 and 1");
  expect_accepted(with(kInside));
  // Relative to a camera moving the other way.
  const auto against = [](double g) {
    return scene(", \"position\": [0, 0, 10], \"velocity\": [" + speed(1000) + ", 0, 0]",
                 ",\n      \"motion\": {\"keyframes\": [{\"time\": 0, \"position\": [0, 0, 0]},\n"
                 "        {\"time\": 1, \"position\": [-" +
                     speed(g) + ", 0, 0]}]}");
  };
  expect_refused(against(550), 6, "objects[0].motion.keyframes[1]", "relative to the camera");
  expect_accepted(against(450));
}

TEST_F(SpeedLimitTest, KeyframedMaximumIsFoundBetweenKeys) {
  // Three keys: the speed peaks between them. The exact maximum against a fine sampling of
  // the world-line, in W and relative to a moving observer.
  const KeyframeWorldLine line({{0, {0, 0, 0}}, {1, {0.6, 0.2, 0}}, {2, {0.8, 0.9, 0}}});
  for (const Vec3 observer : {Vec3{}, Vec3{-0.6, 0.3, 0.1}, Vec3{0.5, 0.5, 0}}) {
    double sampled = 0;
    for (int k = 0; k <= 200000; ++k) {
      const Vec4 u = line.at_world_time(-0.5 + 3.0 * k / 200000).four_velocity;
      sampled = std::max(sampled, lorentz_gamma(observer) * (u.t - dot(observer, u.x)));
    }
    const KeyframeWorldLine::Fastest f = line.max_gamma(observer);
    EXPECT_GE(f.gamma, sampled * (1 - 1e-12));
    EXPECT_NEAR(f.gamma, sampled, 1e-9 * sampled);
  }
}

TEST_F(SpeedLimitTest, SpinningRim) {
  const auto with = [](double g) {
    return scene(", \"position\": [0, 0, 10]",
                 ",\n      \"spin\": {\"axis\": [0, 1, 0], \"rate\": " + rim_rate(g) + "}");
  };
  expect_refused(with(kPast), 5, "objects[0].spin.rate", "rim's fastest point");
  expect_accepted(with(kInside));
  // The review's case: a rim 1e-9 below c (gamma 22,000) is within the limit.
  expect_accepted(scene(", \"position\": [0, 0, 10]",
                        ", \"spin\": {\"axis\": [0, 1, 0], \"rate\": 57.2957794558}"));
}

TEST_F(SpeedLimitTest, SpinningRimAddsToTheBodysVelocity) {
  // Velocity across the axis: the worst rim point moves at gamma 2 g_w g_b.
  const auto across = [](double g) {
    return scene(", \"position\": [0, 0, 10]",
                 ", \"velocity\": [" + speed(1000) +
                     ", 0, 0],\n      \"spin\": {\"axis\": [0, 1, 0], \"rate\": " + rim_rate(g) +
                     "}");
  };
  expect_refused(across(550), 5, "objects[0].spin.rate", "rim's fastest point");
  expect_accepted(across(450));
  // Velocity along the axis: every rim point moves at gamma g_w g_b.
  const auto along = [](double g) {
    return scene(", \"position\": [0, 0, 10]",
                 ", \"velocity\": [0, " + speed(1000) +
                     ", 0],\n      \"spin\": {\"axis\": [0, 1, 0], \"rate\": " + rim_rate(g) + "}");
  };
  expect_refused(along(1100), 5, "objects[0].spin.rate", "rim's fastest point");
  expect_accepted(along(900));
  // An accelerated body: bounded over every direction at its largest speed.
  const auto accelerated = [](double g) {
    return scene(", \"position\": [0, 0, 10]",
                 ",\n      \"motion\": {\"phases\": [{\"duration\": " + number(std::acosh(1000)) +
                     ", \"acceleration\": [1, 0, 0]}]},\n      \"spin\": {\"axis\": [0, 1, 0], "
                     "\"rate\": " +
                     rim_rate(g) + "}");
  };
  expect_refused(accelerated(550), 6, "objects[0].spin.rate", "rim's fastest point");
  expect_accepted(accelerated(450));
}

TEST_F(SpeedLimitTest, SpinningRimRelativeToAMovingCamera) {
  // The body is at rest; the camera moves across the spin axis at gamma 1000, so the worst rim
  // point moves at gamma 2000 g_w relative to it.
  const auto with = [](double g) {
    return scene(", \"position\": [0, 0, 10], \"velocity\": [" + speed(1000) + ", 0, 0]",
                 ",\n      \"spin\": {\"axis\": [0, 1, 0], \"rate\": " + rim_rate(g) + "}");
  };
  expect_refused(with(550), 5, "objects[0].spin.rate", "relative to the camera");
  expect_accepted(with(450));
}

TEST_F(SpeedLimitTest, CameraVelocity) {
  const auto with = [](double g) {
    return scene(",\n    \"position\": [0, 0, 10], \"velocity\": [" + speed(g) + ", 0, 0]", "");
  };
  expect_refused(with(kPast), 3, "camera.velocity", "gamma 1.1e+06");
  expect_accepted(with(kInside));
}

TEST_F(SpeedLimitTest, CameraPhasesMidWayAndAtTheEnd) {
  const auto there_and_back = [](double g) {
    const std::string d = number(std::acosh(g));
    return scene(", \"position\": [0, 0, 10],\n    \"motion\": {\"phases\": [{\"duration\": " + d +
                     ", \"acceleration\": [1, 0, 0]},\n      {\"duration\": " + d +
                     ", \"acceleration\": [-1, 0, 0]}]}",
                 "");
  };
  // Observed at proper time 0, at rest, and at rest again after: fast only in between.
  expect_refused(there_and_back(kPast), 3, "camera.motion.phases[0]", "at the end of phase 0");
  expect_accepted(there_and_back(kInside));
  const auto one = [](double g) {
    return scene(", \"position\": [0, 0, 10],\n    \"motion\": {\"phases\": [{\"duration\": " +
                     number(std::acosh(g)) + ", \"acceleration\": [1, 0, 0]}]}",
                 "");
  };
  expect_refused(one(kPast), 3, "camera.motion.phases[0]");
  expect_accepted(one(kInside));
}

TEST_F(SpeedLimitTest, CameraKeyframes) {
  const auto with = [](double g) {
    return scene(
        ",\n    \"motion\": {\"keyframes\": [{\"time\": 0, \"position\": [0, 0, 10]},\n"
        "      {\"time\": 1, \"position\": [" +
            speed(g) + ", 0, 10]}]}",
        ", \"position\": [0, 0, -10]");
  };
  expect_refused(with(kPast), 4, "camera.motion.keyframes[1]", "between keyframes 0 and 1");
  expect_accepted(with(kInside));
}

TEST_F(SpeedLimitTest, CameraShutter) {
  // The camera starts at rest and, while its shutter is open, speeds up to gamma 550 against a
  // ball moving the other way at gamma 1000: relative gamma 1.1e6 at the shutter's close.
  const auto with = [](double g, double shutter) {
    const std::string d = number(std::acosh(g));
    return scene(", \"position\": [0, 0, 10],\n    \"motion\": {\"phases\": [{\"duration\": " + d +
                     ", \"acceleration\": [1, 0, 0]}]},\n    \"shutter\": " + number(shutter),
                 ",\n      \"velocity\": [-" + speed(1000) + ", 0, 0]");
  };
  expect_refused(with(550, std::acosh(550)), 7, "objects[0].velocity", "shutter");
  expect_accepted(with(450, std::acosh(450)));
  // The shutter open a little: the camera is still slow enough.
  expect_accepted(with(550, 0.5));
  // A phase that ends while the shutter is open, then slows down again: the end counts.
  const auto peak = [](double g) {
    const std::string d = number(std::acosh(g));
    return scene(
        ", \"position\": [0, 0, 10],\n    \"motion\": {\"phases\": [{\"duration\": " + d +
            ", \"acceleration\": [1, 0, 0]}, {\"duration\": " + d +
            ", \"acceleration\": [-1, 0, 0]}]},\n    \"shutter\": " + number(2 * std::acosh(g)),
        ",\n      \"velocity\": [-" + speed(1000) + ", 0, 0]");
  };
  expect_refused(peak(550), 7, "objects[0].velocity", "while its shutter is open");
  expect_accepted(peak(450));
}

TEST_F(SpeedLimitTest, Lights) {
  const auto with = [](double g) {
    return scene(", \"position\": [0, 0, 10]", "",
                 ",\n  \"lights\": [{\"name\": \"lamp\", \"type\": \"point\",\n"
                 "    \"motion\": {\"keyframes\": [{\"time\": 0, \"position\": [0, 5, 0]},\n"
                 "      {\"time\": 1, \"position\": [" +
                     speed(g) + ", 5, 0]}]}}]");
  };
  expect_refused(with(kPast), 8, "lights[0].motion.keyframes[1]");
  expect_accepted(with(kInside));
}

// --- The command line -----------------------------------------------------------------------

class SpeedLimitCliTest : public test::TempDirTest {
 protected:
  void expect_refused_by_cli(const std::string& text, const std::string& where) {
    const fs::path file = write("scene.json", text);
    const fs::path png = dir_ / "out.png", exr = dir_ / "out.exr";
    const CommandResult r =
        run_lightcone("render " + quoted(file) + " -o " + quoted(png) + " --exr " + quoted(exr));
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(file.string() + ":" + where), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("is too close to the speed of light"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(png));
    EXPECT_FALSE(fs::exists(exr));
    const CommandResult info = run_lightcone("info " + quoted(file));
    EXPECT_EQ(info.status, 2) << info.out;
    EXPECT_NE(info.err.find(file.string() + ":" + where), std::string::npos) << info.err;
    for (const auto& entry : fs::directory_iterator(dir_))
      EXPECT_EQ(entry.path().filename(), "scene.json") << "file written: " << entry.path();
  }
};

TEST_F(SpeedLimitCliTest, KeyframesPastTheLimitAreRefused) {
  // The review's ball: gamma 2.2e7, once printed by info and rendered with status 0.
  expect_refused_by_cli(
      scene(", \"position\": [0, 0, 5]",
            ",\n      \"motion\": {\"keyframes\": [{\"time\": 0, \"position\": [0, 0, 0]},\n"
            "        {\"time\": 1, \"position\": [0.999999999999999, 0, 0]}]}"),
      "6: objects[0].motion.keyframes[1]: between keyframes 0 and 1 its speed is too close");
}

TEST_F(SpeedLimitCliTest, SpinningRimPastTheLimitIsRefused) {
  expect_refused_by_cli(
      scene(", \"position\": [0, 0, 5]",
            ",\n      \"spin\": {\"axis\": [0, 1, 0], \"rate\": " + rim_rate(kPast) + "}"),
      "5: objects[0].spin.rate: the speed of the rim's fastest point");
  expect_refused_by_cli(
      scene(", \"position\": [0, 0, 5]",
            ", \"velocity\": [" + speed(1000) +
                ", 0, 0],\n      \"spin\": {\"axis\": [0, 1, 0], \"rate\": " + rim_rate(550) + "}"),
      "5: objects[0].spin.rate: the speed of the rim's fastest point");
}

TEST_F(SpeedLimitCliTest, AnimateHoldsTheLimitAtEveryFrame) {
  // The camera accelerates along +x (gamma cosh(tau)); the ball comes the other way at gamma
  // 100. At proper time 0 they are within the limit, and the file loads; by proper time 9 the
  // ball's gamma relative to the camera is about 2 * 100 * cosh(9) = 1.6e6. The frames before
  // are written, the frame past the limit is refused by number, and no video is made.
  const fs::path file =
      write("scene.json",
            scene(", \"position\": [0, 0, 0], \"forward\": [0, 0, -1],\n               \"motion\": "
                  "{\"phases\": [{\"duration\": 12, \"acceleration\": [1, 0, 0]}]}",
                  ", \"position\": [5, 0, -5], \"velocity\": [-" + speed(100) + ", 0, 0]"));
  const CommandResult r = run_lightcone("animate " + quoted(file) + " --fps 1 --frames 0-12 -o " +
                                        quoted(dir_ / "f%02d.png") + " --quiet");
  EXPECT_EQ(r.status, 2) << r.err;
  // acosh(1e6 / 200) = 9.2: frame 10 is the first past the limit.
  EXPECT_NE(r.err.find("frame 10: by then ball moves too close to the speed of light relative "
                       "to the camera (gamma 2.2e+06; at most 1e+06)"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "f09.png"));
  EXPECT_FALSE(fs::exists(dir_ / "f10.png"));
}

// A ball whose rim is just inside the limit (and the review's rim, 1e-9 below c) renders
// finite, non-negative radiance: once the colour tables covered D = 1 alone and extrapolated
// to radiance of -7.9e5. Every pixel's luminance is >= 0; a channel may be negative only as
// the linear sRGB of a colour outside the sRGB gamut (light redshifted toward the spectral red,
// where green is -0.8 Y), never by more than the pixel's luminance.
TEST_F(SpeedLimitCliTest, RimJustInsideTheLimitRendersFiniteNonNegativeRadiance) {
  for (const std::string& rate : {rim_rate(kInside), std::string("57.2957794558")}) {
    const fs::path file = write(
        "scene.json", scene(", \"position\": [0, 0, 4]",
                            ",\n      \"spin\": {\"axis\": [0, 1, 0], \"rate\": " + rate +
                                "},\n      \"material\": {\"checker\": {\"size\": 0.3, \"colors\": "
                                "[[0.9, 0.6, 0.3], [0.1, 0.2, 0.4]]}}",
                            ",\n  \"sky\": {\"color\": [0.2, 0.3, 0.4]}"));
    const fs::path exr = dir_ / "out.exr";
    const CommandResult r = run_lightcone("render " + quoted(file) + " -o " + quoted(exr));
    ASSERT_EQ(r.status, 0) << r.err;
    const auto image = load_image_file(exr);
    ASSERT_EQ(image->width, 32);
    int bad = 0;
    double brightest = 0;
    for (std::size_t i = 0; i + 2 < image->rgb.size(); i += 3) {
      const double red = image->rgb[i], green = image->rgb[i + 1], blue = image->rgb[i + 2];
      const double y = 0.2126 * red + 0.7152 * green + 0.0722 * blue;
      brightest = std::max(brightest, y);
      const bool good = std::isfinite(y) && y >= 0 && red >= -y && green >= -y && blue >= -y;
      if (!good && ++bad <= 3)
        ADD_FAILURE() << rate << ": pixel " << i / 3 << " is " << red << ", " << green << ", "
                      << blue;
    }
    EXPECT_EQ(bad, 0) << rate;
    EXPECT_GT(brightest, 0) << rate;
  }
}

}  // namespace
}  // namespace lightcone

// `lightcone view` under a virtual X server (Xvfb), driven by xdotool and looked at through
// xwd: the window shows the scene, keys change the speed in the panel and the picture, F12
// writes the view as a PNG, Esc quits; and --benchmark without any display.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "lightcone/frame/image_text.hpp"
#include "lightcone/io/image_file.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

constexpr const char* kScene = R"({
  "camera": {"position": [0, 1, 6], "velocity": [0, 0, -0.5], "fov": 60,
             "width": 800, "height": 500},
  "objects": [
    {"name": "ball", "shape": {"sphere": {"radius": 1.2}}, "position": [1.5, 1.2, 0],
     "velocity": [0.6, 0, 0], "material": {"color": [0.9, 0.5, 0.2]}},
    {"name": "floor", "shape": {"plane": {"size": [40, 40]}}, "position": [0, 0, 0],
     "material": {"checker": {"size": 1, "colors": [[0.7, 0.7, 0.7], [0.2, 0.2, 0.25]]}}}
  ],
  "sky": {"grid": {"spacing": 15}},
  "render": {"exposure": 0, "tonemap": "clamp"}
})";

// Runs a shell command and returns its standard output.
std::string output_of(const std::string& command) {
  std::string out;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[4096];
    std::size_t n;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
    pclose(pipe);
  }
  return out;
}

// An X window dump (xwd's format: a big-endian header, a colour map, then ZPixmap rows) of a
// 24-bit TrueColor window, as 8-bit RGB.
struct Screenshot {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  std::array<int, 3> at(int x, int y) const {
    const std::uint8_t* p = &rgb[3 * (static_cast<std::size_t>(y) * width + x)];
    return {p[0], p[1], p[2]};
  }
};

Screenshot parse_xwd(const std::string& bytes) {
  Screenshot shot;
  if (bytes.size() < 100) return shot;
  const auto field = [&](int i) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + 4 * i;
    return static_cast<std::uint32_t>(p[0]) << 24 | p[1] << 16 | p[2] << 8 | p[3];
  };
  const std::uint32_t header = field(0), width = field(4), height = field(5), byte_order = field(7),
                      bits_per_pixel = field(11), line = field(12), red_mask = field(14),
                      colours = field(19);
  const std::size_t start = header + 12 * static_cast<std::size_t>(colours);
  if (bits_per_pixel != 32 || bytes.size() < start + line * static_cast<std::size_t>(height))
    return shot;
  shot.width = static_cast<int>(width);
  shot.height = static_cast<int>(height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      const auto* p =
          reinterpret_cast<const unsigned char*>(bytes.data()) + start + y * line + 4 * x;
      const std::uint32_t v =
          byte_order == 0
              ? (p[0] | p[1] << 8 | p[2] << 16 | static_cast<std::uint32_t>(p[3]) << 24)
              : (static_cast<std::uint32_t>(p[0]) << 24 | p[1] << 16 | p[2] << 8 | p[3]);
      const bool red_high = red_mask == 0xff0000;
      shot.rgb.push_back(static_cast<std::uint8_t>(red_high ? v >> 16 : v));
      shot.rgb.push_back(static_cast<std::uint8_t>(v >> 8));
      shot.rgb.push_back(static_cast<std::uint8_t>(red_high ? v : v >> 16));
    }
  return shot;
}

// The fraction of pixels of the region [x0, x1) x [y0, y1) where two pictures differ by more
// than `levels` in some channel.
template <class A, class B>
double fraction_different(const A& a, const B& b, int x0, int y0, int x1, int y1, int levels) {
  std::size_t differing = 0, total = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const auto p = a(x, y), q = b(x, y);
      bool d = false;
      for (int c = 0; c < 3; ++c) d = d || std::abs(p[c] - q[c]) > levels;
      differing += d;
      ++total;
    }
  return static_cast<double>(differing) / std::max<std::size_t>(total, 1);
}

std::array<int, 3> png_level(const Image& image, int x, int y) {
  const Rgb c = image.texel(x, y);
  return {static_cast<int>(std::lround(255 * srgb_encode(c.r))),
          static_cast<int>(std::lround(255 * srgb_encode(c.g))),
          static_cast<int>(std::lround(255 * srgb_encode(c.b)))};
}

class ViewerTest : public test::TempDirTest {
 protected:
  void SetUp() override {
    test::TempDirTest::SetUp();
    display_ = fmt::format(":{}", 50 + getpid() % 200);
    xvfb_ = fork();
    if (xvfb_ == 0) {
      unsetenv("LD_PRELOAD");  // the X server is not under test (scripts/sanitize.sh)
      execlp("Xvfb", "Xvfb", display_.c_str(), "-screen", "0", "1024x768x24", "-nolisten", "tcp",
             static_cast<char*>(nullptr));
      _exit(127);
    }
    const fs::path socket = "/tmp/.X11-unix/X" + display_.substr(1);
    for (int i = 0; i < 100 && !fs::exists(socket); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_TRUE(fs::exists(socket)) << "Xvfb did not start (is the xvfb package installed?)";
  }
  void TearDown() override {
    if (viewer_ > 0) {
      kill(viewer_, SIGKILL);
      waitpid(viewer_, nullptr, 0);
    }
    if (xvfb_ > 0) {
      kill(xvfb_, SIGTERM);
      waitpid(xvfb_, nullptr, 0);
    }
    test::TempDirTest::TearDown();
  }

  // Starts `lightcone view` on the virtual display in the test's folder.
  void start_viewer(const fs::path& scene, const std::string& options) {
    viewer_ = fork();
    if (viewer_ == 0) {
      if (chdir(dir_.c_str()) != 0) _exit(126);
      setenv("DISPLAY", display_.c_str(), 1);
      const std::string err = (dir_ / "viewer.err").string();
      if (!freopen(err.c_str(), "w", stderr)) _exit(126);
      const std::string out = (dir_ / "viewer.out").string();
      if (!freopen(out.c_str(), "w", stdout)) _exit(126);
      const std::string command =
          std::string("exec '") + LIGHTCONE_BINARY + "' view '" + scene.string() + "' " + options;
      execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    const std::string found = output_of(
        "DISPLAY=" + display_ + " timeout 30 xdotool search --sync --name 'lightcone view'");
    window_ = found.substr(0, found.find('\n'));
    ASSERT_FALSE(window_.empty()) << "no viewer window: " << test::bytes_of(dir_ / "viewer.err");
  }

  void key(const std::string& name) {
    output_of("DISPLAY=" + display_ + " xdotool key --window " + window_ + " " + name);
  }

  Screenshot screenshot() {
    return parse_xwd(output_of("DISPLAY=" + display_ + " xwd -silent -id " + window_));
  }

  // Waits until the folder holds `count` screenshots of the viewer's, and returns the last.
  fs::path wait_for_png(int count) {
    const fs::path file = dir_ / fmt::format("lightcone-view-{:04d}.png", count);
    for (int i = 0; i < 200 && !fs::exists(file); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // renamed into place whole
    return file;
  }

  // A click of the left button at window point (x, y).
  void click(int x, int y) {
    output_of(fmt::format("DISPLAY={} xdotool mousemove --window {} {} {} click 1", display_,
                          window_, x, y));
  }

  // Lets a few frames pass.
  static void settle() { std::this_thread::sleep_for(std::chrono::milliseconds(1500)); }

  std::string display_, window_;
  pid_t xvfb_ = -1, viewer_ = -1;
};

TEST_F(ViewerTest, ShowsTheSceneChangesSpeedOnAKeySavesPngsAndQuits) {
  const fs::path scene = write("scene.json", kScene);
  // The camera's clock stands still; both sides cut edges on the CPU, so that the automatic
  // choice of a path cannot make them differ.
  start_viewer(scene, "--time-scale 0 --tessellation cpu");
  settle();
  const Screenshot first = screenshot();
  ASSERT_EQ(first.width, 800);
  ASSERT_EQ(first.height, 500);

  // F12: the view as `lightcone render --renderer raster` renders it, and the window shows it
  // (away from the panel in the top left corner).
  key("F12");
  const fs::path png = wait_for_png(1);
  ASSERT_TRUE(fs::exists(png)) << test::bytes_of(dir_ / "viewer.err");
  const auto saved = load_image_file(png);
  const auto rendered = test::run_lightcone("render '" + scene.string() +
                                            "' --renderer raster --tessellation cpu --quiet -o '" +
                                            (dir_ / "rendered.png").string() + "'");
  ASSERT_EQ(rendered.status, 0) << rendered.err;
  const auto reference = load_image_file(dir_ / "rendered.png");
  const auto saved_at = [&](int x, int y) { return png_level(*saved, x, y); };
  const auto reference_at = [&](int x, int y) { return png_level(*reference, x, y); };
  const auto first_at = [&](int x, int y) { return first.at(x, y); };
  EXPECT_LT(fraction_different(saved_at, reference_at, 0, 0, 800, 500, 1), 0.001);
  EXPECT_LT(fraction_different(first_at, saved_at, 450, 300, 800, 500, 2), 0.001);

  // W: faster by a tenth of rapidity (tanh(atanh(0.5) + 0.1) = 0.5712), said on stderr, shown
  // in the panel, and the picture changes.
  key("w");
  settle();
  EXPECT_NE(test::bytes_of(dir_ / "viewer.err").find("speed 0.5712 c"), std::string::npos)
      << test::bytes_of(dir_ / "viewer.err");
  const Screenshot second = screenshot();
  const auto second_at = [&](int x, int y) { return second.at(x, y); };
  EXPECT_GT(fraction_different(first_at, second_at, 0, 0, 300, 120, 2), 0.001);  // the panel
  EXPECT_GT(fraction_different(first_at, second_at, 450, 300, 800, 500, 2), 0.05);
  key("F12");
  ASSERT_TRUE(fs::exists(wait_for_png(2)));

  key("Escape");
  int status = -1;
  for (int i = 0; i < 100; ++i) {
    if (waitpid(viewer_, &status, WNOHANG) == viewer_) {
      viewer_ = -1;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_EQ(viewer_, -1) << "Esc did not quit";
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

// The viewer exposes itself: flying into terrell.json at 0.9c, the relativistic half of the
// split view (blueshifted and searchlit ahead) is metered and stays readable; held at the
// exposure the scene is metered at when the camera is at rest (5.6 EV), a part clips.
TEST_F(ViewerTest, AutomaticExposureKeepsTheRelativisticHalfUnclipped) {
  const fs::path scene = fs::path(LIGHTCONE_SOURCE_DIR) / "scenes/terrell.json";
  const auto clipped_share = [&](const Screenshot& shot) {
    std::size_t clipped = 0, pixels = 0;
    for (int y = 0; y < shot.height; ++y)
      for (int x = shot.width / 2; x < shot.width; ++x, ++pixels) {
        const auto c = shot.at(x, y);
        clipped += c[0] == 255 || c[1] == 255 || c[2] == 255;
      }
    return static_cast<double>(clipped) / pixels;
  };
  const std::string options =
      "--split --time-scale 0 --width 800 --height 450 --set 'camera.velocity=[0,0,-0.9]'";
  start_viewer(scene, options);
  settle();
  const Screenshot metered = screenshot();
  ASSERT_EQ(metered.width, 800);
  EXPECT_LE(clipped_share(metered), 0.02);
  key("Escape");
  waitpid(viewer_, nullptr, 0);
  viewer_ = -1;
  start_viewer(scene, options + " --set render.exposure=5.6");
  settle();
  EXPECT_GE(clipped_share(screenshot()), 0.08);  // 0.13 when written
}

// The viewer on a slide: the split view carries its caption (classical | relativistic, with
// beta) in the window and in the PNG F12 saves; P (presenting) hides the panel and keeps the
// caption.
TEST_F(ViewerTest, TheSplitViewIsCaptionedAndPresentingHidesThePanel) {
  const fs::path scene = write("scene.json", kScene);
  start_viewer(scene, "--split --time-scale 0 --tessellation cpu");
  settle();
  const auto white_in_caption = [](const auto& at, int width) {
    int white = 0;
    for (int y = 0; y < kCaptionHeight; ++y)
      for (int x = width / 4; x < 3 * width / 4; ++x) {
        const auto c = at(x, y);
        white += c[0] > 240 && c[1] > 240 && c[2] > 240;
      }
    return white;
  };
  const Screenshot shown = screenshot();
  const auto shown_at = [&](int x, int y) { return shown.at(x, y); };
  EXPECT_GT(white_in_caption(shown_at, shown.width), 40);
  key("F12");
  const fs::path png = wait_for_png(1);
  ASSERT_TRUE(fs::exists(png)) << test::bytes_of(dir_ / "viewer.err");
  const auto saved = load_image_file(png);
  const auto saved_at = [&](int x, int y) { return png_level(*saved, x, y); };
  EXPECT_GT(white_in_caption(saved_at, saved->width), 40);
  // P: the panel (top left, under the caption) goes; the caption stays.
  key("p");
  settle();
  const Screenshot presenting = screenshot();
  const auto presenting_at = [&](int x, int y) { return presenting.at(x, y); };
  EXPECT_GT(fraction_different(shown_at, presenting_at, 0, kCaptionHeight + 4, 200, 80, 8), 0.2);
  EXPECT_GT(white_in_caption(presenting_at, presenting.width), 40);
}

// R: the view as the scene starts it, however far it was flown: the camera's speed, direction
// and clock undone. The clock runs (1 a second), so the camera, at 0.5c, has flown a unit and
// more before R; after it, the picture is the scene's at its own time to within a frame or two.
TEST_F(ViewerTest, RResetsTheViewToTheScenesCameraAndTime) {
  const fs::path scene = write("scene.json", kScene);
  start_viewer(scene, "--time-scale 1 --tessellation cpu");
  settle();
  key("w");
  output_of("DISPLAY=" + display_ + " xdotool keydown --window " + window_ +
            " Left sleep 0.4 keyup --window " + window_ + " Left");
  settle();
  key("F12");
  const fs::path lost_png = wait_for_png(1);
  ASSERT_TRUE(fs::exists(lost_png)) << test::bytes_of(dir_ / "viewer.err");
  key("r F12");
  const fs::path back_png = wait_for_png(2);
  ASSERT_TRUE(fs::exists(back_png)) << test::bytes_of(dir_ / "viewer.err");
  EXPECT_NE(test::bytes_of(dir_ / "viewer.err").find("lightcone: back at the scene's camera"),
            std::string::npos)
      << test::bytes_of(dir_ / "viewer.err");
  const auto rendered = test::run_lightcone("render '" + scene.string() +
                                            "' --renderer raster --tessellation cpu --quiet -o '" +
                                            (dir_ / "rendered.png").string() + "'");
  ASSERT_EQ(rendered.status, 0) << rendered.err;
  const auto reference = load_image_file(dir_ / "rendered.png");
  const auto lost = load_image_file(lost_png), back = load_image_file(back_png);
  const auto reference_at = [&](int x, int y) { return png_level(*reference, x, y); };
  const auto lost_at = [&](int x, int y) { return png_level(*lost, x, y); };
  const auto back_at = [&](int x, int y) { return png_level(*back, x, y); };
  const double before = fraction_different(lost_at, reference_at, 0, 0, 800, 500, 2);
  const double after = fraction_different(back_at, reference_at, 0, 0, 800, 500, 2);
  std::printf("differing from the scene's own picture: %.4f before R, %.4f after\n", before, after);
  EXPECT_GT(before, 0.3);
  EXPECT_LT(after, 0.15);  // 0.034 when written: the frame or two the clock ran since R
}

// A click probes the pixel under it as `lightcone locate --pixel` does, printing the same JSON
// line on stdout; the F12 PNG carries the readouts (a band along its bottom, a ring at each
// point) until X clears them.
TEST_F(ViewerTest, AClickProbesThePixelAsLocateDoes) {
  const fs::path scene = write("scene.json", kScene);
  const auto centre = nlohmann::json::parse(
      test::run_lightcone("locate '" + scene.string() + "' --object ball --point 0,0,0").out);
  const int ball_x = static_cast<int>(centre["pixel"][0].get<double>());
  const int ball_y = static_cast<int>(centre["pixel"][1].get<double>());
  start_viewer(scene, "--time-scale 0 --tessellation cpu");
  settle();
  // Each probe's line, waited for (a loaded machine draws a few frames a second).
  const auto wait_for_probes = [&](std::size_t count) {
    for (int i = 0; i < 300; ++i) {
      const std::string out = test::bytes_of(dir_ / "viewer.out");
      if (static_cast<std::size_t>(std::count(out.begin(), out.end(), '\n')) >= count) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  };
  click(ball_x, ball_y);
  wait_for_probes(1);
  click(700, 40);  // the sky, away from the panel
  wait_for_probes(2);
  settle();
  key("F12");
  const fs::path with_readouts = wait_for_png(1);
  key("x F12");
  const fs::path cleared = wait_for_png(2);
  ASSERT_TRUE(fs::exists(cleared)) << test::bytes_of(dir_ / "viewer.err");

  std::istringstream lines(test::bytes_of(dir_ / "viewer.out"));
  std::vector<nlohmann::json> probes;
  for (std::string line; std::getline(lines, line);) probes.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(probes.size(), 2u) << test::bytes_of(dir_ / "viewer.out");
  EXPECT_EQ(probes[0]["meets"], "object");
  EXPECT_EQ(probes[0]["object"], "ball");
  EXPECT_EQ(probes[1]["meets"], "sky");
  for (const nlohmann::json& probe : probes) {
    const double x = probe["pixel"][0], y = probe["pixel"][1];
    EXPECT_EQ(x - std::floor(x), 0.5);  // the centre of the pixel clicked
    const auto cli = nlohmann::json::parse(
        test::run_lightcone(fmt::format("locate '{}' --pixel {},{}", scene.string(), x, y)).out);
    ASSERT_EQ(cli.size(), probe.size());
    for (const auto& [key, value] : cli.items()) {
      SCOPED_TRACE(key);
      if (value.is_number()) {
        EXPECT_NEAR(probe[key].get<double>(), value.get<double>(), 1e-9);
      } else if (value.is_array() && value.size() == 3) {
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(probe[key][k].get<double>(), value[k].get<double>(), 1e-9);
      } else {
        EXPECT_EQ(probe[key], value);
      }
    }
  }
  // The readouts darken the PNG's bottom rows (a band under their text); cleared, it is the view.
  const auto marked = load_image_file(with_readouts), plain = load_image_file(cleared);
  const auto marked_at = [&](int x, int y) { return png_level(*marked, x, y); };
  const auto plain_at = [&](int x, int y) { return png_level(*plain, x, y); };
  EXPECT_GT(fraction_different(marked_at, plain_at, 0, 440, 800, 500, 8), 0.5);
  EXPECT_LT(fraction_different(marked_at, plain_at, 0, 0, 800, 400, 8), 0.01);
}

// Near a black hole the clock runs at the scene's own scale unless told: infall.json's clocks,
// falling from 10M (35.1M of their own time), fall in 10 s.
TEST_F(ViewerTest, NearAHoleTheClockShowsAFallInSeconds) {
  start_viewer(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes/infall.json",
               "--width 320 --height 180 --tessellation cpu");
  settle();
  const std::string err = test::bytes_of(dir_ / "viewer.err");
  EXPECT_NE(err.find("lightcone: near the black hole time runs at 3.51 of the camera's own a "
                     "second (the scene's shortest free fall in 10 s)"),
            std::string::npos)
      << err;
}

TEST(ViewerBenchmark, RendersItsFramesWithoutADisplayAndPrintsOneJsonLine) {
  const fs::path dir = test::fresh_temp_dir("benchmark");
  test::write_text(dir / "scene.json", kScene);
  const auto r = test::run_lightcone(
      "view '" + (dir / "scene.json").string() + "' --benchmark 5 --width 160 --height 100",
      "env -u DISPLAY -u WAYLAND_DISPLAY");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto line = nlohmann::json::parse(r.out);
  EXPECT_EQ(line["frames"], 5);
  EXPECT_GT(line["fps"].get<double>(), 0);
  EXPECT_GT(line["triangles"].get<double>(), 100);
  fs::remove_all(dir);
}

// Near a black hole the viewer draws the sky, the disk and the shadow along curved rays, every
// frame's tables of rays built anew (the scripted flight moves the camera toward the hole).
TEST(ViewerBenchmark, DrawsTheBlackHoleScene) {
  const std::string scene = test::quoted(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes/black-hole.json");
  const auto r = test::run_lightcone("view " + scene + " --benchmark 5 --width 160 --height 90",
                                     "env -u DISPLAY -u WAYLAND_DISPLAY");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto line = nlohmann::json::parse(r.out);
  EXPECT_EQ(line["frames"], 5);
  EXPECT_GT(line["fps"].get<double>(), 0);
  EXPECT_EQ(line["triangles"], 0);
}

// The scripted flight heads into the hole from r = 3.5M at up to 0.9c: the camera stops at
// r = 2.01M, outside the horizon, and every frame is drawn.
TEST(ViewerBenchmark, StopsOutsideTheHorizon) {
  const fs::path dir = test::fresh_temp_dir("benchmark_hole");
  test::write_text(dir / "scene.json", R"({
    "camera": {"position": [0, 0, 3.5], "forward": [0, 0, -1], "fov": 120},
    "black_hole": {"mass": 1, "disk": {}}
  })");
  const auto r = test::run_lightcone(
      "view " + test::quoted(dir / "scene.json") + " --benchmark 90 --width 64 --height 36",
      "env -u DISPLAY -u WAYLAND_DISPLAY");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["frames"], 90);
  fs::remove_all(dir);
}

// A camera that has fallen through the horizon (scenes/plunge.json, r = 1.6M) is drawn from
// there; boosts are refused inside, so the scripted flight leaves it falling.
TEST(ViewerBenchmark, DrawsTheViewFromInsideTheHorizon) {
  const auto r = test::run_lightcone(
      "view " + test::quoted(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes/plunge.json") +
          " --benchmark 5 --width 64 --height 36",
      "env -u DISPLAY -u WAYLAND_DISPLAY");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["frames"], 5);
}

TEST(ViewerWithoutOpenGl, RasterRenderAndBenchmarkAreStatusTwoNamingOpenGl) {
  // No EGL driver at all (libglvnd is pointed at none): a clear error, nothing written.
  const fs::path dir = test::fresh_temp_dir("nogl");
  test::write_text(dir / "scene.json", kScene);
  const std::string no_driver = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json";
  const auto render =
      test::run_lightcone("render '" + (dir / "scene.json").string() + "' --renderer raster -o '" +
                              (dir / "out.png").string() + "'",
                          no_driver);
  EXPECT_EQ(render.status, 2);
  EXPECT_NE(render.err.find("needs OpenGL 3.3"), std::string::npos) << render.err;
  EXPECT_FALSE(fs::exists(dir / "out.png"));
  const auto benchmark =
      test::run_lightcone("view '" + (dir / "scene.json").string() + "' --benchmark 2", no_driver);
  EXPECT_EQ(benchmark.status, 2);
  EXPECT_NE(benchmark.err.find("needs OpenGL 3.3"), std::string::npos) << benchmark.err;
  fs::remove_all(dir);
}

TEST(ViewerWithoutDisplay, IsStatusTwoNamingDisplayAndTheHeadlessWays) {
  const fs::path dir = test::fresh_temp_dir("nodisplay");
  test::write_text(dir / "scene.json", kScene);
  const auto r = test::run_lightcone("view '" + (dir / "scene.json").string() + "'",
                                     "env -u DISPLAY -u WAYLAND_DISPLAY");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("DISPLAY"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--benchmark"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--renderer raster"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lightcone

// `lightcone animate`'s automatic exposure: each frame metered on the lattice of its own render
// (one pixel of each 4 x 4 block, every sample), frame i exposed at the mean of the metered EVs
// of the animation's frames within half a second; frames outside the run metered on a render of
// the lattice alone, which equals those pixels of the whole render exactly.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/scene/animation.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using test::bytes_of;
using test::quoted;
using test::run_lightcone;

// Pixel k of the lattice of stride 4 along `extent` pixels: the middle of block k, or the last
// pixel where the image's edge cuts the block short.
int lattice_at(int k, int extent) {
  return std::min(4 * k + 2, extent - 1);
}

// The lattice of stride 4 of `per_pixel` floats a pixel, picked here pixel by pixel.
std::vector<float> every_fourth(const std::vector<float>& values, int width, int height,
                                int per_pixel) {
  std::vector<float> out;
  for (int b = 0; b < (height + 3) / 4; ++b)
    for (int a = 0; a < (width + 3) / 4; ++a)
      for (int c = 0; c < per_pixel; ++c)
        out.push_back(values[(static_cast<std::size_t>(lattice_at(b, height)) * width +
                              lattice_at(a, width)) *
                                 per_pixel +
                             c]);
  return out;
}

// The lattice render (RenderOptions::lattice) against the whole render's lattice pixels, colour
// and subject weights, float for float: flat and curved space, stars, a shutter, a crop, sizes
// that are not multiples of 4.
TEST(LatticeRender, EqualsTheWholeRendersPixelsExactly) {
  struct Case {
    const char* scene;
    int width, height, samples;
    double shutter;
    std::optional<PixelWindow> crop;
  } cases[] = {
      {"terrell.json", 37, 23, 2, 0, std::nullopt},
      {"terrell.json", 40, 24, 3, 0.5, std::nullopt},
      {"terrell.json", 64, 36, 1, 0, PixelWindow{5, 3, 38, 30}},
      {"stars.json", 41, 26, 1, 0, std::nullopt},
      {"black-hole.json", 29, 18, 1, 0, std::nullopt},
  };
  for (const Case& c : cases) {
    Scene scene = test::load_repository_scene(c.scene);
    scene.camera.width = c.width;
    scene.camera.height = c.height;
    scene.camera.samples = c.samples;
    scene.camera.shutter = c.shutter;
    scene.render.auto_exposure = false;
    scene.render.exposure = 0;
    RenderOptions whole_options;
    whole_options.crop = c.crop;
    std::vector<float> whole_subject, lattice_subject;
    whole_options.subject = &whole_subject;
    const Image whole = render_image(scene, whole_options);
    RenderOptions lattice_options = whole_options;
    lattice_options.lattice = 4;
    lattice_options.subject = &lattice_subject;
    const Image lattice = render_image(scene, lattice_options);
    const std::string name = fmt::format("{} {}x{}", c.scene, whole.width, whole.height);
    EXPECT_EQ(lattice.width, (whole.width + 3) / 4) << name;
    EXPECT_EQ(lattice.height, (whole.height + 3) / 4) << name;
    EXPECT_EQ(lattice.rgb, every_fourth(whole.rgb, whole.width, whole.height, 3)) << name;
    EXPECT_EQ(lattice_subject, every_fourth(whole_subject, whole.width, whole.height, 1)) << name;
    // Something to compare: light, and (flat space) a subject.
    EXPECT_GT(*std::max_element(lattice.rgb.begin(), lattice.rgb.end()), 0.0f) << name;
    if (std::string(c.scene) == "terrell.json") {
      EXPECT_GT(*std::max_element(lattice_subject.begin(), lattice_subject.end()), 0.0f) << name;
    }
  }
}

// A moving ball that shines for two seconds and goes dark for two (a blink of period 4), before
// a grey wall at rest: the automatic exposure follows it.
const std::string kBlink = std::string(LIGHTCONE_SOURCE_DIR) + "/tests/data/blink.json";
constexpr double kFps = 8;  // half a second either side: 4 frames

class AnimateExposure : public test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    blink_ = kBlink;
  }
  // Animates `frames` of the blink (more options after them) into PNGs and EXRs named prefix%02d.
  void animate(const std::string& frames, const std::string& prefix) const {
    const auto r =
        run_lightcone("animate " + quoted(blink_) + fmt::format(" --fps {}", kFps) + " --frames " +
                      frames + " -o " + quoted(dir_ / (prefix + "%02d.png")) + " --exr " +
                      quoted(dir_ / (prefix + "%02d.exr")) + " --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
  }
  double ev_written(const std::string& prefix, int i) const {
    const auto image = load_image_file(dir_ / fmt::format("{}{:02d}.exr", prefix, i));
    EXPECT_TRUE(image && image->exposure) << prefix << i;
    return image && image->exposure ? *image->exposure : NAN;
  }
  // Frame j's metered EV, found here: its whole render at exposure 0, the automatic exposure of
  // that render's lattice pixels with their subject weights.
  double metered(int j) const {
    SceneLoadReport report;
    const Scene scene = load_scene_file(blink_, {}, report);
    Scene frame;
    EXPECT_FALSE(animation_frame(scene, j, kFps, AnimationClock::kCamera, frame));
    frame.render.auto_exposure = false;
    frame.render.exposure = 0;
    std::vector<float> subject;
    RenderOptions options;
    options.subject = &subject;
    const Image linear = render_image(frame, options);
    Image lattice;
    lattice.width = (linear.width + 3) / 4;
    lattice.height = (linear.height + 3) / 4;
    lattice.rgb = every_fourth(linear.rgb, linear.width, linear.height, 3);
    return auto_exposure(lattice, frame.render.tonemap,
                         every_fourth(subject, linear.width, linear.height, 1));
  }
  fs::path blink_;
};

// Frame i's EV is the mean of the metered EVs of frames i - 4 to i + 4 of the animation (the
// run's frames unless --animation says more); a one-frame animation's is its own lattice's.
TEST_F(AnimateExposure, AFramesEvIsTheMeanOfItsWindowsLatticeEvs) {
  animate("6-15", "a");
  std::vector<double> ev(16, NAN);
  for (int j = 6; j <= 15; ++j) ev[j] = metered(j);
  for (int i = 6; i <= 15; ++i) {
    double sum = 0;
    int n = 0;
    for (int j = std::max(i - 4, 6); j <= std::min(i + 4, 15); ++j) sum += ev[j], ++n;
    EXPECT_DOUBLE_EQ(ev_written("a", i), sum / n) << i;
  }
  // The blink's change, seen between frames 8 and 12, moves the exposure by several EV.
  EXPECT_GT(std::abs(ev[15] - ev[6]), 3.0);
  animate("9-9", "one");
  EXPECT_DOUBLE_EQ(ev_written("one", 9), ev[9]);
}

// Frames 4-13 in one run, and in two runs of 4-8 and 9-13 told --animation 4-13 (a job array's
// tasks), are the same files, by both renderers.
TEST_F(AnimateExposure, SplitRunsGivenTheAnimationWriteTheSameFiles) {
  for (const std::string renderer : {"trace", "raster"}) {
    const std::string options = " --renderer " + renderer;
    animate("4-13" + options, renderer + "-whole");
    animate("4-8 --animation 4-13" + options, renderer + "-split");
    animate("9-13 --animation 4-13" + options, renderer + "-split");
    for (int i = 4; i <= 13; ++i)
      for (const char* extension : {"png", "exr"})
        EXPECT_EQ(bytes_of(dir_ / fmt::format("{}-whole{:02d}.{}", renderer, i, extension)),
                  bytes_of(dir_ / fmt::format("{}-split{:02d}.{}", renderer, i, extension)))
            << renderer << " frame " << i << " " << extension;
    // Without --animation, a run's window stops at its own frames: frame 8 is then exposed
    // without frames 9-12.
    animate("4-8" + options, renderer + "-alone");
    EXPECT_NE(ev_written(renderer + "-alone", 8), ev_written(renderer + "-whole", 8)) << renderer;
  }
}

// --resume renders the missing and unusable frames again, exposed as before: the frames kept on
// disk are metered on their lattice for their neighbours.
TEST_F(AnimateExposure, ResumedFramesAreExposedAsBefore) {
  animate("4-15", "f");
  std::vector<std::string> before;
  for (int i = 4; i <= 15; ++i) {
    before.push_back(bytes_of(dir_ / fmt::format("f{:02d}.png", i)));
    before.push_back(bytes_of(dir_ / fmt::format("f{:02d}.exr", i)));
  }
  for (const int i : {5, 9, 14}) {
    fs::remove(dir_ / fmt::format("f{:02d}.png", i));
    fs::remove(dir_ / fmt::format("f{:02d}.exr", i));
  }
  test::write_text(dir_ / "f11.png", "not a picture");
  const auto r = run_lightcone("animate " + quoted(blink_) + fmt::format(" --fps {}", kFps) +
                               " --frames 4-15 --resume -o " + quoted(dir_ / "f%02d.png") +
                               " --exr " + quoted(dir_ / "f%02d.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("4 rendered, 8 already there"), std::string::npos) << r.err;
  std::vector<std::string> after;
  for (int i = 4; i <= 15; ++i) {
    after.push_back(bytes_of(dir_ / fmt::format("f{:02d}.png", i)));
    after.push_back(bytes_of(dir_ / fmt::format("f{:02d}.exr", i)));
  }
  EXPECT_EQ(after, before);
}

// A moment the scene cannot be shown at stops the run there, after the frames waiting for their
// exposure are written, exposed as a run that stops before it would expose them (the moment
// counts for none). The camera accelerates along +x and the ball comes the other way at gamma
// 100: by proper time 9.5 their relative gamma, about 200 cosh(9.5), is past the limit.
TEST_F(AnimateExposure, ARefusedMomentStopsTheRunAfterTheFramesBeforeIt) {
  const fs::path file = write("scene.json", R"({
  "camera": {"position": [0, 0, 0], "forward": [0, 0, -1], "width": 16, "height": 9,
             "motion": {"phases": [{"duration": 12, "acceleration": [1, 0, 0]}]}},
  "objects": [{"name": "ball", "shape": {"sphere": {"radius": 1}}, "position": [5, 0, -5],
               "velocity": [-0.9999499987499375, 0, 0]}]
})");
  // At 2 frames a second the exposure is smoothed over a frame either side.
  const std::string common = " --fps 2 --samples 1 --quiet -o ";
  const auto r = run_lightcone("animate " + quoted(file) + " --frames 15-19" + common +
                               quoted(dir_ / "f%02d.exr"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "lightcone: frame 19: by then ball moves too close to the speed of light relative to "
            "the camera (gamma 1.34e+06; at most 1e+06)\n");
  const auto before =
      run_lightcone("animate " + quoted(file) + " --frames 15-18 --animation 15-19" + common +
                    quoted(dir_ / "g%02d.exr"));
  ASSERT_EQ(before.status, 0) << before.err;
  for (int i = 15; i <= 18; ++i)
    EXPECT_EQ(bytes_of(dir_ / fmt::format("f{:02d}.exr", i)),
              bytes_of(dir_ / fmt::format("g{:02d}.exr", i)))
        << i;
  EXPECT_FALSE(fs::exists(dir_ / "f19.exr"));
}

TEST_F(AnimateExposure, ABadAnimationIsRefusedAndWritesNothing) {
  const std::string png = " -o " + quoted(dir_ / "out" / "f%d.png");
  fs::create_directories(dir_ / "out");
  struct Case {
    std::string arguments, message;
  } cases[] = {
      {" --frames 0-9 --animation 2-20",
       "--animation 2-20: the animation must hold the frames 0 to 9 this run renders"},
      {" --frames 4-9 --animation 0-8",
       "--animation 0-8: the animation must hold the frames 4 to 9 this run renders"},
      {" --frames 3-3 --animation 4-9",
       "--animation 4-9: the animation must hold the frame 3 this run renders"},
      {" --duration 1 --animation 1-20",
       "--animation 1-20: the animation must hold the frames 0 to 7 this run renders"},
      {" --frames 0-9 --animation 9-3", "--animation 9-3: the range is reversed (9 after 3)"},
      {" --frames 0-9 --animation 12",
       "--animation 12: expected A-B, the first and last frame numbers (0 <= A <= B)"},
  };
  for (const Case& c : cases) {
    const auto r = run_lightcone("animate " + quoted(blink_) + fmt::format(" --fps {}", kFps) +
                                 c.arguments + png);
    EXPECT_EQ(r.status, 2) << c.arguments << ": " << r.err;
    EXPECT_EQ(r.err, "lightcone: " + c.message + "\n") << c.arguments;
  }
  EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "something was written";
}

}  // namespace
}  // namespace lightcone

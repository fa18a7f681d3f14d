// `lightcone animate` and `lightcone encode`: frames at successive moments of the camera's
// clock, each the render of that moment; videos through ffmpeg; split and resumed runs.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "lightcone/io/image_file.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using test::bytes_of;
using test::have_program;
using test::quoted;
using test::run_lightcone;

class Animate : public test::TempDirTest {
 protected:
  fs::path scene(const std::string& name) const {
    return fs::path(LIGHTCONE_SOURCE_DIR) / "scenes" / name;
  }
  // A small, quick version of a bundled scene's frames, at a fixed exposure (an automatic one is
  // smoothed over the frames, AutomaticExposureFollowsSmoothlyAndSplitRunsJoinUp).
  std::string small() const {
    return " --width 96 --height 54 --samples 1 --quiet --set render.exposure=0";
  }
};

TEST_F(Animate, FrameIIsTheRenderAtThatProperTime) {
  // An accelerated camera (the rocket, proper time 2 + i / 4) and an inertial one (the
  // Terrell scene, proper time 0 + i / 4), pixel for pixel.
  for (const auto& [name, start] :
       {std::pair{"rocket.json", 2.0}, std::pair{"terrell.json", 0.0}}) {
    const auto r = run_lightcone("animate " + quoted(scene(name)) + " --fps 4 --frames 0-5 -o " +
                                 quoted(dir_ / "f-%02d.png") + small());
    ASSERT_EQ(r.status, 0) << r.err;
    for (const int i : {0, 3, 5}) {
      const fs::path single = dir_ / "single.png";
      const auto s =
          run_lightcone("render " + quoted(scene(name)) + " -o " + quoted(single) + small() +
                        " --set camera.proper_time=" + fmt::format("{:.17g}", start + i / 4.0));
      ASSERT_EQ(s.status, 0) << s.err;
      EXPECT_EQ(bytes_of(single), bytes_of(dir_ / fmt::format("f-{:02d}.png", i)))
          << name << " frame " << i;
    }
    // The frames differ from one another: the camera's clock moves.
    EXPECT_NE(bytes_of(dir_ / "f-00.png"), bytes_of(dir_ / "f-05.png")) << name;
  }
}

TEST_F(Animate, TheWorldClockStepsWorldTime) {
  // An inertial camera at 0.6c: world time steps of 1/4 are proper time steps of 0.2.
  const std::string moving = " --set 'camera.velocity=[0.6,0,0]'";
  ASSERT_EQ(run_lightcone("animate " + quoted(scene("terrell.json")) +
                          " --fps 4 --frames 2-2 --clock world -o " + quoted(dir_ / "w%d.png") +
                          small() + moving)
                .status,
            0);
  ASSERT_EQ(run_lightcone("animate " + quoted(scene("terrell.json")) + " --fps 5 --frames 2-2 -o " +
                          quoted(dir_ / "p%d.png") + small() + moving)
                .status,
            0);
  const auto a = load_image_file(dir_ / "w2.png"), b = load_image_file(dir_ / "p2.png");
  EXPECT_LT(test::fraction_differing(*a, *b), 0.001);
}

TEST_F(Animate, SplitRangesMakeTheSameFramesAndResumeRendersOnlyTheMissingOnes) {
  const std::string common = " --fps 8" + small();
  const std::string rocket = quoted(scene("rocket.json"));
  ASSERT_EQ(
      run_lightcone("animate " + rocket + " --frames 0-5 -o " + quoted(dir_ / "a%d.png") + common)
          .status,
      0);
  ASSERT_EQ(
      run_lightcone("animate " + rocket + " --frames 0-2 -o " + quoted(dir_ / "b%d.png") + common)
          .status,
      0);
  ASSERT_EQ(
      run_lightcone("animate " + rocket + " --frames 3-5 -o " + quoted(dir_ / "b%d.png") + common)
          .status,
      0);
  for (int i = 0; i <= 5; ++i)
    EXPECT_EQ(bytes_of(dir_ / fmt::format("a{}.png", i)),
              bytes_of(dir_ / fmt::format("b{}.png", i)))
        << i;
  // Remove two frames; --resume renders just those two, and they come back the same.
  const std::string kept = bytes_of(dir_ / "b4.png");
  fs::remove(dir_ / "b1.png");
  fs::remove(dir_ / "b4.png");
  const auto r = run_lightcone("animate " + rocket + " --frames 0-5 --resume --fps 8 -o " +
                               quoted(dir_ / "b%d.png") +
                               " --width 96 --height 54 --samples 1 --set render.exposure=0");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("2 rendered, 4 already there"), std::string::npos) << r.err;
  EXPECT_EQ(bytes_of(dir_ / "b4.png"), kept);
  EXPECT_EQ(bytes_of(dir_ / "b1.png"), bytes_of(dir_ / "a1.png"));
}

// A moving ball that shines for two seconds and goes dark for two (a blink of period 4), before
// a grey wall at rest: each frame's own automatic exposure would jump 5 EV at the change;
// the animation's follows over the frames within half a second, and a run of some of the frames
// exposes them as the whole run does.
TEST_F(Animate, AutomaticExposureFollowsSmoothlyAndSplitRunsJoinUp) {
  // (tests/data/blink.json, at 64 x 36 and one sample)
  const fs::path file = fs::path(LIGHTCONE_SOURCE_DIR) / "tests/data/blink.json";
  const auto run = [&](const std::string& frames, const std::string& prefix) {
    const auto r = run_lightcone("animate " + quoted(file) +
                                 " --width 64 --height 36 --samples 1 --fps 8 --frames " + frames +
                                 " -o " + quoted(dir_ / (prefix + "%02d.exr")) + " --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
  };
  run("0-23", "all");
  // The EV of each frame, from the wall's radiance in the EXR (a corner pixel); the EXR's
  // header says the same.
  std::vector<double> ev;
  for (int i = 0; i <= 23; ++i) {
    const auto image = load_image_file(dir_ / fmt::format("all{:02d}.exr", i));
    ASSERT_TRUE(image);
    ev.push_back(std::log2(image->rgb[0] / 0.05));
    ASSERT_TRUE(image->exposure.has_value()) << i;
    EXPECT_NEAR(*image->exposure, ev.back(), 1e-6) << i;
  }
  double low = ev[0], high = ev[0], steepest = 0;
  for (std::size_t i = 1; i < ev.size(); ++i) {
    low = std::min(low, ev[i]), high = std::max(high, ev[i]);
    steepest = std::max(steepest, std::abs(ev[i] - ev[i - 1]));
  }
  EXPECT_GE(high - low, 3.0);    // it follows the subject
  EXPECT_LE(steepest, 5.7 / 8);  // a ninth of a jump (and rounding) a frame, not the jump
  run("10-13 --animation 0-23", "part");
  for (int i = 10; i <= 13; ++i)
    EXPECT_EQ(bytes_of(dir_ / fmt::format("part{:02d}.exr", i)),
              bytes_of(dir_ / fmt::format("all{:02d}.exr", i)))
        << i;
  // The raster renderer's frames, --exr beside a PNG, say their EV too.
  const auto rastered = run_lightcone(
      "animate " + quoted(file) + " --fps 8 --frames 0-1 --renderer raster -o " +
      quoted(dir_ / "raster%d.png") + " --exr " + quoted(dir_ / "raster%d.exr") + " --quiet");
  ASSERT_EQ(rastered.status, 0) << rastered.err;
  for (int i = 0; i <= 1; ++i) {
    const auto image = load_image_file(dir_ / fmt::format("raster{}.exr", i));
    ASSERT_TRUE(image->exposure.has_value()) << i;
    EXPECT_NEAR(*image->exposure, std::log2(image->rgb[0] / 0.05), 1e-6) << i;
  }
}

// The peak signal-to-noise ratio of two 8-bit images of one size, in dB.
double psnr(const Image& a, const Image& b) {
  const std::vector<unsigned char> x = display_rgb8(a), y = display_rgb8(b);
  double sum = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sum += (double(x[i]) - y[i]) * (double(x[i]) - y[i]);
  const double mse = sum / x.size();
  return mse == 0 ? 99 : 10 * std::log10(255.0 * 255.0 / mse);
}

TEST_F(Animate, VideosHaveTheCodecFramesSizeAndRateAskedForAndTheFrames) {
  if (!have_program("ffmpeg") || !have_program("ffprobe"))
    GTEST_SKIP() << "ffmpeg is not installed";
  const std::string rocket = quoted(scene("rocket.json"));
  struct Case {
    const char* file;
    const char* codec;
  } cases[] = {{"rocket.mp4", "h264"}, {"rocket.webm", "vp9"}, {"rocket.gif", "gif"}};
  for (const Case& c : cases) {
    const fs::path video = dir_ / c.file;
    const auto r = run_lightcone("animate " + rocket + " --fps 12 --frames 0-9 -o " +
                                 quoted(dir_ / "v%02d.png") + " --video " + quoted(video) +
                                 " --width 160 --height 90 --samples 1 --quiet");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto probe = test::run_command(
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=codec_name,width,height,r_frame_rate,nb_read_frames -of "
        "default=noprint_wrappers=1 " +
        quoted(video));
    ASSERT_EQ(probe.status, 0) << probe.err;
    EXPECT_NE(probe.out.find(std::string("codec_name=") + c.codec), std::string::npos) << probe.out;
    EXPECT_NE(probe.out.find("width=160"), std::string::npos) << probe.out;
    EXPECT_NE(probe.out.find("height=90"), std::string::npos) << probe.out;
    EXPECT_NE(probe.out.find("nb_read_frames=10"), std::string::npos) << probe.out;
    // A GIF's frame delays are whole hundredths of a second, and it has 256 colours: neither
    // its rate nor its fidelity is checked.
    if (std::string(c.codec) == "gif") continue;
    EXPECT_NE(probe.out.find("r_frame_rate=12/1"), std::string::npos) << probe.out;
    // The first and last decoded frames against the frame files.
    for (const int i : {0, 9}) {
      const fs::path decoded = dir_ / fmt::format("decoded-{}.png", i);
      const auto d = test::run_command(
          fmt::format("ffmpeg -v error -y -i {} -vf 'select=eq(n\\,{})' -frames:v 1 {}",
                      quoted(video), i, quoted(decoded)));
      ASSERT_EQ(d.status, 0) << d.err;
      const auto frame = load_image_file(dir_ / fmt::format("v{:02d}.png", i));
      const auto back = load_image_file(decoded);
      EXPECT_GE(psnr(*frame, *back), 35) << c.file << " frame " << i;
    }
  }
  // encode makes the video from the frame files.
  const auto e = run_lightcone("encode " + quoted(dir_ / "v%02d.png") + " --fps 12 -o " +
                               quoted(dir_ / "encoded.mp4") + " --quiet");
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "encoded.mp4"));
}

// A GIF for slides: scaled down to --gif-width (640 by default) when wider, and its frame
// delays, whole hundredths of a second, within one of 1 / fps each and adding up to the rate
// asked for (3, 4, 3, ... at 30 fps).
TEST_F(Animate, GifsAreSizedForSlidesAndKeepTheRate) {
  if (!have_program("ffmpeg") || !have_program("ffprobe"))
    GTEST_SKIP() << "ffmpeg is not installed";
  const fs::path gif = dir_ / "slide.gif";
  const auto r = run_lightcone("animate " + quoted(scene("terrell.json")) +
                               " --fps 30 --frames 0-29 --video " + quoted(gif) +
                               " --width 200 --height 100 --samples 1 --gif-width 120 --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto probe = test::run_command(
      "ffprobe -v error -select_streams v:0 -show_entries stream=width,height -of "
      "default=noprint_wrappers=1 " +
      quoted(gif));
  EXPECT_NE(probe.out.find("width=120\nheight=60"), std::string::npos) << probe.out;
  // The delays of the graphic control extensions (0x21 0xf9 0x04, flags, delay LE).
  const std::string bytes = bytes_of(gif);
  std::vector<int> delays;
  for (std::size_t k = bytes.find("\x21\xf9\x04"); k != std::string::npos && k + 5 < bytes.size();
       k = bytes.find("\x21\xf9\x04", k + 1))
    delays.push_back(static_cast<unsigned char>(bytes[k + 4]) |
                     static_cast<unsigned char>(bytes[k + 5]) << 8);
  ASSERT_EQ(delays.size(), 30u);
  int total = 0;
  for (const int d : delays) {
    EXPECT_LE(std::abs(d - 100.0 / 30), 1.0) << d;
    total += d;
  }
  EXPECT_LE(std::abs(total - 100), 1);  // one second, within a hundredth
}

// A frame the scene cannot be shown at is refused by its number, once (the library's reason
// names it already). The camera accelerates along +x and the ball comes the other way at gamma
// 100: by proper time 10 their relative gamma, about 200 cosh(10), is past the limit.
TEST_F(Animate, ARefusedFrameIsNamedOnce) {
  const fs::path file = write("scene.json", R"({
  "camera": {"position": [0, 0, 0], "forward": [0, 0, -1], "width": 16, "height": 9,
             "motion": {"phases": [{"duration": 12, "acceleration": [1, 0, 0]}]}},
  "objects": [{"name": "ball", "shape": {"sphere": {"radius": 1}}, "position": [5, 0, -5],
               "velocity": [-0.9999499987499375, 0, 0]}],
  "render": {"exposure": 0}
})");
  const auto r = run_lightcone("animate " + quoted(file) + " --fps 1 --frames 9-10 -o " +
                               quoted(dir_ / "f%02d.png") + " --samples 1 --quiet");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "lightcone: frame 10: by then ball moves too close to the speed of light relative to "
            "the camera (gamma 2.2e+06; at most 1e+06)\n");
  EXPECT_TRUE(fs::exists(dir_ / "f09.png"));
}

TEST_F(Animate, BadInputIsRefusedAndWritesNothing) {
  const std::string rocket = quoted(scene("rocket.json"));
  const std::string png = quoted(dir_ / "f%d.png");
  struct Case {
    std::string arguments, message;
  } cases[] = {
      {" --fps 30 --frames 0-3 -o " + quoted(dir_ / "f.png"), "one frame number conversion"},
      {" --fps 30 --frames 0-3 -o " + quoted(dir_ / "f%s.png"), "one frame number conversion"},
      {" --fps 30 --frames 0-3 -o " + quoted(dir_ / "f%d-%d.png"), "one frame number conversion"},
      {" --fps 30 --frames 5-2 -o " + png, "the range is reversed"},
      {" --fps 30 --frames 2- -o " + png, "expected A-B"},
      {" --fps 30 --frames -3 -o " + png, "expected A-B"},
      {" --fps 0 --frames 0-3 -o " + png, "--fps 0: must be greater than 0"},
      {" --fps -2 --frames 0-3 -o " + png, "must be greater than 0"},
      {" --fps 30 --duration 0 -o " + png, "--duration 0: must be greater than 0"},
      {" --fps 30 -o " + png, "--frames A-B or --duration"},
      {" --fps 30 --frames 0-3", "nothing to write"},
      {" --fps 30 --frames 0-3 --width 95 --height 54 --video " + quoted(dir_ / "v.mp4"),
       "need an even width and height"},
      {" --fps 30 --frames 0-3 --video " + quoted(dir_ / "v.avi"), "unknown video format"},
      {" --fps 30 --frames 0-3 -o " + png + " --set camera.shutter=-1", "camera.shutter"},
  };
  for (const Case& c : cases) {
    const auto r = run_lightcone("animate " + rocket + c.arguments);
    EXPECT_EQ(r.status, 2) << c.arguments << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.arguments << ": " << r.err;
  }
  // Without ffmpeg on the PATH: a message naming it.
  const auto r = run_lightcone(
      "animate " + rocket + " --fps 30 --frames 0-1 --video " + quoted(dir_ / "v.mp4"),
      "PATH=/nonexistent");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("needs ffmpeg, which is not installed"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir_)) << "something was written";
}

}  // namespace
}  // namespace lightcone

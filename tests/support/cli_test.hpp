// The `lightcone` command's tests (tests/test_cli*.cpp): a small scene with one value a line, so
// that every value has a known line, and a fixture that runs the real binary in a fresh folder
// and checks that a rejected command wrote nothing.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "lightcone/io/image_file.hpp"
#include "support/test_support.hpp"

namespace lightcone::test {

// One key per line, so that every value has a known line:
//  1 {                                    11 "name": "ball"
//  2   "camera": {                        12 "shape"
//  3     "position"                       13 "position"
//  4     "velocity"                       14 "velocity"
//  5     "fov"                            15 "material"
//  6     "width"                          16 }
//  7     "height"                         17 ],
//  8   },                                 18 "sky"
//  9   "objects": [                       19 "render"
// 10     {                                20 }
// A green ball of radius 2 at rest 10 ahead of a camera at rest, on a blue sky.
inline const std::string kScene = R"({
  "camera": {
    "position": [0, 0, 0],
    "velocity": [0, 0, 0],
    "fov": 30,
    "width": 64,
    "height": 48
  },
  "objects": [
    {
      "name": "ball",
      "shape": {"sphere": {"radius": 2}},
      "position": [0, 0, -10],
      "velocity": [0, 0, 0],
      "material": {"color": [0, 1, 0]}
    }
  ],
  "sky": {"color": [0, 0, 1]},
  "render": {"exposure": 0, "tonemap": "clamp"}
}
)";

// `text` with the one occurrence of `from` replaced by `to` (a test failure where there is not
// exactly one).
std::string edited(const std::string& text, const std::string& from, const std::string& to);
std::size_t line_count(const std::string& text);
// The 8-bit value the PNG holds for a pixel read back as linear (load_image_file decodes sRGB).
int png_byte(float linear);

// The ball of kScene crossing the view at 0.8c, placed so that the light from its centre that
// reaches the camera left it at t = -10 straight ahead. It is black on a red sky at rest: black
// stays black and the sky stays red whatever the Doppler shift, so a pixel tells which it is.
std::string moving_black_ball();

class CliTest : public TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    out_ = dir_ / "out";
    std::filesystem::create_directories(out_);
  }

  std::filesystem::path write_scene(const std::string& json,
                                    const std::string& name = "scene.json") const {
    return write(name, json);
  }

  std::filesystem::path png() const { return out_ / "image.png"; }
  std::filesystem::path exr() const { return out_ / "image.exr"; }

  // `lightcone render SCENE -o out/image.png --exr out/image.exr EXTRA`.
  CommandResult render(const std::filesystem::path& scene, const std::string& extra = "") const {
    return run_lightcone("render " + quoted(scene) + " -o " + quoted(png()) + " --exr " +
                         quoted(exr()) + " " + extra);
  }
  CommandResult locate(const std::filesystem::path& scene, const std::string& extra) const {
    return run_lightcone("locate " + quoted(scene) + " " + extra);
  }

  std::shared_ptr<Image> read_png() const { return load_image_file(png()); }
  std::shared_ptr<Image> read_exr() const { return load_image_file(exr()); }

  // Nothing in the output folder: no PNG, no EXR, no temporary file; and no temporary file
  // anywhere else in the test's folder.
  void expect_nothing_written() const {
    EXPECT_FALSE(std::filesystem::exists(png()));
    EXPECT_FALSE(std::filesystem::exists(exr()));
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir_)) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
          << "temporary file left behind: " << entry.path();
      EXPECT_NE(entry.path().parent_path(), out_) << "file written: " << entry.path();
    }
  }

  // Exit status 2, exactly one line on stderr that starts with "lightcone: " + `start` and
  // contains every one of `parts`, nothing on stdout, nothing written.
  void expect_rejected(const CommandResult& r, const std::string& start,
                       const std::vector<std::string>& parts = {}) const {
    EXPECT_TRUE(r.err.starts_with("lightcone: " + start))
        << "expected 'lightcone: " << start << "...', got: " << r.err;
    expect_rejected_command_line(r, parts);
  }

  // The same for a command line that the option parser rejects: the message need not start
  // with the program's name.
  void expect_rejected_command_line(const CommandResult& r,
                                    const std::vector<std::string>& parts) const {
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(line_count(r.err), 1u) << "stderr is not one line:\n" << r.err;
    EXPECT_TRUE(r.err.ends_with('\n')) << r.err;
    for (const std::string& part : parts)
      EXPECT_NE(r.err.find(part), std::string::npos) << "no '" << part << "' in: " << r.err;
    EXPECT_EQ(r.out, "");
    expect_nothing_written();
  }

  std::filesystem::path out_;
};

}  // namespace lightcone::test

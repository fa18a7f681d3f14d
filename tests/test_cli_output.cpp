// What `lightcone render` writes, through the real binary: output formats by extension, bad
// output requests, replaced files and full disks, crops, seeds, previews and sizes, `check`,
// `info`, a stopped render, AOV channels and colour maps.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "lightcone/io/image_file.hpp"
#include "support/cli_test.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using namespace test;  // the CLI fixture and helpers (support/cli_test.hpp)

// ----------------------------------------------------------------------------------------------
// Output formats, crops, seeds, check, info, the interrupt

// A moving checkered ball over a sky, with 4 samples: different seeds give different pixels.
const std::string kMovingScene = edited(
    edited(kScene, "\"material\": {\"color\": [0, 1, 0]}",
           "\"material\": {\"checker\": {\"size\": 0.3, \"colors\": [[1, 1, 1], [0, 0, 0]]}}"),
    "\"height\": 48", "\"height\": 48, \"samples\": 4");

TEST_F(CliTest, OutputFormatFollowsTheExtension) {
  const fs::path scene = write_scene(kScene);
  for (const char* name : {"a.png", "b.PNG", "c.jpg", "d.jpeg", "e.exr"}) {
    const fs::path out = out_ / name;
    const CommandResult r = run_lightcone("render " + quoted(scene) + " -o " + quoted(out));
    EXPECT_EQ(r.status, 0) << name << ": " << r.err;
    std::ifstream in(out, std::ios::binary);
    std::string magic(4, '\0');
    in.read(magic.data(), 4);
    const std::string ext = image_format_of(out) == ImageFormat::kExr    ? "exr"
                            : image_format_of(out) == ImageFormat::kJpeg ? "jpg"
                                                                         : "png";
    if (ext == "png") {
      EXPECT_EQ(magic.substr(1, 3), "PNG") << name;
    }
    if (ext == "jpg") {
      EXPECT_EQ(static_cast<unsigned char>(magic[0]), 0xFF) << name;
    }
    if (ext == "exr") {
      EXPECT_EQ(magic, std::string("\x76\x2f\x31\x01", 4)) << name;
    }
    // Every format decodes to the same picture (the EXR holds the linear radiance: green 1).
    const auto image = load_image_file(out);
    ASSERT_EQ(image->width, 64);
    const Rgb centre = image->texel(32, 24);
    EXPECT_NEAR(centre.g, 1.0, 0.02) << name;
    EXPECT_NEAR(centre.r, 0.0, 0.02) << name;
  }
}

TEST_F(CliTest, BadOutputRequestsAreErrorsBeforeRendering) {
  const fs::path scene = write_scene(kScene);
  const struct {
    std::string args, message;
  } cases[] = {
      {"-o " + quoted(out_ / "x.tif"),
       "-o " + (out_ / "x.tif").string() + ": unknown image format"},
      {"-o " + quoted(out_ / "noext"), "unknown image format"},
      {"-o " + quoted(png()) + " --exr " + quoted(png()),
       "--exr " + png().string() + ": the name must end in .exr"},
      {"-o " + quoted(exr()) + " --exr " + quoted(exr()), ": is the same file as -o"},
      {"-o ''", "-o: the output file name is empty"},
      {"-o " + quoted(png()) + " --crop 0,0,0,10", "--crop 0,0,0,10: the window must be non-empty"},
      {"-o " + quoted(png()) + " --crop 0,0,65,10", "inside the 64x48 image"},
      {"-o " + quoted(png()) + " --crop 1,2,3", "expected four integers"},
      {"-o " + quoted(png()) + " --seed 1.5", "--seed"},
      {"-o " + quoted(png()) + " --seed x", "--seed"},
      {"-o " + quoted(exr()) + " --aov doppler,speed",
       "--aov doppler,speed: unknown output variable 'speed'"},
      {"-o " + quoted(png()) + " --aov doppler",
       "--aov: the output variables go into an OpenEXR file"},
      {"-o " + quoted(exr()) + " --aov ''", "--aov"},
      {"-o " + quoted(png()) + " --map normal", "--map normal: unknown quantity"},
      {"-o " + quoted(exr()) + " --map doppler", "--map: the map is a picture"},
  };
  for (const auto& c : cases) {
    const CommandResult r = run_lightcone("render " + quoted(scene) + " " + c.args);
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_EQ(line_count(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    expect_nothing_written();
  }
}

TEST_F(CliTest, BodiesMovingApartTooFastForDoublePrecisionAreErrors) {
  // Each at gamma 2236, but 1e7 relative to each other: once a frame of NaN pixels.
  const fs::path scene = write_scene(edited(
      edited(kScene, "\n    \"velocity\": [0, 0, 0]", "\n    \"velocity\": [0, 0, 0.9999999]"),
      "\n      \"velocity\": [0, 0, 0]", "\n      \"velocity\": [0, 0, -0.9999999]"));
  const CommandResult r = render(scene);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(scene.string() + ":14: objects[0].velocity: speed 0.9999999 relative to "
                                        "the camera is too close to the speed of light"),
            std::string::npos)
      << r.err;
  expect_nothing_written();
}

TEST_F(CliTest, OnlyRegularFilesAreReplacedAndLinksAreKept) {
  const fs::path scene = write_scene(kScene);
  // A FIFO and (where the test may create one) a character device named like images.
  const fs::path fifo = out_ / "fifo.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const fs::path device = out_ / "device.png";
  const bool have_device = ::mknod(device.c_str(), S_IFCHR | 0644, makedev(1, 3)) == 0;
  for (const fs::path& special : {fifo, device}) {
    if (special == device && !have_device) continue;
    const CommandResult r = run_lightcone("render " + quoted(scene) + " -o " + quoted(special));
    EXPECT_EQ(r.status, 2) << special;
    EXPECT_NE(r.err.find("is not a regular file"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::is_regular_file(special)) << special << " was replaced";
  }
  // A symbolic link to a regular file: the file is written, the link stays a link.
  const fs::path real = out_ / "real.png", link = out_ / "link.png";
  test::write_text(real, "old");
  fs::create_symlink(real, link);
  const CommandResult r = run_lightcone("render " + quoted(scene) + " -o " + quoted(link));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(load_image_file(real)->width, 64);
  // A name of 250 characters: the temporary name beside it stays short.
  const fs::path long_name = out_ / (std::string(246, 'n') + ".png");
  const CommandResult l = run_lightcone("render " + quoted(scene) + " -o " + quoted(long_name));
  EXPECT_EQ(l.status, 0) << l.err;
  EXPECT_TRUE(fs::is_regular_file(long_name));
}

TEST_F(CliTest, AFullDiskLeavesThePreviousImagesAndExitsOne) {
  const fs::path scene = write_scene(kScene);
  // The sizes of the two files, from a render where the disk has room.
  const fs::path roomy = dir_ / "roomy";
  fs::create_directories(roomy);
  ASSERT_EQ(run_lightcone("render " + quoted(scene) + " -o " + quoted(roomy / "a.png") + " --exr " +
                          quoted(roomy / "a.exr"))
                .status,
            0);
  const auto png_bytes = static_cast<long long>(fs::file_size(roomy / "a.png"));
  const auto exr_bytes = static_cast<long long>(fs::file_size(roomy / "a.exr"));
  // Full at once; full in the middle of the PNG; full in the middle of the EXR (the PNG, written
  // first, fits).
  for (long long budget : {0LL, png_bytes / 2, png_bytes + exr_bytes / 2}) {
    test::write_text(png(), "previous PNG");
    test::write_text(exr(), "previous EXR");
    const std::string environment = "LD_PRELOAD=" + quoted(LIGHTCONE_FULL_DISK_LIBRARY) +
                                    " LIGHTCONE_FULL_DISK_BYTES=" + std::to_string(budget) +
                                    " ASAN_OPTIONS=verify_asan_link_order=0";
    const CommandResult r = run_lightcone(
        "render " + quoted(scene) + " -o " + quoted(png()) + " --exr " + quoted(exr()),
        environment);
    EXPECT_EQ(r.status, 1) << budget << ": " << r.err;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    EXPECT_EQ(bytes_of(png()), "previous PNG") << budget;
    EXPECT_EQ(bytes_of(exr()), "previous EXR") << budget;
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(out_))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"image.exr", "image.png"})) << budget;
  }
}

TEST_F(CliTest, DevicesAndFifosAreNotReadAsInputs) {
  // /dev/zero never ends and a FIFO blocks: both are refused before they are opened.
  const fs::path fifo = dir_ / "fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  for (const std::string& scene : {std::string("/dev/zero"), fifo.string()}) {
    const CommandResult r = run_lightcone("render '" + scene + "' -o " + quoted(png()));
    EXPECT_EQ(r.status, 2) << scene;
    EXPECT_NE(r.err.find(scene + ": cannot read scene file: it is not a regular file"),
              std::string::npos)
        << r.err;
  }
  fs::create_symlink("/dev/zero", dir_ / "zero.obj");  // a mesh name that leads to /dev/zero
  const fs::path mesh_scene = write_scene(
      edited(kScene, "{\"sphere\": {\"radius\": 2}}", "{\"mesh\": {\"file\": \"zero.obj\"}}"));
  const CommandResult r = render(mesh_scene);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("zero.obj: cannot read mesh file: it is not a regular file"),
            std::string::npos)
      << r.err;
  expect_nothing_written();
}

TEST_F(CliTest, MessagesAreCutAndShowControlCharacters) {
  const fs::path big = write_scene(
      edited(kScene, "\"fov\": 30", "\"" + std::string(1000000, 'k') + "\": 1, \"fov\": 30"),
      "big.json");
  const CommandResult r = run_lightcone("check " + quoted(big));
  EXPECT_EQ(r.status, 2);
  EXPECT_LT(r.err.size(), 600u) << r.err.substr(0, 600);
  EXPECT_NE(r.err.find(std::string(70, 'k') + "..."), std::string::npos);
  const fs::path control = write_scene(
      edited(kScene, "\"fov\": 30", "\"a\\u0000\\u001b[31m\": 1, \"fov\": 30"), "control.json");
  const CommandResult c = run_lightcone("check " + quoted(control));
  EXPECT_EQ(c.status, 2);
  EXPECT_NE(c.err.find("camera.a\\x00\\x1b[31m: unknown key"), std::string::npos) << c.err;
  EXPECT_EQ(c.err.find('\x1b'), std::string::npos);
}

TEST_F(CliTest, NonFiniteRendersAreErrorsAndWriteNothing) {
  const fs::path scene = write_scene(kScene);
  const CommandResult r = render(scene, "--set render.exposure=1e308");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("non-finite values"), std::string::npos) << r.err;
  expect_nothing_written();
}

// A PNG written alone is exposed in its tone map's pass, not one of its own: the same file as
// one written beside the EXR (which keeps the exposed picture), at the automatic exposure and a
// fixed one, and refused as that one is where the exposure takes values past a float's range.
TEST_F(CliTest, APngAloneIsThePngBesideAnExr) {
  const fs::path scene = write_scene(kScene);
  for (const std::string exposure : {"", " --set render.exposure=1.5"}) {
    ASSERT_EQ(render(scene, "--quiet" + exposure).status, 0);
    const fs::path alone = out_ / "alone.png";
    ASSERT_EQ(
        run_lightcone("render " + quoted(scene) + " -o " + quoted(alone) + " --quiet" + exposure)
            .status,
        0);
    EXPECT_EQ(test::bytes_of(alone), test::bytes_of(png())) << exposure;
    fs::remove(alone);
    fs::remove(png());
    fs::remove(exr());
  }
  const CommandResult r = run_lightcone("render " + quoted(scene) + " -o " + quoted(png()) +
                                        " --set render.exposure=1e308");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("non-finite values"), std::string::npos) << r.err;
  expect_nothing_written();
}

TEST_F(CliTest, DashWritesThePngToStandardOutput) {
  const fs::path scene = write_scene(kScene);
  const CommandResult r = run_lightcone("render " + quoted(scene) + " -o - --quiet");
  EXPECT_EQ(r.status, 0) << r.err;
  ASSERT_GT(r.out.size(), 8u);
  EXPECT_EQ(r.out.substr(1, 3), "PNG");
  test::write_text(out_ / "stdout.png", r.out);
  const auto image = load_image_file(out_ / "stdout.png");
  EXPECT_EQ(image->width, 64);
  EXPECT_NEAR(image->texel(32, 24).g, 1.0, 1e-6);
}

TEST_F(CliTest, VersionNamesTheVersionAndCommit) {
  const CommandResult r = run_lightcone("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("lightcone 0.", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("(commit "), std::string::npos) << r.out;
}

TEST_F(CliTest, CropIsTheSameRegionOfTheFullRenderPixelForPixel) {
  const fs::path scene = write_scene(kMovingScene);
  ASSERT_EQ(render(scene, "--quiet").status, 0);
  const auto full = read_exr();
  const fs::path crop = out_ / "crop.exr";
  const CommandResult r =
      run_lightcone("render " + quoted(scene) + " -o " + quoted(crop) + " --crop 13,7,45,30");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto part = load_image_file(crop);
  ASSERT_EQ(part->width, 32);
  ASSERT_EQ(part->height, 23);
  int differing = 0;
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 32; ++x) {
      const Rgb a = part->texel(x, y), b = full->texel(x + 13, y + 7);
      differing += a.r != b.r || a.g != b.g || a.b != b.b;
    }
  EXPECT_EQ(differing, 0);
}

TEST_F(CliTest, SeedsChangeTheSamplePatternDeterministically) {
  const fs::path scene = write_scene(kMovingScene);
  const auto run = [&](const std::string& seed) {
    EXPECT_EQ(render(scene, "--quiet " + seed).status, 0);
    return read_exr()->rgb;
  };
  const auto a = run(""), b = run("--seed 0"), c = run("--seed 7"), d = run("--seed 7");
  EXPECT_EQ(a, b);  // 0 is the default
  EXPECT_EQ(c, d);
  EXPECT_NE(a, c);
}

// A seed that is not a whole number from 0 to 2^64 - 1 is refused, saying what a seed is, for
// render and animate alike; no file is written.
TEST_F(CliTest, SeedsOutsideTheirRangeAreRefusedWithTheRange) {
  const fs::path scene = write_scene(kScene);
  for (const char* seed : {"''", "abc", "-1", "18446744073709551616", "1.5", "' 7'"}) {
    SCOPED_TRACE(seed);
    expect_rejected(render(scene, std::string("--seed ") + seed),
                    "--seed: ", {"a seed is a whole number from 0 to 18446744073709551615"});
    EXPECT_FALSE(fs::exists(png()));
    const CommandResult animated =
        run_lightcone("animate " + quoted(scene) + " -o " + quoted(dir_ / "f-%d.png") +
                      " --frames 0-0 --seed " + seed);
    expect_rejected(animated, "--seed: ", {"whole number from 0 to 18446744073709551615"});
  }
  EXPECT_EQ(render(scene, "--quiet --seed 18446744073709551615").status, 0);
}

TEST_F(CliTest, PreviewIsAQuarterSizeOneSampleTheScenesExposure) {
  const fs::path scene = write_scene(kMovingScene);
  const CommandResult r = render(scene, "--preview --stats --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto preview = read_png();
  EXPECT_EQ(preview->width, 16);
  EXPECT_EQ(preview->height, 12);
  EXPECT_EQ(nlohmann::json::parse(r.err).at("rays").get<int>(), 16 * 12);
  // The same picture as a quarter-size render with one sample: the scene's exposure, not auto.
  ASSERT_EQ(render(scene, "--scale 0.25 --samples 1 --quiet").status, 0);
  EXPECT_EQ(test::fraction_differing(*preview, *read_png()), 0.0);
}

// --width and --height keep the scene's field both ways: a narrower picture keeps the
// horizontal field (two balls 40 degrees either side stay in view, where the vertical field
// alone would have lost them), a wider one the vertical field; stderr says which.
TEST_F(CliTest, ASizeOfAnotherAspectKeepsTheScenesField) {
  const fs::path scene = write_scene(R"({
  "camera": {"position": [0, 0, 0], "fov": 40, "width": 96, "height": 36},
  "objects": [
    {"name": "left", "shape": {"sphere": {"radius": 0.2}}, "position": [-6.4279, 0, -7.6604],
     "material": {"color": [1, 1, 1]}},
    {"name": "right", "shape": {"sphere": {"radius": 0.2}}, "position": [6.4279, 0, -7.6604],
     "material": {"color": [1, 1, 1]}}],
  "render": {"exposure": 0}
})");
  // The brightest column of a picture's left or right half.
  const auto brightest_column = [&](bool right) {
    const auto image = read_exr();
    int best = -1;
    float most = 0;
    for (int x = right ? image->width / 2 : 0; x < (right ? image->width : image->width / 2); ++x)
      for (int y = 0; y < image->height; ++y)
        if (const float v = image->rgb[3 * (y * image->width + x) + 1]; v > most) {
          most = v;
          best = x;
        }
    return best;
  };
  // tan 40 over the scene's horizontal half-tangent, tan 20 * 96 / 36, of the half-width.
  const double from_centre =
      std::tan(40 * std::numbers::pi / 180) / (std::tan(20 * std::numbers::pi / 180) * 96 / 36);
  CommandResult r = render(scene, "--width 48 --height 27");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("48x27 is narrower than the scene: its horizontal field of 88.29 degrees "
                       "is kept, the vertical one widens from 40 to 57.27"),
            std::string::npos)
      << r.err;
  EXPECT_NEAR(brightest_column(true), 24 + 24 * from_centre - 0.5, 1.0);
  EXPECT_NEAR(brightest_column(false), 24 - 24 * from_centre - 0.5, 1.0);
  r = render(scene, "--width 200");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("200x36 is wider than the scene: its vertical field of 40 degrees is "
                       "kept, the horizontal one widens from 88.29 to 127.4"),
            std::string::npos)
      << r.err;
  const double wider = from_centre * 96 / 200;  // the same vertical field, 200 / 36 wide
  EXPECT_NEAR(brightest_column(true), 100 + 100 * wider - 0.5, 1.0);
  // At the scene's aspect nothing is said.
  r = render(scene, "--width 192 --height 72");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("field"), std::string::npos) << r.err;
}

// --scale keeps the picture: half the size, with four times the samples, is the full-size
// render averaged over 2x2 blocks, within the sampling noise of the checker's edges.
TEST_F(CliTest, ScaleKeepsThePicture) {
  const fs::path scene = write_scene(kMovingScene);
  ASSERT_EQ(render(scene, "--width 128 --height 96 --samples 4 --quiet").status, 0);
  const auto full = load_image_file(exr());
  ASSERT_EQ(render(scene, "--width 128 --height 96 --scale 0.5 --samples 16 --quiet").status, 0);
  const auto half = load_image_file(exr());
  ASSERT_EQ(half->width, 64);
  ASSERT_EQ(half->height, 48);
  // The mean difference from the blocks `shift` full-size pixels to the right, over their mean.
  const auto difference = [&](int shift) {
    double sum = 0, level = 0;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 63; ++x)
        for (int c = 0; c < 3; ++c) {
          double block = 0;
          for (int k = 0; k < 4; ++k)
            block += full->rgb[3 * ((2 * y + k / 2) * 128 + 2 * x + shift + k % 2) + c] / 4;
          sum += std::abs(half->rgb[3 * (y * 64 + x) + c] - block);
          level += block;
        }
    return sum / level;
  };
  std::printf("--scale 0.5 against 2x2 blocks: %.4f; one pixel over: %.4f\n", difference(0),
              difference(1));
  EXPECT_LT(difference(0), 0.05);
  EXPECT_GT(difference(1), 2 * difference(0));  // the comparison sees a picture moved
  fs::remove(png());
  fs::remove(exr());
  expect_rejected(render(scene, "--scale 0"), "--scale 0: ", {"must be above 0"});
}

TEST_F(CliTest, CheckValidatesWithoutRendering) {
  const fs::path good = write_scene(kScene);
  const CommandResult ok = run_lightcone("check " + quoted(good));
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_NE(ok.out.find(": ok"), std::string::npos) << ok.out;
  const fs::path bad = write_scene(edited(kScene, "\"fov\": 30", "\"fov\": -30"), "bad.json");
  const CommandResult no = run_lightcone("check " + quoted(bad));
  EXPECT_EQ(no.status, 2);
  EXPECT_NE(no.err.find("bad.json:"), std::string::npos) << no.err;
  EXPECT_NE(no.err.find("camera.fov"), std::string::npos) << no.err;
  EXPECT_EQ(std::distance(fs::directory_iterator(out_), fs::directory_iterator()), 0);
}

TEST_F(CliTest, InfoJsonReportsSpeedsGammaDopplerAndTimeWindow) {
  const fs::path scene = write_scene(edited(kScene, "\"velocity\": [0, 0, 0],\n    \"fov\"",
                                            "\"velocity\": [0, 0, -0.6],\n    \"fov\""));
  const CommandResult r = run_lightcone("info " + quoted(scene) + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out);
  EXPECT_EQ(info.at("image").at("width").get<int>(), 64);
  const auto& camera = info.at("bodies").at(0);
  EXPECT_EQ(camera.at("kind"), "camera");
  EXPECT_NEAR(camera.at("speed").get<double>(), 0.6, 1e-12);
  EXPECT_NEAR(camera.at("gamma").get<double>(), 1.25, 1e-12);
  // Flying at 0.6c toward a ball and sky at rest: D = 1 / (gamma (1 - beta cos theta)), theta
  // the camera-frame angle from straight ahead: 2 there, 1.769 at the corners (24.1 degrees).
  EXPECT_NEAR(info.at("doppler").at(1).get<double>(), 2.0, 1e-6);
  EXPECT_NEAR(info.at("doppler").at(0).get<double>(), 1.769, 0.002);
  // Straight ahead the ball's near point, 8 away and at rest in W, sent its light at t = -8;
  // points toward its rim sent it earlier.
  EXPECT_NEAR(info.at("emission_time").at(1).get<double>(), -8.0, 0.05);
  EXPECT_LT(info.at("emission_time").at(0).get<double>(), -8.0);
  EXPECT_GT(info.at("memory_bytes").get<double>(), 64 * 48 * 12);
  const CommandResult text = run_lightcone("info " + quoted(scene));
  EXPECT_EQ(text.status, 0);
  EXPECT_NE(text.out.find("gamma 1.25"), std::string::npos) << text.out;
}

// Near a hole: a clock at the horizon's edge reads below c, and the shift range holds the exact
// g of every clock's image (locate's, for their origins), not the sky's alone (1.035 everywhere
// at the camera's r = 30M: 1 / sqrt(1 - 2/30)).
TEST_F(CliTest, InfoNearAHoleReadsSpeedsBelowCAndTheBodiesShifts) {
  const std::string infall = quoted(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes/infall.json");
  const CommandResult text = run_lightcone("info " + infall);
  ASSERT_EQ(text.status, 0) << text.err;
  // gamma 5202: 1 - beta = 1 / (2 gamma^2) = 1.85e-8.
  EXPECT_NE(text.out.find("early                    speed 0.99999998 c, gamma 5202.07"),
            std::string::npos)
      << text.out;
  const CommandResult r = run_lightcone("info " + infall + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out);
  const double lo = info.at("doppler").at(0), hi = info.at("doppler").at(1);
  EXPECT_EQ(info.at("black_hole").at("shift"), nlohmann::json::array({lo, hi}));
  for (const char* clock : {"late", "middle", "early"}) {
    const CommandResult seen =
        run_lightcone("locate " + infall + " --object " + clock + " --point 0,0,0");
    ASSERT_EQ(seen.status, 0) << seen.err;
    const auto located = nlohmann::json::parse(seen.out);
    for (const auto& image : located.at("images")) {
      if (!image.at("in_view").get<bool>()) continue;
      EXPECT_LE(lo, image.at("g").get<double>()) << clock;
      EXPECT_GE(hi, image.at("g").get<double>()) << clock;
    }
  }
  // The clock nearest the horizon is seen at g = 0.356 (its origin's primary image).
  EXPECT_LT(lo, 0.36);
  // The light seen left the clocks, along curved rays, after the first was let go (t = -76)
  // and before the camera's r = 30M at least 20M away could receive it.
  EXPECT_GT(info.at("emission_time").at(0).get<double>(), -76);
  EXPECT_LT(info.at("emission_time").at(1).get<double>(), -20);
}

// The stars a scene draws: how many, from which catalogue, to which magnitude.
TEST_F(CliTest, InfoCountsTheStars) {
  const CommandResult r =
      run_lightcone("info " + quoted(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes/stars.json") +
                    " --json --set sky.stars.magnitude_limit=3");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto stars = nlohmann::json::parse(r.out).at("stars");
  EXPECT_EQ(stars.at("catalogue"), "bright");
  EXPECT_EQ(stars.at("magnitude_limit").get<double>(), 3);
  // The Bright Star Catalogue has some 170 stars brighter than V = 3.
  EXPECT_GT(stars.at("count").get<int>(), 150);
  EXPECT_LT(stars.at("count").get<int>(), 190);
}

TEST_F(CliTest, AStoppedRenderWritesItsTilesBesideAnUntouchedTarget) {
  // A render that takes seconds, stopped after a moment by Ctrl-C, `timeout`/`scancel`
  // (SIGTERM) or a closed terminal (SIGHUP): the tiles finished go to out.partial.png and
  // .partial.exr, the finished image already there is untouched, and the status is the
  // shell's for that signal.
  const fs::path scene = write_scene(edited(kMovingScene, "\"samples\": 4", "\"samples\": 4096"));
  for (const auto& [signal, status_expected] :
       {std::pair{"INT", 130}, std::pair{"TERM", 143}, std::pair{"HUP", 129}}) {
    test::write_text(png(), "a finished image");
    const fs::path exr = this->exr();
    fs::remove(exr);
    const std::string command = std::string("'") + LIGHTCONE_BINARY + "' render " + quoted(scene) +
                                " -o " + quoted(png()) + " --exr " + quoted(exr) +
                                " --threads 1 2>" + quoted(out_ / "err.txt") +
                                " & pid=$!; sleep 1; kill -" + signal +
                                " $pid; wait $pid; echo $? > " + quoted(out_ / "status.txt");
    test::write_text(dir_ / "interrupt.sh", command + "\n");
    ASSERT_EQ(std::system(("bash " + quoted(dir_ / "interrupt.sh")).c_str()), 0);
    std::ifstream status_file(out_ / "status.txt");
    int status = -1;
    status_file >> status;
    EXPECT_EQ(status, status_expected) << signal;
    std::ifstream err_file(out_ / "err.txt");
    const std::string err((std::istreambuf_iterator<char>(err_file)), {});
    EXPECT_NE(err.find(std::string("stopped by SIG") + signal + " with "), std::string::npos)
        << err;
    EXPECT_NE(err.find(" tiles done: wrote them to "), std::string::npos) << err;
    std::ifstream target(png());
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(target)), {}), "a finished image");
    EXPECT_FALSE(fs::exists(exr)) << signal;
    const auto image = load_image_file(out_ / "image.partial.png");  // a PNG that decodes
    EXPECT_EQ(image->width, 64);
    EXPECT_EQ(load_image_file(out_ / "image.partial.exr")->width, 64);
    for (const fs::directory_entry& e : fs::directory_iterator(out_))
      EXPECT_EQ(e.path().filename().string().find(".lightcone-"), std::string::npos)
          << "a temporary file left: " << e.path();
  }
}

// Under the automatic exposure the EXR holds the radiance times 2^EV, EV set by the scene: its
// header, the summary line and --stats say which EV, and undoing it gives the radiance that
// exposure 0 writes, by either renderer.
TEST_F(CliTest, TheExrSaysWhichExposureScaledTheRadiance) {
  // The green ball of kScene crossing the view at 0.8c, its light Doppler-shifted and dimmed.
  const fs::path scene = write_scene(
      edited(kScene, "\n      \"velocity\": [0, 0, 0]", "\n      \"velocity\": [0.8, 0, 0]"));
  for (const std::string renderer : {"trace", "raster"}) {
    SCOPED_TRACE(renderer);
    const std::string options = " --stats --renderer " + renderer;
    const CommandResult automatic = render(scene, "--set render.exposure=auto" + options);
    ASSERT_EQ(automatic.status, 0) << automatic.err;
    ASSERT_EQ(line_count(automatic.err), 2u) << automatic.err;
    const std::size_t end_of_summary = automatic.err.find('\n');
    const std::string summary = automatic.err.substr(0, end_of_summary);
    const double ev =
        nlohmann::json::parse(automatic.err.substr(end_of_summary + 1)).at("exposure");
    EXPECT_GT(std::abs(ev), 1.0);  // a factor that a reader of the radiance would miss
    EXPECT_TRUE(summary.ends_with(fmt::format(" (exposure {:+.2f} EV)", ev))) << summary;
    const auto scaled = read_exr();
    ASSERT_TRUE(scaled->exposure.has_value());
    EXPECT_EQ(*scaled->exposure, ev);

    const CommandResult unscaled = render(scene, "--set render.exposure=0 --quiet" + options);
    ASSERT_EQ(unscaled.status, 0) << unscaled.err;
    EXPECT_EQ(nlohmann::json::parse(unscaled.err).at("exposure").get<double>(), 0.0);
    const auto radiance = read_exr();
    ASSERT_TRUE(radiance->exposure.has_value());
    EXPECT_EQ(*radiance->exposure, 0.0);
    ASSERT_EQ(scaled->rgb.size(), radiance->rgb.size());
    // The scale went through a float, so the radiance comes back to float precision.
    double worst = 0;
    for (std::size_t i = 0; i < radiance->rgb.size(); ++i)
      worst = std::max(worst, std::abs(scaled->rgb[i] * std::exp2(-ev) - radiance->rgb[i]) /
                                  std::max(radiance->rgb[i], 1e-6f));
    EXPECT_LT(worst, 1e-6);
  }
}

TEST_F(CliTest, AovChannelsGoIntoTheExrByName) {
  const fs::path scene = write_scene(kScene);
  const CommandResult r =
      render(scene, "--quiet --aov doppler,emission_time,distance,object,depth,normal");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto image = read_exr();
  std::vector<std::string> names;
  for (const NamedChannel& c : image->channels) names.push_back(c.name);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"depth", "distance", "doppler", "emission_time",
                                             "normal.X", "normal.Y", "normal.Z", "object"}));
  // The ball at rest 10 ahead, radius 2: its near point is 8 away and sent its light at t = -8.
  for (const NamedChannel& c : image->channels) {
    const float centre = c.values[24 * 64 + 32];
    if (c.name == "distance") {
      EXPECT_NEAR(centre, 8.0, 5e-3);
    }  // half a pixel off the axis
    if (c.name == "emission_time") {
      EXPECT_NEAR(centre, -8.0, 5e-3);
    }
    if (c.name == "doppler") {
      EXPECT_EQ(centre, 1.0f);
    }
    if (c.name == "object") {
      EXPECT_EQ(centre, 0.0f);
    }
    if (c.name == "object") {
      EXPECT_EQ(c.values[0], -1.0f);
    }  // the sky in the corner
  }
}

TEST_F(CliTest, MapWritesAColourMappedPictureWithAScaleBar) {
  const fs::path scene = write_scene(edited(kScene, "\"velocity\": [0, 0, 0],\n    \"fov\"",
                                            "\"velocity\": [0, 0, -0.6],\n    \"fov\""));
  const CommandResult r = render(scene, "--quiet --map doppler");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto picture = read_png();
  EXPECT_EQ(picture->width, 64);
  EXPECT_EQ(picture->height, 48);     // the render's size, the legend inside
  const auto exr_image = read_exr();  // the EXR keeps the render and the mapped channel
  ASSERT_EQ(exr_image->channels.size(), 1u);
  EXPECT_EQ(exr_image->channels[0].name, "doppler");
  EXPECT_NEAR(exr_image->channels[0].values[24 * 64 + 32], 2.0, 1e-3);
}

}  // namespace
}  // namespace lightcone

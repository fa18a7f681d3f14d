// The hostile-input cases of animation, video and the star catalogue, through the real
// `lightcone` command: each gives a non-zero status or a correct result, and loses no file that
// was there before. (Speed limits, mesh references and determinism have their own suites; the
// Python module's boundary is python/tests/test_hostile_input.py.)
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "lightcone/io/image_file.hpp"
#include "lightcone/io/star_catalogue.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using test::bytes_of;
using test::have_program;
using test::quoted;
using test::run_command;
using test::run_lightcone;

// Frames in `ffprobe`'s reading of a video, or -1 if it cannot read it.
int frames_in(const fs::path& video) {
  const auto probe = run_command(
      "ffprobe -v error -count_packets -select_streams v:0 -show_entries stream=nb_read_packets "
      "-of csv=p=0 " +
      quoted(video));
  return probe.status == 0 && !probe.out.empty() ? std::stoi(probe.out) : -1;
}

class HostileInput : public test::TempDirTest {
 protected:
  std::string terrell() const {
    return quoted(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes" / "terrell.json");
  }
  static std::string small() { return " --width 64 --height 36 --samples 1 --quiet"; }
  // Names in the folder that a run may leave only by mistake: temporaries of images or videos.
  std::vector<std::string> leftovers() const {
    std::vector<std::string> found;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir_)) {
      const std::string name = e.path().filename().string();
      if (name.find(".lightcone-") != std::string::npos ||
          name.find(".partial-") != std::string::npos)
        found.push_back(name);
    }
    return found;
  }
};

// The program reads its catalogue beside itself (data/): a copy of it whose catalogue is a FIFO,
// a link to /dev/zero or a crafted file. The reader used to wait on the FIFO for ever and grow
// without end on /dev/zero, heeding neither SIGINT nor SIGTERM, and to take B-V -1 or V -1e30 to
// the render, which then blamed render.exposure for its non-finite picture.
TEST_F(HostileInput, TheStarCatalogueIsReadOnlyWhenItIsARegularFileOfStars) {
  const fs::path program = dir_ / "lightcone", catalogue = dir_ / "data" / kBrightCatalogueFile;
  fs::copy_file(LIGHTCONE_BINARY, program);
  fs::create_directories(catalogue.parent_path());
  const std::string stars = quoted(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes" / "stars.json");
  const auto render = [&] {
    // `timeout` stands for the user's patience: the old reader outlived it on the FIFO.
    return run_command("timeout -s KILL 60 " + quoted(program) + " render " + stars + " -o " +
                       quoted(dir_ / "sky.png") + small());
  };
  const auto expect_refused = [&](const std::string& says) {
    const test::CommandResult r = render();
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(catalogue.string() + ": " + says), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("render.exposure"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "sky.png"));
  };
  ASSERT_EQ(::mkfifo(catalogue.c_str(), 0600), 0);
  expect_refused("cannot read the star catalogue: it is not a regular file");
  fs::remove(catalogue);
  fs::create_symlink("/dev/zero", catalogue);
  expect_refused("cannot read the star catalogue: it is not a regular file");
  fs::remove(catalogue);
  const CatalogueStar vega{{0, 1, 0}, 0.03f, 0.0f};
  write_star_catalogue(catalogue, {vega, {{1, 0, 0}, 2.0f, -1.0f}});
  expect_refused("star 1: B-V colour index -1 is outside");
  write_star_catalogue(catalogue, {vega, {{1, 0, 0}, -1e30f, 0.5f}});
  expect_refused("star 1: V magnitude -1e+30 is outside");
  write_star_catalogue(catalogue, {vega});
  const test::CommandResult fine = render();
  EXPECT_EQ(fine.status, 0) << fine.err;
}

TEST_F(HostileInput, AVideoOnAFullDiskIsAbsentAndTheRunFails) {
  if (!have_program("ffmpeg")) GTEST_SKIP() << "ffmpeg is not installed";
  const fs::path full = dir_ / "full";
  fs::create_directory(full);
  // 16 KiB: the trial frame fits, the whole lossless video does not.
  if (::mount("tmpfs", full.c_str(), "tmpfs", 0, "size=16k") != 0)
    GTEST_SKIP() << "cannot mount a small tmpfs here (needs root)";
  struct Unmount {
    fs::path path;
    ~Unmount() { ::umount2(path.c_str(), MNT_DETACH); }
  } unmount{full};
  for (const char* name : {"v.mp4", "v.webm"}) {
    const auto r = run_lightcone("animate " + terrell() + " --frames 0-29 -o " +
                                 quoted(dir_ / "f-%04d.png") + " --video " + quoted(full / name) +
                                 " --crf 0 --width 320 --height 180 --samples 1 --quiet");
    EXPECT_NE(r.status, 0) << name << ": " << r.err;
    EXPECT_NE(r.err.find("no video written"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(full / name)) << name;
    // The frames are whole: each decodes.
    for (int i = 0; i < 30; ++i)
      EXPECT_NO_THROW(load_image_file(dir_ / fmt::format("f-{:04d}.png", i))) << i;
  }
  const auto e = run_lightcone("encode " + quoted(dir_ / "f-%04d.png") + " -o " +
                               quoted(full / "e.mp4") + " --crf 0 --quiet");
  EXPECT_NE(e.status, 0) << e.err;
  EXPECT_FALSE(fs::exists(full / "e.mp4"));
  EXPECT_TRUE(leftovers().empty()) << leftovers().front();
}

// A stand-in ffmpeg on the PATH: the first call (the trial frame before rendering) is the real
// one; later calls run `behaviour`.
fs::path fake_ffmpeg(const fs::path& folder, const std::string& behaviour) {
  fs::create_directories(folder / "bin");
  const fs::path script = folder / "bin" / "ffmpeg";
  std::string real = run_command("command -v ffmpeg").out;
  real = real.substr(0, real.find('\n'));
  test::write_text(script, "#!/bin/sh\nmark=\"" + (folder / "trial-done").string() +
                               "\"\nif [ ! -e \"$mark\" ]; then : > \"$mark\"; exec " + real +
                               " \"$@\"; fi\n" + behaviour + "\n");
  fs::permissions(script, fs::perms::owner_all);
  return folder / "bin";
}

TEST_F(HostileInput, AnFfmpegThatLiesAboutSuccessLeavesTheOldVideoAlone) {
  if (!have_program("ffmpeg") || !have_program("ffprobe"))
    GTEST_SKIP() << "ffmpeg is not installed";
  // It reads every frame, writes four bytes that are no video in its place, and exits 0.
  const fs::path bin = fake_ffmpeg(
      dir_ / "lying", "cat > /dev/null; for last; do :; done; printf 'junk' > \"$last\"; exit 0");
  const fs::path video = dir_ / "v.mp4";
  test::write_text(video, "the old video");
  const auto r =
      run_lightcone("animate " + terrell() + " --frames 0-3 --video " + quoted(video) + small(),
                    "PATH=" + quoted(bin) + ":\"$PATH\"");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("no video written"), std::string::npos) << r.err;
  EXPECT_EQ(bytes_of(video), "the old video");
  EXPECT_TRUE(leftovers().empty()) << leftovers().front();
}

TEST_F(HostileInput, AStuckFfmpegIsStoppedByTheWatchdog) {
  if (!have_program("ffmpeg") || !have_program("ffprobe"))
    GTEST_SKIP() << "ffmpeg is not installed";
  // It stops reading: frames fill the pipe, then nothing moves.
  const fs::path bin = fake_ffmpeg(dir_ / "stuck", "exec sleep 600");
  // Under `timeout`, so that a watchdog that fails cannot hang the suite.
  const auto r = run_lightcone(
      "animate " + terrell() + " --frames 0-5 --video " + quoted(dir_ / "v.mp4") +
          " --width 320 --height 180 --samples 1 --quiet",
      "timeout 60 env LIGHTCONE_VIDEO_WATCHDOG_SECONDS=1 PATH=" + quoted(bin) + ":\"$PATH\"");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("no frame data for 1 s"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "v.mp4"));
  EXPECT_TRUE(leftovers().empty()) << leftovers().front();
}

TEST_F(HostileInput, EveryFrameNameIsCheckedBeforeTheFirstFrame) {
  const std::string pattern = quoted(dir_ / "f-%04d.png");
  // A FIFO at the second frame's name: refused before frame 0 is written, and still a FIFO.
  ASSERT_EQ(::mkfifo((dir_ / "f-0001.png").c_str(), 0644), 0);
  auto r = run_lightcone("animate " + terrell() + " --frames 0-2 -o " + pattern + small());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("frame 1, "), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "f-0000.png"));
  EXPECT_TRUE(fs::is_fifo(dir_ / "f-0001.png"));
  // A device behind a symbolic link, in the --exr pattern.
  fs::create_symlink("/dev/null", dir_ / "x-2.exr");
  r = run_lightcone("animate " + terrell() + " --frames 0-2 --exr " + quoted(dir_ / "x-%d.exr") +
                    small());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("frame 2, "), std::string::npos) << r.err;
  // A folder that cannot be made for a later frame (the number in the folder's name; a file
  // holds the name).
  fs::create_directory(dir_ / "d0");
  std::ofstream(dir_ / "d1") << "a file";
  r = run_lightcone("animate " + terrell() + " --frames 0-1 -o " + quoted(dir_ / "d%d" / "f.png") +
                    small());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("does not exist and cannot be made"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir_ / "d0"));
  // Two patterns that meet: frame 11 of -o and frame 1 of --exr are both x11.exr.
  r = run_lightcone("animate " + terrell() + " --frames 1-11 -o " + quoted(dir_ / "x%d.exr") +
                    " --exr " + quoted(dir_ / "x1%d.exr") + small());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("are both " + (dir_ / "x11.exr").string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x1.exr"));
}

TEST_F(HostileInput, EncodeRefusesAGapUnlessAllowed) {
  if (!have_program("ffmpeg") || !have_program("ffprobe"))
    GTEST_SKIP() << "ffmpeg is not installed";
  const std::string pattern = quoted(dir_ / "f-%04d.png");
  ASSERT_EQ(run_lightcone("animate " + terrell() + " --frames 0-5 -o " + pattern + small()).status,
            0);
  fs::remove(dir_ / "f-0003.png");  // a cluster task that failed
  const fs::path video = dir_ / "v.mp4";
  auto r = run_lightcone("encode " + pattern + " -o " + quoted(video) + " --quiet");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("frame 3 (" + (dir_ / "f-0003.png").string() + ") is missing"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(video));
  r = run_lightcone("encode " + pattern + " -o " + quoted(video) + " --frames 2-5 --quiet");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_FALSE(fs::exists(video));
  r = run_lightcone("encode " + pattern + " -o " + quoted(video) + " --allow-gaps --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("1 frames missing"), std::string::npos) << r.err;
  EXPECT_EQ(frames_in(video), 5);
  // Frames that start later than 0 are found without --frames.
  fs::remove(dir_ / "f-0000.png");
  fs::remove(dir_ / "f-0001.png");
  fs::remove(dir_ / "f-0002.png");
  r = run_lightcone("encode " + pattern + " -o " + quoted(video) + " --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(frames_in(video), 2);
}

TEST_F(HostileInput, ResumeRendersAgainTheFramesItCannotKeep) {
  const std::string pattern = quoted(dir_ / "f-%04d.png");
  const std::string run = "animate " + terrell() + " --frames 0-5 -o " + pattern + small();
  ASSERT_EQ(run_lightcone(run).status, 0);
  std::vector<std::string> good;
  for (int i = 0; i < 6; ++i) good.push_back(bytes_of(dir_ / fmt::format("f-{:04d}.png", i)));
  test::write_text(dir_ / "f-0001.png", "not an image");
  test::write_text(dir_ / "f-0002.png", good[2].substr(0, good[2].size() / 2));  // half a PNG
  test::write_text(dir_ / "f-0003.png", "");
  ASSERT_EQ(run_lightcone("render " + terrell() + " -o " + quoted(dir_ / "f-0004.png") +
                          " --width 32 --height 18 --samples 1 --quiet")
                .status,
            0);  // another size
  const auto r = run_lightcone(run + " --resume");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const int i : {1, 2, 3, 4})
    EXPECT_NE(r.err.find(fmt::format("frame {}: ", i)), std::string::npos) << i << r.err;
  EXPECT_EQ(r.err.find("frame 0: "), std::string::npos) << r.err;
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(bytes_of(dir_ / fmt::format("f-{:04d}.png", i)), good[i]) << i;
}

TEST_F(HostileInput, SigtermKeepsWholeFramesAndRemovesTemporaries) {
  if (!have_program("ffmpeg")) GTEST_SKIP() << "ffmpeg is not installed";
  // As `timeout` and Slurm's scancel do: the signal goes to the whole process group (ffmpeg
  // too). setsid gives the run its own group.
  const fs::path video = dir_ / "v.mp4";
  test::write_text(video, "the old video");
  // Stopped once its first frame is whole (frames are renamed into place), however slow the build
  // (a sanitized one takes seconds a frame); never before a second, so the video is under way.
  const std::string first_frame_or_a_minute = "sleep 1; for i in $(seq 600); do [ -e " +
                                              quoted(dir_ / "f-0000.png") +
                                              " ] && break; sleep 0.1; done; ";
  const std::string command = "setsid " + std::string(LIGHTCONE_BINARY) + " animate " + terrell() +
                              " --frames 0-500 -o " + quoted(dir_ / "f-%04d.png") + " --video " +
                              quoted(video) + " --width 320 --height 180 --samples 4 --quiet 2>" +
                              quoted(dir_ / "err.txt") + " & pid=$!; " + first_frame_or_a_minute +
                              "kill -TERM -- -$pid; wait $pid; echo $? > " +
                              quoted(dir_ / "status.txt");
  test::write_text(dir_ / "stop.sh", command + "\n");
  ASSERT_EQ(std::system(("bash " + quoted(dir_ / "stop.sh")).c_str()), 0);
  EXPECT_EQ(std::stoi(bytes_of(dir_ / "status.txt")), 143);
  const std::string err = bytes_of(dir_ / "err.txt");
  EXPECT_NE(err.find("stopped by SIGTERM after "), std::string::npos) << err;
  EXPECT_EQ(bytes_of(video), "the old video");
  int frames = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir_))
    if (e.path().extension() == ".png") {
      EXPECT_NO_THROW(load_image_file(e.path())) << e.path();
      ++frames;
    }
  EXPECT_GT(frames, 0);
  EXPECT_LT(frames, 501);
  EXPECT_TRUE(leftovers().empty()) << leftovers().front();
}

TEST_F(HostileInput, VideoSettingsAreRefusedBeforeTheFirstFrame) {
  if (!have_program("ffmpeg") || !have_program("ffprobe"))
    GTEST_SKIP() << "ffmpeg is not installed";
  const std::string frames = " --frames 0-3 -o " + quoted(dir_ / "f-%d.png");
  struct Case {
    std::string arguments, message;
  } cases[] = {
      {" --fps 1e308 --video " + quoted(dir_ / "v.mp4"), "plays from 0.01 to 1000"},
      {" --fps 1e-5 --video " + quoted(dir_ / "v.webm"), "plays from 0.01 to 1000"},
      {" --fps 60 --video " + quoted(dir_ / "v.gif"), "plays from 0.01 to 50"},
      {" --fps 30 --crf 60 --video " + quoted(dir_ / "v.mp4"), "--crf 60"},
  };
  for (const Case& c : cases) {
    const auto r =
        run_lightcone("animate " + terrell() + frames + c.arguments + " --samples 1 --quiet");
    EXPECT_EQ(r.status, 2) << c.arguments << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.arguments << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "f-0.png")) << c.arguments;
  }
  // Whatever else ffmpeg refuses (here: an ffmpeg without the codec), it refuses in the trial
  // frame, before rendering.
  fs::create_directory(dir_ / "bin");
  test::write_text(dir_ / "bin" / "ffmpeg",
                   "#!/bin/sh\necho 'Unknown encoder libx264' >&2\nexit 8\n");
  fs::permissions(dir_ / "bin" / "ffmpeg", fs::perms::owner_all);
  const auto r = run_lightcone("animate " + terrell() + frames + " --video " +
                                   quoted(dir_ / "v.mp4") + " --samples 1 --quiet",
                               "PATH=" + quoted(dir_ / "bin") + ":\"$PATH\"");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("ffmpeg cannot make a"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "f-0.png"));
  EXPECT_TRUE(leftovers().empty()) << leftovers().front();
}

}  // namespace
}  // namespace lightcone

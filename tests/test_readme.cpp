// The README's commands, run as written (its `./build/lightcone` being this build's program) in a
// fresh folder beside the bundled scenes: each succeeds and writes what it names.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

// The README's `./build/lightcone ...` command lines: the indented ones, and the program at the
// end of its first command's chain; without their comments.
std::vector<std::string> readme_commands() {
  std::istringstream readme(test::bytes_of(fs::path(LIGHTCONE_SOURCE_DIR) / "README.md"));
  std::vector<std::string> commands;
  for (std::string line; std::getline(readme, line);) {
    if (line.rfind("    ", 0) != 0) continue;
    const std::size_t at = line.find("./build/lightcone ");
    if (at == std::string::npos) continue;
    std::string command = line.substr(at);
    if (const std::size_t comment = command.find(" #"); comment != std::string::npos)
      command.erase(comment);
    while (!command.empty() && command.back() == ' ') command.pop_back();
    commands.push_back(command);
  }
  return commands;
}

class Readme : public test::TempDirTest {};

TEST_F(Readme, EveryCommandRunsAsWritten) {
  const std::vector<std::string> commands = readme_commands();
  ASSERT_GE(commands.size(), 15u);
  // The folder a user runs them in: the scenes beside it, the program at ./build/lightcone.
  fs::create_directory_symlink(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes", dir_ / "scenes");
  fs::create_directory(dir_ / "build");
  fs::create_symlink(LIGHTCONE_BINARY, dir_ / "build/lightcone");
  for (const std::string& command : commands) {
    SCOPED_TRACE(command);
    // The viewer opens a window and waits for its user (tests/test_viewer.cpp drives it).
    if (command.find("lightcone view ") != std::string::npos) continue;
    // The video needs ffmpeg; the frames are written without it.
    std::string run = command;
    if (command.find("--video") != std::string::npos && !test::have_program("ffmpeg"))
      run = command.substr(0, command.find(" --video"));
    const test::CommandResult r = test::run_command("cd " + test::quoted(dir_) + " && " + run);
    EXPECT_EQ(r.status, 0) << r.out << r.err;
    // What it names with -o (or --video) is there.
    for (const std::string option : {" -o ", " --video "}) {
      const std::size_t at = run.find(option);
      if (at == std::string::npos) continue;
      std::string name = run.substr(at + option.size());
      name = name.substr(0, name.find(' '));
      if (name.find('%') != std::string::npos) name = "frames/rocket-0000.png";
      EXPECT_TRUE(fs::is_regular_file(dir_ / name)) << name;
    }
  }
}

}  // namespace
}  // namespace lightcone

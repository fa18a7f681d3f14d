// Shared by the libFuzzer harnesses: each input is written to a file (the loaders read files,
// as the program does) in a folder of this process's own.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace lightcone::fuzz {

// This process's own folder, under the system's temporary folder.
inline const std::filesystem::path& own_dir() {
  static const std::filesystem::path dir = [] {
    auto d =
        std::filesystem::temp_directory_path() / ("lightcone-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

// Writes the input to `name` (which may name a subfolder) in the own folder.
inline std::filesystem::path input_file(const std::string& name, const std::uint8_t* data,
                                        std::size_t size) {
  const std::filesystem::path file = own_dir() / name;
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (f) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  return file;
}

// A scene loader input: override lines ("key.path=value"), a line "---", then the scene file
// (without the line, all of it is the scene).
struct SceneInput {
  std::vector<std::string> overrides;
  std::string scene;
};
inline SceneInput split_scene_input(const std::string& input) {
  SceneInput out{{}, input};
  if (const std::size_t split = input.find("\n---\n"); split != std::string::npos) {
    for (std::size_t start = 0; start < split;) {
      const std::size_t end = std::min(input.find('\n', start), split);
      out.overrides.push_back(input.substr(start, end - start));
      start = end + 1;
    }
    out.scene = input.substr(split + 5);
  }
  return out;
}

}  // namespace lightcone::fuzz

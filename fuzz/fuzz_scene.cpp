// The scene loader with --set overrides: the input is override lines ("key.path=value"), a
// line "---", then the scene file. Clear errors (InputError) are fine; anything else is a bug.
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> overrides;
  std::string scene = input;
  if (const std::size_t split = input.find("\n---\n"); split != std::string::npos) {
    std::size_t start = 0;
    while (start < split) {
      const std::size_t end = std::min(input.find('\n', start), split);
      overrides.push_back(input.substr(start, end - start));
      start = end + 1;
    }
    scene = input.substr(split + 5);
  }
  const auto file = lightcone::fuzz::input_file(
      "scene.json", reinterpret_cast<const std::uint8_t*>(scene.data()), scene.size());
  try {
    lightcone::SceneLoadReport report;
    lightcone::load_scene_file(file, overrides, report);
  } catch (const lightcone::InputError&) {
  }
  return 0;
}

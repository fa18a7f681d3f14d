// The scene loader with --set overrides: the input is override lines ("key.path=value"), a
// line "---", then the scene file. Clear errors (InputError) are fine; anything else is a bug.
#include <string>

#include "fuzz_support.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const lightcone::fuzz::SceneInput input =
      lightcone::fuzz::split_scene_input(std::string(reinterpret_cast<const char*>(data), size));
  const auto file = lightcone::fuzz::input_file(
      "scene.json", reinterpret_cast<const std::uint8_t*>(input.scene.data()), input.scene.size());
  try {
    lightcone::SceneLoadReport report;
    lightcone::load_scene_file(file, input.overrides, report);
  } catch (const lightcone::InputError&) {
  }
  return 0;
}

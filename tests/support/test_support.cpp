#include "support/test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "lightcone/io/scene_file.hpp"

namespace lightcone::test {

namespace fs = std::filesystem;

fs::path fresh_temp_dir(const std::string& name) {
  static std::atomic<int> counter{0};
  const fs::path dir = fs::temp_directory_path() / ("lightcone-test-" + std::to_string(getpid()) +
                                                    "-" + std::to_string(counter++) + "-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

Scene scene_from_json(const std::string& json) {
  const fs::path file = fresh_temp_dir("scene") / "scene.json";
  write_text(file, json);
  SceneLoadReport report;
  return load_scene_file(file, {}, report);
}

Scene load_repository_scene(const std::string& name) {
  SceneLoadReport report;
  return load_scene_file(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes" / name, {}, report);
}

static std::string read_all(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CommandResult run_lightcone(const std::string& arguments) {
  const fs::path dir = fresh_temp_dir("cmd");
  const std::string command = std::string("'") + LIGHTCONE_BINARY + "' " + arguments + " >'" +
                              (dir / "out").string() + "' 2>'" + (dir / "err").string() +
                              "' </dev/null";
  const int raw = std::system(command.c_str());
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = read_all(dir / "out");
  r.err = read_all(dir / "err");
  fs::remove_all(dir);
  return r;
}

}  // namespace lightcone::test

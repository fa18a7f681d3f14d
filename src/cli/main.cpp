// The `lightcone` command: a thin layer over the library (scene file -> renderer / locate).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/render/locate.hpp"
#include "lightcone/render/renderer.hpp"
#include "lightcone/render/tone_map.hpp"
#include "progress_bar.hpp"

namespace fs = std::filesystem;
using namespace lightcone;

namespace {

constexpr int kBadInput = 2;

Scene load(const std::string& file, const std::vector<std::string>& overrides) {
  SceneLoadReport report;
  Scene scene = load_scene_file(file, overrides, report);
  for (const std::string& w : report.warnings)
    std::fprintf(stderr, "lightcone: warning: %s\n", w.c_str());
  return scene;
}

void require_writable_target(const std::string& option, const std::string& path) {
  if (fs::is_directory(path)) throw InputError(option + " " + path + ": is a folder, not a file");
  const fs::path parent = fs::absolute(fs::path(path)).parent_path();
  if (!fs::is_directory(parent))
    throw InputError(option + " " + path + ": folder " + parent.string() + " does not exist");
}

Vec3 parse_triple(const std::string& option, const std::string& text) {
  Vec3 v;
  std::stringstream in(text);
  std::string part;
  int n = 0;
  while (std::getline(in, part, ',')) {
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (n >= 3 || used != part.size() || part.empty() || !std::isfinite(x))
      throw InputError(option + " " + text + ": expected three numbers x,y,z");
    v[n++] = x;
  }
  if (n != 3) throw InputError(option + " " + text + ": expected three numbers x,y,z");
  return v;
}

nlohmann::ordered_json to_json(const Vec3& v) {
  return nlohmann::json::array({v.x, v.y, v.z});
}

struct RenderArgs {
  std::string scene, png;
  std::optional<std::string> exr;
  std::optional<int> width, height, samples;
  int threads = 0;
  std::vector<std::string> overrides;
  bool stats = false, quiet = false;
};

int run_render(const RenderArgs& a) {
  std::vector<std::string> overrides = a.overrides;
  if (a.width) overrides.push_back("camera.width=" + std::to_string(*a.width));
  if (a.height) overrides.push_back("camera.height=" + std::to_string(*a.height));
  if (a.samples) overrides.push_back("camera.samples=" + std::to_string(*a.samples));
  require_writable_target("-o", a.png);
  if (a.exr) require_writable_target("--exr", *a.exr);
  const Scene scene = [&] {
    try {
      return load(a.scene, overrides);
    } catch (const InputError& e) {
      // --width, --height and --samples travel as overrides; name the option the user typed.
      const std::string message = e.what();
      for (const auto& [option, path, given] :
           {std::tuple{"--width", "--set camera.width:", a.width.has_value()},
            std::tuple{"--height", "--set camera.height:", a.height.has_value()},
            std::tuple{"--samples", "--set camera.samples:", a.samples.has_value()}})
        if (given && message.rfind(path, 0) == 0)
          throw InputError(std::string(option) + ":" + message.substr(std::string(path).size()));
      throw;
    }
  }();

  RenderStats stats;
  Image image;
  {
    ProgressBar bar(!a.quiet && isatty(STDERR_FILENO));
    RenderOptions options;
    options.threads = a.threads;
    options.progress = [&bar](std::size_t done, std::size_t total) { bar.update(done, total); };
    image = render_image(scene, options, &stats);
  }
  write_images(tone_map(image, scene.render.tonemap), image, fs::path(a.png),
               a.exr ? std::optional<fs::path>(*a.exr) : std::optional<fs::path>());
  if (a.stats) {
    const nlohmann::ordered_json line = {
        {"seconds", stats.seconds},
        {"rays", stats.rays},
        {"mrays_per_s", stats.rays / std::max(stats.seconds, 1e-9) / 1e6}};
    std::fprintf(stderr, "%s\n", line.dump().c_str());
  }
  return 0;
}

struct LocateArgs {
  std::string scene;
  std::optional<std::string> object, point, world_point, direction;
  std::vector<std::string> overrides;
};

int run_locate(const LocateArgs& a) {
  LocateQuery query;
  const int given = (a.point ? 1 : 0) + (a.world_point ? 1 : 0) + (a.direction ? 1 : 0);
  if (given != 1)
    throw InputError(
        "locate: give exactly one of --point (with --object), --world-point, --direction");
  if (a.point) {
    if (!a.object) throw InputError("locate: --point needs --object NAME");
    query.kind = LocateQuery::Kind::ObjectPoint;
    query.object = *a.object;
    query.value = parse_triple("--point", *a.point);
  } else if (a.world_point) {
    query.kind = LocateQuery::Kind::WorldPoint;
    query.value = parse_triple("--world-point", *a.world_point);
  } else {
    query.kind = LocateQuery::Kind::SkyDirection;
    query.value = parse_triple("--direction", *a.direction);
    if (length(query.value) == 0) throw InputError("--direction: must not be zero");
  }
  const Scene scene = load(a.scene, a.overrides);
  LocateResult r;
  try {
    r = locate(scene, query);
  } catch (const std::invalid_argument& e) {
    throw InputError(a.scene + ": --object: " + e.what());
  }
  nlohmann::ordered_json out = {{"pixel", {r.pixel_x, r.pixel_y}},
                                {"direction", to_json(r.direction)},
                                {"emission_time", nullptr},
                                {"emission_position", nullptr},
                                {"distance", nullptr},
                                {"in_view", r.in_view},
                                {"doppler", r.doppler}};
  if (r.emission_time) out["emission_time"] = *r.emission_time;
  if (r.emission_position) out["emission_position"] = to_json(*r.emission_position);
  if (r.distance) out["distance"] = *r.distance;
  std::printf("%s\n", out.dump().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"lightcone: what a camera really sees at a large fraction of the speed of light"};
  app.require_subcommand(1);

  RenderArgs render;
  CLI::App* render_cmd = app.add_subcommand("render", "Render a scene to PNG (and OpenEXR)");
  render_cmd->add_option("scene", render.scene, "Scene file (JSON)")->required();
  render_cmd->add_option("-o,--output", render.png, "Output PNG (8-bit sRGB)")->required();
  render_cmd->add_option("--exr", render.exr, "Also write linear radiance to this OpenEXR file");
  render_cmd->add_option("--width", render.width, "Override camera.width");
  render_cmd->add_option("--height", render.height, "Override camera.height");
  render_cmd->add_option("--samples", render.samples, "Override camera.samples");
  render_cmd->add_option("--threads", render.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(0, 4096));
  render_cmd->add_option("--set", render.overrides, "Override a scene value: key.path=value");
  render_cmd->add_flag("--stats", render.stats, "Print one JSON line of timing to stderr");
  render_cmd->add_flag("--quiet", render.quiet, "No progress bar");

  LocateArgs loc;
  CLI::App* locate_cmd =
      app.add_subcommand("locate", "Where a point or direction appears in the image (JSON)");
  locate_cmd->add_option("scene", loc.scene, "Scene file (JSON)")->required();
  locate_cmd->add_option("--object", loc.object, "Object whose point is located");
  locate_cmd->add_option("--point", loc.point, "x,y,z in the object's own coordinates");
  locate_cmd->add_option("--world-point", loc.world_point, "x,y,z of a point at rest in W");
  locate_cmd->add_option("--direction", loc.direction,
                         "x,y,z of a direction at infinity, in the sky's rest frame");
  locate_cmd->add_option("--set", loc.overrides, "Override a scene value: key.path=value");

  if (argc > 1 && argv[1][0] != '-' && std::string(argv[1]) != "render" &&
      std::string(argv[1]) != "locate") {
    std::fprintf(stderr, "lightcone: unknown command '%s' (use render or locate; see --help)\n",
                 argv[1]);
    return kBadInput;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "lightcone: %s (see --help)\n", e.what());
    return kBadInput;
  }
  try {
    if (*render_cmd) return run_render(render);
    return run_locate(loc);
  } catch (const InputError& e) {
    std::fprintf(stderr, "lightcone: %s\n", e.what());
    return kBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lightcone: error: %s\n", e.what());
    return 1;
  }
}

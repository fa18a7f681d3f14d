// The `lightcone` command: a thin layer over the library (scene file -> renderer / locate).
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "animate.hpp"
#include "cli_common.hpp"
#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/pixel_probe.hpp"
#include "lightcone/frame/request_rules.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/locate_json.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/io/spelling.hpp"
#include "lightcone/scene/speed_text.hpp"
#include "lightcone/trace/curved_shadows.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/scene_info.hpp"
#include "render_command.hpp"
#include "version.hpp"
#include "viewer/flight.hpp"
#include "viewer/viewer.hpp"

namespace fs = std::filesystem;
using namespace lightcone;

namespace {

// A seed is a whole number from 0 to 2^64 - 1; CLI11 alone would take '' as 0 and wrap -1.
CLI::Validator seed_value() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (text.empty() || error != std::errc{} || stop != end)
          return fmt::format(
              "a seed is a whole number from 0 to 18446744073709551615 (each picks another "
              "deterministic sample pattern), got '{}'",
              text);
        return {};
      },
      "SEED");
}

void print_error(const std::string& message) {
  const std::string line = "lightcone: " + printable(message) + "\n";
  std::fwrite(line.data(), 1, line.size(), stderr);
}

Vec3 parse_triple(const std::string& option, const std::string& text) {
  const std::vector<double> v = parse_numbers(option, text, 3, false, "three numbers x,y,z");
  return {v[0], v[1], v[2]};
}

// Warnings on stderr for the bodies the camera does not see (bodies_out_of_view), at most ten
// named, then a hint.
void warn_out_of_view(const Scene& scene) {
  const std::vector<BodyOutOfView> hidden = bodies_out_of_view(scene);
  for (std::size_t k = 0; k < std::min<std::size_t>(hidden.size(), 10); ++k) {
    const BodyOutOfView& b = hidden[k];
    const Vec3& d = b.seen.direction;
    if (b.behind)
      std::fprintf(stderr,
                   "lightcone: warning: object \"%s\" is seen behind the camera (look direction "
                   "%.3g, %.3g, %.3g in the camera's frame)\n",
                   b.name.c_str(), d.x, d.y, d.z);
    else
      std::fprintf(stderr,
                   "lightcone: warning: object \"%s\" is seen out of view, at pixel (%.0f, %.0f) "
                   "of %dx%d\n",
                   b.name.c_str(), b.seen.pixel_x, b.seen.pixel_y, scene.camera.width,
                   scene.camera.height);
  }
  if (hidden.size() > 10)
    std::fprintf(stderr, "lightcone: warning: and %zu more\n", hidden.size() - 10);
  if (!hidden.empty())
    std::fprintf(stderr,
                 "lightcone: a moving body is seen where it was when its light left it; "
                 "\"seen_at\" places a body by where it is seen (docs/scene-format.md)\n");
}

int run_check(const std::string& file, const std::vector<std::string>& overrides,
              const SceneLoadOptions& options) {
  const Scene scene = load(file, overrides, options);
  throw_if_refused(scene_refused(scene));  // ok only for a scene the renderers draw
  warn_out_of_view(scene);
  std::printf(
      "%s: ok (%s, %s, %dx%d)\n", file.c_str(), counted(scene.objects.size(), "object").c_str(),
      counted(scene.lights.size(), "light").c_str(), scene.camera.width, scene.camera.height);
  return 0;
}

int run_info(const std::string& file, const std::vector<std::string>& overrides,
             const SceneLoadOptions& options, bool json) {
  const Scene scene = load(file, overrides, options);
  warn_out_of_view(scene);
  const SceneInfo info = scene_info(scene);
  if (json) {
    std::printf("%s\n", scene_info_json(info, scene).c_str());
    return 0;
  }
  std::printf("%s: %dx%d pixels, %s each\n", file.c_str(), info.width, info.height,
              counted(info.samples, "sample").c_str());
  for (const BodyInfo& b : info.bodies)
    std::printf("  %-8s %-24s speed %s c, gamma %.6g\n", b.kind.c_str(), b.name.c_str(),
                speed_text(b.speed).c_str(), b.gamma);
  if (const auto& h = info.hole) {
    std::printf(
        "black hole: M = %.6g; horizon r = %.6g, photon sphere r = %.6g, innermost stable "
        "circular orbit r = %.6g\n",
        h->mass, h->horizon, h->photon_sphere, h->isco);
    if (std::isnan(h->shadow_static_degrees))
      std::printf(
          "  camera at r = %.6g (%.4g M), inside the horizon: shadow %.4f degrees in radius about "
          "the direction straight down (no static observer there)\n",
          h->camera_radius, h->camera_radius / h->mass, h->shadow_degrees);
    else
      std::printf(
          "  camera at r = %.6g (%.4g M): shadow %.4f degrees in radius (%.4f for the static "
          "observer there)\n",
          h->camera_radius, h->camera_radius / h->mass, h->shadow_degrees,
          h->shadow_static_degrees);
    if (h->any_light)
      std::printf("  shift g over the image: %.4g to %.4g; mean image order %.3g\n", h->shift_min,
                  h->shift_max, h->mean_image_order);
  } else {
    std::printf("Doppler factor over the image: %.4g to %.4g\n", info.doppler_min,
                info.doppler_max);
  }
  if (info.emission_time_min)
    std::printf("light seen left the scene between t = %.6g and %.6g (observed at t = %.6g)\n",
                *info.emission_time_min, *info.emission_time_max, info.observation_time);
  if (const auto& stars = scene.sky.stars)
    std::printf("%zu stars of the \"%s\" catalogue, brighter than V %.3g, exposure %+.3g EV\n",
                stars->stars ? stars->stars->size() : 0, stars->catalogue.c_str(),
                stars->magnitude_limit, stars->exposure);
  std::printf("%llu triangles; about %.1f MB to render\n",
              static_cast<unsigned long long>(info.triangles), info.memory_bytes / 1e6);
  return 0;
}

struct LocateArgs {
  std::string scene;
  std::optional<std::string> object, point, world_point, direction, pixel;
  std::vector<std::string> overrides;
  SceneLoadOptions scene_options;  // --allow-outside
};

int run_locate(const LocateArgs& a) {
  LocateQuery query;
  const int given =
      (a.point ? 1 : 0) + (a.world_point ? 1 : 0) + (a.direction ? 1 : 0) + (a.pixel ? 1 : 0);
  if (given != 1)
    throw InputError(
        "locate: give exactly one of --point (with --object), --world-point, --direction, "
        "--pixel");
  if (a.pixel) {
    const std::vector<double> xy = parse_numbers("--pixel", *a.pixel, 0, false, "numbers x,y");
    throw_if_refused(probe_request_refused(xy, a.object.has_value()));
    const Scene scene = load(a.scene, a.overrides, a.scene_options);
    throw_if_refused(probe_refused(scene, xy[0], xy[1]));
    std::printf("%s\n", probe_json(probe_pixel(scene, xy[0], xy[1]), scene).c_str());
    return 0;
  }
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
    if (query.value.x == 0 && query.value.y == 0 && query.value.z == 0)
      throw InputError("--direction: must not be zero");
  }
  const Scene scene = load(a.scene, a.overrides, a.scene_options);
  throw_if_refused(locate_refused(scene, query));
  LocateResult r;
  try {
    r = locate(scene, query);
  } catch (const std::invalid_argument& e) {
    throw InputError(a.scene + ": --object: " + e.what());
  }
  // A point so far away that its light path overflows double precision has no answer to print.
  if (!locate_result_is_finite(r))
    throw InputError(fmt::format(
        "{}: too far from the camera to be located in double precision",
        a.point ? "--point " + *a.point : "--world-point " + a.world_point.value_or("")));
  std::printf("%s\n", locate_json(r, scene).c_str());
  return 0;
}

struct ViewArgs {
  std::string scene;
  std::vector<std::string> overrides;
  SceneLoadOptions scene_options;  // --allow-outside
  std::optional<int> width, height, benchmark;
  bool split = false;
  std::optional<double> time_scale;
  std::string tessellation = "auto";
};

int run_view(const ViewArgs& a) {
  std::vector<std::string> overrides = a.overrides;
  if (a.width) overrides.push_back("camera.width=" + std::to_string(*a.width));
  if (a.height) overrides.push_back("camera.height=" + std::to_string(*a.height));
  const Scene scene = load(a.scene, overrides, a.scene_options);
  throw_if_refused(scene_refused(scene));
  for (const std::string& difference : raster_differences(scene))
    std::fprintf(stderr, "lightcone: warning: %s: the raster renderer differs here: %s\n",
                 a.scene.c_str(), difference.c_str());
  if (a.time_scale && !(*a.time_scale >= 0 && *a.time_scale <= 1e6))
    throw InputError("--time-scale: must be from 0 to 1e6");
  try {
    if (a.benchmark) {
      if (*a.benchmark < 1)
        throw InputError("--benchmark: the number of frames must be at least 1");
      return run_viewer_benchmark(scene, *a.benchmark, tessellation_named(a.tessellation),
                                  curved_body_shadows);
    }
    ViewerOptions options;
    options.scene_path = a.scene;
    options.split = a.split;
    options.time_scale = a.time_scale;
    options.tessellation = tessellation_named(a.tessellation);
    options.curved_shadows = curved_body_shadows;
    options.probe = probe_pixel;
    return run_viewer(scene, options);
  } catch (const GlUnavailable& e) {
    throw InputError(fmt::format(
        "view: {}: the viewer needs OpenGL 3.3 (core profile), e.g. Mesa's llvmpipe", e.what()));
  }
}

// " (did you mean --samples for --sample?)": the nearest option of `command` for each word of the
// command line that looks like an option and is none of its.
std::string option_suggestions(const CLI::App& command, int argc, char** argv) {
  std::vector<std::string> names = {"--help", "-h"};
  for (const CLI::Option* option : command.get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    for (const std::string& name : option->get_snames()) names.push_back("-" + name);
  }
  const std::vector<std::string_view> views(names.begin(), names.end());
  std::vector<std::string> found;
  for (int i = 2; i < argc; ++i) {
    const std::string_view word = std::string_view(argv[i]).substr(0, std::strcspn(argv[i], "="));
    if (word.size() < 2 || word[0] != '-' ||
        std::find(views.begin(), views.end(), word) != views.end())
      continue;
    if (const auto near = nearest_name(word, views))
      found.push_back(fmt::format("{} for {}", *near, word));
  }
  if (found.empty()) return "";
  return fmt::format(" (did you mean {}?)", fmt::join(found, ", "));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"lightcone: what a camera really sees at a large fraction of the speed of light"};
  app.require_subcommand(1);
  app.set_version_flag(
      "--version", std::string("lightcone " LIGHTCONE_VERSION " (commit " LIGHTCONE_COMMIT ")"));

  RenderArgs render;
  CLI::App* render_cmd =
      app.add_subcommand("render", "Render a scene to PNG, JPEG or OpenEXR (by extension)");
  render_cmd->add_option("scene", render.scene, "Scene file (JSON)")->required();
  render_cmd
      ->add_option("-o,--output", render.output,
                   "Output image: .png (8-bit sRGB), .jpg, .exr (linear float), or - for a PNG "
                   "on standard output")
      ->required();
  render_cmd->add_option("--exr", render.exr,
                         "Also write linear radiance times 2^exposure to this OpenEXR file (the "
                         "EV in its header; --set render.exposure=0 for the radiance itself)");
  render_cmd
      ->add_option("--renderer", render.renderer,
                   "trace (the exact ray tracer, the default) or raster (the real-time polygon "
                   "renderer, through OpenGL)")
      ->check(library_rule(renderer_refused, "trace|raster"));
  render_cmd
      ->add_option("--tessellation", render.tessellation,
                   "raster: cut edges on the cpu, on the gpu (tessellation shaders, OpenGL 4), "
                   "or auto (gpu on a hardware OpenGL 4 driver, else cpu; the default)")
      ->check(library_rule(tessellation_refused, "cpu|gpu|auto"));
  render_cmd->add_option("--width", render.width, "Override camera.width");
  render_cmd->add_option("--height", render.height, "Override camera.height");
  render_cmd->add_option("--samples", render.samples, "Override camera.samples");
  render_cmd->add_option("--threads", render.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(0, 4096));
  render_cmd
      ->add_option("--seed", render.seed,
                   "Seed of the sample pattern (another deterministic pattern): 0 to 2^64 - 1")
      ->check(seed_value());
  render_cmd->add_option("--crop", render.crop,
                         "Render only the pixels x0,y0,x1,y1 (x1, y1 exclusive)");
  render_cmd->add_option("--aov", render.aov,
                         "Also write output variables into the EXR as channels: any of "
                         "doppler,emission_time,distance,object,depth,normal");
  render_cmd->add_option("--map", render.map,
                         "Write a colour-mapped picture of doppler, emission_time, distance, "
                         "object or depth (with a scale bar) instead of the render");
  render_cmd->add_option("--scale", render.scale,
                         "Scale the image size by this factor, keeping the picture (0.5: half the "
                         "width and height)");
  render_cmd->add_flag("--preview", render.preview,
                       "Quick look: a quarter of the size, 1 sample, the scene's exposure");
  render_cmd->add_option("--set", render.overrides, "Override a scene value: key.path=value");
  render_cmd->add_flag("--allow-outside", render.scene_options.mesh.allow_outside,
                       kAllowOutsideHelp);
  render_cmd->add_flag("--stats", render.stats,
                       "Print one JSON line of timing and the exposure to stderr");
  render_cmd->add_flag("--quiet", render.quiet, "No progress bar and no summary line");

  LocateArgs loc;
  CLI::App* locate_cmd =
      app.add_subcommand("locate",
                         "Where a point or direction appears in the image, or what a pixel shows "
                         "(JSON)");
  locate_cmd->add_option("scene", loc.scene, "Scene file (JSON)")->required();
  locate_cmd->add_option("--object", loc.object, "Object whose point is located");
  locate_cmd->add_option("--point", loc.point, "x,y,z in the object's own coordinates");
  locate_cmd->add_option("--world-point", loc.world_point, "x,y,z of a point at rest in W");
  locate_cmd->add_option("--pixel", loc.pixel,
                         "x,y of a point of the picture (pixel (i, j) covers [i, i+1) x [j, j+1)): "
                         "what is seen there");
  locate_cmd->add_option("--direction", loc.direction,
                         "x,y,z of a direction at infinity, in the sky's rest frame");
  locate_cmd->add_option("--set", loc.overrides, "Override a scene value: key.path=value");
  locate_cmd->add_flag("--allow-outside", loc.scene_options.mesh.allow_outside, kAllowOutsideHelp);

  std::string check_scene;
  std::vector<std::string> check_overrides;
  CLI::App* check_cmd =
      app.add_subcommand("check", "Validate a scene file (status 0 or 2); render nothing");
  check_cmd->add_option("scene", check_scene, "Scene file (JSON)")->required();
  check_cmd->add_option("--set", check_overrides, "Override a scene value: key.path=value");
  SceneLoadOptions check_options;
  check_cmd->add_flag("--allow-outside", check_options.mesh.allow_outside, kAllowOutsideHelp);

  std::string info_scene;
  std::vector<std::string> info_overrides;
  bool info_json = false;
  CLI::App* info_cmd = app.add_subcommand(
      "info", "Summarise a scene: speeds, Doppler range, time window, memory estimate");
  info_cmd->add_option("scene", info_scene, "Scene file (JSON)")->required();
  info_cmd->add_option("--set", info_overrides, "Override a scene value: key.path=value");
  SceneLoadOptions info_options;
  info_cmd->add_flag("--allow-outside", info_options.mesh.allow_outside, kAllowOutsideHelp);
  info_cmd->add_flag("--json", info_json, "One JSON object, for scripts");

  ViewArgs view;
  CLI::App* view_cmd = app.add_subcommand(
      "view", "Fly through a scene in a window (the real-time renderer, OpenGL 3.3)");
  view_cmd->add_option("scene", view.scene, "Scene file (JSON)")->required();
  view_cmd->add_option("--set", view.overrides, "Override a scene value: key.path=value");
  view_cmd->add_flag("--allow-outside", view.scene_options.mesh.allow_outside, kAllowOutsideHelp);
  view_cmd->add_option("--width", view.width, "Window width (default: camera.width)");
  view_cmd->add_option("--height", view.height, "Window height (default: camera.height)");
  view_cmd->add_flag("--split", view.split, "Start with the classical | relativistic split");
  view_cmd->add_option("--time-scale", view.time_scale,
                       fmt::format("Units of the camera's proper time per second (default 1; "
                                   "near a black hole, the scene's shortest free fall in {:g} s)",
                                   kSceneSeconds));
  view_cmd
      ->add_option("--tessellation", view.tessellation,
                   "Cut edges on the cpu, on the gpu (tessellation shaders, OpenGL 4), or auto "
                   "(gpu on a hardware OpenGL 4 driver, else cpu; the default)")
      ->check(library_rule(tessellation_refused, "cpu|gpu|auto"));
  view_cmd->add_option("--benchmark", view.benchmark,
                       "Render this many frames of a scripted flight offscreen and print one "
                       "JSON line (no window)");

  AnimateArgs animate;
  CLI::App* animate_cmd = app.add_subcommand(
      "animate", "Render frames at successive moments of the camera's clock, and a video");
  animate_cmd->add_option("scene", animate.scene, "Scene file (JSON)")->required();
  animate_cmd->add_option("-o,--output", animate.output,
                          "Frame files: a pattern with one %d, like frames/shot-%04d.png (.png, "
                          ".jpg or .exr)");
  animate_cmd->add_option("--exr", animate.exr,
                          "Also linear radiance times 2^exposure (the EV in each header): a "
                          "pattern ending in .exr");
  animate_cmd->add_option("--video", animate.video,
                          "A video of the frames through ffmpeg: .mp4 (H.264), .webm (VP9) or "
                          ".gif");
  animate_cmd->add_option("--fps", animate.fps, "Frames per unit of the clock (default 30)");
  animate_cmd->add_option("--frames", animate.frames, "Frames A-B (inclusive) only");
  animate_cmd->add_option("--animation", animate.animation,
                          "The whole animation's frames A-B, of which this run renders a part "
                          "(the automatic exposure is smoothed within it; default: the run's)");
  animate_cmd->add_option("--duration", animate.duration,
                          "Frames 0 to duration * fps - 1 (instead of --frames)");
  animate_cmd
      ->add_option("--clock", animate.clock,
                   "proper (the camera's own time, the default) or world (world time)")
      ->check(CLI::IsMember({"proper", "world"}));
  animate_cmd->add_option("--crf", animate.crf,
                          "Video quality, lower is better (default 18; 0 to 63)");
  animate_cmd
      ->add_option("--gif-width", animate.gif_width,
                   "A GIF's width: wider frames are scaled down to it (default 640)")
      ->check(CLI::Range(16, 16384));
  animate_cmd->add_flag("--resume", animate.resume,
                        "Keep frames whose files exist, decode and have the run's size; render "
                        "the rest");
  animate_cmd->add_option("--renderer", animate.renderer, "trace (the default) or raster")
      ->check(library_rule(renderer_refused, "trace|raster"));
  animate_cmd->add_option("--tessellation", animate.tessellation, "raster: cpu, gpu or auto")
      ->check(library_rule(tessellation_refused, "cpu|gpu|auto"));
  animate_cmd->add_option("--width", animate.width, "Override camera.width");
  animate_cmd->add_option("--height", animate.height, "Override camera.height");
  animate_cmd->add_option("--samples", animate.samples, "Override camera.samples");
  animate_cmd->add_option("--scale", animate.scale,
                          "Scale the image size by this factor, keeping the picture");
  animate_cmd->add_option("--threads", animate.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(0, 4096));
  animate_cmd->add_option("--seed", animate.seed, "Seed of the sample pattern: 0 to 2^64 - 1")
      ->check(seed_value());
  animate_cmd->add_option("--set", animate.overrides, "Override a scene value: key.path=value");
  animate_cmd->add_flag("--allow-outside", animate.scene_options.mesh.allow_outside,
                        kAllowOutsideHelp);
  animate_cmd->add_flag("--quiet", animate.quiet, "No progress bar and no summary line");

  EncodeArgs encode;
  CLI::App* encode_cmd =
      app.add_subcommand("encode", "Encode frame files (a %d pattern) into a video with ffmpeg");
  encode_cmd->add_option("pattern", encode.pattern, "Frame files, like frames/shot-%04d.png")
      ->required();
  encode_cmd->add_option("-o,--output", encode.output, "The video: .mp4, .webm or .gif")
      ->required();
  encode_cmd->add_option("--fps", encode.fps, "Frames per second (default 30)");
  encode_cmd->add_option("--frames", encode.frames,
                         "Frames A-B (default: from the first to the last frame file there is)");
  encode_cmd->add_option("--crf", encode.crf, "Quality, lower is better (default 18)");
  encode_cmd
      ->add_option("--gif-width", encode.gif_width,
                   "A GIF's width: wider frames are scaled down to it (default 640)")
      ->check(CLI::Range(16, 16384));
  encode_cmd->add_flag("--allow-gaps", encode.allow_gaps,
                       "Encode the frames there are when some between the first and last are "
                       "missing (default: refuse, naming the first missing one)");
  encode_cmd->add_flag("--quiet", encode.quiet, "No progress bar and no summary line");

  if (argc > 1 && argv[1][0] != '-') {
    // The commands as CLI11 holds them, in the order they were added.
    std::vector<std::string_view> commands;
    for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; }))
      commands.push_back(command->get_name());
    const std::string_view command = argv[1];
    if (std::find(commands.begin(), commands.end(), command) == commands.end()) {
      const auto near = nearest_name(command, commands);
      std::string listed;
      for (std::size_t i = 0; i < commands.size(); ++i)
        listed += fmt::format("{}{}",
                              i == 0                     ? ""
                              : i + 1 == commands.size() ? " or "
                                                         : ", ",
                              commands[i]);
      std::fprintf(stderr, "lightcone: unknown command '%s' (%suse %s; see --help)\n", argv[1],
                   near ? fmt::format("did you mean '{}'? ", *near).c_str() : "", listed.c_str());
      return kBadInput;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::string suggestions;
    if (argc > 1 && argv[1][0] != '-')
      suggestions = option_suggestions(*app.get_subcommand(argv[1]), argc, argv);
    std::fprintf(stderr, "lightcone: %s%s (see --help)\n", e.what(), suggestions.c_str());
    return kBadInput;
  }
  try {
    if (*render_cmd) return run_render(render);
    if (*check_cmd) return run_check(check_scene, check_overrides, check_options);
    if (*info_cmd) return run_info(info_scene, info_overrides, info_options, info_json);
    if (*view_cmd) return run_view(view);
    if (*animate_cmd) return run_animate(animate);
    if (*encode_cmd) return run_encode(encode);
    return run_locate(loc);
  } catch (const InputError& e) {
    print_error(e.what());
    return kBadInput;
  } catch (const Stopped& e) {
    print_error(std::string(e.what()) + " by " + StopSignals::name() + "; nothing written");
    return StopSignals::exit_status();
  } catch (const std::exception& e) {
    print_error(std::string("error: ") + e.what());
    return 1;
  }
}

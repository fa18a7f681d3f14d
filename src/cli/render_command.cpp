#include "render_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "cli_common.hpp"
#include "lightcone/frame/false_colour.hpp"
#include "lightcone/frame/request_rules.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/trace/curved_shadows.hpp"
#include "lightcone/trace/renderer.hpp"
#include "progress_bar.hpp"

namespace lightcone {
namespace {

// x0,y0,x1,y1 in pixels, a non-empty window inside the image.
PixelWindow parse_crop(const std::string& text, int width, int height) {
  const std::vector<double> v = parse_numbers("--crop", text, 4, true, "four integers x0,y0,x1,y1");
  if (v[0] < 0 || v[1] < 0 || v[2] > width || v[3] > height || v[0] >= v[2] || v[1] >= v[3])
    throw InputError("--crop " + text + ": the window must be non-empty and inside the " +
                     std::to_string(width) + "x" + std::to_string(height) + " image");
  return {static_cast<int>(v[0]), static_cast<int>(v[1]), static_cast<int>(v[2]),
          static_cast<int>(v[3])};
}

constexpr const char* kAovNames =
    "doppler, emission_time, distance, object, depth, normal, image_order";

std::vector<Aov> parse_aovs(const std::string& text) {
  std::vector<Aov> aovs;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    const std::optional<Aov> aov = aov_from_name(part);
    if (!aov)
      throw InputError("--aov " + text + ": unknown output variable '" + part + "' (use " +
                       kAovNames + ")");
    if (std::find(aovs.begin(), aovs.end(), *aov) == aovs.end()) aovs.push_back(*aov);
  }
  if (aovs.empty()) throw InputError("--aov: give one or more of " + std::string(kAovNames));
  return aovs;
}

// What a render writes, checked before anything is rendered.
struct RenderOutputs {
  bool to_stdout = false;
  std::optional<ImageFormat> format;
  bool raster = false;
  std::vector<Aov> aovs;
  std::optional<Aov> map;  // --map's quantity (also among aovs)
};

RenderOutputs checked_outputs(const RenderArgs& a) {
  RenderOutputs out;
  out.to_stdout = a.output == "-";
  out.format = ImageFormat::kPng;
  if (!out.to_stdout) {
    if (a.output.empty()) throw InputError("-o: the output file name is empty");
    out.format = image_format_of(a.output);
    if (!out.format)
      throw InputError("-o " + a.output +
                       ": unknown image format (the name must end in .png, .jpg or .exr)");
    require_writable_target("-o", a.output);
    require_writable_target("-o", partial_name(a.output));
  }
  if (a.exr) {
    if (image_format_of(*a.exr) != ImageFormat::kExr)
      throw InputError("--exr " + *a.exr + ": the name must end in .exr");
    require_writable_target("--exr", *a.exr);
    require_writable_target("--exr", partial_name(*a.exr));
    if (!out.to_stdout && same_file(a.output, *a.exr))
      throw InputError("--exr " + *a.exr + ": is the same file as -o");
  }

  out.raster = a.renderer == "raster";
  // Output variables with the raster renderer are refused by the library's rule
  // (render_refused), as every door refuses them.
  if (out.raster && a.crop)
    throw InputError("--crop: only the ray tracer has it (leave out --renderer raster)");
  if (a.aov) {
    out.aovs = parse_aovs(*a.aov);
    if (out.format != ImageFormat::kExr && !a.exr)
      throw InputError(
          "--aov: the output variables go into an OpenEXR file: give -o NAME.exr "
          "or --exr NAME.exr");
  }
  if (a.map) {
    out.map = aov_from_name(*a.map);
    if (!out.map || *out.map == Aov::kNormal)
      throw InputError("--map " + *a.map +
                       ": unknown quantity (use doppler, emission_time, distance, object, depth, "
                       "image_order)");
    if (out.format == ImageFormat::kExr)
      throw InputError(
          "--map: the map is a picture: give -o NAME.png or NAME.jpg (the values "
          "themselves go into an EXR with --aov)");
    if (std::find(out.aovs.begin(), out.aovs.end(), *out.map) == out.aovs.end())
      out.aovs.push_back(*out.map);
  }
  return out;
}

// The scene with the command's size, sample and preview options, refused where the library's
// rules refuse what it asks (frame/request_rules.hpp).
Scene render_scene(const RenderArgs& a, const RenderOutputs& out) {
  std::vector<std::string> overrides = a.overrides;
  if (a.samples) overrides.push_back("camera.samples=" + std::to_string(*a.samples));
  if (a.preview) overrides.push_back("camera.samples=1");

  Scene scene = [&] {
    try {
      return load(a.scene, overrides, a.scene_options);
    } catch (const InputError& e) {
      // --samples travels as an override; name the option the user typed.
      const std::string message = e.what(), path = "--set camera.samples:";
      if (a.samples && message.rfind(path, 0) == 0)
        throw InputError("--samples:" + message.substr(path.size()));
      throw;
    }
  }();
  if (a.width || a.height) {
    const std::string kept = resize_keeping_field(scene.camera, a.width, a.height);
    if (!kept.empty() && !a.quiet) std::fprintf(stderr, "lightcone: %s\n", kept.c_str());
  }
  if (a.scale) scale_image_size(scene.camera, *a.scale);
  if (a.preview) scale_image_size(scene.camera, 0.25);  // a quarter of the size, the same view
  throw_if_refused(render_refused(scene, {.aovs = out.aovs}));
  return scene;
}

struct Rendered {
  Image image;
  RenderStats stats;
  std::size_t raster_triangles = 0;
  bool stopped = false;  // by a signal: the finished tiles only
  std::size_t tiles_done = 0, tiles_total = 0;
  std::vector<float> sky;          // for --map: 1 where the pixel's centre ray met the sky
  bool exposure_deferred = false;  // the image is at EV 0; stats.exposure is still to apply
};

// Only an EXR holds the linear picture; the other files show it tone-mapped.
bool keeps_linear(const RenderArgs& a, const RenderOutputs& out) {
  return a.exr.has_value() || (!out.to_stdout && *out.format == ImageFormat::kExr);
}

// The render, by either renderer, with a progress bar on a terminal.
Rendered render_with_progress(const RenderArgs& a, const Scene& scene, const RenderOutputs& out) {
  if (interrupted) throw Stopped("stopped before rendering");
  RenderOptions options;
  options.threads = a.threads;
  options.seed = a.seed;
  if (a.crop) options.crop = parse_crop(*a.crop, scene.camera.width, scene.camera.height);
  options.cancel = &interrupted;
  options.aovs = out.aovs;
  // A map hatches the sky: where the rays met no surface, the sky or a black hole's shadow
  // (the object variable, not written unless asked for).
  const bool sky_for_map =
      out.map && std::find(out.aovs.begin(), out.aovs.end(), Aov::kObject) == out.aovs.end();
  if (sky_for_map) options.aovs.push_back(Aov::kObject);
  Rendered r;
  std::atomic<std::size_t> tiles_done{0}, tiles_total{0};
  {
    ProgressBar bar(!a.quiet && isatty(STDERR_FILENO));
    options.progress = [&](std::size_t done, std::size_t total) {
      tiles_done = std::max<std::size_t>(tiles_done, done);
      tiles_total = total;
      bar.update(done, total);
    };
    if (out.raster) {
      for (const std::string& difference : raster_differences(scene))
        std::fprintf(stderr, "lightcone: warning: %s: the raster renderer differs here: %s\n",
                     a.scene.c_str(), difference.c_str());
      RasterStats raster_stats;
      try {
        r.image =
            render_raster(scene, &raster_stats, {}, a.seed, tessellation_named(a.tessellation),
                          curved_body_shadows, nullptr, options.aovs);
      } catch (const GlUnavailable& e) {
        throw InputError(fmt::format(
            "--renderer raster: {}: the raster renderer needs OpenGL 3.3 (core profile) through "
            "EGL, e.g. Mesa's llvmpipe; the ray tracer (the default) needs neither",
            e.what()));
      }
      r.raster_triangles = raster_stats.triangles;
      r.stats.seconds = raster_stats.seconds;
      r.stats.exposure = raster_stats.exposure;
      r.stats.rays =
          static_cast<std::uint64_t>(r.image.width) * r.image.height * scene.camera.samples;
    } else {
      // A picture only shown is exposed in the tone map's pass (display_of), not one of its own.
      options.defer_exposure = r.exposure_deferred = !out.map && !keeps_linear(a, out);
      r.image = render_image(scene, options, &r.stats);
    }
  }
  if (out.map)
    for (auto c = r.image.channels.begin(); c != r.image.channels.end(); ++c)
      if (c->name == aov_name(Aov::kObject)) {
        for (const float object : c->values)
          r.sky.push_back(object == kObjectSky || object == kObjectShadow ? 1.0f : 0.0f);
        if (sky_for_map) r.image.channels.erase(c);
        break;
      }
  // A stopped render never replaces a finished image: what it has goes beside the target.
  r.stopped = r.stats.cancelled || interrupted;
  r.tiles_done = tiles_done;
  r.tiles_total = tiles_total;
  return r;
}

// The picture the image files show: the tone-mapped render, or --map's colour map. Without
// `keep_linear` the render is tone-mapped in place.
Image display_of(Rendered& r, const Scene& scene, const RenderOutputs& out, bool keep_linear) {
  if (out.map) {
    const std::vector<std::string> names = aov_channel_names(*out.map);
    const auto channel = std::find_if(r.image.channels.begin(), r.image.channels.end(),
                                      [&](const NamedChannel& c) { return c.name == names[0]; });
    return false_colour(*channel, r.image.width, r.image.height, aov_map_label(*out.map), r.sky);
  }
  if (r.exposure_deferred) {
    std::size_t non_finite = 0;
    Image display =
        expose_and_tone_map(std::move(r.image), r.stats.exposure, scene.render.tonemap, non_finite);
    // As render_image refuses a picture it exposed itself.
    if (const auto refused = picture_refused(scene, non_finite, r.stats.exposure))
      throw std::runtime_error(*refused);
    return display;
  }
  return keep_linear ? tone_map(r.image, scene.render.tonemap)
                     : tone_map(std::move(r.image), scene.render.tonemap);
}

// The files (or standard output), the summary line and --stats; a stopped render's files go
// beside their targets.
int write_rendered(const RenderArgs& a, const Scene& scene, const RenderOutputs& out, Rendered& r) {
  const bool keep_linear = keeps_linear(a, out);
  // The EXR's header says by what the radiance was scaled.
  r.image.exposure = r.stats.exposure;
  const Image display = display_of(r, scene, out, keep_linear);
  const bool stopped = r.stopped;
  if (stopped && out.to_stdout) {
    std::fprintf(stderr, "lightcone: stopped by %s: nothing written to standard output\n",
                 StopSignals::name().c_str());
    return StopSignals::exit_status();
  }
  if (out.to_stdout) {
    const std::vector<unsigned char> png = encode_png(display);
    if (std::fwrite(png.data(), 1, png.size(), stdout) != png.size() || std::fflush(stdout) != 0)
      throw std::runtime_error("cannot write the PNG to standard output");
  }
  const auto target = [&](const std::string& path) { return stopped ? partial_name(path) : path; };
  std::vector<ImageOutput> outputs;
  if (!out.to_stdout) outputs.push_back({target(a.output), *out.format});
  if (a.exr) outputs.push_back({target(*a.exr), ImageFormat::kExr});
  write_images(display, keep_linear ? r.image : display, outputs);

  const std::string written = out.to_stdout ? std::string("standard output") : target(a.output);
  const std::string also = a.exr ? " and " + target(*a.exr) : std::string();
  if (stopped) {
    std::fprintf(stderr,
                 "lightcone: stopped by %s with %zu of %zu tiles done: wrote them to %s%s (the "
                 "tiles not done are black); %s is untouched\n",
                 StopSignals::name().c_str(), r.tiles_done, r.tiles_total, written.c_str(),
                 also.c_str(), a.output.c_str());
    return StopSignals::exit_status();
  }
  const RenderStats& stats = r.stats;
  const double mrays = stats.rays / std::max(stats.seconds, 1e-9) / 1e6;
  if (!a.quiet && out.raster)
    std::fprintf(stderr,
                 "lightcone: %dx%d, %s (raster, %zu triangles): %.2f s; wrote %s%s (exposure "
                 "%+.2f EV)\n",
                 r.image.width, r.image.height, counted(scene.camera.samples, "sample").c_str(),
                 r.raster_triangles, stats.seconds, written.c_str(), also.c_str(), stats.exposure);
  else if (!a.quiet)
    std::fprintf(stderr,
                 "lightcone: %dx%d, %s: %.2f s, %.2f Mrays/s; wrote %s%s (exposure %+.2f EV)\n",
                 r.image.width, r.image.height, counted(scene.camera.samples, "sample").c_str(),
                 stats.seconds, mrays, written.c_str(), also.c_str(), stats.exposure);
  if (a.stats) {
    nlohmann::ordered_json line = {{"seconds", stats.seconds},
                                   {"rays", stats.rays},
                                   {"mrays_per_s", mrays},
                                   {"exposure", stats.exposure}};
    if (scene.black_hole) line["mean_image_order"] = stats.mean_image_order;
    std::fprintf(stderr, "%s\n", line.dump().c_str());
  }
  return 0;
}

}  // namespace

int run_render(const RenderArgs& a) {
  const StopSignals stop_signals;
  const std::unique_ptr<tbb::global_control> threads = thread_limit(a.threads);
  const RenderOutputs outputs = checked_outputs(a);
  const Scene scene = render_scene(a, outputs);
  Rendered rendered = render_with_progress(a, scene, outputs);
  return write_rendered(a, scene, outputs, rendered);
}

}  // namespace lightcone

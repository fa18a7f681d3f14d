#include "animate.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>

#include "cli_common.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/trace/renderer.hpp"
#include "progress_bar.hpp"
#include "video.hpp"

namespace fs = std::filesystem;

namespace lightcone {

FramePattern::FramePattern(const std::string& option, const std::string& pattern) {
  const InputError error(option + " " + pattern +
                         ": a frame file name needs one frame number conversion, like "
                         "frames/shot-%04d.png");
  std::string text;
  bool found = false;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      text += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      text += '%';
      ++i;
      continue;
    }
    // %[0][width]d
    std::size_t j = i + 1;
    const bool zero = j < pattern.size() && pattern[j] == '0';
    std::size_t digits = j;
    while (digits < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[digits])))
      ++digits;
    if (digits >= pattern.size() || pattern[digits] != 'd' || found || digits - j > 2) throw error;
    found = true;
    width_ = digits > j ? std::stoi(pattern.substr(j, digits - j)) : 0;
    zero_ = zero;
    before_ = text;
    text.clear();
    i = digits;
  }
  if (!found) throw error;
  after_ = text;
}

std::string FramePattern::name(long long frame) const {
  const std::string number =
      zero_ ? fmt::format("{:0{}d}", frame, width_) : fmt::format("{:{}d}", frame, width_);
  return before_ + number + after_;
}

std::pair<long long, long long> parse_frame_range(const std::string& option,
                                                  const std::string& text) {
  const InputError error(option + " " + text +
                         ": expected A-B, the first and last frame numbers (0 <= A <= B)");
  const std::size_t dash = text.find('-');
  if (dash == std::string::npos || dash == 0) throw error;
  const auto number = [&](const std::string& part) {
    if (part.empty() || part.size() > 12 ||
        !std::all_of(part.begin(), part.end(), [](unsigned char c) { return std::isdigit(c); }))
      throw error;
    return std::stoll(part);
  };
  const long long first = number(text.substr(0, dash)), last = number(text.substr(dash + 1));
  if (first > last)
    throw InputError(
        fmt::format("{} {}: the range is reversed ({} after {})", option, text, first, last));
  return {first, last};
}

namespace {

// The camera's proper time (in the model's units) at world time `time` on its world-line.
double proper_time_at_world_time(const Camera& camera, double time) {
  const Camera::Motion& m = camera.motion;
  if (!m.keyframes.empty()) return KeyframeWorldLine(m.keyframes).at_world_time(time).proper_time;
  return AcceleratedWorldLine(m.start.time, m.start.position, m.start.velocity, m.phases)
      .at_world_time(time)
      .proper_time;
}

std::string describe_frames(long long first, long long last) {
  return first == last ? fmt::format("frame {}", first)
                       : fmt::format("frames {} to {}", first, last);
}

}  // namespace

int run_animate(const AnimateArgs& a) {
  std::vector<std::string> overrides = a.overrides;
  if (a.width) overrides.push_back("camera.width=" + std::to_string(*a.width));
  if (a.height) overrides.push_back("camera.height=" + std::to_string(*a.height));
  if (a.samples) overrides.push_back("camera.samples=" + std::to_string(*a.samples));

  // Everything is checked before the first frame is rendered.
  if (!(a.fps > 0) || !std::isfinite(a.fps))
    throw InputError(fmt::format("--fps {}: must be greater than 0", a.fps));
  if (a.frames && a.duration)
    throw InputError("--frames and --duration: give one of them, not both");
  if (!a.frames && !a.duration)
    throw InputError("give the frames to render: --frames A-B or --duration SECONDS");
  long long first = 0, last = 0;
  if (a.frames) {
    std::tie(first, last) = parse_frame_range("--frames", *a.frames);
  } else {
    if (!(*a.duration > 0) || !std::isfinite(*a.duration))
      throw InputError(fmt::format("--duration {}: must be greater than 0", *a.duration));
    const double count = std::round(*a.duration * a.fps);
    if (count < 1 || count > 1e9)
      throw InputError(
          fmt::format("--duration {} at --fps {}: {} frames", *a.duration, a.fps, count));
    last = static_cast<long long>(count) - 1;
  }
  if (!a.output && !a.exr && !a.video)
    throw InputError("nothing to write: give -o PATTERN, --exr PATTERN or --video FILE");
  std::optional<FramePattern> output, exr;
  std::optional<ImageFormat> format;
  if (a.output) {
    output.emplace("-o", *a.output);
    format = image_format_of(output->name(first));
    if (!format)
      throw InputError("-o " + *a.output +
                       ": unknown image format (the name must end in .png, .jpg or .exr)");
    require_writable_target("-o", output->name(first));
  }
  if (a.exr) {
    exr.emplace("--exr", *a.exr);
    if (image_format_of(exr->name(first)) != ImageFormat::kExr)
      throw InputError("--exr " + *a.exr + ": the name must end in .exr");
    require_writable_target("--exr", exr->name(first));
    if (output && same_file(output->name(first), exr->name(first)))
      throw InputError("--exr " + *a.exr + ": is the same file as -o");
  }
  const bool raster = a.renderer == "raster";

  const Scene scene = load(a.scene, overrides);
  const Camera& camera = scene.camera;
  if (a.video) check_video("--video", *a.video, camera.width, camera.height, a.fps, a.crf);
  if (raster)
    for (const std::string& difference : raster_differences(scene))
      std::fprintf(stderr, "lightcone: warning: %s: the raster renderer differs here: %s\n",
                   a.scene.c_str(), difference.c_str());

  // Frame i is seen at the camera's proper time tau_0 + i / fps (in the scene's units of time),
  // or at its world time t_0 + i / fps; either way set as camera.proper_time would set it.
  const double c = scene.speed_of_light;
  const double proper_start = camera.motion.proper_time / c,
               world_start = camera.world_line.time / c;
  const auto frame_scene = [&](long long i) {
    Scene s = scene;
    const double step = static_cast<double>(i) / a.fps;
    s.camera.motion.proper_time = a.clock == "world"
                                      ? proper_time_at_world_time(camera, (world_start + step) * c)
                                      : (proper_start + step) * c;
    s.camera.world_line = camera_observation(s.camera.motion);
    const double speed = length(s.camera.world_line.velocity);
    if (!(speed < 1) || !std::isfinite(lorentz_gamma(s.camera.world_line.velocity)))
      throw InputError(fmt::format("frame {}: the camera is at the speed of light by then", i));
    return s;
  };

  std::unique_ptr<VideoWriter> video;
  if (a.video)
    video = std::make_unique<VideoWriter>(*a.video, camera.width, camera.height, a.fps, a.crf);

  const long long count = last - first + 1;
  long long rendered = 0, skipped = 0;
  const auto start = std::chrono::steady_clock::now();
  ProgressBar bar(!a.quiet && isatty(STDERR_FILENO));
  constexpr std::size_t kSteps = 1000;  // progress units a frame
  // Frame i is tone-mapped, encoded and written while frame i + 1 renders: one writer, so
  // files and video frames go out in order; its failure stops the run at the next frame.
  std::future<void> writing;
  const auto wait_for_writer = [&] {
    if (writing.valid()) writing.get();
  };
  const auto in_frame = [](long long i, const std::function<void()>& work) {
    try {
      work();
    } catch (const InputError& e) {
      throw InputError(fmt::format("frame {}: {}", i, e.what()));
    } catch (const std::exception& e) {
      throw std::runtime_error(fmt::format("frame {}: {}", i, e.what()));
    }
  };
  std::signal(SIGINT, on_interrupt);
  for (long long i = first; i <= last; ++i) {
    const std::size_t frames_done = static_cast<std::size_t>(i - first);
    std::vector<ImageOutput> outputs;
    if (output) outputs.push_back({output->name(i), *format});
    if (exr) outputs.push_back({exr->name(i), ImageFormat::kExr});
    const bool present = a.resume && !outputs.empty() &&
                         std::all_of(outputs.begin(), outputs.end(), [](const ImageOutput& o) {
                           return fs::is_regular_file(o.path);
                         });
    if (present) {
      ++skipped;
      wait_for_writer();
      if (video)
        in_frame(i, [&] {
          // The video gets the frame as its file holds it.
          const std::shared_ptr<Image> saved = load_image_file(outputs.front().path);
          video->add(outputs.front().format == ImageFormat::kExr
                         ? tone_map(*saved, scene.render.tonemap)
                         : *saved);
        });
      bar.update((frames_done + 1) * kSteps, static_cast<std::size_t>(count) * kSteps);
      continue;
    }
    bool cancelled = false;
    auto image = std::make_shared<Image>();
    const Scene s = [&] {
      Scene moment;
      in_frame(i, [&] { moment = frame_scene(i); });
      return moment;
    }();
    in_frame(i, [&] {
      if (raster) {
        try {
          *image = render_raster(s, nullptr, {}, a.seed, tessellation_mode(a.tessellation));
        } catch (const GlUnavailable& e) {
          throw InputError(fmt::format(
              "--renderer raster: {}: the raster renderer needs OpenGL 3.3 (core profile) "
              "through EGL, e.g. Mesa's llvmpipe",
              e.what()));
        }
      } else {
        RenderOptions options;
        options.threads = a.threads;
        options.seed = a.seed;
        options.cancel = &interrupted;
        options.progress = [&](std::size_t done, std::size_t total) {
          bar.update(frames_done * kSteps + done * kSteps / std::max<std::size_t>(total, 1),
                     static_cast<std::size_t>(count) * kSteps);
        };
        RenderStats stats;
        *image = render_image(s, options, &stats);
        cancelled = stats.cancelled;
      }
      if (std::any_of(image->rgb.begin(), image->rgb.end(),
                      [](float v) { return !std::isfinite(v); }))
        throw std::runtime_error("the render has non-finite values (NaN or infinity)");
    });
    if (cancelled) break;
    wait_for_writer();
    const ToneMap curve = s.render.tonemap;
    writing = std::async(std::launch::async, [=, &video] {
      in_frame(i, [&] {
        const Image display = tone_map(*image, curve);
        if (!outputs.empty()) write_images(display, *image, outputs);
        if (video) video->add(display);
      });
    });
    ++rendered;
    bar.update((frames_done + 1) * kSteps, static_cast<std::size_t>(count) * kSteps);
  }
  std::signal(SIGINT, SIG_DFL);
  wait_for_writer();
  if (interrupted) {
    std::fprintf(stderr, "lightcone: interrupted after %lld of %lld frames%s\n", rendered + skipped,
                 count, video ? "; no video written" : "");
    return kInterrupted;
  }
  if (video) video->finish();
  if (!a.quiet) {
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "lightcone: %s, %dx%d: %lld rendered, %lld already there, %.2f s%s%s\n",
                 describe_frames(first, last).c_str(), camera.width, camera.height, rendered,
                 skipped, seconds, a.video ? "; wrote " : "", a.video ? a.video->c_str() : "");
  }
  return 0;
}

int run_encode(const EncodeArgs& a) {
  const FramePattern pattern("encode", a.pattern);
  long long first = 0, last = -1;
  if (a.frames) std::tie(first, last) = parse_frame_range("--frames", *a.frames);
  if (!fs::is_regular_file(pattern.name(first)))
    throw InputError(fmt::format("encode {}: the first frame, {}, does not exist", a.pattern,
                                 pattern.name(first)));
  const std::shared_ptr<Image> opening = load_image_file(pattern.name(first));
  check_video("-o", a.output, opening->width, opening->height, a.fps, a.crf);
  // Every frame is read before encoding, so that a missing or odd one writes nothing.
  long long end = first;
  while ((a.frames ? end <= last : true) && fs::is_regular_file(pattern.name(end))) ++end;
  if (a.frames && end <= last)
    throw InputError(
        fmt::format("encode {}: frame {} ({}) is missing", a.pattern, end, pattern.name(end)));
  VideoWriter video(a.output, opening->width, opening->height, a.fps, a.crf);
  ProgressBar bar(!a.quiet && isatty(STDERR_FILENO));
  for (long long i = first; i < end; ++i) {
    const std::shared_ptr<Image> frame = i == first ? opening : load_image_file(pattern.name(i));
    if (frame->width != opening->width || frame->height != opening->height)
      throw InputError(fmt::format("encode: {} is {}x{}, the first frame {}x{}", pattern.name(i),
                                   frame->width, frame->height, opening->width, opening->height));
    video.add(image_format_of(pattern.name(i)) == ImageFormat::kExr
                  ? tone_map(*frame, ToneMap::kClamp)
                  : *frame);
    bar.update(static_cast<std::size_t>(i - first + 1), static_cast<std::size_t>(end - first));
  }
  video.finish();
  if (!a.quiet)
    std::fprintf(stderr, "lightcone: %s: %lld frames at %g fps\n", a.output.c_str(), end - first,
                 a.fps);
  return 0;
}

}  // namespace lightcone

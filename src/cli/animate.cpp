#include "animate.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <deque>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <unordered_map>

#include "cli_common.hpp"
#include "lightcone/frame/pixel_lattice.hpp"
#include "lightcone/frame/request_rules.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/scene/animation.hpp"
#include "lightcone/trace/curved_shadows.hpp"
#include "lightcone/trace/renderer.hpp"
#include "progress_bar.hpp"
#include "video.hpp"

namespace fs = std::filesystem;

namespace lightcone {

FramePattern::FramePattern(const std::string& option, const std::string& pattern) : text_(pattern) {
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

std::optional<long long> FramePattern::frame_of(const std::string& name) const {
  if (name.size() <= before_.size() + after_.size() || name.compare(0, before_.size(), before_) ||
      name.compare(name.size() - after_.size(), after_.size(), after_))
    return std::nullopt;
  const std::string digits =
      name.substr(before_.size(), name.size() - before_.size() - after_.size());
  std::size_t start = 0;
  while (!zero_ && start < digits.size() && digits[start] == ' ') ++start;
  if (start == digits.size() || digits.size() - start > 15 ||
      !std::all_of(digits.begin() + static_cast<std::ptrdiff_t>(start), digits.end(),
                   [](unsigned char c) { return std::isdigit(c); }))
    return std::nullopt;
  const long long frame = std::stoll(digits.substr(start));
  if (this->name(frame) != name) return std::nullopt;
  return frame;
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

// An animation's automatic exposure is averaged over this many seconds either side of a frame,
// each frame's metered on one pixel of each block of this many pixels square.
constexpr double kExposureSmoothing = 0.5;
constexpr int kMeteringLattice = 4;

// Every file the run writes, checked before the first frame: under each pattern, each frame's
// name is a regular file or absent, in a folder that exists and is writable, and no file is
// named by two patterns (`-o x%d.exr --exr x1%d.exr` both name x11.exr).
void check_frame_targets(const std::vector<std::pair<std::string, const FramePattern*>>& patterns,
                         long long first, long long last) {
  std::unordered_map<std::string, fs::path> folders;  // as named -> resolved, once checked
  std::unordered_map<std::string, std::pair<std::string, long long>> claimed;
  for (std::size_t k = 0; k < patterns.size(); ++k) {
    const auto& [option, pattern] = patterns[k];
    for (long long i = first; i <= last; ++i) {
      const std::string name = pattern->name(i);
      const fs::path absolute = fs::absolute(name);
      const std::string parent = absolute.parent_path().string();
      auto folder = folders.find(parent);
      if (folder == folders.end()) {
        require_writable_target(option, name);
        std::error_code ec;
        folder = folders.emplace(parent, fs::weakly_canonical(parent, ec)).first;
      }
      fs::path file = folder->second / absolute.filename();
      std::error_code ec;
      const fs::file_status link = fs::symlink_status(file, ec);
      if (fs::is_symlink(link)) file = fs::weakly_canonical(file, ec);
      const fs::file_status status = fs::is_symlink(link) ? fs::status(file, ec) : link;
      if (fs::is_directory(status))
        throw InputError(fmt::format("{} {}: frame {}, {}, is a folder, not a file", option,
                                     pattern->text(), i, name));
      if (fs::exists(status) && !fs::is_regular_file(status))
        throw InputError(fmt::format(
            "{} {}: frame {}, {}, is not a regular file (a device, a FIFO or a socket); it is "
            "not replaced",
            option, pattern->text(), i, name));
      if (patterns.size() < 2) continue;  // names of one pattern differ in their digits
      const auto [other, fresh] = claimed.emplace(file.string(), std::pair{option, i});
      if (!fresh)
        throw InputError(fmt::format("{} and {}: frame {} of {} and frame {} of {} are both {}",
                                     other->second.first, option, other->second.second,
                                     other->second.first, i, option, name));
    }
  }
}

// Why a frame already on disk cannot be kept by --resume (nullopt if it can): every output
// must decode and have the run's size. `kept` receives the first output's image.
std::optional<std::string> unusable_frame(const std::vector<ImageOutput>& outputs, int width,
                                          int height, std::shared_ptr<Image>& kept) {
  for (const ImageOutput& o : outputs) {
    std::shared_ptr<Image> image;
    try {
      image = load_image_file(o.path);
    } catch (const std::exception& e) {
      return e.what();
    }
    if (image->width != width || image->height != height)
      return fmt::format("{} is {}x{}, not {}x{}", o.path.string(), image->width, image->height,
                         width, height);
    if (!kept) kept = image;
  }
  return std::nullopt;
}

std::string describe_frames(long long first, long long last) {
  return first == last ? fmt::format("frame {}", first)
                       : fmt::format("frames {} to {}", first, last);
}

}  // namespace

int run_animate(const AnimateArgs& a) {
  const StopSignals stop_signals;
  const std::unique_ptr<tbb::global_control> threads = thread_limit(a.threads);
  std::vector<std::string> overrides = a.overrides;
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
  if (last - first + 1 > kMaxFramesPerRun)
    throw InputError(
        fmt::format("{}: {} frames; one run renders at most {} (split it with --frames A-B)",
                    a.frames ? "--frames " + *a.frames : fmt::format("--duration {}", *a.duration),
                    last - first + 1, kMaxFramesPerRun));
  // The whole animation, of which this run renders a part (a job array's task): the automatic
  // exposure's smoothing stops at its ends.
  long long animation_first = first, animation_last = last;
  if (a.animation) {
    std::tie(animation_first, animation_last) = parse_frame_range("--animation", *a.animation);
    if (const auto why = animation_part_refused(first, last, animation_first, animation_last))
      throw InputError(fmt::format("--animation {}: {}", *a.animation, *why));
  }
  if (!a.output && !a.exr && !a.video)
    throw InputError("nothing to write: give -o PATTERN, --exr PATTERN or --video FILE");
  std::optional<FramePattern> output, exr;
  std::optional<ImageFormat> format;
  std::vector<std::pair<std::string, const FramePattern*>> patterns;
  if (a.output) {
    output.emplace("-o", *a.output);
    format = image_format_of(output->name(first));
    if (!format)
      throw InputError("-o " + *a.output +
                       ": unknown image format (the name must end in .png, .jpg or .exr)");
    patterns.emplace_back("-o", &*output);
  }
  if (a.exr) {
    exr.emplace("--exr", *a.exr);
    if (image_format_of(exr->name(first)) != ImageFormat::kExr)
      throw InputError("--exr " + *a.exr + ": the name must end in .exr");
    patterns.emplace_back("--exr", &*exr);
  }
  check_frame_targets(patterns, first, last);
  const bool raster = a.renderer == "raster";

  const Scene scene = [&] {
    Scene s = load(a.scene, overrides, a.scene_options);
    if (a.width || a.height) {
      const std::string kept = resize_keeping_field(s.camera, a.width, a.height);
      if (!kept.empty() && !a.quiet) std::fprintf(stderr, "lightcone: %s\n", kept.c_str());
    }
    if (a.scale) scale_image_size(s.camera, *a.scale);
    return s;
  }();
  throw_if_refused(scene_refused(scene));
  const Camera& camera = scene.camera;
  if (a.video)
    check_video("--video", *a.video, camera.width, camera.height, a.fps, a.crf, a.gif_width);
  if (raster)
    for (const std::string& difference : raster_differences(scene))
      std::fprintf(stderr, "lightcone: warning: %s: the raster renderer differs here: %s\n",
                   a.scene.c_str(), difference.c_str());

  if (const auto refused = animation_refused(scene)) throw InputError(a.scene + ": " + *refused);
  const AnimationClock clock =
      a.clock == "world" ? AnimationClock::kWorld : AnimationClock::kCamera;
  // animation_frame's reasons name their frame already; in_frame names it for other failures.
  struct FrameRefused : InputError {
    using InputError::InputError;
  };
  const auto frame_scene = [&](long long i) {
    Scene s;
    if (const auto why = animation_frame(scene, i, a.fps, clock, s)) throw FrameRefused(*why);
    return s;
  };
  const auto in_frame = [](long long i, const std::function<void()>& work) {
    try {
      work();
    } catch (const Stopped&) {
      throw;
    } catch (const FrameRefused&) {
      throw;
    } catch (const InputError& e) {
      throw InputError(fmt::format("frame {}: {}", i, e.what()));
    } catch (const std::exception& e) {
      throw std::runtime_error(fmt::format("frame {}: {}", i, e.what()));
    }
  };

  // The frame's picture as a renderer makes it; with `subject`, its linear radiance (at
  // exposure 0) and the automatic exposure's subject weights. The tracer renders the lattice
  // alone where asked; the raster renderer draws the whole frame and the lattice is taken.
  struct Rendered {
    Image image;
    double ev = 0;  // applied
    bool cancelled = false;
  };
  const auto render_frame = [&](Scene s, std::vector<float>* subject, int lattice,
                                const std::function<void(std::size_t, std::size_t)>& progress) {
    Rendered out;
    if (subject) {
      s.render.auto_exposure = false;
      s.render.exposure = 0;
    }
    if (raster) {
      try {
        RasterStats stats;
        out.image = render_raster(s, &stats, {}, a.seed, tessellation_named(a.tessellation),
                                  curved_body_shadows, subject);
        out.ev = stats.exposure;
      } catch (const GlUnavailable& e) {
        throw InputError(fmt::format(
            "--renderer raster: {}: the raster renderer needs OpenGL 3.3 (core profile) "
            "through EGL, e.g. Mesa's llvmpipe",
            e.what()));
      }
      if (lattice > 1) {
        if (subject) *subject = lattice_of(*subject, out.image.width, out.image.height, 1, lattice);
        out.image = lattice_of(out.image, lattice);
      }
      return out;
    }
    RenderOptions options;
    options.threads = a.threads;
    options.seed = a.seed;
    options.cancel = &interrupted;
    options.progress = progress;
    options.lattice = lattice;
    options.subject = subject;
    RenderStats stats;
    out.image = render_image(s, options, &stats);
    out.ev = stats.exposure;
    out.cancelled = stats.cancelled;
    return out;
  };

  // With the automatic exposure, frame i is exposed at the mean of the EVs metered on the
  // animation's frames within half a second of it, so that a video neither pumps nor jumps. A
  // frame's EV is the automatic exposure of the lattice of its own linear render (one pixel of
  // each 4 x 4 block, with all its samples): taken from the render of a frame this run makes,
  // else from a render of the lattice alone (a job array's neighbouring tasks' frames, frames
  // kept by --resume). It depends on the frame alone, and the window on the animation
  // (--animation), so the frames of a job array's tasks join up.
  const bool metering = scene.render.auto_exposure;
  const long long reach = metering ? std::llround(a.fps * kExposureSmoothing) : 0;
  std::unordered_map<long long, std::optional<double>> metered;
  const auto lattice_ev = [&](const Image& linear, const std::vector<float>& subject) {
    const Image lattice = lattice_of(linear, kMeteringLattice);
    return auto_exposure(lattice, scene.render.tonemap,
                         lattice_of(subject, linear.width, linear.height, 1, kMeteringLattice));
  };
  const auto metered_ev = [&](long long j) -> std::optional<double> {
    if (const auto found = metered.find(j); found != metered.end()) return found->second;
    std::optional<double> ev;
    try {
      in_frame(j, [&] {
        std::vector<float> subject;
        const Rendered lattice = render_frame(frame_scene(j), &subject, kMeteringLattice, {});
        ev = auto_exposure(lattice.image, scene.render.tonemap, subject);
      });
    } catch (const InputError&) {
      // A moment the scene cannot be shown at (a camera past the speed of light by then): the
      // frames near it are exposed by the others.
    }
    return metered[j] = ev;
  };
  const auto smoothed_exposure = [&](long long i) {
    double sum = 0;
    int n = 0;
    for (long long j = std::max(i - reach, animation_first);
         j <= std::min(i + reach, animation_last); ++j)
      if (const auto ev = metered_ev(j)) sum += *ev, ++n;
    return n > 0 ? sum / n : 0.0;
  };

  std::unique_ptr<VideoWriter> video;
  if (a.video)
    video = std::make_unique<VideoWriter>(*a.video, camera.width, camera.height, a.fps, a.crf,
                                          a.gif_width);

  const long long count = last - first + 1;
  long long rendered = 0, skipped = 0, redone = 0;
  const auto start = std::chrono::steady_clock::now();
  ProgressBar bar(!a.quiet && isatty(STDERR_FILENO));
  constexpr std::size_t kSteps = 1000;  // progress units a frame
  // Frame i is tone-mapped, encoded and written while frame i + 1 renders: one writer, so
  // files and video frames go out in order; its failure stops the run at the next frame. A
  // frame's files are whole or absent whatever stops it, so after a stop signal its failure
  // (ffmpeg killed by the same signal) is not the run's error.
  std::future<void> writing;
  const auto wait_for_writer = [&] {
    if (!writing.valid()) return;
    try {
      writing.get();
    } catch (const std::exception&) {
      if (!interrupted) throw;
    }
  };

  // The frames rendered or kept and not yet written, in order: a rendered frame waits (as
  // linear radiance, with the automatic exposure) until the EVs of the frames up to `reach`
  // after it are known: at most reach + 1 frames.
  struct Pending {
    long long frame;
    std::vector<ImageOutput> outputs;
    std::shared_ptr<Image> image;  // the render, or the file kept by --resume (for the video)
    bool kept = false;
    ToneMap curve;
  };
  std::deque<Pending> pending;
  const auto finish = [&](Pending& p) {
    wait_for_writer();
    if (p.kept) {
      if (video)
        in_frame(p.frame, [&] {
          // The video gets the frame as its file holds it.
          video->add(p.outputs.front().format == ImageFormat::kExr ? tone_map(*p.image, p.curve)
                                                                   : *p.image);
        });
      return;
    }
    const std::optional<double> ev =
        metering ? std::optional(smoothed_exposure(p.frame)) : std::nullopt;
    if (interrupted) return;  // a metering render stopped short
    writing = std::async(std::launch::async, [=, &video, image = p.image] {
      in_frame(p.frame, [&] {
        if (ev) {
          // Each frame's EXR header says by what its radiance was scaled (Image::exposure). The
          // renderer checked the linear picture; the scaled one is checked as it is scaled.
          image->exposure = *ev;
          if (const auto refused = picture_refused(scene, expose(*image, *ev), *ev))
            throw std::runtime_error(*refused);
        }
        const Image display = tone_map(*image, p.curve);
        if (!p.outputs.empty()) write_images(display, *image, p.outputs);
        if (video) video->add(display);
      });
    });
    ++rendered;
  };
  // Writes the frames waiting whose window of frames this run renders ends at or before `done`.
  const auto finish_through = [&](long long done) {
    while (!pending.empty() && !interrupted &&
           (pending.front().kept || std::min(pending.front().frame + reach, last) <= done)) {
      finish(pending.front());
      pending.pop_front();
    }
  };

  for (long long i = first; i <= last && !interrupted; ++i) {
    const std::size_t frames_done = static_cast<std::size_t>(i - first);
    std::vector<ImageOutput> outputs;
    if (output) outputs.push_back({output->name(i), *format});
    if (exr) outputs.push_back({exr->name(i), ImageFormat::kExr});
    const bool present = a.resume && !outputs.empty() &&
                         std::all_of(outputs.begin(), outputs.end(), [](const ImageOutput& o) {
                           return fs::is_regular_file(o.path);
                         });
    if (present) {
      // A kept frame must be one this run would have written: it decodes and has its size.
      std::shared_ptr<Image> saved;
      const std::optional<std::string> unusable =
          unusable_frame(outputs, camera.width, camera.height, saved);
      if (unusable) {
        std::fprintf(stderr, "lightcone: --resume: frame %lld: %s; rendering it again\n", i,
                     unusable->c_str());
        ++redone;
      } else {
        ++skipped;
        pending.push_back(
            {i, std::move(outputs), video ? saved : nullptr, true, scene.render.tonemap});
        finish_through(i);
        bar.update((frames_done + 1) * kSteps, static_cast<std::size_t>(count) * kSteps);
        continue;
      }
    }
    Rendered frame;
    Scene moment;
    try {
      in_frame(i, [&] {
        moment = frame_scene(i);
        std::vector<float> subject;
        frame = render_frame(
            moment, metering ? &subject : nullptr, 1, [&](std::size_t done, std::size_t total) {
              bar.update(frames_done * kSteps + done * kSteps / std::max<std::size_t>(total, 1),
                         static_cast<std::size_t>(count) * kSteps);
            });
        if (metering && !frame.cancelled && !interrupted)
          metered[i] = lattice_ev(frame.image, subject);
      });
    } catch (const InputError&) {
      // A moment that cannot be shown stops the run there: the frames before it are written
      // first, exposed as any run would (the moment counts for none).
      metered[i] = std::nullopt;
      finish_through(last);
      wait_for_writer();
      throw;
    }
    if (frame.cancelled || interrupted) break;
    frame.image.exposure = frame.ev;
    pending.push_back({i, std::move(outputs), std::make_shared<Image>(std::move(frame.image)),
                       false, moment.render.tonemap});
    finish_through(i);
    bar.update((frames_done + 1) * kSteps, static_cast<std::size_t>(count) * kSteps);
  }
  finish_through(last);
  wait_for_writer();
  if (interrupted) {
    video.reset();  // its temporary file goes with it
    std::fprintf(stderr,
                 "lightcone: stopped by %s after %lld of %lld frames (whole frames kept%s)\n",
                 StopSignals::name().c_str(), rendered + skipped, count,
                 a.video ? "; no video written" : "");
    return StopSignals::exit_status();
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

namespace {

// The frame numbers whose files exist under `pattern`, in order, from a listing of its folder.
std::vector<long long> frames_on_disk(const FramePattern& pattern) {
  if (!pattern.number_in_file_name())
    throw InputError("encode " + pattern.text() +
                     ": the frame number is in a folder's name: give the frames with --frames A-B");
  const std::string prefix = pattern.folder_prefix();
  const fs::path folder = prefix.empty() ? fs::path(".") : fs::path(prefix);
  std::error_code ec;
  fs::directory_iterator it(folder, ec);
  if (ec)
    throw InputError(fmt::format("encode {}: cannot list {}: {}", pattern.text(), folder.string(),
                                 ec.message()));
  std::vector<long long> frames;
  for (const fs::directory_entry& entry : it)
    if (const std::optional<long long> frame =
            pattern.frame_of(prefix + entry.path().filename().string()))
      frames.push_back(*frame);
  std::sort(frames.begin(), frames.end());
  return frames;
}

}  // namespace

int run_encode(const EncodeArgs& a) {
  const StopSignals stop_signals;
  const FramePattern pattern("encode", a.pattern);
  // The frames to encode: --frames A-B, or every frame from the first to the last on disk. A
  // missing frame between them (a failed cluster task) is an error unless --allow-gaps.
  std::vector<long long> frames;
  long long span = 0;  // frames from the first to the last asked for
  if (a.frames) {
    const auto [first, last] = parse_frame_range("--frames", *a.frames);
    span = last - first + 1;
    if (last - first + 1 > kMaxFramesPerRun)
      throw InputError(
          fmt::format("--frames {}: more than {} frames", *a.frames, kMaxFramesPerRun));
    for (long long i = first; i <= last; ++i)
      if (fs::is_regular_file(pattern.name(i)))
        frames.push_back(i);
      else if (!a.allow_gaps)
        throw InputError(fmt::format(
            "encode {}: frame {} ({}) is missing (--allow-gaps encodes the frames there are)",
            a.pattern, i, pattern.name(i)));
  } else {
    frames = frames_on_disk(pattern);
    if (frames.size() > static_cast<std::size_t>(kMaxFramesPerRun))
      throw InputError(fmt::format("encode {}: more than {} frames", a.pattern, kMaxFramesPerRun));
    for (std::size_t k = 1; k < frames.size() && !a.allow_gaps; ++k)
      if (frames[k] != frames[k - 1] + 1)
        throw InputError(fmt::format(
            "encode {}: frame {} ({}) is missing between frames {} and {} (--allow-gaps "
            "encodes the frames there are)",
            a.pattern, frames[k - 1] + 1, pattern.name(frames[k - 1] + 1), frames.front(),
            frames.back()));
    if (!frames.empty()) span = frames.back() - frames.front() + 1;
  }
  if (frames.empty())
    throw InputError(fmt::format("encode {}: no frame files match it", a.pattern));
  const long long missing = span - static_cast<long long>(frames.size());
  if (missing > 0)
    std::fprintf(stderr,
                 "lightcone: warning: encode %s: %lld frames missing; encoding the %zu there are\n",
                 a.pattern.c_str(), missing, frames.size());
  const std::string opening_name = pattern.name(frames.front());
  const std::shared_ptr<Image> opening = load_image_file(opening_name);
  check_video("-o", a.output, opening->width, opening->height, a.fps, a.crf, a.gif_width);
  VideoWriter video(a.output, opening->width, opening->height, a.fps, a.crf, a.gif_width);
  ProgressBar bar(!a.quiet && isatty(STDERR_FILENO));
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const std::string name = pattern.name(frames[k]);
    const std::shared_ptr<Image> frame = k == 0 ? opening : load_image_file(name);
    if (frame->width != opening->width || frame->height != opening->height)
      throw InputError(fmt::format("encode: {} is {}x{}, the first frame {}x{}", name, frame->width,
                                   frame->height, opening->width, opening->height));
    video.add(image_format_of(name) == ImageFormat::kExr ? tone_map(*frame, ToneMap::kClamp)
                                                         : *frame);
    bar.update(k + 1, frames.size());
  }
  video.finish();
  if (!a.quiet)
    std::fprintf(stderr, "lightcone: %s: %s (%s) at %g fps\n", a.output.c_str(),
                 counted(frames.size(), "frame").c_str(),
                 describe_frames(frames.front(), frames.back()).c_str(), a.fps);
  return 0;
}

}  // namespace lightcone

// lightcone._lightcone: the library for Python, called as the `lightcone` program calls it
// (src/cli), so that the same scene gives the same numbers and the same messages. Arguments are
// checked in python/lightcone/__init__.py; this layer takes them as the library does.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <future>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/pixel_probe.hpp"
#include "lightcone/frame/request_rules.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/locate_json.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/io/star_catalogue.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/scene/animation.hpp"
#include "lightcone/trace/aov.hpp"
#include "lightcone/trace/curved_shadows.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/scene_info.hpp"
#include "physics_kernels.hpp"
#include "python_json.hpp"

namespace py = pybind11;

namespace lightcone {
namespace {

// A float32 array over `values` (moved into the array's owner: no copy), of shape `shape`.
py::array_t<float> array_of(std::vector<float>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<float>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array_t<float>(shape, owned->data(), owner);
}

Scene load(const std::string& path, const std::vector<std::string>& overrides,
           std::vector<std::string>& warnings) {
  SceneLoadReport report;
  Scene scene = load_scene_file(path, overrides, report);
  warnings = std::move(report.warnings);
  return scene;
}

// How messages name a scene given as Python values (Scene.from_dict), as a file's path names a
// file's scene.
constexpr const char* kDictSource = "<dict>";

// A scene built in code: the document's JSON text read as a file's text would be, its messages
// naming "<dict>" and the value's path without a line, its relative paths read from `folder`.
Scene load_dict(py::handle document, const std::string& folder,
                const std::vector<std::string>& overrides, std::vector<std::string>& warnings) {
  std::string text = json_text(document, kDictSource, "");
  SceneLoadOptions options;
  options.line_numbers = false;
  options.folder = folder;
  SceneLoadReport report;
  std::optional<Scene> scene;
  {
    py::gil_scoped_release unlocked;
    scene = load_scene_text(std::move(text), kDictSource, overrides, report, options);
  }
  warnings = std::move(report.warnings);
  return std::move(*scene);
}

// While a render runs on Python's main thread, its SIGINT handler is replaced by one that asks
// the renderer to stop after its tiles in flight (RenderOptions::cancel), and then restored as it
// was, flags and all (signal() would restore it with SA_RESTART, after which a blocking call,
// a read from a pipe or a wait for a child, no longer wakes for Ctrl-C). Only on the main
// thread, where Python handles signals: a render on another thread leaves Ctrl-C to Python (a
// KeyboardInterrupt in the main thread) and runs on; and two threads' renders would each restore
// the handler the other had replaced.
std::atomic<bool> interrupted{false};
std::atomic<int> renders_running{0};

extern "C" void on_interrupt(int) {
  interrupted = true;
}

bool on_main_thread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

struct InterruptScope {
  struct sigaction previous = {};
  bool replaced = false;
  InterruptScope() {
    if (renders_running++ == 0) interrupted = false;
    if (!on_main_thread()) return;
    struct sigaction ours = {};
    ours.sa_handler = on_interrupt;
    sigemptyset(&ours.sa_mask);
    replaced = sigaction(SIGINT, &ours, &previous) == 0;
  }
  ~InterruptScope() {
    if (replaced) sigaction(SIGINT, &previous, nullptr);
    --renders_running;
  }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
};

// The render: {"rgb": (H, W, 3) float32, linear, exposure applied; each output variable: (H, W)
// or (H, W, k)}, and "exposure", "seconds", "cancelled".
py::dict render(const Scene& scene, const std::string& renderer,
                const std::vector<std::string>& aovs, std::uint64_t seed, int threads,
                const std::string& tessellation, const py::object& progress) {
  RenderOptions options;
  options.threads = threads;
  options.seed = seed;
  options.cancel = &interrupted;
  for (const std::string& name : aovs) options.aovs.push_back(*aov_from_name(name));
  throw_if_refused(renderer_refused(renderer));
  throw_if_refused(tessellation_refused(tessellation));
  throw_if_refused(render_refused(scene, {.aovs = options.aovs}));
  Image image;
  double exposure = 0, seconds = 0;
  bool cancelled = false;
  {
    // Progress from the render's worker threads: only counted there, reported to Python from
    // this thread (which holds the GIL for it) as the render goes.
    std::atomic<std::size_t> done{0}, total{0};
    options.progress = [&](std::size_t d, std::size_t t) {
      std::size_t seen = done.load();
      while (d > seen && !done.compare_exchange_weak(seen, d)) {
      }
      total = t;
    };
    InterruptScope interrupt;
    if (renderer == "raster") {
      RasterStats stats;
      const RasterTessellation mode = tessellation_named(tessellation);
      py::gil_scoped_release unlocked;
      try {
        // Shadows near a black hole through the tracer's Embree scenes, as the CLI casts them.
        image = render_raster(scene, &stats, {}, seed, mode, curved_body_shadows, nullptr,
                              options.aovs);
      } catch (const GlUnavailable& e) {
        throw std::runtime_error(std::string("renderer='raster': ") + e.what() +
                                 ": the raster renderer needs OpenGL 3.3 (core profile) through "
                                 "EGL, e.g. Mesa's llvmpipe; the ray tracer needs neither");
      }
      exposure = stats.exposure;
      seconds = stats.seconds;
    } else {
      RenderStats stats;
      std::exception_ptr failed, progress_failed;
      std::promise<void> finished;
      {
        py::gil_scoped_release unlocked;
        std::thread worker([&] {
          try {
            image = render_image(scene, options, &stats);
          } catch (...) {
            failed = std::current_exception();
          }
          finished.set_value();
        });
        // Woken at once when the render ends; meanwhile the progress every 50 ms.
        // A progress function that raises stops the render, and its error is raised.
        const std::future<void> ended = finished.get_future();
        std::size_t reported = 0;
        while (ended.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
          if (progress.is_none() || done == reported || progress_failed) continue;
          reported = done;
          py::gil_scoped_acquire locked;
          try {
            progress(reported, total.load());
          } catch (...) {
            progress_failed = std::current_exception();
            interrupted = true;
          }
        }
        worker.join();
      }
      if (progress_failed) std::rethrow_exception(progress_failed);
      if (failed) std::rethrow_exception(failed);
      exposure = stats.exposure;
      seconds = stats.seconds;
      cancelled = stats.cancelled;
    }
  }
  if (interrupted) {
    // Ctrl-C: the finished tiles stay in the image KeyboardInterrupt carries (partial).
    py::dict partial;
    partial["rgb"] = array_of(std::move(image.rgb), {image.height, image.width, 3});
    py::object error =
        py::module_::import("builtins")
            .attr("KeyboardInterrupt")(
                "the render was interrupted: the finished tiles are in .partial['rgb']");
    error.attr("partial") = partial;
    PyErr_SetObject(PyExc_KeyboardInterrupt, error.ptr());
    throw py::error_already_set();
  }
  py::dict result;
  const int w = image.width, h = image.height;
  // Each output variable's channels by their EXR names ("doppler"; "normal.X", ...): the
  // package gathers a variable's channels into one array.
  for (NamedChannel& channel : image.channels)
    result[py::str(channel.name)] = array_of(std::move(channel.values), {h, w});
  result["rgb"] = array_of(std::move(image.rgb), {h, w, 3});
  result["exposure"] = exposure;
  result["seconds"] = seconds;
  result["cancelled"] = cancelled;
  return result;
}

using LinearArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

std::size_t count_nan(const float* begin, const float* end) {
  return static_cast<std::size_t>(std::count_if(begin, end, [](float v) { return std::isnan(v); }));
}

// A linear picture from Python, (H, W, 3), times 2^exposure as the renderers expose theirs. A
// NaN is refused: it has no colour (the tone curve would show it black), and no picture the
// library renders holds one.
Image exposed_image(const LinearArray& linear, double exposure, const char* function) {
  if (linear.ndim() != 3 || linear.shape(2) != 3)
    throw py::value_error(std::string(function) +
                          ": the image must be an array of shape (H, W, 3)");
  if (const std::size_t n = count_nan(linear.data(), linear.data() + linear.size()); n > 0)
    throw py::value_error(
        fmt::format("{}: the image holds {} NaN value{} (of {}): a NaN has no colour", function, n,
                    n == 1 ? "" : "s", linear.size()));
  Image image;
  image.height = static_cast<int>(linear.shape(0));
  image.width = static_cast<int>(linear.shape(1));
  image.rgb.assign(linear.data(), linear.data() + linear.size());
  expose(image, exposure);
  if (const std::size_t n = count_nan(image.rgb.data(), image.rgb.data() + image.rgb.size()); n > 0)
    throw py::value_error(
        fmt::format("{}: exposure {} makes {} value{} NaN (2^exposure is beyond "
                    "a float's range, and 0 times infinity is NaN)",
                    function, exposure, n, n == 1 ? "" : "s"));
  return image;
}

// The PNG's 8-bit picture of a linear image: times 2^exposure, tone-mapped by `curve`, sRGB.
py::array_t<std::uint8_t> tonemap(const LinearArray& linear, double exposure, ToneMap curve) {
  const std::vector<unsigned char> codes =
      display_rgb8(tone_map(exposed_image(linear, exposure, "tonemap"), curve));
  py::array_t<std::uint8_t> out({linear.shape(0), linear.shape(1), py::ssize_t{3}});
  std::copy(codes.begin(), codes.end(), out.mutable_data());
  return out;
}

std::string located(const Scene& scene, const std::string& kind, const std::string& object,
                    const std::array<double, 3>& value) {
  LocateQuery query;
  query.kind = kind == "point"         ? LocateQuery::Kind::ObjectPoint
               : kind == "world_point" ? LocateQuery::Kind::WorldPoint
                                       : LocateQuery::Kind::SkyDirection;
  query.object = object;
  query.value = {value[0], value[1], value[2]};
  throw_if_refused(locate_refused(scene, query));
  LocateResult r;
  try {
    r = lightcone::locate(scene, query);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(printable(std::string("object: ") + e.what()));
  }
  if (!locate_result_is_finite(r))
    throw py::value_error("too far from the camera to be located in double precision");
  return locate_json(r, scene);
}

std::string probed(const Scene& scene, const std::vector<double>& pixel, bool object_named) {
  throw_if_refused(probe_request_refused(pixel, object_named));
  throw_if_refused(probe_refused(scene, pixel[0], pixel[1]));
  return probe_json(probe_pixel(scene, pixel[0], pixel[1]), scene);
}

// "FILE:LINE: FIELD: what", "<dict>: FIELD: what" or "--set FIELD: what" into SceneError's
// attributes, each as the message shows it (printable). Read without std::regex, whose matching
// recurses once a character: a message of megabytes would overflow the stack.
void set_location(py::object& error, const std::string& message) {
  error.attr("file") = py::none();
  error.attr("line") = py::none();
  error.attr("field") = py::none();
  const auto starts = [&](std::string_view prefix) { return message.rfind(prefix, 0) == 0; };
  // The field from `at`: up to the first ": ", with no other ':' before it.
  const auto field_at = [&](std::size_t at) -> std::optional<std::string> {
    const std::size_t colon = message.find(':', at);
    if (colon == std::string::npos || colon == at || message.compare(colon, 2, ": ") != 0)
      return std::nullopt;
    return printable(message.substr(at, colon - at));
  };
  const std::string dict = std::string(kDictSource) + ": ";
  if (starts(dict)) {
    error.attr("file") = kDictSource;
    if (const auto field = field_at(dict.size())) error.attr("field") = *field;
    return;
  }
  if (starts("--set ")) {
    if (const auto field = field_at(6)) error.attr("field") = *field;
    return;
  }
  // FILE:LINE: the first ':' with digits and ": " after it, and a field after those.
  for (std::size_t colon = message.find(':'); colon != std::string::npos;
       colon = message.find(':', colon + 1)) {
    std::size_t end = colon + 1;
    while (end < message.size() && end - colon <= 9 &&
           std::isdigit(static_cast<unsigned char>(message[end])))
      ++end;
    if (end == colon + 1 || message.compare(end, 2, ": ") != 0) continue;
    const auto field = field_at(end + 2);
    if (colon == 0 || !field) continue;
    error.attr("file") = printable(message.substr(0, colon));
    error.attr("line") = std::stoi(message.substr(colon + 1, end - colon - 1));
    error.attr("field") = *field;
    return;
  }
}

}  // namespace
}  // namespace lightcone

PYBIND11_MODULE(_lightcone, m) {
  using namespace lightcone;
  m.doc() = "lightcone's library (use the package lightcone, which checks the arguments)";

  static py::exception<InputError> scene_error(m, "SceneError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object error = py::reinterpret_borrow<py::object>(scene_error.ptr())(printable(e.what()));
      set_location(error, e.what());
      PyErr_SetObject(scene_error.ptr(), error.ptr());
    }
  });

  py::class_<Scene>(m, "Scene")
      .def_property_readonly("width", [](const Scene& s) { return s.camera.width; })
      .def_property_readonly("height", [](const Scene& s) { return s.camera.height; })
      .def_property_readonly("samples", [](const Scene& s) { return s.camera.samples; })
      .def_property_readonly("objects",
                             [](const Scene& s) {
                               std::vector<std::string> names;
                               for (const Object& o : s.objects) names.push_back(o.name);
                               return names;
                             })
      .def("with_samples", [](const Scene& s, int samples) {
        Scene copy = s;
        copy.camera.samples = samples;
        throw_if_refused(scene_refused(copy));
        return copy;
      });

  m.def(
      "load",
      [](const std::string& path, const std::vector<std::string>& overrides) {
        std::vector<std::string> warnings;
        Scene scene = load(path, overrides, warnings);
        return std::pair{std::move(scene), warnings};
      },
      py::arg("path"), py::arg("overrides"));
  m.def(
      "load_dict",
      [](const py::dict& document, const std::string& folder,
         const std::vector<std::string>& overrides) {
        std::vector<std::string> warnings;
        Scene scene = load_dict(document, folder, overrides, warnings);
        return std::pair{std::move(scene), warnings};
      },
      py::arg("document"), py::arg("folder"), py::arg("overrides"));
  m.def(
      "json_value",
      [](const py::handle& value, const std::string& path) {
        return json_text(value, "--set", path);
      },
      py::arg("value"), py::arg("path"));
  m.def("render", &render, py::arg("scene"), py::arg("renderer"), py::arg("aovs"), py::arg("seed"),
        py::arg("threads"), py::arg("tessellation"), py::arg("progress"));
  m.def(
      "tonemap",
      [](const LinearArray& image, double exposure, const std::string& curve) {
        const ToneMap map = curve == "clamp"      ? ToneMap::kClamp
                            : curve == "reinhard" ? ToneMap::kReinhard
                                                  : ToneMap::kFilmic;
        return tonemap(image, exposure, map);
      },
      py::arg("image"), py::arg("exposure"), py::arg("curve"));
  m.def("locate", &located, py::arg("scene"), py::arg("kind"), py::arg("object"), py::arg("value"));
  m.def("probe", &probed, py::arg("scene"), py::arg("pixel"), py::arg("object_named"));
  m.def("aov_names", [] {
    std::vector<std::string> names;
    for (int i = 0; i <= static_cast<int>(Aov::kImageOrder); ++i)
      names.push_back(aov_name(static_cast<Aov>(i)));
    return names;
  });
  m.def(
      "set_data_folder", [](const std::string& folder) { set_star_catalogue_folder(folder); },
      py::arg("folder"));
  m.def(
      "info", [](const Scene& scene) { return scene_info_json(scene_info(scene), scene); },
      py::arg("scene"));
  m.def(
      "animation_frame",
      [](const Scene& scene, long long i, double fps, const std::string& clock) {
        if (const auto refused = animation_refused(scene)) throw InputError(*refused);
        Scene frame;
        if (const auto why = animation_frame(
                scene, i, fps, clock == "world" ? AnimationClock::kWorld : AnimationClock::kCamera,
                frame))
          throw InputError(*why);
        return frame;
      },
      py::arg("scene"), py::arg("frame"), py::arg("fps"), py::arg("clock"));
  m.def(
      "read_image",
      [](const std::string& path) {
        std::shared_ptr<Image> image = load_image_file(path);
        py::dict result;
        const int w = image->width, h = image->height;
        for (const NamedChannel& channel : image->channels) {
          std::vector<float> values = channel.values;
          result[py::str(channel.name)] = array_of(std::move(values), {h, w});
        }
        std::vector<float> rgb = image->rgb;
        result["rgb"] = array_of(std::move(rgb), {h, w, 3});
        // The EV the renderer applied (an EXR's lightcone:exposureEV), None where not known.
        result["exposure"] =
            image->exposure ? py::object(py::float_(*image->exposure)) : py::none();
        return result;
      },
      py::arg("path"));
  m.def(
      "png",
      [](const LinearArray& linear, double exposure) {
        const std::vector<unsigned char> png =
            encode_png(tone_map(exposed_image(linear, exposure, "png"), ToneMap::kFilmic));
        return py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
      },
      py::arg("image"), py::arg("exposure"));
  add_physics_kernels(m.def_submodule("physics", "vectorised physics kernels"));
}

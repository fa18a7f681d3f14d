#include "viewer/viewer.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/image_text.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/scene/speed_text.hpp"
#include "viewer/flight.hpp"
#include "viewer/frame_loop.hpp"
#include "viewer/frame_rate.hpp"

namespace lightcone {
namespace {

// The caption of the split view, and of the picture alone while presenting.
std::string caption(bool split, double speed) {
  return fmt::format("{}   beta = {}", split ? "classical | relativistic" : "relativistic",
                     speed_text(speed, 3));
}

// A name for the next screenshot in the working folder that is not taken yet.
// The probes' points, for draw_notes.
std::vector<std::array<double, 2>> marks_of(const ProbeReadouts& probes) {
  std::vector<std::array<double, 2>> out;
  for (const ProbeReadouts::Mark& m : probes.marks()) out.push_back({m.x, m.y});
  return out;
}

std::filesystem::path next_screenshot() {
  for (int i = 1;; ++i) {
    const std::filesystem::path name = fmt::format("lightcone-view-{:04d}.png", i);
    if (!std::filesystem::exists(name)) return name;
  }
}

struct GlfwSession {
  GlfwSession() {
    if (!glfwInit()) throw InputError("view: GLFW cannot open the display");
  }
  ~GlfwSession() { glfwTerminate(); }
};

const char* const kDopplerModels[] = {"spectral", "rgb3", "hue", "off"};
const DopplerModel kDopplerValues[] = {DopplerModel::kSpectral, DopplerModel::kRgb3,
                                       DopplerModel::kHue, DopplerModel::kOff};
const char* const kSearchlightModels[] = {"physical", "chang1996", "off"};
const SearchlightModel kSearchlightValues[] = {
    SearchlightModel::kPhysical, SearchlightModel::kChang1996, SearchlightModel::kOff};
const char* const kToneMaps[] = {"clamp", "reinhard", "filmic"};
const ToneMap kToneMapValues[] = {ToneMap::kClamp, ToneMap::kReinhard, ToneMap::kFilmic};

template <class T, std::size_t N>
int index_of(const T (&values)[N], T value) {
  for (std::size_t i = 0; i < N; ++i)
    if (values[i] == value) return static_cast<int>(i);
  return 0;
}

}  // namespace

int run_viewer(Scene scene, const ViewerOptions& options) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display == nullptr || *display == '\0') && (wayland == nullptr || *wayland == '\0'))
    throw InputError(
        "view: no display to open a window on (DISPLAY is not set): run it on a desktop or under "
        "Xvfb, or render without one: `lightcone view SCENE --benchmark FRAMES`, `lightcone "
        "render SCENE --renderer raster -o FILE.png`");
  const GlfwSession glfw;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(
      scene.camera.width, scene.camera.height,
      fmt::format("lightcone view {}", options.scene_path).c_str(), nullptr, nullptr);
  if (window == nullptr)
    throw InputError("view: no OpenGL 3.3 core context for a window on this display");
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);

  // Key presses, queued for the frame loop (set before ImGui's backend, which chains to it).
  static std::vector<int> pressed;
  pressed.clear();
  glfwSetKeyCallback(window, [](GLFWwindow*, int key, int, int action, int) {
    if (action == GLFW_PRESS) pressed.push_back(key);
  });

  // The left button's presses and releases, where the pointer was: a click can come and go
  // between two frames, which polling the button would miss.
  struct ButtonEvent {
    bool down = false;
    double x = 0, y = 0;
  };
  static std::vector<ButtonEvent> buttons;
  buttons.clear();
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    ButtonEvent e{action == GLFW_PRESS};
    glfwGetCursorPos(w, &e.x, &e.y);
    buttons.push_back(e);
  });

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's folder
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  {
    RasterRenderer renderer;
    renderer.set_curved_shadows(options.curved_shadows);
    const bool on_gpu = tessellate_on_gpu(options.tessellation, renderer.driver());
    const DisplayPass display_pass;
    std::unique_ptr<FloatTarget> relativistic, classical;
    Flight flight(scene.camera);
    // Near a black hole there is no classical picture to show beside the relativistic one.
    bool split = options.split && !scene.black_hole, hud = options.hud, presenting = false;
    if (options.split && scene.black_hole)
      std::fprintf(stderr,
                   "lightcone: warning: --split: a scene with a black hole has no classical "
                   "picture; the view is shown whole\n");
    double time_scale = options.time_scale.value_or(default_time_scale(scene));
    if (!options.time_scale && scene.black_hole)
      std::fprintf(stderr,
                   "lightcone: near the black hole time runs at %.3g of the camera's own a second "
                   "(the scene's shortest free fall in %g s); --time-scale sets it\n",
                   time_scale, kSceneSeconds);
    // The exposure: with the automatic one (a scene file's default), the EV metered on each
    // frame (auto_exposure on a sample of it), followed smoothly so that it does not pump, plus
    // the slider's offset; else the slider's EV.
    bool automatic = scene.render.auto_exposure;
    double exposure_offset = automatic ? 0.0 : scene.render.exposure;
    ExposureFollower meter;
    auto last = std::chrono::steady_clock::now();
    const auto started = last;
    double fps = 0;
    // The scene as drawn (the flight's camera, the panel's settings) and, for the split view,
    // its classical picture: each kept, with its emission tables, from frame to frame.
    Scene frame = scene, still = scene;
    std::unique_ptr<EmissionTable> frame_emission, still_emission;
    // The first impression: the rate this machine reaches, measured once, and what to lower.
    FrameRateProbe probe;
    std::optional<std::string> slow;
    const bool gpu_available =
        renderer.driver().tessellation_shaders && !software_rasteriser(renderer.driver().renderer);
    double last_x = 0, last_y = 0, press_x = 0, press_y = 0;
    bool dragging = false;
    ProbeReadouts probes(options.probe);
    bool readouts_in_screenshots = true;
    FrameDraw drawn;
    bool stopped_said = false;
    while (!glfwWindowShouldClose(window)) {
      glfwPollEvents();
      const auto now = std::chrono::steady_clock::now();
      const double dt = std::chrono::duration<double>(now - last).count();
      last = now;
      fps = fps == 0 ? 1 / std::max(dt, 1e-6) : 0.9 * fps + 0.1 / std::max(dt, 1e-6);

      const ImGuiIO& io = ImGui::GetIO();
      bool screenshot = false;
      if (!io.WantCaptureKeyboard) {
        for (const int key : pressed) {
          if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window, GLFW_TRUE);
          const bool boost = key == GLFW_KEY_W || key == GLFW_KEY_S || key == GLFW_KEY_SPACE;
          if (boost && flight.inside_horizon())
            std::fprintf(stderr, "lightcone: %s\n", Flight::kInsideHorizon);
          if (key == GLFW_KEY_W) flight.change_speed(1);
          if (key == GLFW_KEY_S) flight.change_speed(-1);
          if (key == GLFW_KEY_SPACE) flight.set_speed(0);
          if (key == GLFW_KEY_C && !scene.black_hole) split = !split;
          if ((key == GLFW_KEY_O || key == GLFW_KEY_F) && scene.black_hole) {
            const auto refused = key == GLFW_KEY_O ? flight.start_orbit(*scene.black_hole)
                                                   : flight.start_fall(*scene.black_hole);
            if (refused)
              std::fprintf(stderr, "lightcone: %s\n", refused->c_str());
            else
              std::fprintf(stderr, "lightcone: %s from r = %.4gM\n",
                           key == GLFW_KEY_O ? "orbiting" : "falling",
                           length(flight.camera.world_line.position - scene.black_hole->position) /
                               scene.black_hole->mass);
          }
          if (key == GLFW_KEY_R) {
            // The view as the scene starts it: its camera, where and when it is (a view lost
            // near a hole comes back at once); the panel's settings stay.
            flight = Flight(scene.camera);
            meter.reset();
            std::fprintf(stderr, "lightcone: back at the scene's camera, at t = %.6g\n",
                         flight.camera.world_line.time);
          }
          if (key == GLFW_KEY_X) probes.clear();
          if (key == GLFW_KEY_H) hud = !hud;
          if (key == GLFW_KEY_P) presenting = !presenting;
          if (key == GLFW_KEY_F12) screenshot = true;
          if (key == GLFW_KEY_W || key == GLFW_KEY_S || key == GLFW_KEY_SPACE)
            std::fprintf(stderr, "lightcone: speed %s c\n", speed_text(flight.speed, 4).c_str());
        }
        const double turn = 1.2 * dt;
        if (glfwGetKey(window, GLFW_KEY_LEFT) == GLFW_PRESS) flight.turn(turn, 0);
        if (glfwGetKey(window, GLFW_KEY_RIGHT) == GLFW_PRESS) flight.turn(-turn, 0);
        if (glfwGetKey(window, GLFW_KEY_UP) == GLFW_PRESS) flight.turn(0, turn);
        if (glfwGetKey(window, GLFW_KEY_DOWN) == GLFW_PRESS) flight.turn(0, -turn);
      }
      pressed.clear();
      if (!io.WantCaptureMouse) {
        double x = 0, y = 0;
        glfwGetCursorPos(window, &x, &y);
        const bool down = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        if (down && dragging) flight.turn(-(x - last_x) * 0.004, -(y - last_y) * 0.004);
        dragging = down;
        last_x = x;
        last_y = y;
      }
      for (const ButtonEvent& e : buttons) {
        // A press and release that did not drag is a click: a probe of the pixel under it (its
        // centre, in the framebuffer's pixels, which a high-density screen makes more). The
        // panel's own clicks are not the picture's.
        if (e.down) {
          press_x = e.x, press_y = e.y;
        } else if (!io.WantCaptureMouse && std::hypot(e.x - press_x, e.y - press_y) < 3) {
          int window_width = 0, window_height = 0;
          glfwGetWindowSize(window, &window_width, &window_height);
          // (`frame` is still the scene as last drawn, the one clicked.)
          const double sx = static_cast<double>(frame.camera.width) / std::max(window_width, 1);
          const double sy = static_cast<double>(frame.camera.height) / std::max(window_height, 1);
          probes.click(frame, std::floor(e.x * sx) + 0.5, std::floor(e.y * sy) + 0.5);
        }
      }
      buttons.clear();
      probes.poll(frame);
      const bool moved =
          flight.advance(dt * time_scale, scene.black_hole ? &*scene.black_hole : nullptr);
      if (!moved && !stopped_said) {
        if (flight.mode == Flight::Mode::kFall)
          std::fprintf(stderr, "lightcone: the fall is drawn down to r = %gM, and ends there\n",
                       kCameraInnermostRadius);
        else
          std::fprintf(stderr, "lightcone: stopped at r = %gM, outside the black hole's horizon\n",
                       Flight::kClosestToHole);
      }
      stopped_said = !moved;  // (said once, until it moves again)

      int width = 0, height = 0;
      glfwGetFramebufferSize(window, &width, &height);
      if (width <= 0 || height <= 0) continue;
      if (!relativistic || relativistic->width() != width || relativistic->height() != height) {
        relativistic = std::make_unique<FloatTarget>(width, height);
        classical = std::make_unique<FloatTarget>(width, height);
      }
      frame.camera = flight.camera;
      frame.camera.width = width;
      frame.camera.height = height;
      frame.render = scene.render;
      drawn = draw_scene(renderer, frame, *relativistic, on_gpu, frame_emission);
      if (split) {
        still.camera = frame.camera;
        still.render = scene.render;
        still.render.relativity = false;
        draw_scene(renderer, still, *classical, on_gpu, still_emission);
      }

      const double exposure =
          automatic ? meter.follow(*relativistic, scene.render.tonemap, dt) + exposure_offset
                    : exposure_offset;

      // F12: the view as a PNG, as `lightcone render` would write it (no panel).
      if (screenshot) {
        Image linear = relativistic->read();
        if (split) {
          const Image left = classical->read();
          for (int y = 0; y < height; ++y)
            for (int x = 0; x < width / 2; ++x)
              for (int c = 0; c < 3; ++c) {
                const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x) + c;
                linear.rgb[i] = left.rgb[i];
              }
        }
        const auto scale = static_cast<float>(std::exp2(exposure));
        for (float& v : linear.rgb) v *= scale;
        const std::filesystem::path file = next_screenshot();
        Image display = tone_map(linear, scene.render.tonemap);
        if (split || presenting) draw_caption(display, caption(split, flight.speed));
        if (readouts_in_screenshots) draw_notes(display, probes.lines(), marks_of(probes));
        write_images(display, linear, {{file, ImageFormat::kPng}});
        std::fprintf(stderr, "lightcone: wrote %s\n", file.string().c_str());
      }

      if (probe.frame(std::chrono::duration<double>(now - started).count())) {
        slow = slow_viewer_advice(*probe.measured(), width, height, on_gpu, gpu_available, split);
        if (slow) std::fprintf(stderr, "lightcone: warning: %s\n", slow->c_str());
      }

      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      glViewport(0, 0, width, height);
      display_pass.draw(*relativistic, split ? classical.get() : nullptr, exposure,
                        scene.render.tonemap);

      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      if (split || presenting) {
        // The caption, as F12 stamps it into the PNG: centred along the top, on a dark band.
        const std::string text = caption(split, flight.speed);
        ImDrawList* draw = ImGui::GetForegroundDrawList();
        const ImVec2 size = ImGui::CalcTextSize(text.c_str());
        draw->AddRectFilled(ImVec2(0, 0), ImVec2(static_cast<float>(width), kCaptionHeight),
                            IM_COL32(0, 0, 0, 204));
        draw->AddText(
            ImVec2((static_cast<float>(width) - size.x) / 2, (kCaptionHeight - size.y) / 2),
            IM_COL32(255, 255, 255, 255), text.c_str());
      }
      {
        // Each probe's point, marked and numbered.
        ImDrawList* draw = ImGui::GetForegroundDrawList();
        int window_width = 0, window_height = 0;
        glfwGetWindowSize(window, &window_width, &window_height);
        const float sx = static_cast<float>(window_width) / static_cast<float>(width);
        const float sy = static_cast<float>(window_height) / static_cast<float>(height);
        int number = 0;
        for (const ProbeReadouts::Mark& m : probes.marks()) {
          const ImVec2 at(static_cast<float>(m.x) * sx, static_cast<float>(m.y) * sy);
          draw->AddCircle(at, 6, IM_COL32(255, 255, 255, 255), 0, 1.5f);
          draw->AddText(ImVec2(at.x + 8, at.y - 16), IM_COL32(255, 255, 255, 255),
                        std::to_string(++number).c_str());
        }
      }
      if (hud && !presenting) {
        ImGui::SetNextWindowPos(ImVec2(10, kCaptionHeight + 4), ImGuiCond_FirstUseEver);
        ImGui::Begin("lightcone", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
        const double gamma = lorentz_gamma(flight.camera.world_line.velocity);
        ImGui::Text("beta %s   gamma %.3f", speed_text(flight.speed, 4).c_str(), gamma);
        ImGui::Text("%.1f fps", fps);
        if (const auto measured = probe.measured())
          ImGui::Text("this machine: %.1f fps over the first %.0f s", *measured,
                      FrameRateProbe::kSeconds);
        if (slow) {
          ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28);
          ImGui::TextColored(ImVec4(1.0f, 0.55f, 0.3f, 1.0f), "%s", slow->c_str());
          ImGui::PopTextWrapPos();
        }
        if (probes.available()) {
          const std::vector<std::string> lines = probes.lines();
          if (lines.empty())
            ImGui::TextUnformatted("click the picture: what is seen there, and when");
          for (const std::string& line : lines) ImGui::TextUnformatted(line.c_str());
          if (!lines.empty()) ImGui::Checkbox("readouts in F12 PNGs", &readouts_in_screenshots);
        }
        float speed = static_cast<float>(flight.speed);
        if (ImGui::SliderFloat("speed (c)", &speed, 0.0f, 0.999f, "%.3f")) flight.set_speed(speed);
        // The rest folds away, so that the panel starts small (a slide shows the picture).
        if (ImGui::CollapsingHeader("more")) {
          ImGui::Text("Doppler on screen %.3g to %.3g", drawn.doppler_min, drawn.doppler_max);
          ImGui::Text("%zu triangles (%s)", drawn.triangles,
                      on_gpu ? "cut on the GPU" : "tessellated on the CPU");
          if (scene.black_hole) {
            // Curved spacetime has no classical picture to compare with.
            const Vec3 from_hole = flight.camera.world_line.position - scene.black_hole->position;
            const char* modes[] = {"powered", "on a circular orbit", "falling freely"};
            ImGui::Text("black hole: camera at r = %.4gM, %s",
                        length(from_hole) / scene.black_hole->mass,
                        modes[static_cast<int>(flight.mode)]);
          } else {
            ImGui::Checkbox("relativity", &scene.render.relativity);
            ImGui::Checkbox("light delay", &scene.render.light_delay);
          }
          int doppler = index_of(kDopplerValues, scene.render.doppler);
          if (ImGui::Combo("colour", &doppler, kDopplerModels, 4))
            scene.render.doppler = kDopplerValues[doppler];
          int searchlight = index_of(kSearchlightValues, scene.render.searchlight);
          if (ImGui::Combo("searchlight", &searchlight, kSearchlightModels, 3))
            scene.render.searchlight = kSearchlightValues[searchlight];
          if (ImGui::Checkbox("automatic exposure", &automatic)) {
            // Off: the picture stays as it was. On: the metered EV, at once.
            exposure_offset = automatic ? 0.0 : exposure;
            meter.reset();
          }
          float ev = static_cast<float>(exposure_offset);
          if (ImGui::SliderFloat(automatic ? "exposure offset (EV)" : "exposure (EV)", &ev, -10.0f,
                                 10.0f, "%.1f"))
            exposure_offset = ev;
          if (automatic) ImGui::Text("metered %.1f EV", meter.metered());
          int curve = index_of(kToneMapValues, scene.render.tonemap);
          if (ImGui::Combo("tone map", &curve, kToneMaps, 3))
            scene.render.tonemap = kToneMapValues[curve];
          float scale = static_cast<float>(time_scale);
          // Logarithmic: from a stopped clock through 1 to a hole's scale of hundreds a second.
          if (ImGui::SliderFloat("time scale", &scale, 0.0f, 1000.0f, "%.3g",
                                 ImGuiSliderFlags_Logarithmic))
            time_scale = scale;
          if (!scene.black_hole) ImGui::Checkbox("classical | relativistic (C)", &split);
          ImGui::TextUnformatted(
              scene.black_hole
                  ? "W/S boost, Space hover, O orbit, F fall, drag or arrows "
                    "look, click probe, X clear probes, R reset view, F12 PNG, H panel, P present"
                  : "W/S speed, Space stop, drag or arrows look, click probe, X clear "
                    "probes, R reset view, F12 PNG, H panel, P present");
        }
        ImGui::End();
      }
      ImGui::Render();
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      glfwSwapBuffers(window);
    }
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  return 0;
}

int run_viewer_benchmark(Scene scene, int frames, RasterTessellation tessellation,
                         const CurvedShadowSource& curved_shadows) {
  const HeadlessGlContext context;
  RasterRenderer renderer;
  renderer.set_curved_shadows(curved_shadows);
  const bool on_gpu = tessellate_on_gpu(tessellation, renderer.driver());
  const FloatTarget target(scene.camera.width, scene.camera.height);
  const FlightBenchmark run = benchmark_flight(renderer, scene, target, frames, on_gpu);
  const double seconds = run.seconds;
  const nlohmann::ordered_json line = {{"frames", frames},
                                       {"seconds", seconds},
                                       {"fps", frames / std::max(seconds, 1e-9)},
                                       {"triangles", run.triangles},
                                       {"width", scene.camera.width},
                                       {"height", scene.camera.height},
                                       {"tessellation", on_gpu ? "gpu" : "cpu"},
                                       {"gl", context.description()}};
  std::printf("%s\n", line.dump().c_str());
  return 0;
}

}  // namespace lightcone

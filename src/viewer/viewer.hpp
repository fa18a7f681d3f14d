// `lightcone view`: the interactive viewer on the raster renderer (a GLFW window with a Dear
// ImGui panel), and its offscreen benchmark.
#pragma once

#include <optional>
#include <string>

#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/scene/scene.hpp"
#include "viewer/probe_readouts.hpp"

namespace lightcone {

struct ViewerOptions {
  std::string scene_path;  // for messages and the window's title
  bool split = false;      // start with the classical | relativistic split
  bool hud = true;
  // Units of camera proper time per second of wall-clock time; none: default_time_scale's
  // (flight.hpp), said on stderr near a black hole.
  std::optional<double> time_scale;
  RasterTessellation tessellation = RasterTessellation::kAuto;
  CurvedShadowSource curved_shadows;  // near a black hole (RasterRenderer::set_curved_shadows)
  PixelProbeSource probe;             // what a click probes with (none: clicks only look)
};

// Opens the window and runs until it is closed (Esc). Throws InputError when there is no
// display to open it on.
int run_viewer(Scene scene, const ViewerOptions& options);

// Renders `frames` frames of a scripted flight through the scene offscreen (EGL), at the
// scene's image size, and prints one JSON line {"frames", "seconds", "fps", "triangles"}
// (triangles: the average a frame after tessellation on the CPU, before it on the GPU), and
// which tessellation path drew them.
int run_viewer_benchmark(Scene scene, int frames,
                         RasterTessellation tessellation = RasterTessellation::kAuto,
                         const CurvedShadowSource& curved_shadows = {});

}  // namespace lightcone

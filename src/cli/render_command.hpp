// `lightcone render`: one picture of a scene, by the ray tracer or the raster renderer, to PNG,
// JPEG or OpenEXR files (or a PNG on standard output), with output variables, a colour map of
// one of them, a crop and a preview.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lightcone/io/scene_file.hpp"

namespace lightcone {

struct RenderArgs {
  std::string scene, output, renderer = "trace", tessellation = "auto";
  std::optional<std::string> exr, crop, aov, map;
  std::optional<int> width, height, samples;
  std::optional<double> scale;
  int threads = 0;
  std::uint64_t seed = 0;
  std::vector<std::string> overrides;
  SceneLoadOptions scene_options;  // --allow-outside
  bool stats = false, quiet = false, preview = false;
};
int run_render(const RenderArgs& args);

}  // namespace lightcone

// How the raster renderer's programs are put together from the embedded sources: a version line,
// the shared code (common.glsl, and for vertices where bodies are seen, body_projection.glsl),
// then the stage's own source.
#pragma once

#include <string>

#include "lightcone/raster/shader_sources.hpp"

namespace lightcone {

// GLSL 330 for the CPU tessellation path, 400 for the GPU one (tessellation shaders).
inline std::string version_line(bool tessellation) {
  return tessellation ? "#version 400 core\n" : "#version 330 core\n";
}
inline std::string vertex_shader(const char* source, bool tessellation = false) {
  return version_line(tessellation) + shader_sources::common_glsl +
         shader_sources::body_projection_glsl + source;
}
inline std::string fragment_shader(const char* source, const std::string& extra = "",
                                   const char* defines = "", bool tessellation = false) {
  return version_line(tessellation) + "#define LIGHTCONE_FRAGMENT_STAGE 1\n" + defines +
         shader_sources::common_glsl + extra + source;
}

}  // namespace lightcone

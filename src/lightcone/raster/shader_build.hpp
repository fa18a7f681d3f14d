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

// What a body program may leave out when no body of the frame uses it (shaders/body.frag,
// patterns.glsl, common.glsl): spinning bodies, blinks and clocks, and shading at per-pixel
// sample offsets (several samples a pixel). The defines take out those a frame does not use.
enum BodyFeature {
  kBodySpin = 1,
  kBodyTimedPattern = 2,
  kBodySampleOffsets = 4,
  kAllBodyFeatures = 7,
};
inline std::string body_variant_defines(int features) {
  std::string defines;
  if (!(features & kBodySpin)) defines += "#define LIGHTCONE_NO_SPIN 1\n";
  if (!(features & kBodyTimedPattern)) defines += "#define LIGHTCONE_NO_TIMED_PATTERNS 1\n";
  if (!(features & kBodySampleOffsets)) defines += "#define LIGHTCONE_NO_SAMPLE_OFFSETS 1\n";
  return defines;
}

}  // namespace lightcone

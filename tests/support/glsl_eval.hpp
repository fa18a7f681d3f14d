// The raster renderer's GLSL functions evaluated on the current OpenGL context, through
// transform feedback, for the tests that hold them against their C++ kernels.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/shader_sources.hpp"

namespace lightcone {

// Runs `expression` (GLSL, of the vertex inputs a, b, c, giving a vec4) once per input triple
// in a vertex shader made of common.glsl, `sources` and the expression, and returns the
// results. `setup` is called with the program in use before the draw (uniforms, textures).
std::vector<std::array<float, 4>> evaluate_glsl(
    const std::string& expression, const std::vector<std::array<float, 9>>& inputs,
    const std::string& sources = shader_sources::lighting_glsl,
    const std::function<void(GLuint)>& setup = {});

}  // namespace lightcone

// The uniforms of shaders/patterns.glsl for one body: which pattern it shows and its sizes and
// periods (shared by the flat bodies' programs and those near a black hole).
#pragma once

#include "lightcone/raster/gl.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// `pattern`: 0 one colour, 1 checker, 2 texture, 3 blink, 4 clock. The program is in use.
void set_pattern_uniforms(GLuint program, const Object& object, int pattern);

}  // namespace lightcone

// The OpenGL 3.3 core functions, as libglvnd's libOpenGL exports them (in the browser build,
// OpenGL ES 3.0's, which WebGL 2 is), and small helpers that turn GL errors into exceptions.
#pragma once

#include <stdexcept>

#ifdef __EMSCRIPTEN__
#include <GLES3/gl3.h>
// WebGL 2 has no tessellation stages (gl_has_tessellation_shaders is false there, so the GPU
// tessellation path is never taken) and sizes points from the shader always: the names the
// native code uses, with OpenGL 4's values.
constexpr GLenum GL_TESS_CONTROL_SHADER = 0x8E88;
constexpr GLenum GL_TESS_EVALUATION_SHADER = 0x8E87;
constexpr GLenum GL_PATCHES = 0x000E;
constexpr GLenum GL_PATCH_VERTICES = 0x8E72;
inline void glPatchParameteri(GLenum, GLint) {
  throw std::logic_error("tessellation shaders in WebGL 2");
}
inline void glClearDepth(double depth) {
  glClearDepthf(static_cast<float>(depth));
}
#else
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#endif

#include <string>

#include "lightcone/physics/lorentz.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/tessellation.hpp"

namespace lightcone {

// Throws std::runtime_error naming `what` when GL reports an error.
void check_gl(const char* what);

// The current context's version and renderer, for messages.
std::string gl_description();

// A program from vertex and fragment shader sources, and tessellation control and evaluation
// sources when given; throws with the compiler's log.
GLuint link_program(const std::string& vertex, const std::string& fragment,
                    const std::string& control = "", const std::string& evaluation = "");

// Whether the current context is OpenGL 4 or later (tessellation shaders).
bool gl_has_tessellation_shaders();

// The current context's renderer (GL_RENDERER): "llvmpipe (LLVM 15.0.6, 256 bits)" and the like.
std::string gl_renderer();

// Face culling for the triangles drawn next: none, or the hidden ones.
void skip_faces(HiddenFaces hidden);

// Attaches to the bound framebuffer a new width x height RGBA float texture (sampled nearest) at
// colour attachment `index`, and returns it.
GLuint attach_float_colour(int index, int width, int height);
// Attaches to the bound framebuffer a new 32-bit float depth buffer, and returns it.
GLuint attach_float_depth(int width, int height);

// Uniforms of `program` (in use) by name, from double-precision values.
GLint uniform(GLuint program, const char* name);
void set_vec3(GLuint program, const char* name, const Vec3& v);
void set_mat3(GLuint program, const char* name, const Mat3& m);
void set_mat4(GLuint program, const char* name, const Mat4& m);  // on (t, x, y, z)

}  // namespace lightcone

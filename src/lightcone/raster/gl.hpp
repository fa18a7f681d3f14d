// The OpenGL 3.3 core functions, as libglvnd's libOpenGL exports them, and small helpers that
// turn GL errors into exceptions.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <stdexcept>
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

// Uniforms of `program` (in use) by name, from double-precision values.
GLint uniform(GLuint program, const char* name);
void set_vec3(GLuint program, const char* name, const Vec3& v);
void set_mat3(GLuint program, const char* name, const Mat3& m);
void set_mat4(GLuint program, const char* name, const Mat4& m);  // on (t, x, y, z)

}  // namespace lightcone

#include "lightcone/raster/gl.hpp"

#include <fmt/format.h>

#include <vector>

namespace lightcone {

void check_gl(const char* what) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
    throw std::runtime_error(fmt::format("OpenGL error 0x{:x} while {}", error, what));
}

namespace {

std::string gl_text(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return std::string(s != nullptr ? s : "?");
}

const char* stage_name(GLenum stage) {
  switch (stage) {
    case GL_VERTEX_SHADER:
      return "vertex";
    case GL_TESS_CONTROL_SHADER:
      return "tessellation control";
    case GL_TESS_EVALUATION_SHADER:
      return "tessellation evaluation";
    default:
      return "fragment";
  }
}

// A shader's or program's info log (glGetShaderiv / glGetShaderInfoLog or the program ones).
template <class GetParameter, class GetLog>
std::string info_log(GLuint object, GetParameter get_parameter, GetLog get_log) {
  GLint length = 0;
  get_parameter(object, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)));
  get_log(object, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return log.data();
}

GLuint compile(GLenum stage, const std::string& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = info_log(shader, glGetShaderiv, glGetShaderInfoLog);
    glDeleteShader(shader);
    throw std::runtime_error(fmt::format("{} shader does not compile: {}", stage_name(stage), log));
  }
  return shader;
}

}  // namespace

GLuint link_program(const std::string& vertex, const std::string& fragment,
                    const std::string& control, const std::string& evaluation) {
  std::vector<GLuint> shaders = {compile(GL_VERTEX_SHADER, vertex),
                                 compile(GL_FRAGMENT_SHADER, fragment)};
  if (!control.empty()) {
    shaders.push_back(compile(GL_TESS_CONTROL_SHADER, control));
    shaders.push_back(compile(GL_TESS_EVALUATION_SHADER, evaluation));
  }
  const GLuint program = glCreateProgram();
  for (GLuint shader : shaders) glAttachShader(program, shader);
  glLinkProgram(program);
  for (GLuint shader : shaders) glDeleteShader(shader);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = info_log(program, glGetProgramiv, glGetProgramInfoLog);
    glDeleteProgram(program);
    throw std::runtime_error(fmt::format("shaders do not link: {}", log));
  }
  return program;
}

std::string gl_description() {
  return fmt::format("OpenGL {}, {}", gl_text(GL_VERSION), gl_text(GL_RENDERER));
}

std::string gl_renderer() {
  return gl_text(GL_RENDERER);
}

bool gl_has_tessellation_shaders() {
  GLint major = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  return major >= 4;
}

}  // namespace lightcone

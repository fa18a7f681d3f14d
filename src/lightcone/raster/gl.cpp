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

void skip_faces(HiddenFaces hidden) {
  if (hidden == HiddenFaces::kNone) return glDisable(GL_CULL_FACE);
  glEnable(GL_CULL_FACE);
  glCullFace(hidden == HiddenFaces::kBack ? GL_BACK : GL_FRONT);
}

GLuint attach_float_colour(int index, int width, int height) {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + index, GL_TEXTURE_2D, texture, 0);
  return texture;
}

GLuint attach_float_depth(int width, int height) {
  GLuint depth = 0;
  glGenRenderbuffers(1, &depth);
  glBindRenderbuffer(GL_RENDERBUFFER, depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  return depth;
}

GLint uniform(GLuint program, const char* name) {
  return glGetUniformLocation(program, name);
}

void set_vec3(GLuint program, const char* name, const Vec3& v) {
  glUniform3f(uniform(program, name), static_cast<float>(v.x), static_cast<float>(v.y),
              static_cast<float>(v.z));
}

void set_mat3(GLuint program, const char* name, const Mat3& m) {
  float values[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) values[3 * r + c] = static_cast<float>(m.m[r][c]);
  glUniformMatrix3fv(uniform(program, name), 1, GL_TRUE, values);  // row-major
}

void set_mat4(GLuint program, const char* name, const Mat4& m) {
  float values[16];
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) values[4 * r + c] = static_cast<float>(m.m[r][c]);
  glUniformMatrix4fv(uniform(program, name), 1, GL_TRUE, values);  // row-major
}

}  // namespace lightcone

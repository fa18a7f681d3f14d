#include "support/glsl_eval.hpp"

#include <gtest/gtest.h>

namespace lightcone {

std::vector<std::array<float, 4>> evaluate_glsl(const std::string& expression,
                                                const std::vector<std::array<float, 9>>& inputs,
                                                const std::string& sources,
                                                const std::function<void(GLuint)>& setup) {
  const std::string vertex = std::string("#version 330 core\n") + shader_sources::common_glsl +
                             sources +
                             "layout(location = 0) in vec3 a;\n"
                             "layout(location = 1) in vec3 b;\n"
                             "layout(location = 2) in vec3 c;\n"
                             "out vec4 result;\n"
                             "void main() { result = " +
                             expression + "; gl_Position = vec4(0.0); }\n";
  const std::string fragment =
      "#version 330 core\nout vec4 colour;\nvoid main() { colour = vec4(0.0); }\n";
  const auto compile = [](GLenum stage, const std::string& source) {
    const GLuint s = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    char log[4096] = "";
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    EXPECT_TRUE(ok) << log;
    return s;
  };
  const GLuint program = glCreateProgram();
  glAttachShader(program, compile(GL_VERTEX_SHADER, vertex));
  glAttachShader(program, compile(GL_FRAGMENT_SHADER, fragment));
  const char* varyings[] = {"result"};
  glTransformFeedbackVaryings(program, 1, varyings, GL_INTERLEAVED_ATTRIBS);
  glLinkProgram(program);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  EXPECT_TRUE(linked);
  glUseProgram(program);
  if (setup) setup(program);
  // A surfaceless context has no default framebuffer: draw into a 1x1 one.
  GLuint framebuffer = 0, colour = 0;
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glGenRenderbuffers(1, &colour);
  glBindRenderbuffer(GL_RENDERBUFFER, colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 1, 1);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  GLuint array = 0, buffers[2] = {0, 0};
  glGenVertexArrays(1, &array);
  glBindVertexArray(array);
  glGenBuffers(2, buffers);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(inputs.size() * sizeof(inputs[0])),
               inputs.data(), GL_STATIC_DRAW);
  for (GLuint k = 0; k < 3; ++k) {
    glEnableVertexAttribArray(k);
    glVertexAttribPointer(k, 3, GL_FLOAT, GL_FALSE, sizeof(inputs[0]),
                          reinterpret_cast<const void*>(k * 3 * sizeof(float)));
  }
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, buffers[1]);
  glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER,
               static_cast<GLsizeiptr>(inputs.size() * 4 * sizeof(float)), nullptr, GL_STATIC_READ);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffers[1]);
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(inputs.size()));
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  std::vector<std::array<float, 4>> out(inputs.size());
  glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0,
                     static_cast<GLsizeiptr>(out.size() * sizeof(out[0])), out.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  glDeleteBuffers(2, buffers);
  glDeleteVertexArrays(1, &array);
  glDeleteProgram(program);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteRenderbuffers(1, &colour);
  glDeleteFramebuffers(1, &framebuffer);
  return out;
}

}  // namespace lightcone

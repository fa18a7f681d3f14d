#include "lightcone/raster/star_pass.hpp"

#include <vector>

#include "lightcone/raster/shader_build.hpp"

namespace lightcone {
namespace {

constexpr int kFloatsPerStar = 5;  // image point, flux
// GL points are clipped whole when their centre leaves the viewport: it reaches this many pixels
// past each edge of the picture, more than a sprite's half width.
constexpr int kViewportMargin = 2;

}  // namespace

StarPass::StarPass() {
  program_ =
      link_program(vertex_shader(shader_sources::star_vert),
                   fragment_shader(shader_sources::star_frag, shader_sources::star_filter_glsl));
  glGenVertexArrays(1, &vertex_array_);
  glGenBuffers(1, &buffer_);
  glBindVertexArray(vertex_array_);
  glBindBuffer(GL_ARRAY_BUFFER, buffer_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, kFloatsPerStar * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, kFloatsPerStar * sizeof(float),
                        reinterpret_cast<const void*>(2 * sizeof(float)));
  glBindVertexArray(0);
  check_gl("creating the star pass");
}

StarPass::~StarPass() {
  glDeleteBuffers(1, &buffer_);
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteProgram(program_);
}

void StarPass::prepare(const ResolvedScene& scene) {
  count_ = 0;
  if (!scene.scene->sky.stars) return;
  // A margin of one unit of ln g: a camera that speeds up keeps the table for a while.
  if (!photometry_ || !photometry_->serves(scene)) photometry_ = star_photometry(scene, 1.0);
  if (scene.hole && scene.hole->camera_radius > 2 * scene.hole->mass &&
      !(lens_ && star_lens_serves(*lens_, *scene.hole)))
    lens_ = star_lens_table(*scene.hole);
  const std::vector<StarImage> stars =
      star_images(scene, *photometry_, scene.hole && lens_ ? &*lens_ : nullptr);
  std::vector<float> data;
  data.reserve(stars.size() * kFloatsPerStar);
  for (const StarImage& s : stars)
    for (const double v : {s.x, s.y, s.flux.r, s.flux.g, s.flux.b})
      data.push_back(static_cast<float>(v));
  glBindBuffer(GL_ARRAY_BUFFER, buffer_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data(),
               GL_STREAM_DRAW);
  count_ = stars.size();
  check_gl("uploading the stars");
}

void StarPass::draw(const ResolvedScene& scene) const {
  if (count_ == 0) return;
  glUseProgram(program_);
  set_camera_uniforms(program_, scene.camera);
  glUniform2f(uniform(program_, "viewport_margin"), kViewportMargin, kViewportMargin);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  // colour += star * destination alpha; the alpha stays.
  glBlendFuncSeparate(GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE);
#ifndef __EMSCRIPTEN__
  glEnable(GL_PROGRAM_POINT_SIZE);  // (always so in WebGL 2)
#endif
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  glViewport(viewport[0] - kViewportMargin, viewport[1] - kViewportMargin,
             viewport[2] + 2 * kViewportMargin, viewport[3] + 2 * kViewportMargin);
  glBindVertexArray(vertex_array_);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(count_));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  glBindVertexArray(0);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  check_gl("drawing the stars");
}

}  // namespace lightcone

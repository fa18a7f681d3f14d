#include "lightcone/raster/frame_target.hpp"

#include <cmath>
#include <stdexcept>

#include "lightcone/frame/pixel_lattice.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/shader_build.hpp"

namespace lightcone {

FloatTarget::FloatTarget(int width, int height) : width_(width), height_(height) {
  glGenFramebuffers(1, &framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  colour_ = attach_float_colour(0, width, height);
  depth_ = attach_float_depth(width, height);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("cannot create a float framebuffer");
  glViewport(0, 0, width, height);
}

FloatTarget::~FloatTarget() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteRenderbuffers(1, &depth_);
  glDeleteTextures(1, &colour_);
  glDeleteFramebuffers(1, &framebuffer_);
}

void FloatTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, width_, height_);
}

void FloatTarget::read_back() const {
  pixels_.resize(4 * static_cast<std::size_t>(width_) * height_);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, pixels_.data());
  check_gl("reading the image back");
}

void FloatTarget::add_to(std::vector<double>& sum, std::vector<float>* subject,
                         float weight) const {
  read_back();
  // GL's rows run from the bottom up.
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const float* p = &pixels_[4 * (static_cast<std::size_t>(height_ - 1 - y) * width_ + x)];
      double* q = &sum[3 * (static_cast<std::size_t>(y) * width_ + x)];
      q[0] += p[0], q[1] += p[1], q[2] += p[2];
      if (subject && p[3] > 1.5f) (*subject)[static_cast<std::size_t>(y) * width_ + x] += weight;
    }
}

double FloatTarget::metered_exposure(ToneMap curve) const {
  read_back();
  metered_.width = lattice_size(width_, kMeteringStep);
  metered_.height = lattice_size(height_, kMeteringStep);
  metered_.rgb.clear();
  metered_subject_.clear();
  for (int b = 0; b < metered_.height; ++b)
    for (int a = 0; a < metered_.width; ++a) {
      const int x = lattice_pixel(a, width_, kMeteringStep);
      const int y = lattice_pixel(b, height_, kMeteringStep);
      const float* p = &pixels_[4 * (static_cast<std::size_t>(height_ - 1 - y) * width_ + x)];
      metered_.rgb.insert(metered_.rgb.end(), {p[0], p[1], p[2]});
      metered_subject_.push_back(p[3] > 1.5f ? 1.0f : 0.0f);
    }
  return auto_exposure(metered_, curve, metered_subject_);
}

Image FloatTarget::read() const {
  std::vector<double> sum(3 * static_cast<std::size_t>(width_) * height_, 0.0);
  add_to(sum);
  Image image;
  image.width = width_;
  image.height = height_;
  image.rgb.assign(sum.begin(), sum.end());
  return image;
}

DisplayPass::DisplayPass() {
  program_ = link_program(
      version_line(false) + shader_sources::common_glsl + shader_sources::fullscreen_vert,
      version_line(false) + "#define LIGHTCONE_FRAGMENT_STAGE 1\n" + shader_sources::common_glsl +
          shader_sources::tone_map_glsl + shader_sources::display_frag);
  glGenVertexArrays(1, &vertex_array_);
  check_gl("creating the display pass");
}

DisplayPass::~DisplayPass() {
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteProgram(program_);
}

void DisplayPass::draw(const FloatTarget& relativistic, const FloatTarget* classical,
                       double exposure_ev, ToneMap curve) const {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(program_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, relativistic.texture());
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, classical ? classical->texture() : relativistic.texture());
  glUniform1i(glGetUniformLocation(program_, "relativistic_image"), 0);
  glUniform1i(glGetUniformLocation(program_, "classical_image"), 1);
  glUniform1i(glGetUniformLocation(program_, "split"), classical ? 1 : 0);
  glUniform2f(glGetUniformLocation(program_, "image_size"),
              static_cast<float>(relativistic.width()), static_cast<float>(relativistic.height()));
  glUniform1f(glGetUniformLocation(program_, "exposure_scale"),
              static_cast<float>(std::exp2(exposure_ev)));
  glUniform1i(glGetUniformLocation(program_, "tone_curve"), curve == ToneMap::kReinhard ? 1
                                                            : curve == ToneMap::kFilmic ? 2
                                                                                        : 0);
  glBindVertexArray(vertex_array_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  // The targets are drawn into next: left bound, WebGL refuses those draws as feedback loops.
  for (const GLenum unit : {GL_TEXTURE1, GL_TEXTURE0}) {
    glActiveTexture(unit);
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  check_gl("drawing the display pass");
}

}  // namespace lightcone

// The raster renderer's output variables: every body's nearest surface at each pixel's centre,
// met exactly by the fragment's own ray (body.frag, LIGHTCONE_SURFACE_VARIABLES), into two
// float targets; each pixel's values then follow from that surface by the ray tracer's own
// definitions (frame/ray_seen.hpp).
#include <cmath>
#include <stdexcept>
#include <vector>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/ray_seen.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/raster_renderer_impl.hpp"
#include "lightcone/raster/shader_build.hpp"

namespace lightcone {
namespace {

// Two RGBA float colour attachments and a depth buffer, for one frame's output variables.
class SurfaceTarget {
 public:
  SurfaceTarget(int width, int height) : width_(width), height_(height) {
    glGenFramebuffers(1, &framebuffer_);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glGenTextures(2, colours_);
    for (int i = 0; i < 2; ++i) {
      glBindTexture(GL_TEXTURE_2D, colours_[i]);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
      glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D, colours_[i],
                             0);
    }
    glGenRenderbuffers(1, &depth_);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("cannot create the output variables' float framebuffer");
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, buffers);
    glViewport(0, 0, width, height);
  }
  ~SurfaceTarget() {
    glDeleteRenderbuffers(1, &depth_);
    glDeleteTextures(2, colours_);
    glDeleteFramebuffers(1, &framebuffer_);
  }
  SurfaceTarget(const SurfaceTarget&) = delete;
  SurfaceTarget& operator=(const SurfaceTarget&) = delete;

  // Attachment i's pixels, RGBA, rows from the bottom.
  std::vector<float> read(int i) const {
    std::vector<float> pixels(4 * static_cast<std::size_t>(width_) * height_);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    glReadBuffer(GL_COLOR_ATTACHMENT0 + i);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, pixels.data());
    check_gl("reading the output variables back");
    return pixels;
  }

 private:
  int width_, height_;
  GLuint framebuffer_ = 0, colours_[2] = {0, 0}, depth_ = 0;
};

}  // namespace

void RasterRenderer::surface_variables(std::span<const Aov> aovs, Image& image) {
  Impl& frame = *impl_;
  const ResolvedScene& resolved = *frame.scene;
  const int width = resolved.camera.width, height = resolved.camera.height;
  GLint bound_draw = 0, bound_read = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound_draw);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &bound_read);
  const SurfaceTarget target(width, height);
  // Alpha 0: no surface (the sky).
  glClearColor(0, 0, 0, 0);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  frame.shading_offsets = nullptr;
  frame.bind_frame_state();
  glDepthFunc(GL_LESS);
  frame.bind_body_buffers();
  const GLuint program = frame.body_program =
      frame.body_program_for(Impl::kSurfaceVariables, frame.gpu_tessellation,
                             frame.specialise ? frame.frame_features : kAllBodyFeatures);
  glUseProgram(program);
  frame.set_common(program, resolved, frame.first_log_doppler, 0.5, 0.5);
  glUniform2f(uniform(program, "depth_range"), std::log(kDepthNear), std::log(kDepthFar));
  for (const Impl::BodyDraw& draw : frame.draws) {
    const Object& object = *resolved.bodies[draw.body].object;
    const Vec3 inverse_scale{1 / object.scale.x, 1 / object.scale.y, 1 / object.scale.z};
    set_mat3(program, "normal_to_rest", object.rotation * Mat3::diagonal(inverse_scale));
    glUniform1f(uniform(program, "body_index"), static_cast<float>(draw.body));
    frame.draw_body(resolved, draw, false);
  }
  skip_faces(HiddenFaces::kNone);
  check_gl("drawing the output variables");
  const std::vector<float> normal_distance = target.read(0), object_doppler = target.read(1);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(bound_draw));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(bound_read));

  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  const std::size_t first = image.channels.size();
  for (const Aov aov : aovs)
    for (const std::string& name : aov_channel_names(aov))
      image.channels.push_back({name, std::vector<float>(pixels)});
  std::vector<float> values(image.channels.size() - first);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // GL's rows run from the bottom up.
      const std::size_t gl_at = 4 * (static_cast<std::size_t>(height - 1 - y) * width + x);
      const float* nd = &normal_distance[gl_at];
      const float* od = &object_doppler[gl_at];
      const Vec3 u = look_direction(resolved.camera, x + 0.5, y + 0.5);
      RaySeen seen;
      if (od[3] > 0) {
        const double s = nd[3];
        seen.surface = true;
        seen.object = od[0];
        seen.doppler = od[1];
        seen.event = resolved.trace_to_world(Vec4{resolved.ray_time * s, u * s});
        seen.distance = s;
        seen.normal = {nd[0], nd[1], nd[2]};
      } else {
        seen.doppler = resolved.doppler(u, resolved.sky_velocity);
      }
      write_aov_values(resolved, u, seen, aovs, values.data());
      const std::size_t at = static_cast<std::size_t>(y) * width + x;
      for (std::size_t c = 0; c < values.size(); ++c)
        image.channels[first + c].values[at] = values[c];
    }
}

}  // namespace lightcone

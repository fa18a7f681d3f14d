// The raster renderer's output variables: every body's nearest surface at each pixel's centre,
// met exactly by the fragment's own ray (body.frag, LIGHTCONE_SURFACE_VARIABLES), into two
// float targets; each pixel's values then follow from that surface by the ray tracer's own
// definitions (frame/ray_seen.hpp). Near a black hole the bodies' images of orders 0 and 1 are
// drawn as the colour pass draws them (hole_body.frag: their normal, time of flight, shift and
// order interpolated between exact vertices), and a pixel that shows none takes the disk, the
// shadow or the sky its curved ray meets (seen_along_curved_ray), as the sky pass draws them.
#include <cmath>
#include <stdexcept>
#include <vector>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/hole_view.hpp"
#include "lightcone/frame/ray_seen.hpp"
#include "lightcone/portable.hpp"
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
    for (int i = 0; i < 2; ++i) colours_[i] = attach_float_colour(i, width, height);
    depth_ = attach_float_depth(width, height);
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

// Near a black hole, what a pixel whose centre shows a body's image saw, from hole_body.frag's
// two targets there: the shape normal and the light's coordinate time of flight `nf`; the body,
// ln g and the image's order `os`.
RaySeen hole_image_seen(const ResolvedScene& scene, const Vec3& u, const float* nf,
                        const float* os) {
  RaySeen seen;
  const auto body = static_cast<std::size_t>(os[0]);
  seen.surface = true;
  seen.object = os[0];
  seen.doppler = std::exp(static_cast<double>(os[1]));
  seen.order = static_cast<int>(os[2]);
  // The vertices' time of flight is counted from the camera's time (hole_bodies.cpp).
  seen.event.t = scene.scene->camera.world_line.time - nf[3];
  seen.distance = camera_frame_distance(*scene.hole, u, scene.observation_event.t - seen.event.t);
  seen.normal = normalize(normal_to_rest(*scene.bodies[body].object) * Vec3{nf[0], nf[1], nf[2]});
  return seen;
}

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
    set_mat3(program, "normal_to_rest", normal_to_rest(object));
    glUniform1f(uniform(program, "body_index"), static_cast<float>(draw.body));
    frame.draw_body(resolved, draw, false);
  }
  skip_faces(HiddenFaces::kNone);
  if (resolved.hole && !frame.hole_body_list.empty()) {
    const bool disk = resolved.hole->disk.has_value();
    const GLuint hole_program = frame.hole_bodies->program(disk, true);
    glUseProgram(hole_program);
    frame.set_common(hole_program, resolved, frame.first_log_doppler, 0.5, 0.5);
    if (disk)
      frame.black_hole->set_uniforms(hole_program, *resolved.hole, frame.disk_floor, frame.disk_row,
                                     resolved.scene->render);
    frame.hole_bodies->draw(resolved, hole_program);
  }
  check_gl("drawing the output variables");
  const std::vector<float> normal_distance = target.read(0), object_doppler = target.read(1);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(bound_draw));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(bound_read));

  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  const std::size_t first = image.channels.size();
  for (const Aov aov : aovs)
    for (const std::string& name : aov_channel_names(aov))
      image.channels.push_back({name, std::vector<float>(pixels)});
  const std::size_t channels = image.channels.size() - first;
  // A row at a time on the thread pool (near a black hole each pixel without a body follows its
  // curved ray).
  parallel_for(0, height, [&](int y) {
    std::vector<float> values(channels);
    for (int x = 0; x < width; ++x) {
      // GL's rows run from the bottom up.
      const std::size_t gl_at = 4 * (static_cast<std::size_t>(height - 1 - y) * width + x);
      const float* nd = &normal_distance[gl_at];
      const float* od = &object_doppler[gl_at];
      const Vec3 u = look_direction(resolved.camera, x + 0.5, y + 0.5);
      RaySeen seen;
      if (resolved.hole) {
        seen =
            od[3] > 0 ? hole_image_seen(resolved, u, nd, od) : seen_along_curved_ray(resolved, u);
      } else if (od[3] > 0) {
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
      for (std::size_t c = 0; c < channels; ++c) image.channels[first + c].values[at] = values[c];
    }
  });
}

}  // namespace lightcone

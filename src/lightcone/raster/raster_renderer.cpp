#include "lightcone/raster/raster_renderer.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <map>
#include <tuple>

#include "lightcone/frame/received_colour.hpp"
#include "lightcone/frame/sampler.hpp"
#include "lightcone/frame/tone_map.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/shader_sources.hpp"

namespace lightcone {

std::vector<std::string> raster_differences(const Scene& scene) {
  std::vector<std::string> differences;
  bool lit = false, textured = false;
  for (const Object& o : scene.objects) {
    lit = lit || !o.material.unlit;
    textured = textured || std::holds_alternative<Texture>(o.material.pattern);
  }
  if (lit) differences.push_back("lit materials are drawn black (not yet lit)");
  if (textured) differences.push_back("textured materials are drawn black");
  if (std::holds_alternative<SkyImage>(scene.sky.pattern))
    differences.push_back("the sky image is drawn black");
  if (lit && scene.render.shadows && !scene.lights.empty())
    differences.push_back("no shadows are cast");
  return differences;
}

namespace {

// Received colour rows: nodes in ln D over the factors the image shows, two spare nodes past
// each end; linear interpolation between nodes 1/512 of a unit of ln D apart is far below
// what 8 bits show.
constexpr double kLogDopplerStep = 1.0 / 512;
constexpr int kFloatsPerVertex = 7;  // shape point, face plane (tessellate())

std::string vertex_shader(const char* source) {
  return std::string("#version 330 core\n") + shader_sources::common_glsl + source;
}
std::string fragment_shader(const char* source) {
  return std::string("#version 330 core\n#define LIGHTCONE_FRAGMENT_STAGE 1\n") +
         shader_sources::common_glsl + source;
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

// Same emission, same row.
using EmissionKey = std::tuple<float, float, float, const DopplerXyzTable*, const DopplerXyzTable*,
                               const DopplerXyzTable*, double, double, double, int>;
EmissionKey key_of(const PointEmission& e) {
  return {static_cast<float>(e.rest_rgb.r),
          static_cast<float>(e.rest_rgb.g),
          static_cast<float>(e.rest_rgb.b),
          e.tables[0],
          e.tables[1],
          e.tables[2],
          e.weights[0],
          e.weights[1],
          e.weights[2],
          e.table_count};
}

}  // namespace

struct RasterRenderer::Impl {
  GLuint body_program = 0, sky_program = 0;
  GLuint vertex_array = 0, vertex_buffer = 0, rows_texture = 0, offsets_texture = 0;
  std::vector<float> vertices;  // reused from frame to frame

  Impl() {
    body_program = link_program(vertex_shader(shader_sources::body_vert),
                                fragment_shader(shader_sources::body_frag));
    sky_program = link_program(vertex_shader(shader_sources::fullscreen_vert),
                               fragment_shader(shader_sources::sky_frag));
    glGenVertexArrays(1, &vertex_array);
    glGenBuffers(1, &vertex_buffer);
    glGenTextures(1, &rows_texture);
    glGenTextures(1, &offsets_texture);
    glBindVertexArray(vertex_array);
    glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, kFloatsPerVertex * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, kFloatsPerVertex * sizeof(float),
                          reinterpret_cast<const void*>(3 * sizeof(float)));
    check_gl("creating the renderer");
  }

  ~Impl() {
    glDeleteTextures(1, &rows_texture);
    glDeleteTextures(1, &offsets_texture);
    glDeleteBuffers(1, &vertex_buffer);
    glDeleteVertexArrays(1, &vertex_array);
    glDeleteProgram(body_program);
    glDeleteProgram(sky_program);
  }

  void set_common(GLuint program, const ResolvedScene& scene, double first_log_doppler, double ox,
                  double oy) {
    const CameraBasis& c = scene.camera;
    set_vec3(program, "camera_forward", c.forward);
    set_vec3(program, "camera_right", c.right);
    set_vec3(program, "camera_up", c.up);
    glUniform2f(uniform(program, "camera_tan_half"), static_cast<float>(c.tan_half_fov * c.aspect),
                static_cast<float>(c.tan_half_fov));
    glUniform2f(uniform(program, "image_size"), static_cast<float>(c.width),
                static_cast<float>(c.height));
    glUniform2f(uniform(program, "pixel_offset"), static_cast<float>(ox), static_cast<float>(oy));
    glUniform1i(uniform(program, "colour_rows"), 0);
    glUniform1i(uniform(program, "sample_offsets"), 1);
    glUniform1i(uniform(program, "shade_at_sample_offsets"), shading_offsets ? 1 : 0);
    glUniform1f(uniform(program, "log_doppler_first"), static_cast<float>(first_log_doppler));
    glUniform1f(uniform(program, "log_doppler_step"), static_cast<float>(kLogDopplerStep));
    glUniform1f(uniform(program, "ray_time"), static_cast<float>(scene.ray_time));
  }

  // The Doppler factor's velocity and gamma for an emitter moving with `velocity` in F.
  static void set_doppler(GLuint program, const ResolvedScene& scene, const Vec3& velocity) {
    const bool relativity = scene.scene->render.relativity;
    set_vec3(program, "doppler_velocity", relativity ? velocity : Vec3{});
    glUniform1f(uniform(program, "doppler_gamma"),
                relativity ? static_cast<float>(lorentz_gamma(velocity)) : 1.0f);
  }

  // What one frame keeps between its passes.
  struct BodyDraw {
    std::size_t body = 0, first_vertex = 0, vertex_count = 0;
    int first_row = 0, pattern = 0;
  };
  const ResolvedScene* scene = nullptr;
  std::vector<BodyDraw> draws;
  double first_log_doppler = 0;
  int sky_first_row = 0;

  // Tessellates every body and tabulates the colour rows for one frame.
  RasterFrameStats prepare(const ResolvedScene& resolved, const EmissionTable& emission,
                           const TessellationLimits& limits) {
    scene = &resolved;
    const Scene& s = *resolved.scene;
    // Rows: every distinct fixed emission of the bodies and the sky.
    std::map<EmissionKey, int> row_of;
    std::vector<const PointEmission*> rows;
    const auto row = [&](const PointEmission& e) {
      const auto [it, added] = row_of.emplace(key_of(e), static_cast<int>(rows.size()));
      if (added) rows.push_back(&e);
      return it->second;
    };
    static const PointEmission kBlack{};
    draws.clear();
    vertices.clear();
    std::map<const void*, RestMesh> meshes;  // per shape, for this frame
    for (std::size_t i = 0; i < resolved.bodies.size(); ++i) {
      const ResolvedBody& body = resolved.bodies[i];
      BodyDraw draw;
      draw.body = i;
      const Material& m = body.object->material;
      const bool drawable = m.unlit && !std::holds_alternative<Texture>(m.pattern);
      if (!drawable) {
        draw.first_row = row(kBlack);
      } else if (std::holds_alternative<Checker>(m.pattern)) {
        // A checker's two colours take consecutive rows of their own.
        draw.first_row = static_cast<int>(rows.size());
        draw.pattern = 1;
        rows.push_back(&emission.object_colour(i, 0));
        rows.push_back(&emission.object_colour(i, 1));
      } else {
        draw.first_row = row(emission.object_colour(i, 0));
      }
      const Shape& shape = body.object->shape;
      const void* shape_key = std::visit([](const auto& x) -> const void* { return &x; }, shape);
      auto it = meshes.find(shape_key);
      if (it == meshes.end()) it = meshes.emplace(shape_key, rest_mesh(shape)).first;
      draw.first_vertex = vertices.size() / kFloatsPerVertex;
      tessellate(resolved, body_view(body), it->second, limits, vertices);
      draw.vertex_count = vertices.size() / kFloatsPerVertex - draw.first_vertex;
      if (draw.vertex_count > 0) draws.push_back(draw);
    }
    const bool grid = std::holds_alternative<SkyGrid>(s.sky.pattern);
    const bool sky_image = std::holds_alternative<SkyImage>(s.sky.pattern);
    sky_first_row = static_cast<int>(rows.size());
    rows.push_back(sky_image ? &kBlack : &emission.sky_colour(0));
    rows.push_back(grid ? &emission.sky_colour(1) : rows.back());

    // The nodes cover the factors the image shows (both kinds: lit bodies are drawn black).
    const LogDopplerRange unlit = visible_log_doppler(resolved, false);
    const LogDopplerRange lit = visible_log_doppler(resolved, true);
    const double lo = std::min(unlit.lo, lit.empty ? unlit.lo : lit.lo) - 2 * kLogDopplerStep;
    const double hi = std::max(unlit.hi, lit.empty ? unlit.hi : lit.hi) + 2 * kLogDopplerStep;
    first_log_doppler = lo;
    const int nodes = std::max(2, static_cast<int>(std::ceil((hi - lo) / kLogDopplerStep)) + 1);
    std::vector<float> texels(static_cast<std::size_t>(nodes) * rows.size() * 3);
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int k = 0; k < nodes; ++k) {
        const double d = std::exp(lo + k * kLogDopplerStep);
        const LinearRgb c = received_colour(*rows[r], d, s.render);
        float* t = &texels[3 * (r * nodes + k)];
        t[0] = static_cast<float>(c.r);
        t[1] = static_cast<float>(c.g);
        t[2] = static_cast<float>(c.b);
      }
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, rows_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, nodes, static_cast<GLsizei>(rows.size()), 0, GL_RGB,
                 GL_FLOAT, texels.data());
    glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
                 vertices.data(), GL_STATIC_DRAW);
    check_gl("uploading the frame");
    RasterFrameStats stats;
    stats.triangles = vertices.size() / (3 * kFloatsPerVertex);
    return stats;
  }

  const std::vector<float>* shading_offsets = nullptr;

  // One pass of the prepared frame, its samples at (ox, oy) within each pixel.
  void pass(double ox, double oy, const std::vector<float>* offsets) {
    const ResolvedScene& resolved = *scene;
    const Scene& s = *resolved.scene;
    shading_offsets = offsets;
    if (offsets) {
      glActiveTexture(GL_TEXTURE1);
      glBindTexture(GL_TEXTURE_2D, offsets_texture);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, resolved.camera.width, resolved.camera.height, 0,
                   GL_RG, GL_FLOAT, offsets->data());
    }
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, rows_texture);

    glUseProgram(body_program);
    set_common(body_program, resolved, first_log_doppler, ox, oy);
    // Depth: the light travel distance on a log scale between these.
    glUniform2f(uniform(body_program, "depth_range"), std::log(1e-6f), std::log(1e12f));
    glDepthFunc(GL_LESS);
    glBindVertexArray(vertex_array);
    for (const BodyDraw& draw : draws) {
      const ResolvedBody& body = resolved.bodies[draw.body];
      const BodyView view = body_view(body);
      set_mat3(body_program, "shape_to_trace", view.shape_to_trace);
      set_vec3(body_program, "shape_origin", view.shape_origin);
      set_vec3(body_program, "world_line_velocity", view.velocity);
      glUniform1f(uniform(body_program, "one_minus_beta2"),
                  static_cast<float>(1.0 - dot(view.velocity, view.velocity)));
      set_vec3(body_program, "ray_offset", body.ray_offset);
      set_mat3(body_program, "shape_spatial", body.spatial);
      set_doppler(body_program, resolved, body.velocity);
      glUniform1i(uniform(body_program, "colour_row"), draw.first_row);
      glUniform1i(uniform(body_program, "pattern"), draw.pattern);
      const Shape& shape = body.object->shape;
      const auto* checker = std::get_if<Checker>(&body.object->material.pattern);
      glUniform1f(uniform(body_program, "checker_size"),
                  checker ? static_cast<float>(checker->size) : 1.0f);
      const auto* box = std::get_if<Box>(&shape);
      const auto* sphere = std::get_if<Sphere>(&shape);
      glUniform1i(uniform(body_program, "shape_kind"), box                                    ? 1
                                                       : std::holds_alternative<Plane>(shape) ? 2
                                                       : sphere                               ? 3
                                                                                              : 0);
      set_vec3(body_program, "box_size", box ? box->size : Vec3{1, 1, 1});
      glUniform1f(uniform(body_program, "sphere_radius"),
                  sphere ? static_cast<float>(sphere->radius) : 0.0f);
      glDrawArrays(GL_TRIANGLES, static_cast<GLint>(draw.first_vertex),
                   static_cast<GLsizei>(draw.vertex_count));
    }
    check_gl("drawing the bodies");

    glUseProgram(sky_program);
    set_common(sky_program, resolved, first_log_doppler, ox, oy);
    set_vec3(sky_program, "sky_time_column", resolved.sky_time_column);
    set_mat3(sky_program, "sky_spatial", resolved.sky_spatial);
    set_doppler(sky_program, resolved, resolved.sky_velocity);
    glUniform1i(uniform(sky_program, "colour_row"), sky_first_row);
    const auto* g = std::get_if<SkyGrid>(&s.sky.pattern);
    glUniform1i(uniform(sky_program, "pattern"), g ? 1 : 0);
    glUniform1f(uniform(sky_program, "grid_spacing"),
                g ? static_cast<float>(g->spacing_degrees) : 1.0f);
    glUniform1f(uniform(sky_program, "grid_half_width"),
                g ? static_cast<float>(0.5 * g->line_width_degrees) : 0.0f);
    glDepthFunc(GL_LEQUAL);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    check_gl("drawing the sky");
  }
};

RasterRenderer::RasterRenderer() : impl_(std::make_unique<Impl>()) {}
RasterRenderer::~RasterRenderer() = default;

RasterFrameStats RasterRenderer::prepare(const ResolvedScene& scene, const EmissionTable& emission,
                                         const TessellationLimits& limits) {
  return impl_->prepare(scene, emission, limits);
}

void RasterRenderer::pass(double pixel_offset_x, double pixel_offset_y,
                          const std::vector<float>* shading_offsets) {
  impl_->pass(pixel_offset_x, pixel_offset_y, shading_offsets);
}

Image render_raster(const Scene& scene, RasterStats* stats, const TessellationLimits& limits,
                    std::uint64_t seed) {
  const auto start = std::chrono::steady_clock::now();
  const HeadlessGlContext context;
  const ResolvedScene resolved = resolve_scene(scene);
  const EmissionTable emission(resolved);
  RasterRenderer renderer;
  const int width = scene.camera.width, height = scene.camera.height;
  const FloatTarget target(width, height);
  // camera.samples passes: each covers the pixels at one point of a multi-jittered pattern and
  // shades every pixel at the ray tracer's own sample for it (one sample: the centres).
  const int n = std::max(1, scene.camera.samples);
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  std::vector<double> sum(3 * pixels, 0.0);
  std::vector<float> offsets(n > 1 ? 2 * pixels : 0);
  const std::size_t triangles = renderer.prepare(resolved, emission, limits).triangles;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int k = 0; k < n; ++k) {
    if (n == 1) {
      renderer.pass(0.5, 0.5);
    } else {
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const PixelSample p = pixel_sample(x, y, k, n, seed);
          float* o = &offsets[2 * (static_cast<std::size_t>(height - 1 - y) * width + x)];
          o[0] = static_cast<float>(p.x);
          o[1] = static_cast<float>(p.y);
        }
      const std::array<double, 2> cover =
          multi_jittered(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(n), 0);
      renderer.pass(cover[0], cover[1], &offsets);
    }
    target.add_to(sum);
  }
  Image image;
  image.width = width;
  image.height = height;
  image.rgb.resize(3 * pixels);
  for (std::size_t i = 0; i < sum.size(); ++i) image.rgb[i] = static_cast<float>(sum[i] / n);
  const double ev = scene.render.auto_exposure ? auto_exposure(image) : scene.render.exposure;
  const auto scale = static_cast<float>(std::exp2(ev));
  for (float& v : image.rgb) v *= scale;
  if (stats) {
    stats->exposure = ev;
    stats->triangles = triangles;
    stats->gl = context.description();
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return image;
}

}  // namespace lightcone

#include "lightcone/raster/raster_renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

#include "lightcone/frame/lighting.hpp"
#include "lightcone/frame/shading.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/raster/body_patterns.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer_impl.hpp"
#include "lightcone/raster/shader_build.hpp"
#include "lightcone/raster/shader_sources.hpp"

namespace lightcone {

std::optional<std::string> tessellation_refused(std::string_view name) {
  if (name == "cpu" || name == "gpu" || name == "auto") return std::nullopt;
  return fmt::format("tessellation '{}': must be cpu, gpu or auto", name);
}

RasterTessellation tessellation_named(std::string_view name) {
  return name == "cpu"   ? RasterTessellation::kCpu
         : name == "gpu" ? RasterTessellation::kGpu
                         : RasterTessellation::kAuto;
}
namespace {

// The surface textures' units in the lighting pass: 4 (the sky's image in its own pass) and
// units no other program of the frame uses.
constexpr std::array<int, kSurfaceTextures> kSurfaceUnits{4, 6, 14};
constexpr std::array<const char*, kSurfaceTextures> kSurfaceSamplers{"lit_surface", "lit_motion",
                                                                     "lit_albedo"};

// The Doppler factor's velocity and gamma for an emitter moving with `velocity` in F.
void set_doppler(GLuint program, const ResolvedScene& scene, const Vec3& velocity) {
  const bool relativity = scene.scene->render.relativity;
  set_vec3(program, "doppler_velocity", relativity ? velocity : Vec3{});
  glUniform1f(uniform(program, "doppler_gamma"),
              relativity ? static_cast<float>(lorentz_gamma(velocity)) : 1.0f);
}

}  // namespace

// The sky program of a kind of sky (sky_variant) and colour model.
GLuint RasterRenderer::Impl::sky_program_for(int variant, bool hue) {
  GLuint& program = sky_programs[variant][hue ? 1 : 0];
  if (program) return program;
  const std::string defines = std::string(variant == 1 ? "#define LIGHTCONE_SKY_IMAGE 1\n" : "") +
                              (hue ? "" : "#define LIGHTCONE_NO_HUE 1\n");
  return program = link_program(vertex_shader(shader_sources::fullscreen_vert),
                                fragment_shader(shader_sources::sky_frag, "", defines.c_str()));
}

// The body program of a kind of material, path and features (body_variant_defines).
GLuint RasterRenderer::Impl::body_program_for(int variant, bool gpu, int features) {
  static_assert(kAllBodyFeatures < 1024);
  GLuint& program = body_program_cache[(variant * 2 + (gpu ? 1 : 0)) * 1024 + features];
  if (program) return program;
  const std::string defines =
      std::string(variant == kLit                ? "#define LIGHTCONE_LIT 1\n"
                  : variant == kTextured         ? "#define LIGHTCONE_TEXTURED 1\n"
                  : variant == kSurfaceVariables ? "#define LIGHTCONE_SURFACE_VARIABLES 1\n"
                                                 : "") +
      body_variant_defines(features);
  const std::string fragment = fragment_shader(shader_sources::body_frag,
                                               shader_sources::patterns_glsl, defines.c_str(), gpu);
  if (!gpu)
    return program =
               link_program(vertex_shader(shader_sources::body_vert, false, defines), fragment);
  const std::string common = version_line(true) + defines + shader_sources::common_glsl +
                             shader_sources::body_projection_glsl;
  return program =
             link_program(common + shader_sources::patch_vert, fragment,
                          common + shader_sources::body_tesc, common + shader_sources::body_tese);
}

// The lighting pass's program of a set of body and lighting features (body_variant_defines,
// lighting_variant_defines).
GLuint RasterRenderer::Impl::lighting_program_for(int features, int lighting) {
  GLuint& program = lighting_program_cache[{features, lighting}];
  if (program) return program;
  const std::string defines = body_variant_defines(features) + lighting_variant_defines(lighting);
  program = link_program(vertex_shader(shader_sources::fullscreen_vert),
                         fragment_shader(shader_sources::lit_surfaces_frag,
                                         shader_sources::lighting_glsl, defines.c_str()));
  glUseProgram(program);
  for (int i = 0; i < kSurfaceTextures; ++i)
    glUniform1i(uniform(program, kSurfaceSamplers[i]), kSurfaceUnits[i]);
  return program;
}

RasterRenderer::Impl::Impl() {
  driver.tessellation_shaders = gl_has_tessellation_shaders();
  driver.renderer = gl_renderer();
  // The common programs now, so that the first frame does not wait for them.
  for (int v = 0; v < 3; ++v) body_program_for(v, false, 0);
  for (int v = 0; v < 2; ++v) sky_program_for(v, false);
  glGenVertexArrays(1, &vertex_array);
  glGenBuffers(1, &vertex_buffer);
  glGenBuffers(1, &patch_buffer);
  glGenBuffers(1, &face_uv_buffer);
  glGenTextures(1, &rows_texture);
  glGenTextures(1, &offsets_texture);
  glGenTextures(1, &tables_texture);
  glGenTextures(1, &light_table_texture);
  glGenTextures(1, &reflection_index_texture);
  glBindVertexArray(vertex_array);
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, kFloatsPerVertex * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, kFloatsPerVertex * sizeof(float),
                        reinterpret_cast<const void*>(3 * sizeof(float)));
  check_gl("creating the renderer");
}

RasterRenderer::Impl::~Impl() {
  for (const auto& [image, name] : images) glDeleteTextures(1, &name);
  glDeleteTextures(1, &rows_texture);
  glDeleteTextures(1, &offsets_texture);
  glDeleteTextures(1, &tables_texture);
  glDeleteTextures(1, &light_table_texture);
  glDeleteTextures(1, &reflection_index_texture);
  glDeleteBuffers(1, &vertex_buffer);
  glDeleteVertexArrays(1, &vertex_array);
  for (const auto& [key, program] : body_program_cache) glDeleteProgram(program);
  glDeleteBuffers(1, &patch_buffer);
  glDeleteBuffers(1, &face_uv_buffer);
  for (const auto& [key, program] : lighting_program_cache) glDeleteProgram(program);
  if (surfaces_framebuffer) {
    glDeleteFramebuffers(1, &surfaces_framebuffer);
    glDeleteTextures(kSurfaceTextures, surface_textures.data());
  }
  for (const auto& programs : sky_programs)
    for (GLuint program : programs)
      if (program) glDeleteProgram(program);
  for (const auto& programs : hole_sky_programs)
    for (GLuint program : programs)
      if (program) glDeleteProgram(program);
}

void RasterRenderer::Impl::set_common(GLuint program, const ResolvedScene& scene,
                                      double first_log_doppler, double ox, double oy) {
  set_camera_uniforms(program, scene.camera, ox, oy);
  glUniform1i(uniform(program, "colour_rows"), 0);
  glUniform1i(uniform(program, "sample_offsets"), 1);
  glUniform1i(uniform(program, "shade_at_sample_offsets"), shading_offsets ? 1 : 0);
  glUniform1f(uniform(program, "log_doppler_first"), static_cast<float>(first_log_doppler));
  glUniform1f(uniform(program, "log_doppler_step"), static_cast<float>(kLogDopplerStep));
  glUniform1f(uniform(program, "ray_time"), static_cast<float>(scene.ray_time));
  glUniform1i(uniform(program, "spectral"),
              scene.scene->render.doppler == DopplerModel::kSpectral ? 1 : 0);
  const RenderSettings& settings = scene.scene->render;
  glUniform1i(uniform(program, "hue_model"), settings.doppler != DopplerModel::kHue ? 0
                                             : settings.hue_loop                    ? 2
                                                                                    : 1);
  glUniform1i(uniform(program, "hue_searchlight"),
              settings.searchlight == SearchlightModel::kPhysical    ? 0
              : settings.searchlight == SearchlightModel::kChang1996 ? 1
                                                                     : 2);
  glUniform1iv(uniform(program, "primary_rows"), 3, final_rows.data());
  glUniform1i(uniform(program, "basis_first_row"), basis_first_row);
  const LinearRgb w = reference_white();
  glUniform3f(uniform(program, "reference_white"), static_cast<float>(w.r), static_cast<float>(w.g),
              static_cast<float>(w.b));
}

// A texture or sky image as a float texture (once per image), with mip levels for the sky's
// filtered lookups (exact lookups read level 0 texel by texel, whatever the filter).
GLuint RasterRenderer::Impl::upload(const Image& image) {
  auto [it, added] = images.emplace(&image, 0);
  if (added) {
    glGenTextures(1, &it->second);
    glBindTexture(GL_TEXTURE_2D, it->second);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    // RGBA: mip levels are generated only for colour-renderable formats in GLES 3 (WebGL 2),
    // and RGB32F is not one.
    std::vector<float> rgba(4 * static_cast<std::size_t>(image.width) * image.height, 1.0f);
    for (std::size_t i = 0; i < rgba.size() / 4; ++i)
      for (int c = 0; c < 3; ++c) rgba[4 * i + c] = image.rgb[3 * i + c];
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, image.width, image.height, 0, GL_RGBA, GL_FLOAT,
                 rgba.data());
    glGenerateMipmap(GL_TEXTURE_2D);
    check_gl("uploading an image");
  }
  return it->second;
}

// The lights and what lit surfaces share, on the lighting pass's program p (lighting.glsl's
// uniforms).
void RasterRenderer::Impl::set_lights(GLuint p, const ResolvedScene& resolved, int lighting) {
  const RenderSettings& settings = resolved.scene->render;
  // The light table: a row of kLightTexels RGBA texels a light (lighting.glsl's lamp()).
  constexpr int kLightTexels = 7;
  const int n = static_cast<int>(lights.size());
  const bool maps = (frame_features & kBodyShadows) != 0;
  std::vector<float> table(4 * kLightTexels * static_cast<std::size_t>(std::max(n, 1)), 0.0f);
  for (int l = 0; l < n; ++l) {
    const LightDraw& d = lights[static_cast<std::size_t>(l)];
    // Its shadow maps where the frame casts shadows (else none: the full programs of the tests'
    // reference read them too).
    const ShadowMapView none;
    const ShadowMapView& view = maps ? shadow_maps->view(static_cast<std::size_t>(l)) : none;
    const double texels[4 * kLightTexels] = {double(d.kind),  double(d.fixed_event),
                                             double(d.row),   double(view.layer),
                                             d.event.t,       d.event.x.x,
                                             d.event.x.y,     d.event.x.z,
                                             d.position.x,    d.position.y,
                                             d.position.z,    d.time,
                                             d.velocity.x,    d.velocity.y,
                                             d.velocity.z,    1.0 - dot(d.velocity, d.velocity),
                                             d.axis.x,        d.axis.y,
                                             d.axis.z,        d.intensity,
                                             d.half_cone,     d.falloff,
                                             d.radius,        view.far,
                                             view.origin.t,   view.origin.x.x,
                                             view.origin.x.y, view.origin.x.z};
    std::transform(std::begin(texels), std::end(texels),
                   table.begin() + 4 * kLightTexels * static_cast<std::ptrdiff_t>(l),
                   [](double x) { return static_cast<float>(x); });
  }
  if (lighting & kLightingManyLights) {
    glActiveTexture(GL_TEXTURE7);
    glBindTexture(GL_TEXTURE_2D, light_table_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kLightTexels, std::max(n, 1), 0, GL_RGBA, GL_FLOAT,
                 table.data());
  } else {
    glUniform4fv(uniform(p, "lamp_texels"), kLightTexels * n, table.data());
  }
  glActiveTexture(GL_TEXTURE8);
  glBindTexture(GL_TEXTURE_2D, reflection_index_texture);
  glActiveTexture(GL_TEXTURE0);
  glUniform1i(uniform(p, "light_table"), 7);
  glUniform1i(uniform(p, "reflection_index"), 8);
  glUniform1i(uniform(p, "light_count"), n);
  glUniform1i(uniform(p, "shadow_maps"), 5);
  glUniform1f(uniform(p, "shadow_texel"),
              maps ? 2.0f / static_cast<float>(shadow_maps->face_size()) : 0.0f);
  if (frame_features & kBodyShadows) shadow_maps->bind(5);
  // The spectral fit's samplers on units of their own in every program that has them, bound or
  // not: samplers of two types on one unit make a draw fail.
  if (frame_features & kBodySpectralTextures)
    spectral_albedo->bind(p, kSpectralAlbedoUnit);
  else
    SpectralAlbedo::assign_units(p, kSpectralAlbedoUnit);
  if (frame_features & kBodyShadows)
    shadow_casters->bind(p, kCasterTableUnit, kCasterMeshUnit);
  else
    glUniform1i(uniform(p, "caster_count"), 0);
  // The linear part of the map from F to W: events relative to the observation event.
  set_mat4(p, "trace_to_world", resolved.trace_to_world.linear);
  set_vec3(p, "camera_velocity",
           settings.relativity ? resolved.scene->camera.world_line.velocity : Vec3{});
  glUniform1i(uniform(p, "searchlight_model"),
              settings.searchlight == SearchlightModel::kPhysical    ? 0
              : settings.searchlight == SearchlightModel::kChang1996 ? 1
                                                                     : 2);
  glUniform1i(uniform(p, "reflection_tables"), 2);
  glUniform4f(uniform(p, "reflection_grid"), static_cast<float>(table_camera_first),
              static_cast<float>(kTableCameraStep), static_cast<float>(table_light_first),
              static_cast<float>(kTableLightStep));
  glUniform1i(uniform(p, "reflection_light_nodes"), table_light_nodes);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, tables_texture);
  glActiveTexture(GL_TEXTURE0);
}

// A lit body's own uniforms: what its surfaces write for the lighting pass.
void RasterRenderer::Impl::set_lit_body(const ResolvedScene& resolved, const BodyDraw& draw) {
  const GLuint p = body_program;
  const Object& object = *resolved.bodies[draw.body].object;
  const Material& m = object.material;
  Rgb albedo[2];
  if (pattern_colours(m, albedo) == 1) albedo[1] = albedo[0];
  const float albedos[6] = {albedo[0].r, albedo[0].g, albedo[0].b,
                            albedo[1].r, albedo[1].g, albedo[1].b};
  glUniform3fv(uniform(p, "albedo"), 2, albedos);
  set_mat3(p, "normal_to_rest", normal_to_rest(object));
  set_vec3(p, "surface_velocity_of_body", lit_body_velocity(resolved, object));
  glUniform1i(uniform(p, "reflection_body"), draw.reflection_body);
}

// One body of the prepared frame with the program in use: its world-line, pattern, clock, spin
// and (lit) lighting uniforms, then its triangles.
void RasterRenderer::Impl::draw_body(const ResolvedScene& resolved, const BodyDraw& draw,
                                     bool lit) {
  const ResolvedBody& body = resolved.bodies[draw.body];
  const BodyView view = body_view(resolved, body);
  set_vec3(body_program, "shape_origin", view.shape_origin);
  if (gpu_tessellation) {
    // The shape points' world-lines, which the tessellation shaders meet (vertices tessellated
    // on the CPU arrive at their events).
    set_mat3(body_program, "shape_to_trace", view.shape_to_trace);
    set_vec3(body_program, "world_line_velocity", view.velocity);
    glUniform1f(uniform(body_program, "one_minus_beta2"),
                static_cast<float>(1.0 - dot(view.velocity, view.velocity)));
  }
  set_vec3(body_program, "ray_offset", body.ray_offset);
  set_mat3(body_program, "shape_spatial", body.spatial);
  set_doppler(body_program, resolved, body.velocity);
  glUniform1i(uniform(body_program, "relativity"), resolved.scene->render.relativity ? 1 : 0);
  glUniform1i(uniform(body_program, "colour_row"), draw.first_row);
  glUniform1f(uniform(body_program, "subject_alpha"),
              body.moves_relative_to_camera() ? 2.0f : 1.0f);
  set_pattern_uniforms(body_program, *body.object, draw.pattern);
  const Shape& shape = body.object->shape;
  // The body's clock along the sample's ray, s (ray_time row.t + row.x . u), and the
  // patterns that read it.
  glUniform1f(uniform(body_program, "proper_time_origin"),
              static_cast<float>(body.proper_time_origin));
  set_vec3(body_program, "proper_time_row", body.proper_time_row.x);
  glUniform1f(uniform(body_program, "proper_time_ray"),
              static_cast<float>(body.proper_time_row.t * resolved.ray_time));
  // A spinning body: its points' turn and motion, per fragment.
  glUniform1i(uniform(body_program, "spinning"), body.spin >= 0 ? 1 : 0);
  if (body.spin >= 0) {
    const ResolvedSpin& spin = resolved.spins[body.spin];
    glUniform1i(uniform(body_program, "spin_round"), spin.round ? 1 : 0);
    set_vec3(body_program, "spin_axis", spin.axis);
    glUniform1f(uniform(body_program, "spin_rate"), static_cast<float>(spin.rate));
    set_mat3(body_program, "rest_from_shape", spin.rest_from_shape);
    set_mat3(body_program, "shape_of_rest", spin.shape_of_rest);
    set_mat4(body_program, "trace_from_rest", spin.trace_from_rest);
  }
  const auto* sphere = std::get_if<Sphere>(&shape);
  glUniform1i(uniform(body_program, "texture_image"), 3);
  if (draw.pattern == 2) {
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D,
                  images.at(std::get<Texture>(body.object->material.pattern).image.get()));
    glActiveTexture(GL_TEXTURE0);
  }
  glUniform1f(uniform(body_program, "sphere_radius"),
              sphere ? static_cast<float>(sphere->radius) : 0.0f);
  if (lit) set_lit_body(resolved, draw);
  if (gpu_tessellation) {
    glUniform1f(uniform(body_program, "sphere_radius_for_tessellation"),
                static_cast<float>(draw.sphere_radius));
    glUniform1f(uniform(body_program, "max_error_pixels"),
                static_cast<float>(tessellation_limits.max_error_pixels));
    // The GPU's levels go to 64 (every OpenGL 4 implementation's least maximum).
    glUniform1f(uniform(body_program, "max_level"),
                static_cast<float>(1 << std::clamp(tessellation_limits.max_level, 0, 6)));
  }
  for (GLuint row : {2u, 3u})
    if (draw.face_uvs) glEnableVertexAttribArray(row);
  skip_faces(draw.hidden);
  glDrawArrays(gpu_tessellation ? GL_PATCHES : GL_TRIANGLES, static_cast<GLint>(draw.first_vertex),
               static_cast<GLsizei>(draw.vertex_count));
  for (GLuint row : {2u, 3u})
    if (draw.face_uvs) glDisableVertexAttribArray(row);
}

// The lit bodies into the surface textures: their exact depths on the frame's own depth buffer
// (the bodies drawn before them included) decide which surface is nearest at each pixel, and
// that one's normal, motion, albedo and finish are kept there for the lighting pass.
void RasterRenderer::Impl::draw_lit_surfaces(double ox, double oy, int features) {
  const ResolvedScene& resolved = *scene;
  const int width = resolved.camera.width, height = resolved.camera.height;
  GLint target = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  GLint depth_type = GL_NONE, depth = 0;
  glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
                                        GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &depth_type);
  glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
                                        GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &depth);
  if (!surfaces_framebuffer) {
    glGenFramebuffers(1, &surfaces_framebuffer);
    glGenTextures(kSurfaceTextures, surface_textures.data());
  }
  glBindFramebuffer(GL_FRAMEBUFFER, surfaces_framebuffer);
  if (width != surfaces_size[0] || height != surfaces_size[1]) {
    for (int i = 0; i < kSurfaceTextures; ++i) {
      glBindTexture(GL_TEXTURE_2D, surface_textures[i]);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D,
                             surface_textures[i], 0);
    }
    glBindTexture(GL_TEXTURE_2D, rows_texture);
    surfaces_size = {width, height};
  }
  if (depth_type == GL_RENDERBUFFER)
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                              static_cast<GLuint>(depth));
  else
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D,
                           static_cast<GLuint>(depth), 0);
  const GLenum buffers[kSurfaceTextures] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                                            GL_COLOR_ATTACHMENT2};
  glDrawBuffers(kSurfaceTextures, buffers);
  const GLfloat empty[4] = {0, 0, 0, 0};
  glClearBufferfv(GL_COLOR, 2, empty);  // no lit surface anywhere yet (lit_albedo's code 0)
  body_program = body_program_for(kLit, gpu_tessellation, features);
  glUseProgram(body_program);
  set_common(body_program, resolved, first_log_doppler, ox, oy);
  glUniform2f(uniform(body_program, "depth_range"), std::log(kDepthNear), std::log(kDepthFar));
  set_mat4(body_program, "trace_to_world", resolved.trace_to_world.linear);
  for (const BodyDraw& draw : draws)
    if (draw.lit) draw_body(resolved, draw, true);
  skip_faces(HiddenFaces::kNone);
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target));
}

// The lighting pass: every pixel whose nearest surface is lit, lit once into the frame's target
// (lit_surfaces.frag); the depth buffer already holds those surfaces.
void RasterRenderer::Impl::light_surfaces(double ox, double oy, int features) {
  const ResolvedScene& resolved = *scene;
  const int lighting = specialise ? lighting_features : kAllLightingFeatures;
  const GLuint program = lighting_program_for(features, lighting);
  glUseProgram(program);
  set_common(program, resolved, first_log_doppler, ox, oy);
  set_lights(program, resolved, lighting);
  for (int i = 0; i < kSurfaceTextures; ++i) {
    glActiveTexture(GL_TEXTURE0 + kSurfaceUnits[i]);
    glBindTexture(GL_TEXTURE_2D, surface_textures[i]);
  }
  glActiveTexture(GL_TEXTURE0);
  glDisable(GL_DEPTH_TEST);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glEnable(GL_DEPTH_TEST);
  check_gl("lighting the lit surfaces");
}

void RasterRenderer::Impl::bind_frame_state() {
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, rows_texture);
  glBindVertexArray(vertex_array);
}

void RasterRenderer::Impl::bind_body_buffers() {
  glBindBuffer(GL_ARRAY_BUFFER, gpu_tessellation ? patch_buffer : vertex_buffer);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, kFloatsPerVertex * sizeof(float), nullptr);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, kFloatsPerVertex * sizeof(float),
                        reinterpret_cast<const void*>(3 * sizeof(float)));
  if (gpu_tessellation) glPatchParameteri(GL_PATCH_VERTICES, 3);
  // The textured meshes' texture coordinates' maps, read by their draws alone.
  glBindBuffer(GL_ARRAY_BUFFER, face_uv_buffer);
  for (int row = 0; row < 2; ++row)
    glVertexAttribPointer(2 + row, 4, GL_FLOAT, GL_FALSE, kFloatsPerUvMap * sizeof(float),
                          reinterpret_cast<const void*>(4 * row * sizeof(float)));
}

// One pass of the prepared frame, its samples at (ox, oy) within each pixel.
void RasterRenderer::Impl::pass(double ox, double oy, const std::vector<float>* offsets) {
  const ResolvedScene& resolved = *scene;
  const Scene& s = *resolved.scene;
  shading_offsets = offsets;
  if (offsets) {
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, offsets_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, resolved.camera.width, resolved.camera.height, 0,
                 GL_RGBA, GL_FLOAT, offsets->data());
  }
  glClearColor(0, 0, 0, 0);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  bind_frame_state();

  glDepthFunc(GL_LESS);
  bind_body_buffers();
  const int features =
      specialise ? frame_features | (offsets ? kBodySampleOffsets : 0) : kAllBodyFeatures;
  for (const Variant variant : {kEmitter, kTextured}) {
    body_program = body_program_for(variant, gpu_tessellation, features);
    glUseProgram(body_program);
    set_common(body_program, resolved, first_log_doppler, ox, oy);
    // Depth: the light travel distance on a log scale between these.
    glUniform2f(uniform(body_program, "depth_range"), std::log(kDepthNear), std::log(kDepthFar));
    for (const BodyDraw& draw : draws)
      if (!draw.lit && (draw.pattern == 2) == (variant == kTextured))
        draw_body(resolved, draw, false);
  }
  skip_faces(HiddenFaces::kNone);
  if (any_lit) {
    draw_lit_surfaces(ox, oy, features);
    light_surfaces(ox, oy, features);
  }
  if (resolved.hole && !hole_body_list.empty()) {
    const bool disk = resolved.hole->disk.has_value();
    const GLuint program = hole_bodies->program(disk);
    glUseProgram(program);
    set_common(program, resolved, first_log_doppler, ox, oy);
    if (disk) black_hole->set_uniforms(program, *resolved.hole, disk_floor, disk_row, s.render);
    hole_bodies->draw(resolved, program);
  }
  check_gl("drawing the bodies");
  draw_sky(ox, oy);
}

void RasterRenderer::Impl::draw_sky(double ox, double oy) {
  const ResolvedScene& resolved = *scene;
  const Scene& s = *resolved.scene;
  const GLuint sky_program =
      resolved.hole ? hole_sky_programs[sky_variant(s)][colour_kind(s.render)]
                    : sky_program_for(sky_variant(s), s.render.doppler == DopplerModel::kHue);
  glUseProgram(sky_program);
  set_common(sky_program, resolved, first_log_doppler, ox, oy);
  if (resolved.hole)
    black_hole->set_uniforms(sky_program, *resolved.hole, disk_floor, disk_row, s.render);
  set_vec3(sky_program, "sky_time_column", resolved.sky_time_column);
  set_mat3(sky_program, "sky_spatial", resolved.sky_spatial);
  set_doppler(sky_program, resolved, resolved.sky_velocity);
  glUniform1i(uniform(sky_program, "colour_row"), sky_first_row);
  const auto* g = std::get_if<SkyGrid>(&s.sky.pattern);
  const auto* sky_image = std::get_if<SkyImage>(&s.sky.pattern);
  glUniform1i(uniform(sky_program, "pattern"), g ? 1 : sky_image ? 2 : 0);
  glUniform1i(uniform(sky_program, "sky_image"), 4);
  if (sky_image) {
    glActiveTexture(GL_TEXTURE4);
    glBindTexture(GL_TEXTURE_2D, images.at(sky_image->image.get()));
    glActiveTexture(GL_TEXTURE0);
  }
  glUniform1f(uniform(sky_program, "grid_spacing"),
              g ? static_cast<float>(g->spacing_degrees) : 1.0f);
  glUniform1f(uniform(sky_program, "grid_half_width"),
              g ? static_cast<float>(0.5 * g->line_width_degrees) : 0.0f);
  glDepthFunc(GL_LEQUAL);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  check_gl("drawing the sky");
  if (stars) stars->draw(resolved);
}

RasterRenderer::TessellatedBodies RasterRenderer::tessellated_bodies() const {
  TessellatedBodies out{impl_->vertex_array, impl_->vertex_buffer, kFloatsPerVertex, {}};
  if (!impl_->gpu_tessellation)
    for (const Impl::BodyDraw& d : impl_->draws)
      out.draws.push_back({d.body, d.first_vertex, d.vertex_count, d.hidden});
  return out;
}

RasterRenderer::RasterRenderer() : impl_(std::make_unique<Impl>()) {}
RasterRenderer::~RasterRenderer() = default;

RasterFrameStats RasterRenderer::prepare(const ResolvedScene& scene, const EmissionTable& emission,
                                         const TessellationLimits& limits, bool on_gpu) {
  return impl_->prepare(scene, emission, limits, on_gpu);
}

void RasterRenderer::set_curved_shadows(CurvedShadowSource source) {
  impl_->curved_shadow_source = std::move(source);
}

void RasterRenderer::set_specialised_programs(bool specialise) {
  impl_->specialise = specialise;
}

const GlDriver& RasterRenderer::driver() const {
  return impl_->driver;
}

void RasterRenderer::sky_pass() {
  impl_->shading_offsets = nullptr;
  impl_->bind_frame_state();
  impl_->draw_sky(0.5, 0.5);
}

void RasterRenderer::pass(double pixel_offset_x, double pixel_offset_y,
                          const std::vector<float>* shading_offsets) {
  impl_->pass(pixel_offset_x, pixel_offset_y, shading_offsets);
}

}  // namespace lightcone

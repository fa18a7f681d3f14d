#include "lightcone/raster/raster_renderer.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <tuple>

#include "lightcone/color/sigmoid_polynomial.hpp"
#include "lightcone/frame/lighting.hpp"
#include "lightcone/frame/received_colour.hpp"
#include "lightcone/frame/shading.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/raster/black_hole_pass.hpp"
#include "lightcone/raster/body_patterns.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/hole_bodies.hpp"
#include "lightcone/raster/shader_build.hpp"
#include "lightcone/raster/shader_sources.hpp"
#include "lightcone/raster/star_pass.hpp"

namespace lightcone {

namespace {

// Received colour rows: nodes in ln D over the factors the image shows, two spare nodes past
// each end; linear interpolation between nodes 1/512 of a unit of ln D apart is far below
// what 8 bits show.
constexpr double kLogDopplerStep = 1.0 / 512;
constexpr int kFloatsPerVertex = 7;  // shape point, face plane (tessellate())
// A moving light's reflection table: ln D_camera and ln D_light nodes, bilinear between them.
constexpr double kTableCameraStep = 1.0 / 128, kTableLightStep = 1.0 / 64;

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

// The sky program: 1 for a sky image the colour model draws, else 0 (one colour or a grid).
int sky_variant(const Scene& scene) {
  return std::holds_alternative<SkyImage>(scene.sky.pattern) &&
                 scene.render.doppler != DopplerModel::kHue
             ? 1
             : 0;
}

}  // namespace

struct RasterRenderer::Impl {
  // One program per kind of material (kEmitter, kTextured, kLit) and of sky (plain or grid, and
  // image): small programs run faster than one with every branch.
  enum Variant { kEmitter = 0, kTextured = 1, kLit = 2 };
  // And one per path (CPU or GPU tessellation) and set of features its frame uses: a frame runs
  // only the code its bodies need, since a branch on a uniform still costs a software
  // rasteriser every fragment it masks (twice the time of street.json's frame). Each is built
  // the first time a frame asks for it.
  std::map<int, GLuint> body_program_cache;
  int frame_features = 0;  // of the prepared frame's bodies (kBodySpin, kBodyTimedPattern)
  bool specialise = true;  // false: every body program has every feature (the tests' reference)
  GLuint sky_programs[2] = {0, 0};
  // The sky near a black hole (plain or grid, and image; the disk's colour model spectral or
  // not): each built with the first frame that needs it.
  GLuint hole_sky_programs[2][2] = {{0, 0}, {0, 0}};
  std::unique_ptr<BlackHolePass> black_hole;
  // The bodies near a black hole: built with the first frame that has them.
  std::unique_ptr<HoleBodiesPass> hole_bodies;
  // The stars: built with the first frame that has them.
  std::unique_ptr<StarPass> stars;
  int disk_row = 0;
  double disk_floor = 0;
  GlDriver driver;
  bool gpu_tessellation = false;  // which path the frame is prepared for
  GLuint body_program = 0;        // the one in use
  GLuint patch_buffer = 0;
  GLuint vertex_array = 0, vertex_buffer = 0, rows_texture = 0, offsets_texture = 0,
         tables_texture = 0;

  // What a body program puts between the shared code and body.frag.
  static std::string body_fragment_extra(int variant) {
    return std::string(shader_sources::patterns_glsl) +
           (variant == kLit ? shader_sources::lighting_glsl : "");
  }

  // The body program of a kind of material, path and features (body_variant_defines).
  GLuint body_program_for(int variant, bool gpu, int features) {
    GLuint& program = body_program_cache[(variant * 2 + (gpu ? 1 : 0)) * 8 + features];
    if (program) return program;
    const std::string defines =
        std::string(variant == kLit        ? "#define LIGHTCONE_LIT 1\n"
                    : variant == kTextured ? "#define LIGHTCONE_TEXTURED 1\n"
                                           : "") +
        body_variant_defines(features);
    const std::string fragment = fragment_shader(
        shader_sources::body_frag, body_fragment_extra(variant), defines.c_str(), gpu);
    if (!gpu) return program = link_program(vertex_shader(shader_sources::body_vert), fragment);
    const std::string common =
        version_line(true) + shader_sources::common_glsl + shader_sources::body_projection_glsl;
    return program =
               link_program(common + shader_sources::patch_vert, fragment,
                            common + shader_sources::body_tesc, common + shader_sources::body_tese);
  }

  Impl() {
    driver.tessellation_shaders = gl_has_tessellation_shaders();
    driver.renderer = gl_renderer();
    // The common programs now, so that the first frame does not wait for them.
    for (int v = 0; v < 3; ++v) body_program_for(v, false, 0);
    for (int v = 0; v < 2; ++v)
      sky_programs[v] =
          link_program(vertex_shader(shader_sources::fullscreen_vert),
                       fragment_shader(shader_sources::sky_frag, "",
                                       v == 1 ? "#define LIGHTCONE_SKY_IMAGE 1\n" : ""));
    glGenVertexArrays(1, &vertex_array);
    glGenBuffers(1, &vertex_buffer);
    glGenBuffers(1, &patch_buffer);
    glGenTextures(1, &rows_texture);
    glGenTextures(1, &offsets_texture);
    glGenTextures(1, &tables_texture);
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
    for (const auto& [image, name] : images) glDeleteTextures(1, &name);
    glDeleteTextures(1, &rows_texture);
    glDeleteTextures(1, &offsets_texture);
    glDeleteTextures(1, &tables_texture);
    glDeleteBuffers(1, &vertex_buffer);
    glDeleteVertexArrays(1, &vertex_array);
    for (const auto& [key, program] : body_program_cache) glDeleteProgram(program);
    glDeleteBuffers(1, &patch_buffer);
    for (GLuint program : sky_programs) glDeleteProgram(program);
    for (const auto& programs : hole_sky_programs)
      for (GLuint program : programs)
        if (program) glDeleteProgram(program);
  }

  void set_common(GLuint program, const ResolvedScene& scene, double first_log_doppler, double ox,
                  double oy) {
    set_camera_uniforms(program, scene.camera, ox, oy);
    glUniform1i(uniform(program, "colour_rows"), 0);
    glUniform1i(uniform(program, "sample_offsets"), 1);
    glUniform1i(uniform(program, "shade_at_sample_offsets"), shading_offsets ? 1 : 0);
    glUniform1f(uniform(program, "log_doppler_first"), static_cast<float>(first_log_doppler));
    glUniform1f(uniform(program, "log_doppler_step"), static_cast<float>(kLogDopplerStep));
    glUniform1f(uniform(program, "ray_time"), static_cast<float>(scene.ray_time));
    glUniform1i(uniform(program, "spectral"),
                scene.scene->render.doppler == DopplerModel::kSpectral ? 1 : 0);
    glUniform1iv(uniform(program, "primary_rows"), 3, final_rows.data());
    glUniform1i(uniform(program, "basis_first_row"), basis_first_row);
    const LinearRgb w = reference_white();
    glUniform3f(uniform(program, "reference_white"), static_cast<float>(w.r),
                static_cast<float>(w.g), static_cast<float>(w.b));
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
    bool lit = false;
    std::array<int, 2 * kRasterMaxLights> reflection_row{}, reflection_moving{};
    const RestMesh* mesh = nullptr;  // during prepare()
    double sphere_radius = 0;        // the GPU path's: its mesh's
  };
  struct LightDraw {
    int kind = 0, fixed_event = 0, row = 0;
    Vec4 event;  // relative to the observation event
    Vec3 position, velocity, axis;
    double time = 0, intensity = 0, radius = 0, half_cone = 0, falloff = 0;
  };
  const ResolvedScene* scene = nullptr;
  std::vector<BodyDraw> draws;
  std::vector<HoleBodiesPass::Body> hole_body_list;
  std::vector<LightDraw> lights;
  std::array<int, 3> final_rows{};
  int basis_first_row = 0;
  std::map<const Image*, GLuint> images;  // textures and sky images, uploaded once
  double first_log_doppler = 0;
  int sky_first_row = 0;
  double table_camera_first = 0, table_light_first = 0;
  int table_light_nodes = 2;

  // A texture or sky image as a float texture (once per image), with mip levels for the sky's
  // filtered lookups (exact lookups read level 0 texel by texel, whatever the filter).
  GLuint upload(const Image& image) {
    auto [it, added] = images.emplace(&image, 0);
    if (added) {
      glGenTextures(1, &it->second);
      glBindTexture(GL_TEXTURE_2D, it->second);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, image.width, image.height, 0, GL_RGB, GL_FLOAT,
                   image.rgb.data());
      glGenerateMipmap(GL_TEXTURE_2D);
      check_gl("uploading an image");
    }
    return it->second;
  }

  // Tessellates every body and tabulates the colour rows for one frame.
  RasterFrameStats prepare(const ResolvedScene& resolved, const EmissionTable& emission,
                           const TessellationLimits& limits, bool on_gpu) {
    scene = &resolved;
    // Spinning bodies' points each turn on their own world-line, which only the CPU path solves.
    gpu_tessellation = on_gpu && driver.tessellation_shaders && resolved.spins.empty();
    tessellation_limits = limits;
    const Scene& s = *resolved.scene;
    const RenderSettings& settings = s.render;
    const Lighting lighting(resolved, nullptr);
    const bool spectral = settings.doppler == DopplerModel::kSpectral;
    // Rows: each a colour against D, tabulated over the frame's range of ln D.
    std::vector<std::function<LinearRgb(double)>> rows;
    const auto add_row = [&](std::function<LinearRgb(double)> f) {
      rows.push_back(std::move(f));
      return static_cast<int>(rows.size() - 1);
    };
    std::map<EmissionKey, int> row_of;
    const auto emission_row = [&](const PointEmission& e) {
      const auto [it, added] = row_of.emplace(key_of(e), static_cast<int>(rows.size()));
      if (added) add_row([&e, &settings](double d) { return received_colour(e, d, settings); });
      return it->second;
    };
    static const PointEmission kBlack{};

    // The lights, relative to the observation event in W.
    const Vec4& observation = resolved.observation_event;
    lights.clear();
    RenderSettings unshifted = settings;  // the light's colour shift alone
    unshifted.searchlight = SearchlightModel::kOff;
    for (std::size_t l = 0; l < s.lights.size() && l < kRasterMaxLights; ++l) {
      const Light& light = s.lights[l];
      LightDraw d;
      d.velocity = settings.relativity ? light.world_line.velocity : Vec3{};
      d.position = light.world_line.position - observation.x;
      d.time = light.world_line.time - observation.t;
      d.intensity = light.intensity;
      if (const auto* spot = std::get_if<SpotLight>(&light.kind)) {
        d.kind = 1;
        d.axis = normalize(spot->direction);
        d.half_cone = spot->cone_degrees / 2;
        d.falloff = spot->falloff_degrees;
      } else if (const auto* sun = std::get_if<DirectionalLight>(&light.kind)) {
        d.kind = 2;
        d.axis = normalize(sun->direction);
        d.intensity = sun->irradiance;
      } else if (const auto* sphere = std::get_if<SphereLight>(&light.kind)) {
        d.kind = 3;
        d.radius = sphere->radius;
      }
      // The emission event, where it does not depend on the lit point (Lighting's own).
      if (const auto& fixed = lighting.fixed_emission_event(l)) {
        d.fixed_event = 1;
        d.event = *fixed - observation;
      }
      if (spectral) {
        d.row = add_row(
            [&lighting, l](double x) { return linear_srgb_from_xyz(lighting.light_seen(l, x)); });
      } else {
        const LinearRgb rgb = lighting.light_rgb(l);
        d.row = add_row([rgb, &unshifted](double x) {
          return received_colour(PointEmission{rgb}, x, unshifted);
        });
      }
      lights.push_back(d);
    }
    // The colour models other than spectral: the received colour of outgoing radiance.
    for (int c = 0; c < 3; ++c) {
      const LinearRgb unit{c == 0 ? 1.0 : 0.0, c == 1 ? 1.0 : 0.0, c == 2 ? 1.0 : 0.0};
      final_rows[c] = add_row([unit, &settings](double x) {
        return received_colour(PointEmission{unit}, x, settings);
      });
    }

    // Textures and sky images, spectral model: the RGB white's and the emitter nodes' rows,
    // which received_rgb (common.glsl) combines per sample.
    const bool per_sample_colours =
        std::holds_alternative<SkyImage>(s.sky.pattern) ||
        std::any_of(s.objects.begin(), s.objects.end(), [](const Object& o) {
          return o.material.unlit && std::holds_alternative<Texture>(o.material.pattern);
        });
    basis_first_row = 0;
    if (spectral && per_sample_colours) {
      const auto basis_row = [&](const DopplerXyzTable& table) {
        PointEmission e;
        e.rest_rgb = linear_srgb_from_xyz(table.at_rest());
        e.tables[0] = &table;
        e.weights[0] = 1;
        e.table_count = 1;
        return add_row([e, &settings](double d) { return received_colour(e, d, settings); });
      };
      basis_first_row = basis_row(emission.white_table());
      for (int c = 0; c < kRgbEmitterCases; ++c)
        for (int n = 0; n < kRgbToSpectrumRes; ++n) basis_row(emission.emitter_node_table(c, n));
    }

    // Lit bodies' reflection rows (co-moving lights) and tables (moving lights).
    const LogDopplerRange unlit = visible_log_doppler(resolved, false);
    const LogDopplerRange lit_range = visible_log_doppler(resolved, true);
    const double reach = lighting.light_rapidity();
    table_camera_first = (lit_range.empty ? 0.0 : lit_range.lo) - 2 * kTableCameraStep;
    const double table_camera_last = (lit_range.empty ? 0.0 : lit_range.hi) + 2 * kTableCameraStep;
    const int table_camera_nodes = std::max(
        2,
        static_cast<int>(std::ceil((table_camera_last - table_camera_first) / kTableCameraStep)) +
            1);
    table_light_first = -reach - 2 * kTableLightStep;
    table_light_nodes = std::max(
        2, static_cast<int>(std::ceil(2 * (reach + 2 * kTableLightStep) / kTableLightStep)) + 1);
    std::vector<float> table_texels;
    int table_rows = 0;
    struct ReflectionKey {
      float r, g, b;
      std::size_t light;
      bool operator<(const ReflectionKey& o) const {
        return std::tie(r, g, b, light) < std::tie(o.r, o.g, o.b, o.light);
      }
    };
    std::map<ReflectionKey, int> reflection_rows, reflection_tables;

    draws.clear();
    frame_features = 0;
    hole_body_list.clear();
    std::map<const void*, RestMesh> meshes;  // per shape, for this frame
    for (std::size_t i = 0; i < resolved.bodies.size(); ++i) {
      const ResolvedBody& body = resolved.bodies[i];
      // Bodies out of view need neither rows nor triangles (near a black hole their images can
      // be anywhere).
      if (!resolved.hole && !may_be_in_view(resolved.camera, body.trace_bounds)) continue;
      BodyDraw draw;
      draw.body = i;
      const Material& m = body.object->material;
      Rgb colours[2];
      const bool two_colours = pattern_colours(m, colours) == 2;
      const bool textured = std::holds_alternative<Texture>(m.pattern);
      draw.pattern = std::holds_alternative<Checker>(m.pattern) ? 1
                     : std::holds_alternative<Blink>(m.pattern) ? 3
                     : std::holds_alternative<Clock>(m.pattern) ? 4
                                                                : 0;
      if (draw.pattern >= 3) frame_features |= kBodyTimedPattern;
      if (body.spin >= 0) frame_features |= kBodySpin;
      if (textured) {
        draw.first_row = emission_row(kBlack);
        const bool drawable = m.unlit && !std::holds_alternative<MeshShape>(body.object->shape) &&
                              settings.doppler != DopplerModel::kHue;
        draw.pattern = drawable ? 2 : 0;
        if (drawable) upload(*std::get<Texture>(m.pattern).image);
      } else if (m.unlit) {
        if (two_colours) {
          // A checker's (blink's, clock's) two colours take consecutive rows of their own.
          const PointEmission& a = emission.object_colour(i, 0);
          const PointEmission& b = emission.object_colour(i, 1);
          draw.first_row =
              add_row([&a, &settings](double d) { return received_colour(a, d, settings); });
          add_row([&b, &settings](double d) { return received_colour(b, d, settings); });
        } else {
          draw.first_row = emission_row(emission.object_colour(i, 0));
        }
      } else {
        draw.lit = true;
        const std::size_t object = static_cast<std::size_t>(body.object - s.objects.data());
        // (Near a black hole lit bodies are coloured per vertex: raster/hole_bodies.hpp.)
        for (int k = 0; k < (two_colours ? 2 : 1) && spectral && !resolved.hole; ++k) {
          const Rgb albedo = colours[k];
          for (std::size_t l = 0; l < lights.size(); ++l) {
            const ReflectionKey key{albedo.r, albedo.g, albedo.b, l};
            const std::size_t slot = kRasterMaxLights * static_cast<std::size_t>(k) + l;
            if (lighting.co_moving(object, l)) {
              auto [it, added] = reflection_rows.emplace(key, 0);
              if (added)
                it->second = add_row([&lighting, object, k, l](double d) {
                  return linear_srgb_from_xyz(lighting.reflected(object, k, l, d, 1.0));
                });
              draw.reflection_row[slot] = it->second;
            } else {
              auto [it, added] = reflection_tables.emplace(key, table_rows);
              if (added) {
                for (int jl = 0; jl < table_light_nodes; ++jl, ++table_rows)
                  for (int jc = 0; jc < table_camera_nodes; ++jc) {
                    const LinearRgb c = linear_srgb_from_xyz(lighting.reflected(
                        object, k, l, std::exp(table_camera_first + jc * kTableCameraStep),
                        std::exp(table_light_first + jl * kTableLightStep)));
                    table_texels.insert(table_texels.end(),
                                        {static_cast<float>(c.r), static_cast<float>(c.g),
                                         static_cast<float>(c.b)});
                  }
              }
              draw.reflection_row[slot] = it->second;
              draw.reflection_moving[slot] = 1;
            }
          }
        }
      }
      const Shape& shape = body.object->shape;
      const void* shape_key = std::visit([](const auto& x) -> const void* { return &x; }, shape);
      auto it = meshes.find(shape_key);
      if (it == meshes.end())
        it = meshes.emplace(shape_key, rest_mesh(shape, gpu_tessellation && !resolved.hole ? 8 : 2))
                 .first;
      draw.mesh = &it->second;
      if (resolved.hole)
        hole_body_list.push_back({i, draw.mesh, draw.first_row, draw.pattern, draw.lit});
      else
        draws.push_back(draw);
    }
    RasterFrameStats stats;
    if (resolved.hole && !hole_body_list.empty()) {
      if (!hole_bodies)
        hole_bodies = std::make_unique<HoleBodiesPass>(link_program(
            vertex_shader(shader_sources::hole_body_vert),
            fragment_shader(shader_sources::hole_body_frag, shader_sources::patterns_glsl)));
      stats.triangles += hole_bodies->prepare(resolved, hole_body_list, emission, lighting, limits);
    }
    if (gpu_tessellation) {
      // Each shape's untessellated triangles, once; the tessellation shaders cut them per body.
      std::map<const RestMesh*, std::pair<std::size_t, std::size_t>> ranges;
      std::vector<float> patches;
      for (BodyDraw& draw : draws) {
        auto [it, added] = ranges.emplace(draw.mesh, std::pair<std::size_t, std::size_t>{});
        if (added) {
          const std::size_t first = patches.size() / kFloatsPerVertex;
          TessellationLimits none;
          none.max_level = 0;
          tessellate(resolved, body_view(resolved, resolved.bodies[draw.body]), *draw.mesh, none,
                     patches);
          it->second = {first, patches.size() / kFloatsPerVertex - first};
        }
        draw.first_vertex = it->second.first;
        draw.vertex_count = it->second.second;
        draw.sphere_radius = draw.mesh->sphere_radius;
        stats.triangles += draw.vertex_count / 3;
      }
      glBindBuffer(GL_ARRAY_BUFFER, patch_buffer);
      glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(patches.size() * sizeof(float)),
                   patches.data(), GL_STATIC_DRAW);
    } else {
      // The bodies are tessellated in parallel, each into its own buffer, then laid end to end.
      std::vector<std::vector<float>> parts(draws.size());
      tbb::parallel_for(std::size_t{0}, draws.size(), [&](std::size_t d) {
        tessellate(resolved, body_view(resolved, resolved.bodies[draws[d].body]), *draws[d].mesh,
                   limits, parts[d]);
      });
      std::size_t total = 0;
      for (std::size_t d = 0; d < draws.size(); ++d) {
        draws[d].first_vertex = total;
        draws[d].vertex_count = parts[d].size() / kFloatsPerVertex;
        total += draws[d].vertex_count;
      }
      glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer);
      glBufferData(GL_ARRAY_BUFFER,
                   static_cast<GLsizeiptr>(total * kFloatsPerVertex * sizeof(float)), nullptr,
                   GL_STATIC_DRAW);
      for (std::size_t d = 0; d < draws.size(); ++d)
        if (!parts[d].empty())
          glBufferSubData(
              GL_ARRAY_BUFFER,
              static_cast<GLintptr>(draws[d].first_vertex * kFloatsPerVertex * sizeof(float)),
              static_cast<GLsizeiptr>(parts[d].size() * sizeof(float)), parts[d].data());
      stats.triangles += total / 3;
    }
    const bool grid = std::holds_alternative<SkyGrid>(s.sky.pattern);
    const bool sky_image = std::holds_alternative<SkyImage>(s.sky.pattern);
    if (sky_image) upload(*std::get<SkyImage>(s.sky.pattern).image);
    const PointEmission& sky0 = sky_image ? kBlack : emission.sky_colour(0);
    const PointEmission& sky1 = grid ? emission.sky_colour(1) : sky0;
    sky_first_row =
        add_row([&sky0, &settings](double d) { return received_colour(sky0, d, settings); });
    add_row([&sky1, &settings](double d) { return received_colour(sky1, d, settings); });

    // Near a black hole: the frame's rays, and the disk's row against ln s.
    std::optional<LogRange> disk_range;
    if (resolved.hole) {
      if (!black_hole) black_hole = std::make_unique<BlackHolePass>();
      GLuint& program = hole_sky_programs[sky_variant(s)][spectral ? 1 : 0];
      if (!program) {
        const std::string defines = std::string("#define LIGHTCONE_BLACK_HOLE 1\n") +
                                    (sky_variant(s) == 1 ? "#define LIGHTCONE_SKY_IMAGE 1\n" : "") +
                                    (spectral ? "#define LIGHTCONE_SPECTRAL_DISK 1\n" : "");
        program = link_program(vertex_shader(shader_sources::fullscreen_vert),
                               fragment_shader(shader_sources::sky_frag,
                                               shader_sources::black_hole_glsl, defines.c_str()));
      }
      black_hole->prepare(*resolved.hole);
      if (resolved.hole->disk) {
        const ThermalEmission& disk = emission.disk();
        disk_row = add_row([&disk](double s) { return disk_row_colour(disk, s); });
        disk_range = disk_row_range(*resolved.hole, disk);
        disk_floor = disk.floor;
      }
    }

    // The rows' nodes cover every factor a fragment can ask for: the camera's of emitters, the
    // sky and lit bodies, the lights' on their legs, and the glossy lobe's product of both.
    double lo = std::min(unlit.lo, lit_range.empty ? unlit.lo : lit_range.lo);
    double hi = std::max(unlit.hi, lit_range.empty ? unlit.hi : lit_range.hi);
    if (!lights.empty()) {
      lo = std::min(lo - reach, -reach);
      hi = std::max(hi + reach, reach);
    }
    if (disk_range) {
      lo = std::min(lo, disk_range->lo);
      hi = std::max(hi, disk_range->hi);
    }
    lo -= 2 * kLogDopplerStep;
    hi += 2 * kLogDopplerStep;
    first_log_doppler = lo;
    const int nodes = std::max(2, static_cast<int>(std::ceil((hi - lo) / kLogDopplerStep)) + 1);
    std::vector<float> texels(static_cast<std::size_t>(nodes) * rows.size() * 3);
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int k = 0; k < nodes; ++k) {
        const LinearRgb c = rows[r](std::exp(lo + k * kLogDopplerStep));
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
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, tables_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (table_rows == 0) table_texels.assign(3 * 2 * table_camera_nodes, 0.0f);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, table_camera_nodes, std::max(table_rows, 2), 0,
                 GL_RGB, GL_FLOAT, table_texels.data());

    if (resolved.scene->sky.stars && !stars) stars = std::make_unique<StarPass>();
    if (stars) stars->prepare(resolved);
    check_gl("uploading the frame");
    return stats;
  }

  const std::vector<float>* shading_offsets = nullptr;
  TessellationLimits tessellation_limits;

  // The lights and what lit bodies share (lighting.glsl's uniforms).
  void set_lights(const ResolvedScene& resolved) {
    const GLuint p = body_program;
    const RenderSettings& settings = resolved.scene->render;
    const int n = static_cast<int>(lights.size());
    glUniform1i(uniform(p, "light_count"), n);
    for (int l = 0; l < n; ++l) {
      const LightDraw& d = lights[static_cast<std::size_t>(l)];
      const auto name = [l](const char* field) { return fmt::format("{}[{}]", field, l); };
      glUniform1i(uniform(p, name("light_kind").c_str()), d.kind);
      glUniform1i(uniform(p, name("light_fixed_event").c_str()), d.fixed_event);
      glUniform4f(uniform(p, name("light_event").c_str()), static_cast<float>(d.event.t),
                  static_cast<float>(d.event.x.x), static_cast<float>(d.event.x.y),
                  static_cast<float>(d.event.x.z));
      set_vec3(p, name("light_position").c_str(), d.position);
      glUniform1f(uniform(p, name("light_time").c_str()), static_cast<float>(d.time));
      set_vec3(p, name("light_velocity").c_str(), d.velocity);
      glUniform1f(uniform(p, name("light_one_minus_beta2").c_str()),
                  static_cast<float>(1.0 - dot(d.velocity, d.velocity)));
      glUniform1f(uniform(p, name("light_intensity").c_str()), static_cast<float>(d.intensity));
      set_vec3(p, name("light_axis").c_str(), d.axis);
      glUniform2f(uniform(p, name("light_cone").c_str()), static_cast<float>(d.half_cone),
                  static_cast<float>(d.falloff));
      glUniform1f(uniform(p, name("light_radius").c_str()), static_cast<float>(d.radius));
      glUniform1i(uniform(p, name("light_row").c_str()), d.row);
    }
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

  // A body's own lighting uniforms.
  void set_lit_body(const ResolvedScene& resolved, const BodyDraw& draw) {
    const GLuint p = body_program;
    const Object& object = *resolved.bodies[draw.body].object;
    const Material& m = object.material;
    Rgb albedo[2];
    if (pattern_colours(m, albedo) == 1) albedo[1] = albedo[0];
    const float albedos[6] = {albedo[0].r, albedo[0].g, albedo[0].b,
                              albedo[1].r, albedo[1].g, albedo[1].b};
    glUniform3fv(uniform(p, "albedo"), 2, albedos);
    const Vec3 inverse_scale{1 / object.scale.x, 1 / object.scale.y, 1 / object.scale.z};
    set_mat3(p, "normal_to_rest", object.rotation * Mat3::diagonal(inverse_scale));
    glUniform1i(uniform(p, "relativity"), resolved.scene->render.relativity ? 1 : 0);
    set_vec3(p, "surface_velocity_of_body",
             resolved.scene->render.relativity ? object.world_line.velocity : Vec3{});
    glUniform1f(uniform(p, "diffuse"),
                m.glossy ? static_cast<float>(1 - m.glossy->specular) : 1.0f);
    glUniform1i(uniform(p, "glossy"), m.glossy ? 1 : 0);
    glUniform1f(uniform(p, "glossy_roughness"),
                m.glossy ? static_cast<float>(m.glossy->roughness) : 1.0f);
    glUniform1f(uniform(p, "glossy_specular"),
                m.glossy ? static_cast<float>(m.glossy->specular) : 0.0f);
    glUniform1iv(uniform(p, "reflection_row"), 2 * kRasterMaxLights, draw.reflection_row.data());
    glUniform1iv(uniform(p, "reflection_moving"), 2 * kRasterMaxLights,
                 draw.reflection_moving.data());
  }

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
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, resolved.camera.width, resolved.camera.height, 0,
                   GL_RGBA, GL_FLOAT, offsets->data());
    }
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, rows_texture);

    glDepthFunc(GL_LESS);
    glBindVertexArray(vertex_array);
    glBindBuffer(GL_ARRAY_BUFFER, gpu_tessellation ? patch_buffer : vertex_buffer);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, kFloatsPerVertex * sizeof(float), nullptr);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, kFloatsPerVertex * sizeof(float),
                          reinterpret_cast<const void*>(3 * sizeof(float)));
    if (gpu_tessellation) glPatchParameteri(GL_PATCH_VERTICES, 3);
    for (const Variant variant : {kEmitter, kTextured, kLit}) {
      body_program = body_program_for(
          variant, gpu_tessellation,
          specialise ? frame_features | (offsets ? kBodySampleOffsets : 0) : kAllBodyFeatures);
      glUseProgram(body_program);
      set_common(body_program, resolved, first_log_doppler, ox, oy);
      // Depth: the light travel distance on a log scale between these.
      glUniform2f(uniform(body_program, "depth_range"), std::log(kDepthNear), std::log(kDepthFar));
      if (variant == kLit) set_lights(resolved);
      for (const BodyDraw& draw : draws) {
        if (draw.lit != (variant == kLit) || (draw.pattern == 2) != (variant == kTextured))
          continue;
        const ResolvedBody& body = resolved.bodies[draw.body];
        const BodyView view = body_view(resolved, body);
        set_mat3(body_program, "shape_to_trace", view.shape_to_trace);
        set_vec3(body_program, "shape_origin", view.shape_origin);
        set_vec3(body_program, "world_line_velocity", view.velocity);
        glUniform1f(uniform(body_program, "one_minus_beta2"),
                    static_cast<float>(1.0 - dot(view.velocity, view.velocity)));
        set_vec3(body_program, "ray_offset", body.ray_offset);
        set_mat3(body_program, "shape_spatial", body.spatial);
        set_doppler(body_program, resolved, body.velocity);
        glUniform1i(uniform(body_program, "colour_row"), draw.first_row);
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
          const Vec3& k = body.object->scale;
          glUniform1i(uniform(body_program, "spin_round"),
                      std::holds_alternative<Sphere>(shape) && k.x == k.y && k.y == k.z ? 1 : 0);
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
        if (variant == kLit) set_lit_body(resolved, draw);
        if (gpu_tessellation) {
          glUniform1f(uniform(body_program, "sphere_radius_for_tessellation"),
                      static_cast<float>(draw.sphere_radius));
          glUniform1f(uniform(body_program, "max_error_pixels"),
                      static_cast<float>(tessellation_limits.max_error_pixels));
          // The GPU's levels go to 64 (every OpenGL 4 implementation's least maximum).
          glUniform1f(uniform(body_program, "max_level"),
                      static_cast<float>(1 << std::clamp(tessellation_limits.max_level, 0, 6)));
        }
        glDrawArrays(gpu_tessellation ? GL_PATCHES : GL_TRIANGLES,
                     static_cast<GLint>(draw.first_vertex),
                     static_cast<GLsizei>(draw.vertex_count));
      }
    }
    if (resolved.hole && !hole_body_list.empty()) {
      glUseProgram(hole_bodies->program());
      set_common(hole_bodies->program(), resolved, first_log_doppler, ox, oy);
      hole_bodies->draw(resolved);
    }
    check_gl("drawing the bodies");

    const GLuint sky_program =
        resolved.hole
            ? hole_sky_programs[sky_variant(s)][s.render.doppler == DopplerModel::kSpectral ? 1 : 0]
            : sky_programs[sky_variant(s)];
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
    const bool draw_image = sky_image && s.render.doppler != DopplerModel::kHue;
    glUniform1i(uniform(sky_program, "pattern"), g ? 1 : draw_image ? 2 : 0);
    glUniform1i(uniform(sky_program, "sky_image"), 4);
    if (draw_image) {
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
};

RasterRenderer::TessellatedBodies RasterRenderer::tessellated_bodies() const {
  TessellatedBodies out{impl_->vertex_array, impl_->vertex_buffer, kFloatsPerVertex, {}};
  if (!impl_->gpu_tessellation)
    for (const Impl::BodyDraw& d : impl_->draws)
      out.draws.push_back({d.body, d.first_vertex, d.vertex_count});
  return out;
}

RasterRenderer::RasterRenderer() : impl_(std::make_unique<Impl>()) {}
RasterRenderer::~RasterRenderer() = default;

RasterFrameStats RasterRenderer::prepare(const ResolvedScene& scene, const EmissionTable& emission,
                                         const TessellationLimits& limits, bool on_gpu) {
  return impl_->prepare(scene, emission, limits, on_gpu);
}

void RasterRenderer::set_specialised_programs(bool specialise) {
  impl_->specialise = specialise;
}

const GlDriver& RasterRenderer::driver() const {
  return impl_->driver;
}

void RasterRenderer::pass(double pixel_offset_x, double pixel_offset_y,
                          const std::vector<float>* shading_offsets) {
  impl_->pass(pixel_offset_x, pixel_offset_y, shading_offsets);
}

}  // namespace lightcone

// One frame's preparation for the raster renderer: the colour rows every body, the sky and the
// lights read, each body's tessellation, and the tables lit surfaces read.

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>

#include "lightcone/color/sigmoid_polynomial.hpp"
#include "lightcone/frame/body_segments.hpp"
#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/frame/lighting.hpp"
#include "lightcone/frame/received_colour.hpp"
#include "lightcone/frame/shading.hpp"
#include "lightcone/portable.hpp"
#include "lightcone/raster/body_patterns.hpp"
#include "lightcone/raster/raster_renderer_impl.hpp"
#include "lightcone/raster/shader_build.hpp"
#include "lightcone/raster/shader_sources.hpp"
#include "lightcone/raster/spectral_albedo.hpp"

namespace lightcone {

namespace {

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

// The factors (ln D) at which a row's tables answer: a row is read only at its own source's
// factors, which its tables were built to cover, while the rows span every source's. Its
// texels past them, which nothing reads, hold its nearest answered colour.
constexpr LogRange kEveryFactor{-std::numeric_limits<double>::infinity(),
                                std::numeric_limits<double>::infinity()};
LogRange answered(const DopplerGrid& grid) {
  return {grid.lowest_log_d(), grid.highest_log_d()};
}
LogRange answered(const PointEmission& e) {
  return e.table_count > 0 ? answered(e.tables[0]->grid()) : kEveryFactor;
}
double held(double log_d, const LogRange& domain) {
  return std::exp(std::clamp(log_d, domain.lo, domain.hi));
}

}  // namespace

const RestMesh& RasterRenderer::Impl::rest_mesh_for(const Shape& shape, int face_grid) {
  const MeshShape* mesh = std::get_if<MeshShape>(&shape);
  const std::array<double, 3> sizes = std::visit(
      [](const auto& s) -> std::array<double, 3> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Sphere>) return {s.radius, 0, 0};
        if constexpr (std::is_same_v<T, Box>) return {s.size.x, s.size.y, s.size.z};
        if constexpr (std::is_same_v<T, Plane>) return {s.size_x, s.size_z, 0};
        return {};
      },
      shape);
  const RestMeshKey key{shape.index(), sizes, mesh ? mesh->mesh.get() : nullptr, face_grid};
  auto it = rest_meshes.find(key);
  if (it == rest_meshes.end())
    it = rest_meshes
             .emplace(key, KeptRestMesh{mesh ? mesh->mesh : nullptr, rest_mesh(shape, face_grid)})
             .first;
  it->second.used = true;
  return it->second.mesh;
}

RasterFrameStats RasterRenderer::Impl::prepare(const ResolvedScene& resolved,
                                               const EmissionTable& emission,
                                               const TessellationLimits& limits, bool on_gpu) {
  scene = &resolved;
  // Spinning bodies' points each turn on their own world-line, which only the CPU path solves.
  gpu_tessellation = on_gpu && driver.tessellation_shaders && resolved.spins.empty();
  tessellation_limits = limits;
  const Scene& s = *resolved.scene;
  const RenderSettings& settings = s.render;
  // The lights' tables, kept from frame to frame while they serve (a viewer's frames differ in
  // the camera alone); built 0.25 of ln D wider than a frame needs, as the emission tables are.
  // (Near a black hole they are made anew for each frame, with their shadows' query.)
  const bool lighting_kept = kept_lighting && kept_lighting->serves(resolved);
  if (lighting_kept) {
    kept_lighting->follow(resolved);
  } else {
    std::unique_ptr<CurvedShadowQuery> frame_shadows;
    if (resolved.hole && settings.shadows && !s.lights.empty())
      frame_shadows = curved_shadow_source
                          ? curved_shadow_source(resolved)
                          : curved_body_shadows_met_by(
                                resolved, std::make_unique<DirectBodySegments>(resolved));
    kept_lighting = std::make_unique<Lighting>(resolved, nullptr, frame_shadows.get(),
                                               EmissionTable::kKeptMargin);
    curved_shadows = std::move(frame_shadows);
  }
  const Lighting& lighting = *kept_lighting;
  const bool spectral = settings.doppler == DopplerModel::kSpectral;
  // Rows: each a colour against D, tabulated over the frame's range of ln D (unless the rows
  // kept from the frame before serve), and what each is tabulated from.
  std::vector<std::function<LinearRgb(double)>> rows;
  std::vector<LogRange> row_domains;
  std::vector<RowSource> row_sources;
  const auto add_row = [&](RowSource source, std::function<LinearRgb(double)> f,
                           const LogRange& domain) {
    rows.push_back(std::move(f));
    row_domains.push_back(domain);
    row_sources.push_back(source);
    return static_cast<int>(rows.size() - 1);
  };
  const auto received_row = [&](const PointEmission& e) {
    return add_row(
        {RowSource::kEmission, &e},
        [&e, &settings](double d) { return received_colour(e, d, settings); }, answered(e));
  };
  std::map<EmissionKey, int> row_of;
  const auto emission_row = [&](const PointEmission& e) {
    const auto [it, added] = row_of.emplace(key_of(e), static_cast<int>(rows.size()));
    if (added) received_row(e);
    return it->second;
  };
  static const PointEmission kBlack{};

  // The lights, relative to the observation event in W.
  const Vec4& observation = resolved.observation_event;
  lights.clear();
  RenderSettings unshifted = settings;  // the light's colour shift alone
  unshifted.searchlight = SearchlightModel::kOff;
  for (std::size_t l = 0; l < s.lights.size(); ++l) {
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
          {RowSource::kLightSeen, nullptr, 0, l},
          [&lighting, l](double x) { return linear_srgb_from_xyz(lighting.light_seen(l, x)); },
          answered(lighting.light_seen_grid(l)));
    } else {
      const LinearRgb rgb = lighting.light_rgb(l);
      d.row = add_row(
          {RowSource::kLightRgb, nullptr, 0, l},
          [rgb, &unshifted](double x) { return received_colour(PointEmission{rgb}, x, unshifted); },
          kEveryFactor);
    }
    lights.push_back(d);
  }
  // The colour models other than spectral: the received colour of outgoing radiance.
  for (int c = 0; c < 3; ++c) {
    const LinearRgb unit{c == 0 ? 1.0 : 0.0, c == 1 ? 1.0 : 0.0, c == 2 ? 1.0 : 0.0};
    final_rows[c] = add_row(
        {RowSource::kPrimary, nullptr, 0, 0, c},
        [unit, &settings](double x) { return received_colour(PointEmission{unit}, x, settings); },
        kEveryFactor);
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
      return add_row(
          {RowSource::kBasis, &table},
          [e, &settings](double d) { return received_colour(e, d, settings); }, answered(e));
    };
    basis_first_row = basis_row(emission.white_table());
    for (int c = 0; c < kRgbEmitterCases; ++c)
      for (int n = 0; n < kRgbToSpectrumRes; ++n) basis_row(emission.emitter_node_table(c, n));
  }

  // Lit bodies' reflection rows (co-moving lights) and tables (moving lights).
  // Near a black hole lit bodies are coloured per vertex on the CPU (raster/hole_bodies.hpp): no
  // row or table is read at their factors or their lights'.
  const LogDopplerRange lit_range =
      resolved.hole ? LogDopplerRange{} : visible_log_doppler(resolved, true);
  const double reach = resolved.hole ? 0.0 : lighting.light_rapidity();
  table_camera_first = (lit_range.empty ? 0.0 : lit_range.lo) - 2 * kTableCameraStep;
  const double table_camera_last = (lit_range.empty ? 0.0 : lit_range.hi) + 2 * kTableCameraStep;
  const int table_camera_nodes = std::max(
      2,
      static_cast<int>(std::ceil((table_camera_last - table_camera_first) / kTableCameraStep)) + 1);
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
  // Two floats (row, moving) per fixed colour and light, a row per lit body.
  std::vector<float> reflection_index;
  // Per lit body: (row, moving) for each fixed colour and light, then its finish (roughness, -1
  // for matte; specular), which the lighting pass reads there (lit_surfaces.frag).
  const std::size_t reflection_row_floats = 4 * std::max<std::size_t>(lights.size(), 1) + 2;
  frame_features = settings.doppler == DopplerModel::kHue ? kBodyHueModel : 0;
  lighting_features = (lights.size() > kUniformLamps ? kLightingManyLights : 0) |
                      (spectral ? kLightingSpectralModel : kLightingOtherModels);
  for (const LightDraw& d : lights)
    lighting_features |= (d.kind == 1   ? kLightingSpot
                          : d.kind == 2 ? kLightingSun
                          : d.kind == 3 ? kLightingSphere
                                        : 0) |
                         (d.velocity != Vec3{} ? kLightingMovingLights : 0);
  hole_body_list.clear();
  for (auto& [key, kept] : rest_meshes) kept.used = false;
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
    if (draw.pattern == 4 && std::holds_alternative<MeshShape>(body.object->shape) &&
        !resolved.hole) {  // (near a hole every vertex carries its face's coordinates)
      draw.face_uvs = true;
      frame_features |= kBodyMeshClocks;
    }
    if (body.spin >= 0) frame_features |= kBodySpin;
    const bool mesh = std::holds_alternative<MeshShape>(body.object->shape);
    // Lit textures: under the colour models linear in the albedo each texel is the albedo;
    // under the spectral model it is fitted to a reflectance per sample, as the tracer does
    // (spectral_albedo.hpp; the browser first fits the columns of the table its texels need).
    const bool lit_texture = textured && !m.unlit && !resolved.hole;
    if (lit_texture) {
      draw.pattern = 2;
      draw.face_uvs = mesh;
      upload(*std::get<Texture>(m.pattern).image);
      frame_features |= kBodyLitTextures | (spectral ? kBodySpectralTextures : 0);
    }
    if (textured && !lit_texture) {
      // An unlit texture, or near a black hole a lit one: its colours are then its vertices'
      // (raster/hole_bodies.hpp).
      draw.first_row = emission_row(kBlack);
      draw.pattern = 2;
      draw.face_uvs = m.unlit && mesh;
      draw.lit = !m.unlit;
      if (m.unlit) upload(*std::get<Texture>(m.pattern).image);
    } else if (m.unlit) {
      if (two_colours) {
        // A checker's (blink's, clock's) two colours take consecutive rows of their own.
        const PointEmission& a = emission.object_colour(i, 0);
        const PointEmission& b = emission.object_colour(i, 1);
        draw.first_row = received_row(a);
        received_row(b);
      } else {
        draw.first_row = emission_row(emission.object_colour(i, 0));
      }
    } else {
      draw.lit = true;
      const std::size_t object = static_cast<std::size_t>(body.object - s.objects.data());
      // Its row of reflection_index: (row, moving) for each fixed colour k and light l.
      const std::size_t index_row = reflection_index.size();
      draw.reflection_body = static_cast<int>(index_row / reflection_row_floats);
      reflection_index.resize(index_row + reflection_row_floats, 0.0f);
      const auto& glossy = body.object->material.glossy;
      reflection_index[index_row + reflection_row_floats - 2] =
          glossy ? static_cast<float>(glossy->roughness) : -1.0f;
      reflection_index[index_row + reflection_row_floats - 1] =
          glossy ? static_cast<float>(glossy->specular) : 0.0f;
      // (Near a black hole lit bodies are coloured per vertex: raster/hole_bodies.hpp. A lit
      // texture's colours are summed per sample: spectral_albedo.hpp.)
      for (int k = 0; k < (two_colours ? 2 : 1) && spectral && !resolved.hole && !textured; ++k) {
        const Rgb albedo = colours[k];
        for (std::size_t l = 0; l < lights.size(); ++l) {
          const ReflectionKey key{albedo.r, albedo.g, albedo.b, l};
          float* slot =
              &reflection_index[index_row + 2 * (static_cast<std::size_t>(k) * lights.size() + l)];
          if (lighting.co_moving(object, l)) {
            auto [it, added] = reflection_rows.emplace(key, 0);
            if (added)
              it->second = add_row(
                  {RowSource::kReflection, nullptr, object, l, k},
                  [&lighting, object, k, l](double d) {
                    return linear_srgb_from_xyz(lighting.reflected(object, k, l, d, 1.0));
                  },
                  answered(lighting.camera_grid()));
            slot[0] = static_cast<float>(it->second);
          } else {
            auto [it, added] = reflection_tables.emplace(key, table_rows);
            if (added) {
              for (int jl = 0; jl < table_light_nodes; ++jl, ++table_rows)
                for (int jc = 0; jc < table_camera_nodes; ++jc) {
                  const LinearRgb c = linear_srgb_from_xyz(
                      lighting.reflected(object, k, l,
                                         held(table_camera_first + jc * kTableCameraStep,
                                              answered(lighting.camera_grid())),
                                         held(table_light_first + jl * kTableLightStep,
                                              answered(lighting.light_grid()))));
                  table_texels.insert(table_texels.end(),
                                      {static_cast<float>(c.r), static_cast<float>(c.g),
                                       static_cast<float>(c.b), 0.0f});
                }
            }
            slot[0] = static_cast<float>(it->second);
            slot[1] = 1;
          }
        }
      }
    }
    draw.mesh = &rest_mesh_for(body.object->shape, gpu_tessellation && !resolved.hole ? 8 : 2);
    draw.hidden = hidden_faces(*draw.mesh, body);
    if (resolved.hole)
      hole_body_list.push_back(
          {i, draw.mesh, draw.first_row, draw.pattern, draw.lit,
           draw.pattern == 2 && m.unlit ? images.at(std::get<Texture>(m.pattern).image.get()) : 0});
    else
      draws.push_back(draw);
  }
  if (!reflection_tables.empty()) lighting_features |= kLightingMovingReflections;
  if (frame_features & kBodySpectralTextures) {
    if (!spectral_albedo) spectral_albedo = std::make_unique<SpectralAlbedo>();
    // Every product of the factors the reflection tables span; the lights' spectra are kept
    // with the lights' tables while they cover it.
    const double lowest = table_camera_first + table_light_first;
    const double highest =
        table_camera_last + table_light_first + (table_light_nodes - 1) * kTableLightStep;
    if (!lighting_kept || !spectral_albedo->covers(lowest, highest))
      spectral_albedo->prepare(lighting, lights.size(), lowest, highest);
    std::vector<const Image*> lit_images;
    for (const BodyDraw& d : draws)
      if (d.lit && d.pattern == 2)
        lit_images.push_back(
            std::get<Texture>(resolved.bodies[d.body].object->material.pattern).image.get());
    spectral_albedo->cover(lit_images);
  }
  glActiveTexture(GL_TEXTURE8);
  glBindTexture(GL_TEXTURE_2D, reflection_index_texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  if (reflection_index.empty()) reflection_index.assign(reflection_row_floats, 0.0f);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, static_cast<GLsizei>(reflection_row_floats / 2),
               static_cast<GLsizei>(reflection_index.size() / reflection_row_floats), 0, GL_RG,
               GL_FLOAT, reflection_index.data());
  glActiveTexture(GL_TEXTURE0);

  // Shadows of the lights on the lit bodies (not near a black hole: its bodies are lit per
  // vertex, raster/hole_bodies.hpp).
  any_lit = std::any_of(draws.begin(), draws.end(), [](const BodyDraw& d) { return d.lit; });
  for (const BodyDraw& d : draws) {
    if (!d.lit) continue;
    const ResolvedBody& body = resolved.bodies[d.body];
    if (body.object->material.glossy) lighting_features |= kLightingGlossy;
    if (body.spin >= 0 || lit_body_velocity(resolved, *body.object) != Vec3{})
      lighting_features |= kLightingMovingSurfaces;
  }
  if (settings.shadows && any_lit && !resolved.hole && !lights.empty()) {
    if (!shadow_maps) shadow_maps = std::make_unique<ShadowMaps>();
    shadow_maps->prepare(resolved, lights.size());
    if (!shadow_casters) shadow_casters = std::make_unique<ShadowCasters>();
    shadow_casters->prepare(resolved, lights.size());
    frame_features |= kBodyShadows | (shadow_casters->any_mesh() ? kBodyMeshShadows : 0) |
                      (shadow_casters->any_spinning() ? kBodySpinShadows : 0);
    if (shadow_casters->count() > 0) lighting_features |= kLightingExactShadows;
  }
  RasterFrameStats stats;
  if (resolved.hole && !hole_body_list.empty()) {
    if (!hole_bodies) hole_bodies = std::make_unique<HoleBodiesPass>();
    stats.triangles += hole_bodies->prepare(resolved, hole_body_list, emission, lighting, limits);
  }
  // Textured meshes' vertices come first, so that their texture coordinates' maps (a buffer of
  // their own: no other body pays for them) share their vertex indices.
  std::vector<std::size_t> order(draws.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_partition(order.begin(), order.end(),
                        [this](std::size_t d) { return draws[d].face_uvs; });
  std::vector<float> uv_maps;
  if (gpu_tessellation) {
    // Each shape's untessellated triangles, once; the tessellation shaders cut them per body.
    std::map<std::pair<const RestMesh*, bool>, std::pair<std::size_t, std::size_t>> ranges;
    std::vector<float> patches;
    for (const std::size_t d : order) {
      BodyDraw& draw = draws[d];
      auto [it, added] = ranges.emplace(std::pair{draw.mesh, draw.face_uvs},
                                        std::pair<std::size_t, std::size_t>{});
      if (added) {
        const std::size_t first = patches.size() / kFloatsPerVertex;
        rest_patches(*draw.mesh, patches, draw.face_uvs ? &uv_maps : nullptr);
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
    // (Their buffers are kept, so that a frame like the last allocates nothing.)
    auto& parts = tessellated_parts;
    auto& uv_parts = tessellated_uv_parts;
    for (auto* kept : {&parts, &uv_parts}) {
      kept->resize(draws.size());
      for (std::vector<float>& part : *kept) part.clear();
    }
    parallel_for(std::size_t{0}, draws.size(), [&](std::size_t d) {
      tessellate(resolved, body_view(resolved, resolved.bodies[draws[d].body]), *draws[d].mesh,
                 limits, parts[d], draws[d].face_uvs ? &uv_parts[d] : nullptr, draws[d].hidden);
    });
    std::size_t total = 0;
    for (const std::size_t d : order) {
      draws[d].first_vertex = total;
      draws[d].vertex_count = parts[d].size() / kFloatsPerVertex;
      total += draws[d].vertex_count;
      uv_maps.insert(uv_maps.end(), uv_parts[d].begin(), uv_parts[d].end());
    }
    glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer);
    const std::size_t bytes = total * kFloatsPerVertex * sizeof(float);
    if (bytes > vertex_buffer_bytes) {
      vertex_buffer_bytes = bytes + bytes / 4;  // room for the next frames' changes
      glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertex_buffer_bytes), nullptr,
                   GL_DYNAMIC_DRAW);
    }
    for (std::size_t d = 0; d < draws.size(); ++d)
      if (!parts[d].empty())
        glBufferSubData(
            GL_ARRAY_BUFFER,
            static_cast<GLintptr>(draws[d].first_vertex * kFloatsPerVertex * sizeof(float)),
            static_cast<GLsizeiptr>(parts[d].size() * sizeof(float)), parts[d].data());
    stats.triangles += total / 3;
  }
  if (!uv_maps.empty()) {
    glBindBuffer(GL_ARRAY_BUFFER, face_uv_buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(uv_maps.size() * sizeof(float)),
                 uv_maps.data(), GL_STATIC_DRAW);
  }
  const bool grid = std::holds_alternative<SkyGrid>(s.sky.pattern);
  const bool sky_image = std::holds_alternative<SkyImage>(s.sky.pattern);
  if (sky_image) upload(*std::get<SkyImage>(s.sky.pattern).image);
  const PointEmission& sky0 = sky_image ? kBlack : emission.sky_colour(0);
  const PointEmission& sky1 = grid ? emission.sky_colour(1) : sky0;
  sky_first_row = received_row(sky0);
  received_row(sky1);

  // Near a black hole: the frame's rays, and the disk's row against ln s.
  std::optional<LogRange> disk_range;
  if (resolved.hole) {
    if (!black_hole) black_hole = std::make_unique<BlackHolePass>();
    GLuint& program = hole_sky_programs[sky_variant(s)][colour_kind(settings)];
    if (!program) {
      const std::string defines =
          std::string("#define LIGHTCONE_BLACK_HOLE 1\n") +
          (sky_variant(s) == 1 ? "#define LIGHTCONE_SKY_IMAGE 1\n" : "") +
          (spectral ? "#define LIGHTCONE_SPECTRAL_DISK 1\n" : "") +
          (settings.doppler == DopplerModel::kHue ? "" : "#define LIGHTCONE_NO_HUE 1\n");
      program = link_program(vertex_shader(shader_sources::fullscreen_vert),
                             fragment_shader(shader_sources::sky_frag,
                                             shader_sources::black_hole_glsl, defines.c_str()));
    }
    black_hole->prepare(*resolved.hole);
    if (resolved.hole->disk) {
      const ThermalEmission& disk = emission.disk();
      disk_row = add_row(
          {RowSource::kDisk, &disk}, [&disk](double s) { return disk_row_colour(disk, s); },
          answered(disk.peak));
      disk_range = disk_row_range(*resolved.hole, disk);
      disk_floor = disk.floor;
    }
  }

  // The rows' nodes cover every factor a fragment can ask for: the camera's of emitters, the
  // sky and lit bodies, the lights' on their legs, and the glossy lobe's product of both.
  // Near a black hole the bodies' shifts are their vertices' (a fragment's ln g lies between its
  // triangle's): tighter than their world-lines' bounds, which on a fall reach the horizon, where
  // the shift has no bound.
  LogDopplerRange unlit;
  if (resolved.hole) {
    const LogShiftRange sky = sky_log_shift_range(*resolved.hole);
    unlit = {sky.lo, sky.hi, false};
    if (hole_bodies && !hole_body_list.empty()) {
      const std::optional<LogShiftRange> bodies = hole_bodies->log_shift_range();
      if (bodies) unlit = {std::min(unlit.lo, bodies->lo), std::max(unlit.hi, bodies->hi), false};
    }
  } else {
    unlit = visible_log_doppler(resolved, false);
  }
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
  // The rows kept from the frame before serve when they are the same rows, read from the same
  // tables and lights, over a range that covers this frame's. Else they are tabulated anew,
  // away from a black hole kKeptMargin wider on each side where a texture that wide may be
  // made (near one the tables change with every frame).
  const bool rows_kept =
      lighting_kept && !resolved.hole && kept_rows.emission_serial == emission.serial() &&
      kept_rows.doppler == settings.doppler && kept_rows.searchlight == settings.searchlight &&
      kept_rows.hue_loop == settings.hue_loop && kept_rows.sources == row_sources &&
      kept_rows.first <= lo && hi <= kept_rows.last;
  stats.rows_tabulated = !rows_kept;
  if (!rows_kept) {
    GLint widest = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &widest);
    const double margin = EmissionTable::kKeptMargin;
    if (!resolved.hole && (hi - lo + 2 * margin) / kLogDopplerStep + 2 <= widest) {
      lo -= margin;
      hi += margin;
    }
    const int nodes = std::max(2, static_cast<int>(std::ceil((hi - lo) / kLogDopplerStep)) + 1);
    // RGBA texels: llvmpipe fetches four aligned floats faster than three (a frame of
    // street-lit.json, which reads a row per lamp at each pixel, took some 4 % less).
    std::vector<float> texels(static_cast<std::size_t>(nodes) * rows.size() * 4);
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int k = 0; k < nodes; ++k) {
        const LinearRgb c = rows[r](held(lo + k * kLogDopplerStep, row_domains[r]));
        float* t = &texels[4 * (r * nodes + k)];
        t[0] = static_cast<float>(c.r);
        t[1] = static_cast<float>(c.g);
        t[2] = static_cast<float>(c.b);
      }
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, rows_texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, nodes, static_cast<GLsizei>(rows.size()), 0, GL_RGBA,
                 GL_FLOAT, texels.data());
    kept_rows = {resolved.hole ? 0 : emission.serial(),
                 settings.doppler,
                 settings.searchlight,
                 settings.hue_loop,
                 std::move(row_sources),
                 lo,
                 lo + (nodes - 1) * kLogDopplerStep};
  }
  first_log_doppler = kept_rows.first;
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, tables_texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  if (table_rows == 0) table_texels.assign(4 * 2 * table_camera_nodes, 0.0f);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, table_camera_nodes, std::max(table_rows, 2), 0,
               GL_RGBA, GL_FLOAT, table_texels.data());

  if (resolved.scene->sky.stars && !stars) stars = std::make_unique<StarPass>();
  if (stars) stars->prepare(resolved);
  check_gl("uploading the frame");
  std::erase_if(rest_meshes, [](const auto& entry) { return !entry.second.used; });
  return stats;
}

}  // namespace lightcone

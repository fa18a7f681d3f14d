// The raster renderer's state, private to src/lightcone/raster: raster_renderer.cpp builds its
// programs and draws the passes, raster_prepare.cpp prepares each frame (the colour rows, the
// tessellation, the lighting tables).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "lightcone/frame/lighting.hpp"
#include "lightcone/raster/black_hole_pass.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/hole_bodies.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/raster/shadow_casters.hpp"
#include "lightcone/raster/shadow_maps.hpp"
#include "lightcone/raster/spectral_albedo.hpp"
#include "lightcone/raster/star_pass.hpp"

namespace lightcone {

// Received colour rows: nodes in ln D over the factors the image shows, two spare nodes past
// each end; linear interpolation between nodes 1/512 of a unit of ln D apart is far below
// what 8 bits show.
constexpr double kLogDopplerStep = 1.0 / 512;
constexpr int kFloatsPerVertex = 7;  // apparent position, face plane (tessellate())
constexpr int kFloatsPerUvMap = 8;   // two rows of an affine map (triangle_uv_map)
// The lit surfaces' textures (body.frag's LIGHTCONE_LIT outputs, lit_surfaces.frag's samplers).
constexpr int kSurfaceTextures = 3;
// A moving light's reflection table: ln D_camera and ln D_light nodes, bilinear between them.
constexpr double kTableCameraStep = 1.0 / 128, kTableLightStep = 1.0 / 64;

// The sky program: 1 for a sky image, else 0 (one colour or a grid).
inline int sky_variant(const Scene& scene) {
  return std::holds_alternative<SkyImage>(scene.sky.pattern) ? 1 : 0;
}

// Which colour model's code a frame's sky and disk need: 0 rgb3 or off, 1 spectral, 2 hue.
inline int colour_kind(const RenderSettings& settings) {
  return settings.doppler == DopplerModel::kSpectral ? 1
         : settings.doppler == DopplerModel::kHue    ? 2
                                                     : 0;
}

// A lit body's velocity in W, as its surfaces give it to the lighting pass (0 for the classical
// picture; a spinning body's points add their own).
inline Vec3 lit_body_velocity(const ResolvedScene& scene, const Object& object) {
  return scene.scene->render.relativity ? object.world_line.velocity : Vec3{};
}

// rotation * diag(1 / scale): a body's normals from shape coordinates to W's axes (its rest
// frame's).
inline Mat3 normal_to_rest(const Object& object) {
  const Vec3 inverse_scale{1 / object.scale.x, 1 / object.scale.y, 1 / object.scale.z};
  return object.rotation * Mat3::diagonal(inverse_scale);
}

struct RasterRenderer::Impl {
  // One program per kind of material (kEmitter, kTextured, kLit) and of sky (plain or grid, and
  // image): small programs run faster than one with every branch. kSurfaceVariables draws every
  // body's surface for the output variables (surface_variables.cpp).
  enum Variant { kEmitter = 0, kTextured = 1, kLit = 2, kSurfaceVariables = 3 };
  // And one per path (CPU or GPU tessellation) and set of features its frame uses: a frame runs
  // only the code its bodies need, since a branch on a uniform still costs a software
  // rasteriser every fragment it masks (twice the time of street.json's frame). Each is built
  // the first time a frame asks for it.
  std::map<int, GLuint> body_program_cache;
  int frame_features = 0;     // of the prepared frame (kBodySpin, kBodyTimedPattern, kBodyHueModel)
  bool any_lit = false;       // whether the prepared frame has lit bodies (a lighting pass)
  int lighting_features = 0;  // and what its lighting pass needs (LightingFeature)
  // The lighting pass's programs, by body and lighting features (lit_surfaces.frag).
  std::map<std::pair<int, int>, GLuint> lighting_program_cache;
  bool specialise = true;  // false: every body program has every feature (the tests' reference)
  // The sky (plain or grid, and image; the hue model or another), and near a black hole (the
  // same; the colour model another, spectral or hue: colour_kind): each built with the first
  // frame that needs it.
  GLuint sky_programs[2][2] = {{0, 0}, {0, 0}};
  GLuint hole_sky_programs[2][3] = {{0, 0, 0}, {0, 0, 0}};
  std::unique_ptr<BlackHolePass> black_hole;
  // The bodies near a black hole: built with the first frame that has them.
  std::unique_ptr<HoleBodiesPass> hole_bodies;
  // The stars: built with the first frame that has them.
  std::unique_ptr<StarPass> stars;
  // The lights' shadow maps: made with the first frame that casts shadows, kept while they
  // serve.
  std::unique_ptr<ShadowMaps> shadow_maps;
  // Lit textures under the spectral model: made with the first frame that has them.
  std::unique_ptr<SpectralAlbedo> spectral_albedo;
  // The bodies whose shadows are met exactly: made with the first frame that casts shadows.
  std::unique_ptr<ShadowCasters> shadow_casters;
  // Near a black hole: what casts the lit bodies' shadows, and its query for the prepared frame
  // (which kept_lighting asks, and so outlives).
  CurvedShadowSource curved_shadow_source;
  std::unique_ptr<CurvedShadowQuery> curved_shadows;
  std::unique_ptr<Lighting> kept_lighting;  // the lights' tables (prepare())
  // The shapes' rest meshes with their edges indexed, kept from frame to frame while some body
  // has the shape: keyed by the shape's values (a mesh's by its address, held so that it
  // stays) and the face grid.
  using RestMeshKey = std::tuple<std::size_t, std::array<double, 3>, const Mesh*, int>;
  struct KeptRestMesh {
    std::shared_ptr<const Mesh> held;
    RestMesh mesh;
    bool used = false;
  };
  std::map<RestMeshKey, KeptRestMesh> rest_meshes;
  // The CPU path's triangles and texture coordinates' maps, a buffer per body (prepare()).
  std::vector<std::vector<float>> tessellated_parts, tessellated_uv_parts;
  const RestMesh& rest_mesh_for(const Shape& shape, int face_grid);
  int disk_row = 0;
  double disk_floor = 0;
  GlDriver driver;
  bool gpu_tessellation = false;  // which path the frame is prepared for
  GLuint body_program = 0;        // the one in use
  GLuint patch_buffer = 0;
  // Per vertex of the textured meshes (laid first in the vertex or patch buffer), the map from
  // shape points to texture coordinates of the face it lies on (triangle_uv_map).
  GLuint face_uv_buffer = 0;
  GLuint vertex_array = 0, vertex_buffer = 0, rows_texture = 0, offsets_texture = 0,
         tables_texture = 0;
  // The vertex buffer's size in bytes. It only grows: a store made anew each frame costs a
  // software driver fresh pages (a fault each) for every vertex.
  std::size_t vertex_buffer_bytes = 0;
  // The lights' parameters, a row each (lighting.glsl's Lamp), and the lit bodies' reflection
  // rows (lighting.glsl's reflection_index).
  GLuint light_table_texture = 0, reflection_index_texture = 0;

  // The body program of a kind of material, path and features (body_variant_defines).
  GLuint body_program_for(int variant, bool gpu, int features);
  GLuint lighting_program_for(int features, int lighting);
  GLuint sky_program_for(int variant, bool hue);

  Impl();

  ~Impl();

  void set_common(GLuint program, const ResolvedScene& scene, double first_log_doppler, double ox,
                  double oy);

  // What one frame keeps between its passes.
  struct BodyDraw {
    std::size_t body = 0, first_vertex = 0, vertex_count = 0;
    int first_row = 0, pattern = 0;
    bool lit = false;
    bool face_uvs = false;     // a textured mesh: its faces' texture coordinates' maps are drawn
    int reflection_body = -1;  // a lit body's row of reflection_index_texture (its finish too)
    const RestMesh* mesh = nullptr;  // during prepare()
    HiddenFaces hidden = HiddenFaces::kNone;
    double sphere_radius = 0;  // the GPU path's: its mesh's
  };
  struct LightDraw {
    int kind = 0, fixed_event = 0, row = 0;
    Vec4 event;  // relative to the observation event
    Vec3 position, velocity, axis;
    double time = 0, intensity = 0, radius = 0, half_cone = 0, falloff = 0;
  };
  // What a colour row is tabulated from (raster_prepare.cpp): an emission, table or disk of
  // the frame's EmissionTable, or a light, primary or lit colour of the kept Lighting.
  struct RowSource {
    enum Kind { kEmission, kLightSeen, kLightRgb, kPrimary, kBasis, kReflection, kDisk };
    Kind kind = kEmission;
    const void* source = nullptr;
    std::size_t object = 0, light = 0;
    int colour = 0;
    bool operator==(const RowSource&) const = default;
  };
  // The rows on rows_texture, kept while the next frame's are the same rows over a range of
  // ln D inside theirs (a viewer's frames differ in the camera alone).
  struct KeptRows {
    std::uint64_t emission_serial = 0;  // 0: none kept
    DopplerModel doppler = DopplerModel::kSpectral;
    SearchlightModel searchlight = SearchlightModel::kPhysical;
    bool hue_loop = false;
    std::vector<RowSource> sources;
    double first = 0, last = 0;  // ln D of the first and last node
  } kept_rows;
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
  GLuint upload(const Image& image);

  // Tessellates every body and tabulates the colour rows for one frame (raster_prepare.cpp).
  RasterFrameStats prepare(const ResolvedScene& resolved, const EmissionTable& emission,
                           const TessellationLimits& limits, bool on_gpu);

  const std::vector<float>* shading_offsets = nullptr;
  TessellationLimits tessellation_limits;

  // The lights and what lit surfaces share, on the lighting pass's program p of lighting
  // features `lighting` (lighting.glsl's uniforms).
  void set_lights(GLuint p, const ResolvedScene& resolved, int lighting);

  // A lit body's own uniforms: what its surfaces write for the lighting pass.
  void set_lit_body(const ResolvedScene& resolved, const BodyDraw& draw);

  // What every pass draws with: the depth test, no culling or blending, the colour rows on unit
  // 0, the bodies' vertex array.
  void bind_frame_state();
  // The bodies' vertex (or patch) buffer and texture coordinates' maps on their attributes.
  void bind_body_buffers();
  // One pass of the prepared frame, its samples at (ox, oy) within each pixel.
  void pass(double ox, double oy, const std::vector<float>* offsets);
  // The sky and its stars, behind what the bound target's depth buffer holds.
  void draw_sky(double ox, double oy);
  void draw_body(const ResolvedScene& resolved, const BodyDraw& draw, bool lit);
  // The lit bodies' nearest surfaces into the surface textures, then the lighting pass over
  // them into the frame's target (deferred shading).
  void draw_lit_surfaces(double ox, double oy, int features);
  void light_surfaces(double ox, double oy, int features);
  // The surface textures (lit_surfaces.frag's), on the frame's own depth buffer: made with the
  // first lit frame, anew when the size changes.
  GLuint surfaces_framebuffer = 0;
  std::array<GLuint, kSurfaceTextures> surface_textures{};
  std::array<int, 2> surfaces_size{0, 0};
};

}  // namespace lightcone

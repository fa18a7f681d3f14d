// What makes the real-time renderer's frames fast draws them as the slow way does: the
// pass-through baseline and the floor of bench/bench_raster.cpp draw the frame's own triangles
// and sky, colour rows kept between frames give a first frame's colours, and each program
// specialised by frame draws its scene as the programs with every feature do; and every
// variant compiles as GLSL ES 3.00.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/raster/baseline_pass.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/raster/shader_build.hpp"
#include "lightcone/raster/shader_sources.hpp"
#include "support/raster_agreement.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

// The pass-through baseline of bench/bench_raster.cpp draws the triangles the frame it mirrors
// drew, where the frame draws them: the pixels it covers are those where the frame (under a
// black sky) shows a body.
// street.json at 160 x 90, one sample a pixel, prepared on the CPU into a bound target.
struct PreparedStreet {
  explicit PreparedStreet(bool black_sky) : scene(street(black_sky)), target(160, 90) {
    target.bind();
    triangles = renderer.prepare(resolved, emission, {}, /*on_gpu=*/false).triangles;
  }
  static Scene street(bool black_sky) {
    Scene s = test::load_repository_scene("street.json");
    s.camera.width = 160, s.camera.height = 90, s.camera.samples = 1;
    if (black_sky) s.sky.pattern = SolidColor{{0, 0, 0}};
    return s;
  }
  const Scene scene;
  const HeadlessGlContext context;
  RasterRenderer renderer;
  const FloatTarget target;
  const ResolvedScene resolved = resolve_scene(scene);
  const EmissionTable emission{resolved};
  std::size_t triangles = 0;
};

TEST(RasterBaseline, DrawsTheFramesTriangles) {
  PreparedStreet street(/*black_sky=*/true);
  ASSERT_GT(street.triangles, 1000u);
  const BaselinePass baseline;
  EXPECT_EQ(baseline.draw(street.resolved, street.renderer), street.triangles);
  const Image drawn = street.target.read();
  street.renderer.pass();
  const Image frame = street.target.read();
  std::size_t covered = 0, differ = 0;
  for (std::size_t p = 0; p < drawn.rgb.size() / 3; ++p) {
    const bool base = drawn.rgb[3 * p] == 1.0f;
    const bool body = frame.rgb[3 * p] + frame.rgb[3 * p + 1] + frame.rgb[3 * p + 2] > 0;
    covered += base;
    differ += base != body;
  }
  EXPECT_GT(covered, 160u * 90 / 10);  // the street's houses fill much of the view
  EXPECT_EQ(differ, 0u);
}

// RasterFloor (bench/bench_raster.cpp) is the frame with its bodies shaded for nothing: the
// baseline's bodies, and behind them the frame's own sky, drawn as the frame draws it.
TEST(RasterBaseline, FloorDrawsTheFramesSkyBehindTheBodies) {
  PreparedStreet street(/*black_sky=*/false);
  ASSERT_TRUE(std::holds_alternative<SkyGrid>(street.scene.sky.pattern));
  const BaselinePass baseline;
  baseline.draw(street.resolved, street.renderer);
  const Image bodies = street.target.read();
  street.renderer.sky_pass();
  const Image floor = street.target.read();
  street.renderer.pass();
  const Image frame = street.target.read();
  std::size_t sky = 0;
  for (std::size_t i = 0; i < floor.rgb.size(); ++i) {
    const bool body = bodies.rgb[i - i % 3] == 1.0f;
    sky += !body && i % 3 == 0;
    ASSERT_EQ(floor.rgb[i], body ? bodies.rgb[i] : frame.rgb[i]) << i;
  }
  EXPECT_GT(sky, 160u * 90 / 10);
}

// The colour rows are kept from frame to frame while they are the same rows over a range that
// covers the next frame's, as in the viewer, whose frames differ in the camera alone: each frame
// is drawn as a renderer drawing it first draws it (up to the nodes' interpolation), and the
// rows are tabulated anew where the camera's speed leaves their range or a setting changes.
// (The emission tables are kept over a wide range, so that the rows' own range decides.)
TEST(RasterKeptRows, EachFrameIsDrawnAsAFirstFrameIs) {
  for (const char* name : {"street.json", "street-lit.json"}) {
    SCOPED_TRACE(name);
    Scene scene = test::load_repository_scene(name);
    scene.camera.width = 160, scene.camera.height = 90, scene.camera.samples = 1;
    const HeadlessGlContext context;
    const FloatTarget target(160, 90);
    target.bind();
    RasterRenderer kept_renderer;
    std::unique_ptr<EmissionTable> kept_emission;
    const auto draw_kept = [&](bool& tabulated) {
      const ResolvedScene resolved = resolve_scene(scene);
      if (!kept_emission || !kept_emission->serves(resolved))
        kept_emission = std::make_unique<EmissionTable>(resolved, 2.0);
      tabulated =
          kept_renderer.prepare(resolved, *kept_emission, {}, /*on_gpu=*/false).rows_tabulated;
      kept_renderer.pass();
      return target.read();
    };
    const auto draw_first = [&] {
      RasterRenderer renderer;
      const ResolvedScene resolved = resolve_scene(scene);
      const EmissionTable emission(resolved);
      renderer.prepare(resolved, emission, {}, /*on_gpu=*/false);
      renderer.pass();
      return target.read();
    };
    struct Step {
      const char* change;
      std::function<void()> apply;
      bool tabulated;
    };
    const Vec3 velocity = scene.camera.world_line.velocity;
    for (const Step& step : {
             Step{"the first frame", [] {}, true},
             Step{"the camera a little ahead", [&] { scene.camera.world_line.position.z -= 0.5; },
                  false},
             Step{"the camera a little faster",
                  [&] { scene.camera.world_line.velocity = velocity * 1.01; }, false},
             Step{"the camera far faster",
                  [&] { scene.camera.world_line.velocity = velocity * (0.97 / length(velocity)); },
                  true},
             Step{"the searchlight off", [&] { scene.render.searchlight = SearchlightModel::kOff; },
                  true},
             Step{"the hue model", [&] { scene.render.doppler = DopplerModel::kHue; }, true},
         }) {
      SCOPED_TRACE(step.change);
      step.apply();
      bool tabulated = false;
      const Image kept = draw_kept(tabulated);
      EXPECT_EQ(tabulated, step.tabulated);
      const Image first = draw_first();
      const test::ValueDifference d = test::compare_values(kept, first, 1e-4f);
      EXPECT_EQ(d.differing, 0u);
      EXPECT_GT(d.lit, first.rgb.size() / 4);
    }
  }
}

// A frame's body programs hold only the features its bodies use (raster/shader_build.hpp,
// body_variant_defines); each such frame is drawn exactly as by the programs with every feature:
// street.json (none), the spinning wheel, the twin paradox's clocks, street-lit.json (lit; and
// with its towers moving, their shadows met exactly; and glossy under a sphere lamp and the sun),
// the wheel lit by a lamp (a spinning mesh's shadow met along its curve), the cubes with several
// samples a pixel (per-pixel shading offsets), a spot light (headlight.json) and a light moving
// relative to what it lights (interceptor.json).
TEST(RasterVariants, EachDrawsItsSceneAsTheFullProgramsDo) {
  const auto draw = [](const Scene& scene, bool specialise, bool offsets) {
    const HeadlessGlContext context;
    RasterRenderer renderer;
    renderer.set_specialised_programs(specialise);
    const FloatTarget target(scene.camera.width, scene.camera.height);
    target.bind();
    const ResolvedScene resolved = resolve_scene(scene);
    const EmissionTable emission(resolved);
    renderer.prepare(resolved, emission, {}, /*on_gpu=*/false);
    // Offsets: each pixel shaded at a point of its own (the second of four samples).
    std::vector<float> shading(4 * static_cast<std::size_t>(scene.camera.width) *
                               scene.camera.height);
    for (std::size_t i = 0; i < shading.size(); i += 4) {
      shading[i] = 0.3f + 0.4f * static_cast<float>((i / 4) % 7) / 7;
      shading[i + 1] = 0.6f;
      shading[i + 2] = shading[i + 3] = 0.5f;
    }
    renderer.pass(0.5, 0.5, offsets ? &shading : nullptr);
    return target.read();
  };
  struct Case {
    const char* scene;
    bool offsets;
    bool hue = false;
    bool lit_textures = false;       // its textures lit by a lamp (the spectral fit per sample)
    bool moving_meshes = false;      // its meshes moving relative to the lamps (met exactly)
    bool glossy_more_lamps = false;  // its lit bodies glossy, and a sphere lamp and the sun
  };
  for (const Case c :
       {Case{"street.json", false}, Case{"wheel.json", false}, Case{"twin-paradox.json", false},
        Case{"street-lit.json", false}, Case{"cubes.json", true},
        Case{"street-lit.json", false, true}, Case{"texture-mapping.json", false, false, true},
        Case{"street-lit.json", false, false, false, true}, Case{"wheel.json", false, false, true},
        Case{"headlight.json", false}, Case{"interceptor.json", false},
        Case{"street-lit.json", false, false, false, false, true}}) {
    SCOPED_TRACE(c.scene);
    Scene scene = test::load_repository_scene(c.scene);
    if (c.hue) scene.render.doppler = DopplerModel::kHue;
    if (c.moving_meshes)
      for (Object& o : scene.objects)
        if (std::holds_alternative<MeshShape>(o.shape)) o.world_line.velocity = {0, 0, 0.3};
    if (c.glossy_more_lamps) {
      for (Object& o : scene.objects) o.material.glossy = Glossy{0.4, 0.1};
      Light lamp;
      lamp.name = "sphere lamp";
      lamp.kind = SphereLight{0.5};
      lamp.world_line.position = scene.camera.world_line.position + Vec3{-2, 3, -6};
      lamp.intensity = 40;
      scene.lights.push_back(lamp);
      Light sun;
      sun.name = "sun";
      sun.kind = DirectionalLight{{0.3, -1, -0.4}, 0.5};
      scene.lights.push_back(sun);
    }
    if (c.lit_textures) {
      for (Object& o : scene.objects) o.material.unlit = false;
      Light lamp;
      lamp.name = "lamp";
      lamp.kind = PointLight{};
      lamp.world_line.position = scene.camera.world_line.position + Vec3{1, 2, 0};
      lamp.intensity = 20;
      scene.lights.push_back(lamp);
    }
    scene.camera.width = 160, scene.camera.height = 90;
    const Image specialised = draw(scene, true, c.offsets), full = draw(scene, false, c.offsets);
    ASSERT_EQ(specialised.rgb.size(), full.rgb.size());
    const test::ValueDifference d = test::compare_values(specialised, full, 1e-6f);
    EXPECT_EQ(d.differing, 0u);
    EXPECT_GT(d.lit, full.rgb.size() / 10);
  }
}

// ---------------------------------------------------------------------------------------------
// The shaders as GLSL ES 3.00 (WebGL 2): the same sources with only the version and precision
// lines changed, through the reference compiler.

TEST(RasterShaders, CompileAsGlslEs300) {
  const fs::path dir = test::fresh_temp_dir("glsl-es");
  struct Stage {
    const char* name;
    const char* source;
    bool fragment;
    const char* extra = "";    // what the program puts between the shared code and the stage
    const char* defines = "";  // which variant of the stage
  };
  const std::string patterns = shader_sources::patterns_glsl;
  const std::string lighting = shader_sources::lighting_glsl;
  const std::string stripped = body_variant_defines(0);
  const std::string stripped_textured = "#define LIGHTCONE_TEXTURED 1\n" + stripped;
  const std::string stripped_lit = "#define LIGHTCONE_LIT 1\n" + stripped;
  const std::string every_light = lighting_variant_defines(kAllLightingFeatures);
  const std::string patterns_and_hole = patterns + shader_sources::black_hole_glsl;
  const Stage stages[] = {
      {"body.vert", shader_sources::body_vert, false, shader_sources::body_projection_glsl},
      {"body-textured.vert", shader_sources::body_vert, false, shader_sources::body_projection_glsl,
       "#define LIGHTCONE_TEXTURED 1\n"},
      {"body.frag", shader_sources::body_frag, true, patterns.c_str()},
      {"body-textured.frag", shader_sources::body_frag, true, patterns.c_str(),
       "#define LIGHTCONE_TEXTURED 1\n"},
      {"body-lit.frag", shader_sources::body_frag, true, patterns.c_str(),
       "#define LIGHTCONE_LIT 1\n"},
      {"body-lit-textured.frag", shader_sources::body_frag, true, patterns.c_str(),
       "#define LIGHTCONE_LIT 1\n#define LIGHTCONE_LIT_TEXTURES 1\n"},
      {"body-lit-textured.vert", shader_sources::body_vert, false,
       shader_sources::body_projection_glsl, "#define LIGHTCONE_LIT_TEXTURES 1\n"},
      {"body-lit-textured-spectral.frag", shader_sources::body_frag, true, patterns.c_str(),
       "#define LIGHTCONE_LIT 1\n#define LIGHTCONE_LIT_TEXTURES 1\n"
       "#define LIGHTCONE_SPECTRAL_TEXTURES 1\n"},
      {"body-mesh-clocks.frag", shader_sources::body_frag, true, patterns.c_str(),
       "#define LIGHTCONE_MESH_CLOCKS 1\n"},
      {"lit_surfaces.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str()},
      {"lit_surfaces-spectral-textures.frag", shader_sources::lit_surfaces_frag, true,
       lighting.c_str(), "#define LIGHTCONE_SPECTRAL_TEXTURES 1\n"},
      {"lit_surfaces-exact-shadows.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       "#define LIGHTCONE_EXACT_SHADOWS 1\n"},
      {"lit_surfaces-mesh-shadows.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       "#define LIGHTCONE_EXACT_SHADOWS 1\n#define LIGHTCONE_MESH_SHADOWS 1\n"},
      {"lit_surfaces-spin-shadows.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       "#define LIGHTCONE_EXACT_SHADOWS 1\n#define LIGHTCONE_MESH_SHADOWS 1\n"
       "#define LIGHTCONE_SPIN_SHADOWS 1\n"},
      // Each with every feature a frame may leave out left out (body_variant_defines).
      {"body-specialised.frag", shader_sources::body_frag, true, patterns.c_str(),
       stripped.c_str()},
      {"body-textured-specialised.frag", shader_sources::body_frag, true, patterns.c_str(),
       stripped_textured.c_str()},
      {"body-lit-specialised.frag", shader_sources::body_frag, true, patterns.c_str(),
       stripped_lit.c_str()},
      {"lit_surfaces-specialised.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       stripped.c_str()},
      {"lit_surfaces-every-light.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       every_light.c_str()},
      {"lit_surfaces-spectral-model.frag", shader_sources::lit_surfaces_frag, true,
       lighting.c_str(), "#define LIGHTCONE_SPECTRAL_MODEL 1\n"},
      {"lit_surfaces-other-models.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       "#define LIGHTCONE_OTHER_MODELS 1\n"},
      {"hole_body.vert", shader_sources::hole_body_vert, false,
       shader_sources::body_projection_glsl},
      {"hole_body.frag", shader_sources::hole_body_frag, true, patterns.c_str()},
      {"hole_body-disk.frag", shader_sources::hole_body_frag, true, patterns_and_hole.c_str(),
       "#define LIGHTCONE_DISK_HIDES_BODIES 1\n"},
      {"fullscreen.vert", shader_sources::fullscreen_vert, false},
      {"display.frag", shader_sources::display_frag, true, shader_sources::tone_map_glsl},
      {"sky.frag", shader_sources::sky_frag, true},
      {"sky-image.frag", shader_sources::sky_frag, true, "", "#define LIGHTCONE_SKY_IMAGE 1\n"},
      {"sky-hole.frag", shader_sources::sky_frag, true, shader_sources::black_hole_glsl,
       "#define LIGHTCONE_BLACK_HOLE 1\n"},
      {"sky-hole-image.frag", shader_sources::sky_frag, true, shader_sources::black_hole_glsl,
       "#define LIGHTCONE_BLACK_HOLE 1\n#define LIGHTCONE_SKY_IMAGE 1\n"},
      {"star.vert", shader_sources::star_vert, false, shader_sources::body_projection_glsl},
      {"baseline.vert", shader_sources::baseline_vert, false, shader_sources::body_projection_glsl},
      {"baseline.frag", shader_sources::baseline_frag, true},
      {"shadow.vert", shader_sources::shadow_vert, false, shader_sources::body_projection_glsl},
      {"shadow.frag", shader_sources::shadow_frag, true},
      {"star.frag", shader_sources::star_frag, true, shader_sources::star_filter_glsl}};
  for (const Stage& stage : stages) {
    const fs::path file = dir / stage.name;
    test::write_text(file, std::string("#version 300 es\nprecision highp float;\nprecision highp "
                                       "int;\nprecision highp sampler2D;\n") +
                               (stage.fragment ? "#define LIGHTCONE_FRAGMENT_STAGE 1\n" : "") +
                               stage.defines + shader_sources::common_glsl + stage.extra +
                               stage.source);
    const std::string command =
        "glslangValidator '" + file.string() + "' > '" + (dir / "log").string() + "' 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream log(dir / "log");
    const std::string text((std::istreambuf_iterator<char>(log)), {});
    EXPECT_EQ(status, 0) << stage.name << ": " << text;
  }
  // The tessellation stages are OpenGL 4 only (WebGL 2 has none): checked as GLSL 400.
  const Stage tessellation_stages[] = {{"body.tesc", shader_sources::body_tesc, false},
                                       {"body.tese", shader_sources::body_tese, false},
                                       {"patch.vert", shader_sources::patch_vert, false}};
  for (const Stage& stage : tessellation_stages)
    for (const char* defines : {"", "#define LIGHTCONE_TEXTURED 1\n"}) {
      const fs::path file = dir / (std::string(*defines ? "textured-" : "") + stage.name);
      test::write_text(file, std::string("#version 400 core\n") + defines +
                                 shader_sources::common_glsl +
                                 shader_sources::body_projection_glsl + stage.source);
      const int status = std::system(
          ("glslangValidator '" + file.string() + "' > '" + (dir / "log").string() + "' 2>&1")
              .c_str());
      std::ifstream log(dir / "log");
      const std::string text((std::istreambuf_iterator<char>(log)), {});
      EXPECT_EQ(status, 0) << stage.name << ": " << text;
    }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lightcone

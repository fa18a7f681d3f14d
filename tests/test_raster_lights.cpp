// The real-time renderer's lights against the ray tracer: lit scenes with and without shadows
// (retarded shadows from maps in each light's rest frame, and exactly for bodies moving relative
// to a light), any number of lights, and every colour, searchlight and delay model on the lit
// street.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/raster/shadow_casters.hpp"
#include "lightcone/raster/shadow_maps.hpp"
#include "support/raster_agreement.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using test::agreement;
using test::Agreement;
using test::expect_agreement;

// Lit scenes: point lamps at rest (street-lit), a headlight moving with the camera, and a
// light-delay comparison (interceptor), without shadows.
TEST(RasterAgreement, LitScenesMatchTheRayTracerWithoutShadows) {
  for (const char* scene : {"street-lit.json", "headlight.json", "interceptor.json"})
    expect_agreement(scene, "--set render.shadows=false", 4);
}

// With shadows: the lamps' shadows of the street's buildings on the road, on each other and on
// the towers, from the lamps' maps in their rest frame; a headlight moving with the camera past
// the street's boxes; and a light at 0.5c over a moon's boulders (the seed's failure case),
// whose shadows are met exactly in the boulders' frame.
TEST(RasterAgreement, RetardedShadowsMatchTheRayTracer) {
  for (const char* settings : {"--set render.light_source_delay=camera",
                               "--set render.relativity=false", "--tessellation gpu"})
    expect_agreement("street-lit.json", settings, 4);
  expect_agreement("headlight.json", "", 4);  // a spot moving with the camera
  // A light at 0.5c in the classical picture: lit and shadowed from where it is at the camera's
  // time, where its boulders are drawn.
  expect_agreement("interceptor.json", "--set render.relativity=false", 4);
  // The shadows are seen: drawn without them, at least half a percent more pixels differ.
  for (const char* scene : {"street-lit.json", "interceptor.json"}) {
    const Agreement with = agreement(scene, 4);
    EXPECT_GE(with.within, 0.99) << scene;
    EXPECT_EQ(with.raster_err, "") << scene;
    std::printf("%s with shadows: %.4f within 4/255\n", scene, with.within);
    const Agreement without = agreement(scene, 4, "", "--set render.shadows=false");
    std::printf("%s, raster without shadows: %.4f within 4/255\n", scene, without.within);
    EXPECT_LT(without.within + 0.005, with.within) << scene;
  }
}

// Glossy finishes: the wall under the moving headlight, shiny and then rough, its finish carried
// from its surface to the lighting pass (lit_surfaces.frag) and applied as the tracer applies
// it. The lobe is seen: the raster picture of a rougher finish than the tracer's differs.
TEST(RasterAgreement, GlossyFinishesMatchTheRayTracer) {
  const std::string shiny =
      "--set objects.0.material.glossy.roughness=0.25 "
      "--set objects.0.material.glossy.specular=0.3";
  const std::string rough =
      "--set objects.0.material.glossy.roughness=0.8 "
      "--set objects.0.material.glossy.specular=0.3";
  expect_agreement("headlight.json", shiny, 4);
  expect_agreement("headlight.json", rough, 4);
  const Agreement other = agreement("headlight.json", 4, shiny, rough);
  std::printf("headlight.json, raster rougher than traced: %.4f within 4/255\n", other.within);
  EXPECT_LT(other.within, 0.95);
}

// Any number of lights: twenty lamps of five colours round a yard, the last four the brightest,
// without and with their shadows of two crates and a ball (the maps at 256 texels a face past
// eight lights; the ball met exactly in them, so its shadows are round).
TEST(RasterAgreement, TwentyLightsMatchTheRayTracer) {
  const fs::path dir = test::fresh_temp_dir("twenty-lights");
  std::string lights;
  const char* colours[] = {"[1, 0.6, 0.3]", "[0.4, 0.7, 1]", "[0.5, 1, 0.5]", "[1, 0.4, 0.8]",
                           "[1, 1, 0.9]"};
  for (int i = 0; i < 20; ++i) {
    const double a = 2 * std::numbers::pi * i / 20;
    lights +=
        fmt::format(R"({}{{"name": "lamp-{}", "type": "point", "position": [{:.3f}, {}, {:.3f}],)"
                    R"( "color": {}, "intensity": {}}})",
                    i ? ",\n    " : "", i, 7 * std::cos(a), 3 + i % 3, 7 * std::sin(a) - 2,
                    colours[i % 5], i >= 16 ? 60 : 12);
  }
  test::write_text(dir / "scene.json", R"({
  "camera": {"position": [0, 9, 12], "forward": [0, -0.7, -1], "fov": 60},
  "objects": [
    {"name": "yard", "shape": {"plane": {"size": [30, 30]}}, "position": [0, 0, -2],
     "material": {"color": [0.7, 0.7, 0.7], "unlit": false}},
    {"name": "crate", "shape": {"box": {"size": [2, 2, 2]}}, "position": [-2, 1, -2],
     "material": {"color": [0.8, 0.5, 0.3], "unlit": false}},
    {"name": "tall-crate", "shape": {"box": {"size": [1, 3, 1]}}, "position": [2.5, 1.5, -3],
     "material": {"color": [0.5, 0.5, 0.8], "unlit": false}},
    {"name": "ball", "shape": {"sphere": {"radius": 1}}, "position": [1, 1, 1],
     "material": {"color": [0.6, 0.8, 0.6], "unlit": false}}
  ],
  "lights": [
    )" + lights + R"(
  ],
  "sky": {"color": [0.02, 0.02, 0.03]},
  "render": {"exposure": -1}
})");
  expect_agreement((dir / "scene.json").string(), "--set render.shadows=false", 4);
  expect_agreement((dir / "scene.json").string(), "", 4);
  fs::remove_all(dir);
}

// Lit and unlit bodies hide each other both ways (the lit ones are drawn after the others into
// the surface textures, on the frame's depth buffer, and lit by a pass of their own): an unlit
// ball in front of a lit box, a lit ball in front of an unlit box, a lit box and an unlit ball
// at 0.6c, an unlit checkered floor under all, and a lit crate half sunk into an unlit block
// (the two surfaces cross).
TEST(RasterAgreement, LitAndUnlitBodiesHideEachOther) {
  const fs::path dir = test::fresh_temp_dir("lit-and-unlit");
  test::write_text(dir / "scene.json", R"({
  "camera": {"position": [0, 4, 10], "forward": [0, -0.35, -1], "fov": 60},
  "objects": [
    {"name": "floor", "shape": {"plane": {"size": [30, 30]}}, "position": [0, 0, -3],
     "material": {"checker": {"size": 1.5, "colors": [[0.6, 0.6, 0.6], [0.3, 0.3, 0.35]]}}},
    {"name": "lit-box", "shape": {"box": {"size": [3, 3, 1]}}, "position": [-3, 1.5, -4],
     "material": {"color": [0.8, 0.5, 0.3], "unlit": false}},
    {"name": "unlit-ball", "shape": {"sphere": {"radius": 1}}, "position": [-2.5, 1.2, -2],
     "material": {"color": [0.2, 0.6, 0.9]}},
    {"name": "unlit-box", "shape": {"box": {"size": [3, 3, 1]}}, "position": [3, 1.5, -4],
     "material": {"color": [0.9, 0.8, 0.2]}},
    {"name": "lit-ball", "shape": {"sphere": {"radius": 1}}, "position": [2.5, 1.2, -2],
     "material": {"color": [0.4, 0.8, 0.5], "unlit": false}},
    {"name": "lit-runner", "shape": {"box": {"size": [1.5, 1, 1]}}, "position": [-4, 0.6, 1],
     "time": -10, "velocity": [0.6, 0, 0],
     "material": {"color": [0.9, 0.3, 0.5], "unlit": false}},
    {"name": "unlit-runner", "shape": {"sphere": {"radius": 0.6}}, "position": [4, 0.7, 0.8],
     "time": -10, "velocity": [-0.6, 0, 0], "material": {"color": [0.5, 0.3, 0.9]}},
    {"name": "block", "shape": {"box": {"size": [2, 1, 2]}}, "position": [0, 0.5, -6],
     "material": {"color": [0.3, 0.8, 0.8]}},
    {"name": "sunk-crate", "shape": {"box": {"size": [1.2, 1.2, 1.2]}},
     "position": [0.4, 1.1, -5.6], "rotation": {"axis": [0, 1, 0], "degrees": 30},
     "material": {"color": [0.8, 0.8, 0.7], "unlit": false}}
  ],
  "lights": [
    {"name": "lamp", "type": "point", "position": [0, 6, 2], "intensity": 150}
  ],
  "sky": {"color": [0.02, 0.02, 0.03]},
  "render": {"exposure": 0}
})");
  expect_agreement((dir / "scene.json").string(), "", 4);
  fs::remove_all(dir);
}

// At one sample a pixel, a sphere lamp lights each pixel from the ray tracer's own point on it
// (the pixel's light sample), not from one point for all: half the pixels of this scene were
// more than 4/255 off before.
TEST(RasterAgreement, ASphereLampAtOneSampleMatchesTheRayTracer) {
  const fs::path dir = test::fresh_temp_dir("sphere-lamp");
  test::write_text(dir / "scene.json", R"({
  "camera": {"position": [0, 5, 9], "forward": [0, -0.5, -1], "fov": 60},
  "objects": [
    {"name": "floor", "shape": {"plane": {"size": [30, 30]}}, "position": [0, 0, 0],
     "material": {"color": [0.7, 0.7, 0.7], "unlit": false}},
    {"name": "crate", "shape": {"box": {"size": [2, 2, 2]}}, "position": [0, 1, 0],
     "material": {"color": [0.8, 0.4, 0.3], "unlit": false}}
  ],
  "lights": [{"name": "globe", "type": "sphere", "position": [1, 4, 1], "radius": 0.8,
              "intensity": 60}],
  "sky": {"color": [0.02, 0.02, 0.03]},
  "render": {"exposure": 0}
})");
  expect_agreement((dir / "scene.json").string(), "", 1);
  fs::remove_all(dir);
}

// The raster renderer's shadows of `scene` agree with the tracer's at 16 samples, and they show:
// drawn without them, more than 2 % of the pixels differ.
void expect_shadows_that_show(const std::string& scene, const char* label,
                              const std::string& extra = "") {
  expect_agreement(scene, extra, 16);
  const Agreement without = agreement(scene, 16, extra, "--set render.shadows=false");
  std::printf("%s, raster without shadows: %.4f within 4/255\n", label, without.within);
  EXPECT_LT(without.within, 0.98);
}

// Occluders moving relative to the lights: a box at 0.7c and a ball at 0.5c crossing between a
// lamp at rest (and a sun, and a sphere lamp) and the floor, whose shadows are retarded: each
// met exactly along each shadow ray in the body's own rest frame.
TEST(RasterAgreement, ShadowsOfMovingOccludersMatchTheRayTracer) {
  expect_shadows_that_show(
      std::string(LIGHTCONE_SOURCE_DIR) + "/tests/data/moving-occluders.json", "moving occluders",
      "--set render.doppler=off --set render.searchlight=off --set render.exposure=0");
}

// Every kind of body casts: a mesh at 0.6c and the same mesh at rest (in the lamp's maps,
// met exactly for the sun and the sphere lamp), an accelerated crate and a keyframed ball on
// their tangent world-lines, a round ball, a box and the mesh spinning (each shadow ray met
// along its curve through the turning shape), and a row of twenty crates at 0.4c (any number of
// exactly cast bodies), over a floor lit by a lamp, the sun and a sphere lamp.
TEST(RasterAgreement, ShadowsOfMeshesAndBodiesInAnyMotionMatchTheRayTracer) {
  const fs::path dir = test::fresh_temp_dir("casters");
  // An arrowhead: a tetrahedron with a notch, eight faces, closed.
  test::write_text(dir / "arrow.obj", R"(v 0 0 1.2
v -0.8 0 -0.6
v 0.8 0 -0.6
v 0 0.7 -0.3
v 0 -0.7 -0.3
v 0 0 -0.1
f 1 3 4
f 1 4 2
f 1 2 5
f 1 5 3
f 6 4 3
f 6 2 4
f 6 5 2
f 6 3 5
)");
  std::string crates;
  for (int i = 0; i < 20; ++i)
    crates += fmt::format(
        R"(,
    {{"name": "crate-{}", "shape": {{"box": {{"size": [0.35, 0.35, 0.35]}}}},)"
        R"( "position": [{:.2f}, 1.2, -6.5], "time": -4, "velocity": [0.4, 0, 0],)"
        R"( "material": {{"color": [0.8, 0.6, 0.3], "unlit": false}}}})",
        i, -7.5 + 0.7 * i);
  test::write_text(dir / "scene.json", R"({
  "camera": {"position": [0, 7, 9], "forward": [0, -0.65, -1], "fov": 65},
  "objects": [
    {"name": "floor", "shape": {"plane": {"size": [40, 40]}}, "position": [0, 0, -2],
     "material": {"checker": {"size": 2, "colors": [[0.7, 0.7, 0.7], [0.5, 0.5, 0.55]]},
                  "unlit": false}},
    {"name": "dart", "shape": {"mesh": {"file": "arrow.obj"}}, "scale": [1.5, 1.5, 1.5],
     "position": [-6, 2.2, -1], "time": -10, "velocity": [0.6, 0, 0],
     "material": {"color": [0.3, 0.5, 0.9], "unlit": false}},
    {"name": "statue", "shape": {"mesh": {"file": "arrow.obj"}}, "scale": [1.3, 1.3, 1.3],
     "position": [3.5, 1.5, 1], "material": {"color": [0.9, 0.8, 0.6], "unlit": false}},
    {"name": "rocket", "shape": {"box": {"size": [1.4, 0.8, 0.8]}}, "position": [-3, 2.5, 2],
     "velocity": [0.3, 0, 0], "motion": {"phases": [{"duration": 4, "acceleration": [0.008, 0, -0.004]}]},
     "material": {"color": [0.8, 0.3, 0.3], "unlit": false}},
    {"name": "drone", "shape": {"sphere": {"radius": 0.6}},
     "motion": {"keyframes": [{"time": -14, "position": [1, 2, -3]}, {"time": -4, "position": [2, 2.6, -2]},
                              {"time": 6, "position": [2.5, 2.2, -1]}]},
     "material": {"color": [0.4, 0.8, 0.4], "unlit": false}},
    {"name": "globe", "shape": {"sphere": {"radius": 0.8}}, "position": [-1, 1.8, -4],
     "velocity": [0, 0, 0.3], "time": -3, "spin": {"axis": [0.3, 1, 0], "rate": 20},
     "material": {"checker": {"size": 0.4, "colors": [[0.9, 0.9, 0.9], [0.2, 0.2, 0.6]]},
                  "unlit": false}},
    {"name": "top", "shape": {"box": {"size": [1.6, 0.5, 1.0]}}, "position": [5.5, 2.6, -4],
     "spin": {"axis": [0, 1, 0.4], "rate": 0.8},
     "material": {"color": [0.9, 0.5, 0.7], "unlit": false}},
    {"name": "spinner", "shape": {"mesh": {"file": "arrow.obj"}}, "scale": [1.2, 1.2, 1.2],
     "position": [-5, 3, -3.5], "velocity": [0.2, 0, 0], "time": -5,
     "spin": {"axis": [0, 1, 0], "rate": 0.5},
     "material": {"color": [0.6, 0.9, 0.9], "unlit": false}})" +
                                           crates + R"(
  ],
  "lights": [
    {"name": "lamp", "type": "point", "position": [0, 8, -1], "intensity": 220},
    {"name": "sun", "type": "directional", "direction": [0.4, -1, -0.3], "irradiance": 0.3},
    {"name": "bulb", "type": "sphere", "position": [5, 5, -2], "radius": 0.3, "intensity": 50}
  ],
  "sky": {"color": [0.02, 0.02, 0.03]},
  "render": {"doppler": "off", "searchlight": "off", "exposure": 0}
})");
  expect_shadows_that_show((dir / "scene.json").string(), "every caster");
  fs::remove_all(dir);
}

// How each body casts (raster_shadow_cast): in a point or spot light's maps where it stands
// still relative to the light, exactly otherwise (spinning bodies too); the CLI warns of none.
TEST(RasterShadowCast, EveryBodyCasts) {
  Scene scene;
  Light lamp;
  lamp.kind = PointLight{};
  Light bulb = lamp;
  bulb.kind = SphereLight{0.2};
  Light sun;
  sun.kind = DirectionalLight{};
  auto mesh = std::make_shared<Mesh>();
  mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh->triangles = {{0, 1, 2}};
  Object box, moving_mesh, ball, flat, spinning_box, still_mesh;
  box.shape = Box{{1, 1, 1}};
  still_mesh.shape = MeshShape{mesh};
  moving_mesh.shape = MeshShape{mesh};
  moving_mesh.world_line.velocity = {0.5, 0, 0};
  ball.shape = Sphere{1};
  ball.spin = Spin{{0, 1, 0}, 3};
  flat = ball;
  flat.scale = {1, 0.5, 1};
  spinning_box = box;
  spinning_box.spin = Spin{{0, 1, 0}, 3};
  const RenderSettings& r = scene.render;
  EXPECT_EQ(raster_shadow_cast(box, lamp, r), RasterShadowCast::kMap);
  EXPECT_EQ(raster_shadow_cast(still_mesh, lamp, r), RasterShadowCast::kMap);
  for (const Light& light : {bulb, sun}) {
    EXPECT_EQ(raster_shadow_cast(box, light, r), RasterShadowCast::kExact);
    EXPECT_EQ(raster_shadow_cast(still_mesh, light, r), RasterShadowCast::kExact);
  }
  EXPECT_EQ(raster_shadow_cast(moving_mesh, lamp, r), RasterShadowCast::kExact);
  EXPECT_EQ(raster_shadow_cast(ball, lamp, r), RasterShadowCast::kExact);
  EXPECT_EQ(raster_shadow_cast(flat, lamp, r), RasterShadowCast::kExact);
  EXPECT_EQ(raster_shadow_cast(spinning_box, lamp, r), RasterShadowCast::kExact);

  scene.lights = {lamp};
  box.material.unlit = false;
  scene.objects = {box, moving_mesh, ball, flat, spinning_box};
  EXPECT_TRUE(raster_differences(scene).empty());
}

// Each colour, searchlight and light-delay model on the lit street (shaded at the ray tracer's
// own samples, four are enough away from the outlines).
class RasterModels : public testing::TestWithParam<const char*> {};

TEST_P(RasterModels, MatchTheRayTracer) {
  expect_agreement("street-lit.json", std::string("--set render.shadows=false ") + GetParam(), 4);
}

INSTANTIATE_TEST_SUITE_P(
    ColourSearchlightAndDelay, RasterModels,
    testing::Values("--set render.doppler=rgb3", "--set render.doppler=off",
                    "--set render.doppler=hue", "--set render.searchlight=chang1996",
                    "--set render.searchlight=off", "--set render.light_source_delay=camera",
                    "--set render.light_delay=false", "--set render.relativity=false"));

}  // namespace
}  // namespace lightcone

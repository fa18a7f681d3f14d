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

// Occluders moving relative to the lights: a box at 0.7c and a ball at 0.5c crossing between a
// lamp at rest (and a sun, and a sphere lamp) and the floor, whose shadows are retarded: each
// met exactly along each shadow ray in the body's own rest frame.
TEST(RasterAgreement, ShadowsOfMovingOccludersMatchTheRayTracer) {
  const fs::path dir = test::fresh_temp_dir("moving-occluders");
  test::write_text(dir / "scene.json", R"({
  "camera": {"position": [0, 7, 11], "forward": [0, -0.6, -1], "fov": 60},
  "objects": [
    {"name": "floor", "shape": {"plane": {"size": [40, 40]}}, "position": [0, 0, 0],
     "material": {"checker": {"size": 2, "colors": [[0.7, 0.7, 0.7], [0.5, 0.5, 0.55]]},
                  "unlit": false}},
    {"name": "crate", "shape": {"box": {"size": [2, 2, 2]}}, "position": [-2, 2.5, 0],
     "time": -12, "velocity": [0.7, 0, 0], "material": {"color": [0.8, 0.4, 0.3], "unlit": false}},
    {"name": "ball", "shape": {"sphere": {"radius": 1.2}}, "position": [2.5, 2, -3], "time": -12,
     "velocity": [0, 0, 0.5], "material": {"color": [0.3, 0.6, 0.8], "unlit": false}}
  ],
  "lights": [
    {"name": "lamp", "type": "point", "position": [0, 8, -1], "intensity": 200},
    {"name": "sun", "type": "directional", "direction": [0.3, -1, 0.2], "irradiance": 0.4},
    {"name": "globe", "type": "sphere", "position": [4, 6, 2], "radius": 0.3, "intensity": 60}
  ],
  "sky": {"color": [0.02, 0.02, 0.03]},
  "render": {"doppler": "off", "searchlight": "off", "exposure": 0}
})");
  const std::string scene = (dir / "scene.json").string();
  expect_agreement(scene, "", 16);
  const Agreement without = agreement(scene, 16, "", "--set render.shadows=false");
  std::printf("moving occluders, raster without shadows: %.4f within 4/255\n", without.within);
  EXPECT_LT(without.within, 0.98);
  fs::remove_all(dir);
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

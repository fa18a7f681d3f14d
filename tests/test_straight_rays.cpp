// Rays a black hole leaves straight to within the image's resolution (frame/straight_rays.hpp):
// a negligible hole gives the flat picture, and rays that the hole bends are not taken for
// straight.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/straight_rays.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/trace/renderer.hpp"

namespace lightcone {
namespace {

Scene terrell(const std::vector<std::string>& overrides = {}) {
  SceneLoadReport report;
  std::vector<std::string> all{"camera.width=160", "camera.height=90", "camera.samples=2"};
  all.insert(all.end(), overrides.begin(), overrides.end());
  return load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/terrell.json", all, report);
}

// The negligible hole: 1e-9 units of mass, 866 units away (behind the camera).
Scene with_negligible_hole(Scene s) {
  s.black_hole = BlackHole{{500, 500, 500}, 1e-9, std::nullopt};
  return s;
}

TEST(StraightRays, NegligibleHoleGivesTheFlatPicture) {
  // At the scene's automatic exposure and at a fixed one: the same values, pixel for pixel.
  for (const auto& overrides : {std::vector<std::string>{}, {"render.exposure=0"}}) {
    const Scene flat = terrell(overrides);
    RenderOptions options;
    options.threads = 2;
    const Image expected = render_image(flat, options);
    const Image seen = render_image(with_negligible_hole(flat), options);
    ASSERT_EQ(seen.rgb.size(), expected.rgb.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < seen.rgb.size(); ++i) differing += seen.rgb[i] != expected.rgb[i];
    EXPECT_EQ(differing, 0u) << (overrides.empty() ? "automatic exposure" : "fixed exposure");
  }
}

TEST(StraightRays, EveryRayOfTheNegligibleHoleIsStraight) {
  const Scene scene = with_negligible_hole(terrell());  // (the resolved scene points to it)
  const ResolvedScene resolved = resolve_scene(scene);
  const auto rays = StraightRays::of(resolved);
  ASSERT_TRUE(rays);
  for (int j = 0; j < 90; j += 7)
    for (int i = 0; i < 160; i += 7)
      EXPECT_TRUE(rays->straight(look_direction(resolved.camera, i + 0.5, j + 0.5)));
}

TEST(StraightRays, BentRaysAreNot) {
  // A hole of mass 1e-9 at 30 units straight ahead; a pixel spans under 9.7 mrad, so a ray is
  // straight when its bounds sum to less than 9.7e-9. 0.5 degrees off the hole a ray passes at 0.26
  // units, 2.6e8 M, where the turning and the delay alone sum to some 2.6e-8: curved. 30 degrees
  // off, at 15 units: 4.5e-10, straight.
  Scene s = terrell();
  s.black_hole = BlackHole{{0, 0, -30}, 1e-9, std::nullopt};
  const ResolvedScene resolved = resolve_scene(s);
  const auto rays = StraightRays::of(resolved);
  ASSERT_TRUE(rays);
  const auto off = [](double degrees) {
    const double a = degrees * std::numbers::pi / 180;
    return Vec3{std::sin(a), 0, -std::cos(a)};
  };
  EXPECT_FALSE(rays->straight(off(0.5)));
  EXPECT_TRUE(rays->straight(off(30)));
  // Straight at the hole: no periapsis far from it.
  EXPECT_FALSE(rays->straight({0, 0, -1}));
  // A hole of 1e-5 at 30 units: its well at the camera alone (2M / r = 6.7e-7) is too much for any.
  s.black_hole->mass = 1e-5;
  EXPECT_FALSE(StraightRays::of(resolve_scene(s)));
}

TEST(StraightRays, OnlyForScenesFlatSpaceDrawsAlike) {
  // Bodies on falls (unlit), or a lit body, have no flat picture.
  SceneLoadReport report;
  EXPECT_FALSE(StraightRays::of(resolve_scene(
      load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/infall.json", {}, report))));
  Scene lit = with_negligible_hole(terrell());
  lit.objects[0].material.unlit = false;
  Light sun;
  sun.name = "sun";
  sun.kind = DirectionalLight{};
  lit.lights.push_back(sun);
  EXPECT_FALSE(StraightRays::of(resolve_scene(lit)));
  EXPECT_FALSE(StraightRays::of(resolve_scene(terrell())));
  // A hole whose well at the camera alone bends light by more than the tolerance: none asked.
  EXPECT_FALSE(StraightRays::of(resolve_scene(
      load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/black-hole.json", {}, report))));
}

}  // namespace
}  // namespace lightcone

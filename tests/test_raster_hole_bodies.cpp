// The raster renderer's bodies near a black hole (raster/hole_bodies.hpp): their images of
// orders 0 and 1 against the ray tracer's picture of the bundled scenes, off the outlines, and
// their vertices against locate's images of the same points. Units: G = c = 1, M = 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/hole_leg_starts.hpp"
#include "lightcone/frame/lighting.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/raster/hole_bodies.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/trace/aov.hpp"
#include "lightcone/trace/curved_shadows.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

// The 8-bit value a PNG holds for a pixel read back as linear.
int level(float linear) {
  return static_cast<int>(std::lround(255 * srgb_encode(std::min(linear, 1.0f))));
}

struct Agreement {
  std::size_t body_pixels = 0, body_within = 0;  // off the outlines, on a body
  std::size_t secondary_pixels = 0;              // of those, in an image of order 1
  std::size_t other_pixels = 0, other_within = 0;
};

// Both renderers' pictures of `scene` (one sample a pixel, the exposure fixed), compared off the
// outlines: pixels whose traced ray, or a neighbour's, meets another object or image order.
// The raster renderer casts shadows near the hole through `curved_shadows` (by default its own,
// which meet the bodies directly).
Agreement compare(Scene s, const CurvedShadowSource& curved_shadows = {}) {
  s.camera.samples = 1;
  s.render.auto_exposure = false;
  RenderOptions options;
  options.aovs = {Aov::kObject, Aov::kImageOrder};
  const Image traced = render_image(s, options);
  const Image rastered =
      render_raster(s, nullptr, {}, 0, RasterTessellation::kAuto, curved_shadows);
  const int w = s.camera.width, h = s.camera.height;
  const auto key = [&](int x, int y) {
    const std::size_t i = static_cast<std::size_t>(y) * w + x;
    return std::pair{traced.channels[0].values[i], traced.channels[1].values[i]};
  };
  Agreement a;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          edge =
              edge || key(std::clamp(x + dx, 0, w - 1), std::clamp(y + dy, 0, h - 1)) != key(x, y);
      if (edge) continue;
      const Rgb p = traced.texel(x, y), q = rastered.texel(x, y);
      const bool within = std::abs(level(p.r) - level(q.r)) <= 4 &&
                          std::abs(level(p.g) - level(q.g)) <= 4 &&
                          std::abs(level(p.b) - level(q.b)) <= 4;
      if (key(x, y).first >= 0) {
        ++a.body_pixels;
        a.body_within += within;
        a.secondary_pixels += key(x, y).second == 1;
      } else {
        ++a.other_pixels;
        a.other_within += within;
      }
    }
  return a;
}

// A clock at rest behind the hole (its primary and flipped secondary image, which left it 9.6
// units of time apart), three clocks falling in, reddening and freezing, and a lit moon on its
// orbit (lit by a sun, directly and round the far side): both renderers agree off the outlines.
// Painted one colour, the bodies agree as the sky does (their shapes and shifts); with their
// patterns (clock faces, a checker), the hands, rims and squares are outlines the test does not
// know of, drawn within half a pixel of the tracer's, and a few percent of the pixels differ.
TEST(RasterHoleBodies, MatchTheRayTracerOffTheOutlines) {
  for (const auto& [name, width, least_secondary] : {std::tuple{"lensed-clock.json", 320, 20},
                                                     {"infall.json", 480, 0},
                                                     {"orbit.json", 480, 20}}) {
    for (const bool faces : {false, true}) {
      SCOPED_TRACE(name);
      Scene s = test::load_repository_scene(name);
      s.camera.height = s.camera.height * width / s.camera.width;
      s.camera.width = width;
      if (!faces)
        for (Object& o : s.objects) o.material.pattern = SolidColor{{1, 0.95f, 0.8f}};
      const Agreement a = compare(s);
      const double bodies = static_cast<double>(a.body_within) / a.body_pixels;
      const double others = static_cast<double>(a.other_within) / a.other_pixels;
      std::printf("%s %dx%d%s: bodies %.4f of %zu pixels (%zu of order 1), the rest %.4f of %zu\n",
                  name, s.camera.width, s.camera.height, faces ? "" : " (one colour)", bodies,
                  a.body_pixels, a.secondary_pixels, others, a.other_pixels);
      EXPECT_GT(a.body_pixels, 150u);
      EXPECT_GE(a.secondary_pixels, static_cast<std::size_t>(least_secondary));
      // (A lit body's colour is interpolated between its vertices', within 1/128 of its
      // brightest: in the dark a few levels of 255.)
      const bool lit = !s.objects.front().material.unlit;
      EXPECT_GE(bodies, faces ? 0.93 : lit ? 0.98 : 0.99);
      EXPECT_GE(others, 0.99);
    }
  }
}

// Textures near the hole: the clock behind it as a textured box, a textured ball, a textured
// quad (a mesh's own texture coordinates) and the quad as a clock (its dial read at those
// coordinates, as the tracer reads a mesh's clock). Each texel is received with g as the flat
// bodies' are, at the surface point interpolated between the exact vertices: within half a pixel
// of the exact one, so that where the texture changes fast across a pixel (the edges between the
// box's faces, where each face's coordinates start anew, and its faces seen at a grazing angle)
// a few to a fifth of the pixels differ; the texture is smooth and periodic (u and v wrap), so
// that no other edge is drawn. Drawn black, as they once were, almost none would agree. Lit by a
// sun, the box, ball and quad are lit at their vertices at the texel there (the tracer's albedo
// at that point), and their edges split where the colour changes: closer to the tracer than the
// unlit ones, whose texels are read at interpolated points.
TEST(RasterHoleBodies, TexturesAndMeshClocksMatchTheRayTracer) {
  auto grid = std::make_shared<Image>();
  grid->width = grid->height = 32;
  constexpr double kStep = 2 * std::numbers::pi / 32;  // one period across, as u and v wrap
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      grid->rgb.insert(grid->rgb.end(),
                       {0.5f + 0.4f * static_cast<float>(std::sin(x * kStep)),
                        0.5f + 0.4f * static_cast<float>(std::cos(y * kStep)),
                        0.5f + 0.3f * static_cast<float>(std::sin((x + y) * kStep))});
  auto quad = std::make_shared<Mesh>();
  quad->positions = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
  quad->triangles = {{0, 1, 2}, {0, 2, 3}};
  quad->uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  struct Case {
    const char* name;
    Shape shape;
    // the share of the bodies' pixels within 4/255 (measured: 0.78, 0.98, 0.96, 0.98; lit:
    // 0.994, 0.998, 1)
    double least;
    bool clock = false, lit = false;
  };
  for (const Case& c :
       {Case{"box", Box{{4, 4, 4}}, 0.75}, Case{"ball", Sphere{2.2}, 0.94},
        Case{"quad", MeshShape{quad}, 0.95}, Case{"quad clock", MeshShape{quad}, 0.95, true},
        Case{"lit box", Box{{4, 4, 4}}, 0.75, false, true},
        Case{"lit ball", Sphere{2.2}, 0.94, false, true},
        Case{"lit quad", MeshShape{quad}, 0.95, false, true}}) {
    SCOPED_TRACE(c.name);
    Scene s = test::load_repository_scene("lensed-clock.json");
    s.camera.height = s.camera.height * 320 / s.camera.width;
    s.camera.width = 320;
    Object& o = s.objects.front();
    o.shape = c.shape;
    if (!c.clock) o.material.pattern = Texture{grid};
    if (c.lit) {
      // Lit by a sun from above and beside the camera, its light bent by the hole.
      o.material.unlit = false;
      Light sun;
      sun.name = "sun";
      sun.kind = DirectionalLight{{-0.4, -0.5, -1}, 3};
      s.lights.push_back(sun);
    }
    EXPECT_EQ(raster_differences(s).size(), c.clock ? 0u : 1u);
    const Agreement a = compare(s, curved_body_shadows);
    const double bodies = static_cast<double>(a.body_within) / a.body_pixels;
    std::printf("lensed %s 320x180: bodies %.4f of %zu pixels (%zu of order 1)\n", c.name, bodies,
                a.body_pixels, a.secondary_pixels);
    EXPECT_GT(a.body_pixels, 150u);
    EXPECT_GE(bodies, c.least);
    EXPECT_GE(static_cast<double>(a.other_within) / a.other_pixels, 0.99);
  }
}

// Shadows near the hole (tests/data/hole-shadows.json): a slab held at r = 8 beside it, a ball
// held above the slab and a pebble on its orbit at 0.33c above both, lit by a sun whose light the
// hole bends: the ball and the pebble shadow the slab, the pebble the ball. The raster renderer
// lights each vertex with the tracer's Lighting, whose curved shadow paths meet the bodies as the
// tracer's do (frame/curved_bodies.hpp); lit edges are split until the colours along them lie
// within 1/128, so a shadow's edge is drawn to within a pixel, as an outline is. Without shadows
// a fifth of the bodies' pixels differ.
TEST(RasterHoleBodies, ShadowsMatchTheRayTracer) {
  SceneLoadReport report;
  const Scene s = load_scene_file(
      std::string(LIGHTCONE_SOURCE_DIR) + "/tests/data/hole-shadows.json", {}, report);
  EXPECT_TRUE(raster_differences(s).empty());
  // The chords of the shadow paths met through the tracer's Embree scenes, or directly (as the
  // browser's page meets them), or nothing casting shadows in the raster renderer.
  struct Case {
    const char* name;
    CurvedShadowSource source;
    bool shadows;
  };
  const CurvedShadowSource nothing = [](const ResolvedScene&) {
    return std::unique_ptr<CurvedShadowQuery>();
  };
  for (const Case& c : {Case{"through Embree", curved_body_shadows, true},
                        Case{"met directly", nullptr, true}, Case{"not cast", nothing, false}}) {
    SCOPED_TRACE(c.name);
    const Agreement a = compare(s, c.source);
    const double bodies = static_cast<double>(a.body_within) / a.body_pixels;
    std::printf("hole shadows %s: bodies %.4f of %zu pixels (%zu of order 1), the rest %.4f\n",
                c.name, bodies, a.body_pixels, a.secondary_pixels,
                static_cast<double>(a.other_within) / a.other_pixels);
    EXPECT_GT(a.body_pixels, 5000u);
    if (c.shadows)
      EXPECT_GE(bodies, 0.99);  // (measured: 0.994)
    else
      EXPECT_LT(bodies, 0.9);
  }
}

// A lit body falling toward the hole: its world-line's bound on ln g reaches the horizon, where
// the shift has none, and the colour rows once covered it (and the lights' rapidity relative to
// it, unbounded too), wider than any texture. The rows cover the vertices' shifts: the frame is
// drawn, and matches the tracer.
TEST(RasterHoleBodies, LitFallingBodyIsDrawn) {
  Scene s = test::scene_from_json(R"({
    "camera": {"position": [0, 6, 26], "forward": [7, -6, -26], "fov": 28,
               "width": 240, "height": 135, "samples": 1},
    "black_hole": {"mass": 1},
    "objects": [
      {"name": "pebble", "shape": {"sphere": {"radius": 1}},
       "motion": {"fall": {"from": 11.5, "direction": [10, 4.5, -1.5], "time": -28}},
       "material": {"color": [0.4, 0.7, 0.9], "unlit": false}}
    ],
    "lights": [{"name": "sun", "type": "directional", "direction": [-0.3, -1, -0.2],
                "irradiance": 4}],
    "render": {"exposure": -1, "tonemap": "filmic", "doppler": "rgb3"}
  })");
  const Agreement a = compare(s, curved_body_shadows);
  EXPECT_GT(a.body_pixels, 100u);
  EXPECT_GE(static_cast<double>(a.body_within) / a.body_pixels, 0.99);
}

// The accretion disk hides a body beyond it: a ball held below the disk's plane on the far side
// shows only its top above the disk, and a box on the near side above the plane hides the disk.
// Each body fragment follows its pixel's ray to the disk's first crossing (shaders/black_hole.glsl)
// and is left out where the disk is crossed at a smaller swept angle than the body's, as the
// tracer's follow_curved_ray meets a body only before the disk. The pixels the ball changes in
// each renderer's picture are the same but for its outline (7 of 291 differ; drawn in front of
// the disk, as the raster renderer once drew it, 1,200 would).
TEST(RasterHoleBodies, TheDiskHidesBodiesBeyondIt) {
  const char* json = R"({
    "camera": {"position": [0, 10.4189, 59.0885], "forward": [0, -0.17365, -0.98481],
               "fov": 22, "width": 480, "height": 270, "samples": 1},
    "black_hole": {"mass": 1,
                   "disk": {"inner": 6, "outer": 20, "temperature": 7000, "luminance": 1}},
    "objects": [
      {"name": "front", "shape": {"box": {"size": [2, 2, 2]}}, "position": [-9, 1.6, 14],
       "material": {"color": [0.9, 0.3, 0.9]}},
      {"name": "behind", "shape": {"sphere": {"radius": 2}}, "position": [9, -1.2, -16],
       "material": {"color": [0.2, 0.9, 0.3]}}
    ],
    "sky": {"color": [0.004, 0.005, 0.01]},
    "render": {"exposure": -1, "tonemap": "filmic"}
  })";
  Scene s = test::scene_from_json(json);
  EXPECT_TRUE(raster_differences(s).empty());
  const Agreement a = compare(s);
  std::printf("disk and bodies: bodies %.4f of %zu pixels, the rest %.4f of %zu\n",
              static_cast<double>(a.body_within) / a.body_pixels, a.body_pixels,
              static_cast<double>(a.other_within) / a.other_pixels, a.other_pixels);
  EXPECT_GE(static_cast<double>(a.body_within) / a.body_pixels, 0.99);
  EXPECT_GE(static_cast<double>(a.other_within) / a.other_pixels, 0.99);

  // The pixels the ball changes (by more than 4/255 in a channel), in each renderer.
  s.render.auto_exposure = false;
  Scene without = s;
  without.objects.pop_back();
  const auto changed = [](const Image& with_ball, const Image& without_ball) {
    std::vector<bool> out(with_ball.rgb.size() / 3);
    for (std::size_t i = 0; i < out.size(); ++i)
      for (int c = 0; c < 3; ++c)
        out[i] = out[i] ||
                 std::abs(level(with_ball.rgb[3 * i + c]) - level(without_ball.rgb[3 * i + c])) > 4;
    return out;
  };
  const std::vector<bool> traced = changed(render_image(s, {}), render_image(without, {}));
  const std::vector<bool> rastered = changed(render_raster(s), render_raster(without));
  std::size_t traced_count = 0, differing = 0;
  for (std::size_t i = 0; i < traced.size(); ++i) {
    traced_count += traced[i];
    differing += traced[i] != rastered[i];
  }
  std::printf("the ball changes %zu pixels in the tracer's picture; %zu differ\n", traced_count,
              differing);
  EXPECT_GT(traced_count, 40u);
  EXPECT_LE(differing, traced_count / 4);
}

// The angle a body's light swept about the hole (the disk hides what lies past its crossing):
// from the point met and the image's order alone, it is the angle the tracer's ray swept to the
// point along its path, on the clock behind the hole in both images.
TEST(RasterHoleBodies, SweptAngleIsTheTracersAlongThePath) {
  Scene s = test::load_repository_scene("lensed-clock.json");
  s.camera.height = s.camera.height * 320 / s.camera.width;
  s.camera.width = 320;
  const ResolvedScene resolved = resolve_scene(s);
  const Tracer tracer(resolved);
  const CurvedBodies bodies(resolved, tracer);
  const HoleView& hole = *resolved.hole;
  int met[2] = {0, 0};
  for (int y = 0; y < s.camera.height; y += 2)
    for (int x = 0; x < s.camera.width; x += 2) {
      const Vec3 u = look_direction(resolved.camera, x + 0.5, y + 0.5);
      const CurvedRay ray = follow_curved_ray(hole, u, &bodies);
      if (ray.end != CurvedRayEnd::kBody || ray.order > 1) continue;
      ++met[ray.order];
      EXPECT_NEAR(hole_swept_angle(ray.event.x - hole.centre, hole.outward, ray.order), ray.phi,
                  1e-9);
    }
  EXPECT_GT(met[0], 50);
  EXPECT_GT(met[1], 10);
}

// A lit ball's vertices start their lights' legs from the last ones solved, as the tracer's tiles
// do (some 5 evaluations of the sweep a leg where a cold solve takes 15): each light's start
// holds a solved leg afterwards, and the vertices are those solved cold (their colours within
// the legs' rounding; the same vertices).
TEST(RasterHoleBodies, LitVerticesStartTheirLegsFromTheLast) {
  Scene s = test::scene_from_json(R"({
    "camera": {"position": [0, 6, 40], "forward": [0, -0.15, -1], "fov": 45,
               "width": 320, "height": 180, "samples": 1},
    "black_hole": {"mass": 1},
    "objects": [{"name": "ball", "shape": {"sphere": {"radius": 1}}, "position": [7, 0.5, 2],
                 "material": {"color": [0.9, 0.8, 0.6], "unlit": false}}],
    "lights": [{"name": "lamp", "type": "point", "position": [-14, 10, 6], "intensity": 300},
               {"name": "sun", "type": "directional", "direction": [-1, -0.3, -0.2],
                "irradiance": 2}]
  })");
  const ResolvedScene resolved = resolve_scene(s);
  const EmissionTable emission(resolved);
  const Lighting lighting(resolved, nullptr);
  const Object& ball = s.objects[0];
  const RestMesh mesh = rest_mesh(ball.shape);
  const HoleWorldLine line = hole_world_line(*resolved.hole, ball);
  HoleLitBody lit{&lighting, 0, {&emission.object_colour(0, 0), &emission.object_colour(0, 0)}};
  for (int order = 0; order <= 1; ++order) {
    SCOPED_TRACE(order);
    std::vector<float> cold, warm;
    tessellate_hole_image(resolved, ball, line, mesh, order, {}, cold, &lit);
    HoleLegStarts starts;
    starts.begin_tile(1);
    HoleLitBody started = lit;
    started.leg_starts = &starts;
    tessellate_hole_image(resolved, ball, line, mesh, order, {}, warm, &started);
    for (std::size_t light = 0; light < 2; ++light)
      for (int leg = 0; leg < HoleLegStarts::kOrders; ++leg) {
        EXPECT_GT(starts.at(0, light, leg).rate, 0) << light << " " << leg;
      }
    ASSERT_EQ(warm.size(), cold.size());
    ASSERT_GT(cold.size(), 1000u);
    for (std::size_t i = 0; i < cold.size(); ++i)
      ASSERT_NEAR(warm[i], cold[i], 1e-6 * std::max(1.0f, std::abs(cold[i]))) << i;
  }
}

}  // namespace
}  // namespace lightcone

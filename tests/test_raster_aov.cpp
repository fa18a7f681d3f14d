// The raster renderer's output variables (render_raster's aovs) are the ray tracer's: per pixel
// the same object, and on it the same emission time, distance, depth, normal and Doppler
// factor, within the raster's tessellation, in flat space and near a black hole.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "lightcone/frame/output_variable.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

const std::vector<Aov> kEveryAov = {Aov::kDoppler,   Aov::kEmissionTime, Aov::kDistance,
                                    Aov::kObject,    Aov::kDepth,        Aov::kNormal,
                                    Aov::kImageOrder};

const std::vector<float>& channel(const Image& image, const std::string& name) {
  for (const NamedChannel& c : image.channels)
    if (c.name == name) return c.values;
  throw std::runtime_error("no channel " + name);
}

// How the two renderers' variables compare over a picture.
struct AovComparison {
  std::size_t pixels = 0;
  std::size_t object_differs = 0;  // pixels whose object (or sky) differs
  std::size_t surface = 0;         // pixels where both met the same body
  // Of those, pixels where the two met the body at different points: the distances differ by
  // over `apart` of it, or the normals by over `apart` in 1 - cos, as where a pixel's centre
  // lies on a box's edge, or on a moving spinning mesh (body.frag meets it by Newton's method
  // on the face the rasteriser drew).
  std::size_t point_differs = 0;
  // The largest differences on the rest: relative in distance, depth and the Doppler factor, in
  // emission time against the distance (the light's travel time), and in the normal's angle
  // (1 - cos).
  double distance = 0, depth = 0, emission_time = 0, doppler = 0, normal = 0;
  // Pixels of the sky (a black hole's disk and shadow too) whose values differ by over 1e-5.
  std::size_t sky_differs = 0;
};

AovComparison compare(const Image& traced, const Image& rastered, double apart = 1e-3) {
  AovComparison c;
  const auto& object_t = channel(traced, "object");
  const auto& object_r = channel(rastered, "object");
  c.pixels = object_t.size();
  for (std::size_t i = 0; i < c.pixels; ++i) {
    auto value = [&](const Image& image, const char* name) {
      return static_cast<double>(channel(image, name)[i]);
    };
    auto relative = [&](const char* name) {
      return std::abs(value(traced, name) - value(rastered, name)) / std::abs(value(traced, name));
    };
    if (object_t[i] != object_r[i]) {
      ++c.object_differs;
      continue;
    }
    if (object_t[i] < 0) {
      for (const char* name :
           {"doppler", "emission_time", "distance", "depth", "normal.X", "image_order"})
        if (!(value(traced, name) == value(rastered, name) || relative(name) <= 1e-5)) {
          ++c.sky_differs;
          break;
        }
      continue;
    }
    ++c.surface;
    double cosine = 0;
    for (const char* axis : {"normal.X", "normal.Y", "normal.Z"})
      cosine += value(traced, axis) * value(rastered, axis);
    if (relative("distance") > apart || 1 - cosine > apart) {
      ++c.point_differs;
      continue;
    }
    c.distance = std::max(c.distance, relative("distance"));
    c.depth = std::max(c.depth, relative("depth"));
    c.doppler = std::max(c.doppler, relative("doppler"));
    c.emission_time = std::max(c.emission_time, std::abs(value(traced, "emission_time") -
                                                         value(rastered, "emission_time")) /
                                                    value(traced, "distance"));
    c.normal = std::max(c.normal, 1 - cosine);
  }
  return c;
}

void print(const std::string& what, const AovComparison& c) {
  std::printf(
      "%s: %zu pixels, object differs on %zu, %zu on the same body, %zu of them at another "
      "point; on the rest the largest relative distance %.2g, depth %.2g, Doppler %.2g, "
      "emission time %.2g of the distance, normal 1 - cos %.2g; sky differs on %zu\n",
      what.c_str(), c.pixels, c.object_differs, c.surface, c.point_differs, c.distance, c.depth,
      c.doppler, c.emission_time, c.normal, c.sky_differs);
}

Image traced(const Scene& scene) {
  RenderOptions options;
  options.aovs = kEveryAov;
  return render_image(scene, options);
}

Image rastered(const Scene& scene, RasterTessellation mode = RasterTessellation::kAuto) {
  return render_raster(scene, nullptr, {}, 0, mode, {}, nullptr, kEveryAov);
}

// terrell.json: a checkered ball and box crossing the view at 0.9c over a floor, at rest.
TEST(RasterAov, AMovingBallAndBoxAsTheRayTracerGivesThem) {
  Scene scene = test::load_repository_scene("terrell.json");
  scene.camera.width = 320;
  scene.camera.height = 180;
  scene.camera.samples = 1;
  const Image t = traced(scene), r = rastered(scene);
  ASSERT_EQ(r.channels.size(), t.channels.size());
  for (std::size_t i = 0; i < t.channels.size(); ++i)
    EXPECT_EQ(r.channels[i].name, t.channels[i].name);
  const AovComparison c = compare(t, r);
  print("terrell.json at 320 x 180", c);
  EXPECT_GT(c.surface, c.pixels / 2);
  // Along the outlines, where the tessellated edge lies up to half a pixel inside the true one
  // (56 of 57600 pixels).
  EXPECT_LE(c.object_differs, c.pixels / 500);
  // The fragment meets its surface in single precision: 1.5e-5 of the distance on the floor.
  EXPECT_LE(c.distance, 1e-4);
  EXPECT_LE(c.depth, 1e-4);
  EXPECT_LE(c.doppler, 1e-5);
  EXPECT_LE(c.emission_time, 1e-4);
  EXPECT_LE(c.normal, 1e-6);
  EXPECT_LE(c.point_differs, c.pixels / 1000);
  EXPECT_EQ(c.sky_differs, 0u);
}

// The same with the edges cut on the GPU, by tessellation shaders (a GPU's path by default):
// its coarser outlines differ on 88 pixels.
TEST(RasterAov, TessellatedOnTheGpuToo) {
  Scene scene = test::load_repository_scene("terrell.json");
  scene.camera.width = 320;
  scene.camera.height = 180;
  scene.camera.samples = 1;
  const AovComparison c = compare(traced(scene), rastered(scene, RasterTessellation::kGpu));
  print("terrell.json at 320 x 180, tessellated on the GPU", c);
  EXPECT_GT(c.surface, c.pixels / 2);
  EXPECT_LE(c.object_differs, c.pixels / 500);
  EXPECT_LE(c.distance, 1e-4);
  EXPECT_LE(c.normal, 1e-6);
  EXPECT_LE(c.point_differs, c.pixels / 1000);
  EXPECT_EQ(c.sky_differs, 0u);
}

// Lit, spinning and textured bodies, meshes and boxes, with relativity and in the classical
// picture.
TEST(RasterAov, EveryKindOfBody) {
  for (const char* name : {"street-lit.json", "wheel.json", "texture-mapping.json", "cubes.json"}) {
    for (const bool relativity : {true, false}) {
      SCOPED_TRACE(std::string(name) + (relativity ? "" : ", classical"));
      Scene scene = test::load_repository_scene(name);
      scene.camera.width = 320;
      scene.camera.height = 180;
      scene.camera.samples = 1;
      scene.camera.shutter = 0;
      scene.render.relativity = relativity;
      scene.render.light_delay = relativity;
      const AovComparison c = compare(traced(scene), rastered(scene));
      print(name, c);
      EXPECT_GT(c.surface, c.pixels / 10);
      EXPECT_LE(c.object_differs, c.pixels / 500);
      // On the wheel spinning at relativistic speed 36 of 57600 (its normal turned with its spin
      // as its lighting takes it, 567 without).
      EXPECT_LE(c.point_differs, c.pixels / 500);
      EXPECT_LE(c.distance, 1e-4);
      EXPECT_LE(c.depth, 1e-4);
      EXPECT_LE(c.emission_time, 1e-4);
      // The classical picture's Doppler factor is 1, a spinning body's too.
      EXPECT_LE(c.doppler, 1e-5);
      EXPECT_LE(c.normal, 1e-6);
      EXPECT_EQ(c.sky_differs, 0u);
    }
  }
}

// Near a black hole: a ball behind the hole, seen over it and (order 1) under it, a moving box
// before it, the disk, the shadow and the sky.
TEST(RasterAov, ABallBehindTheHoleAndTheDisk) {
  Scene scene = test::scene_from_json(R"({
    "camera": {"position": [0, 3, 30], "time": 4, "fov": 40, "width": 320, "height": 180,
               "samples": 1},
    "black_hole": {"mass": 1, "disk": {"inner": 6, "outer": 12}},
    "objects": [{"name": "ball", "shape": {"sphere": {"radius": 3}}, "position": [1, 5, -20]},
                {"name": "crate", "shape": {"box": {"size": [2, 2, 2]}}, "position": [-2, 2, 2],
                 "velocity": [0.2, 0, 0]}]
  })");
  const Image t = traced(scene), r = rastered(scene);
  // The raster renderer's images near the hole are interpolated between exact vertices, the
  // edges split until the drawing lies within half a pixel of the image: on the ball's thin arc
  // over the hole the surface point at a pixel lies up to 0.9 % of the distance off the exact
  // one (its normal 9 degrees, 1 - cos 0.013), as its colour's does.
  const AovComparison c = compare(t, r, 0.02);
  print("a ball behind the hole at 320 x 180", c);
  for (const float code : {0.0f, 1.0f, kObjectDisk, kObjectShadow, kObjectSky})
    EXPECT_GT(std::count(channel(r, "object").begin(), channel(r, "object").end(), code), 50)
        << code;
  // The ball's image under the hole, round its far side, as well as the disk's.
  const auto& order = channel(r, "image_order");
  const auto& object = channel(r, "object");
  std::size_t ball_round_the_far_side = 0;
  for (std::size_t i = 0; i < order.size(); ++i)
    ball_round_the_far_side += object[i] == 0 && order[i] == 1;
  EXPECT_GT(ball_round_the_far_side, 20u);
  EXPECT_LE(c.object_differs, c.pixels / 1000);
  EXPECT_EQ(c.point_differs, 0u);
  EXPECT_LE(c.distance, 0.01);
  EXPECT_LE(c.depth, 0.01);
  EXPECT_LE(c.emission_time, 0.01);
  EXPECT_LE(c.doppler, 1e-3);
  EXPECT_LE(c.normal, 0.02);
  // The disk, the shadow and the sky: the same curved rays.
  EXPECT_EQ(c.sky_differs, 0u);
}

}  // namespace
}  // namespace lightcone

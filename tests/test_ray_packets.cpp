// The tracer's ray packets find what single rays find: for every kind of body (analytic shapes
// and meshes, at rest and moving, spinning), seen from a camera at rest and one in flight and in
// the simultaneous picture, trace(directions, hits) equals trace(u) ray by ray, in every lane of
// full and partial packets. Camera rays through the image's bins find what the BVH alone finds.
#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

using test::make_object;
using test::solid;

// An octahedron of radius 1.
std::shared_ptr<const Mesh> octahedron() {
  auto mesh = std::make_shared<Mesh>();
  mesh->positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  mesh->triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                     {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return mesh;
}

Scene mixed_scene() {
  Scene s;
  s.camera.width = 67;  // not a multiple of the packet's width or height
  s.camera.height = 45;
  s.camera.fov_degrees = 60;
  const Material white = solid({1, 1, 1});
  s.objects.push_back(make_object("ball", Sphere{0.8}, {-2, 0.5, -6}, {0.7, 0, 0}, white));
  s.objects.push_back(make_object("box", Box{{1, 1.5, 0.7}}, {0.5, -1, -5}, {}, white));
  s.objects.push_back(make_object("floor", Plane{20, 20}, {0, -2, -6}, {0, 0, 0.3}, white));
  s.objects.push_back(make_object("still mesh", MeshShape{octahedron()}, {2, 1, -7}, {}, white));
  s.objects.push_back(
      make_object("fast mesh", MeshShape{octahedron()}, {-0.5, 1.5, -5}, {-0.9, 0, 0}, white));
  Object spinning =
      make_object("spinning mesh", MeshShape{octahedron()}, {1.5, -0.3, -4}, {0, 0.3, 0}, white);
  spinning.spin = Spin{normalize(Vec3{0.3, 1, 0.2}), 0.6};
  s.objects.push_back(spinning);
  // Each is seen near its position: light left it there about that far back in time.
  for (Object& o : s.objects) o.world_line.time = -length(o.world_line.position);
  return s;
}

void expect_same_hit(const std::optional<Hit>& single, const std::optional<Hit>& packet,
                     const std::string& where) {
  ASSERT_EQ(single.has_value(), packet.has_value()) << where;
  if (!single) return;
  EXPECT_EQ(single->body, packet->body) << where;
  EXPECT_EQ(single->s, packet->s) << where;
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(single->shape_point[k], packet->shape_point[k]) << where;
    EXPECT_EQ(single->shape_normal[k], packet->shape_normal[k]) << where;
    EXPECT_EQ(single->velocity[k], packet->velocity[k]) << where;
  }
  EXPECT_EQ(single->uv, packet->uv) << where;
  EXPECT_EQ(single->proper_time, packet->proper_time) << where;
  EXPECT_EQ(single->spin_angle, packet->spin_angle) << where;
}

TEST(RayPackets, FindWhatSingleRaysFind) {
  struct View {
    const char* name;
    Vec3 camera_velocity;
    bool simultaneous;
  } views[] = {{"camera at rest", {}, false},
               {"camera in flight", {0.3, -0.1, -0.6}, false},
               {"simultaneous picture", {0.2, 0, 0}, true}};
  for (const View& view : views) {
    Scene s = mixed_scene();
    s.camera.world_line.velocity = view.camera_velocity;
    s.render.light_delay = !view.simultaneous;
    const ResolvedScene resolved = resolve_scene(s);
    const Tracer tracer(resolved);
    std::vector<Vec3> directions;
    for (int j = 0; j < s.camera.height; ++j)
      for (int i = 0; i < s.camera.width; ++i)
        directions.push_back(look_direction(resolved.camera, i + 0.5, j + 0.5));
    // One call over the whole image, and runs of awkward lengths that leave packets partly
    // empty.
    std::vector<std::optional<Hit>> whole(directions.size());
    tracer.trace(directions, whole);
    std::vector<std::optional<Hit>> runs(directions.size());
    for (std::size_t first = 0, length = 1; first < directions.size();
         first += length, length = length % 13 + 1) {
      const std::size_t count = std::min(length, directions.size() - first);
      tracer.trace(std::span(directions).subspan(first, count),
                   std::span(runs).subspan(first, count));
    }
    std::vector<int> hits_per_body(resolved.bodies.size(), 0);
    for (std::size_t r = 0; r < directions.size(); ++r) {
      const std::optional<Hit> single = tracer.trace(directions[r]);
      const std::string where = std::string(view.name) + ", ray " + std::to_string(r);
      expect_same_hit(single, whole[r], where + " (whole image)");
      expect_same_hit(single, runs[r], where + " (runs)");
      if (single) ++hits_per_body[single->body];
    }
    // Every body is seen, so every kind of intersection was compared.
    for (std::size_t b = 0; b < hits_per_body.size(); ++b)
      EXPECT_GT(hits_per_body[b], 10) << view.name << ", " << resolved.bodies[b].object->name;
  }
}

// Rays through the view and beyond it, and behind the camera (those the bins do not cover).
std::vector<Vec3> view_and_beyond(const ResolvedScene& r) {
  std::vector<Vec3> directions;
  const CameraBasis& c = r.camera;
  for (int j = -4; j < c.height + 4; ++j)
    for (int i = -4; i < c.width + 4; ++i)
      directions.push_back(look_direction(c, i + 0.5, j + 0.5));
  for (int k = 0; k < 500; ++k) {
    const double z = 1 - 2 * (k + 0.5) / 500, phi = 2.399963 * k;  // a spiral over the sphere
    const double rho = std::sqrt(1 - z * z);
    directions.push_back({rho * std::cos(phi), rho * std::sin(phi), z});
  }
  return directions;
}

// The bins and the BVH agree on the body met and where, for every ray; the still mesh is an
// Embree instance in the BVH (a float transform), so its points agree to float rounding.
void expect_bins_find_what_the_bvh_finds(const Scene& s, const std::string& name) {
  const ResolvedScene resolved = resolve_scene(s);
  const Tracer bins(resolved), bvh(resolved, ShadowBounds::kLabelled, CameraRays::kBvh);
  const std::vector<Vec3> directions = view_and_beyond(resolved);
  std::vector<std::optional<Hit>> by_bins(directions.size()), by_bvh(directions.size());
  bins.trace(directions, by_bins);
  bvh.trace(directions, by_bvh);
  int hits = 0;
  for (std::size_t r = 0; r < directions.size(); ++r) {
    const std::string where = name + ", ray " + std::to_string(r);
    ASSERT_EQ(by_bins[r].has_value(), by_bvh[r].has_value()) << where;
    if (!by_bins[r]) continue;
    ++hits;
    EXPECT_EQ(by_bins[r]->body, by_bvh[r]->body) << where;
    EXPECT_NEAR(by_bins[r]->s, by_bvh[r]->s, 1e-5 * by_bvh[r]->s) << where;
    EXPECT_NEAR(by_bins[r]->proper_time, by_bvh[r]->proper_time,
                1e-5 * (1 + std::abs(by_bvh[r]->proper_time)))
        << where;
  }
  EXPECT_GT(hits, static_cast<int>(directions.size() / 4)) << name;
}

TEST(RayPackets, ImageBinsFindWhatTheBvhFinds) {
  Scene s = mixed_scene();
  expect_bins_find_what_the_bvh_finds(s, "camera at rest");
  s.camera.world_line.velocity = {0.3, -0.1, -0.6};
  expect_bins_find_what_the_bvh_finds(s, "camera in flight");
  s.render.light_delay = false;
  expect_bins_find_what_the_bvh_finds(s, "simultaneous picture");
}

// A crowd about the camera: bodies beside and behind it, fast ones, and near ones covering
// most of the image, too many to list cell by cell (the BVH takes those).
TEST(RayPackets, ImageBinsFindWhatTheBvhFindsInACrowdAboutTheCamera) {
  Scene s;
  s.camera.width = 48;
  s.camera.height = 32;
  s.camera.fov_degrees = 100;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  for (int k = 0; k < 300; ++k) {
    const Vec3 at{4 * uniform(random), 4 * uniform(random), 4 * uniform(random)};
    if (length(at) < 1.5) continue;
    const Vec3 v{0.6 * uniform(random), 0.6 * uniform(random), 0.6 * uniform(random)};
    const Shape shape = k % 3 == 0   ? Shape{Sphere{0.3 + 0.9 * std::abs(uniform(random))}}
                        : k % 3 == 1 ? Shape{Box{{1.5, 1.2, 1.6}}}
                                     : Shape{MeshShape{octahedron()}};
    s.objects.push_back(make_object("body " + std::to_string(k), shape, at, v, solid({1, 1, 1})));
  }
  // Large balls farther off, each covering most of the image.
  for (int k = 0; k < 40; ++k)
    s.objects.push_back(make_object("large " + std::to_string(k), Sphere{3},
                                    {uniform(random), uniform(random), -7 - uniform(random)},
                                    {0.6 * uniform(random), 0, 0}, solid({1, 1, 1})));
  // A wall from behind the camera to before it, at the image's right.
  s.objects.push_back(make_object("wall", Box{{0.2, 3, 8}}, {1.2, 0, 0}, {}, solid({1, 1, 1})));
  for (Object& o : s.objects) o.world_line.time = -length(o.world_line.position);
  expect_bins_find_what_the_bvh_finds(s, "crowd");
}

}  // namespace
}  // namespace lightcone

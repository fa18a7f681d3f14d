// Chords of curved rays near a black hole meet bodies through BodySegments: the ray tracer's on
// Embree, or DirectBodySegments where there is no Embree (the browser's page). On random
// segments through each kind of shape both find the same first point: analytic shapes by the
// same closed forms, meshes (a generated octahedron and the bundled wheel, 1,056 triangles) to
// Embree's single precision, on the same triangle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include "lightcone/frame/body_segments.hpp"
#include "lightcone/frame/mesh_bvh.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

using test::make_object;
using test::solid;

TEST(BodySegments, DirectSegmentsMeetBodiesWhereTheTracersDo) {
  auto octahedron = std::make_shared<Mesh>();
  octahedron->positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  octahedron->triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                           {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  const Scene wheel = test::load_repository_scene("wheel.json");
  Scene s;
  const Material white = solid({1, 1, 1});
  s.objects.push_back(make_object("ball", Sphere{0.8}, {-2, 0.5, -6}, {0.7, 0, 0}, white));
  s.objects.push_back(make_object("box", Box{{1, 1.5, 0.7}}, {0.5, -1, -5}, {}, white));
  s.objects.push_back(make_object("floor", Plane{4, 3}, {0, -2, -6}, {0, 0, 0.3}, white));
  s.objects.push_back(
      make_object("octahedron", MeshShape{octahedron}, {2, 1, -7}, {-0.5, 0, 0}, white));
  s.objects.push_back(make_object("wheel", wheel.objects[0].shape, {-1, 1, -4}, {}, white));
  const ResolvedScene resolved = resolve_scene(s);
  const Tracer tracer(resolved);
  const DirectBodySegments direct(resolved);

  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> within(-1.0, 1.0);
  const double reach[] = {1.5, 1.5, 2.5, 1.5, 1.5};  // past each body, in its shape coordinates
  for (int body = 0; body < 5; ++body) {
    SCOPED_TRACE(s.objects[body].name);
    const bool mesh = std::holds_alternative<MeshShape>(s.objects[body].shape);
    int met = 0, differ = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec3 from{reach[body] * within(random), reach[body] * within(random),
                      reach[body] * within(random)};
      const Vec3 to{reach[body] * within(random), reach[body] * within(random),
                    reach[body] * within(random)};
      const auto embree = tracer.body_on_shape_segment(body, from, to);
      const auto own = direct.body_on_shape_segment(body, from, to);
      if (embree.has_value() != own.has_value()) {
        ++differ;  // a segment that grazes an edge or ends on the surface, within rounding
        continue;
      }
      if (!own) continue;
      ++met;
      if (mesh) {
        EXPECT_NEAR(own->s, embree->s, 2e-6 * (1 + length(to - from)));
        if (own->prim != embree->prim) ++differ;  // only across an edge, within rounding
      } else {
        EXPECT_EQ(own->s, embree->s);
      }
    }
    std::printf("%s: %d of 20000 segments met, %d differ\n", s.objects[body].name.c_str(), met,
                differ);
    EXPECT_GT(met, 3000);
    EXPECT_LE(differ, mesh ? 10 : 0);
  }
}

// A mesh's hierarchy (exact shadows, segments met directly): every triangle in one leaf, every
// leaf's box holding its triangles and every inner box its children's, leaves of at most four
// triangles, and a depth the traversal stacks hold (median splits: about log2 of the leaves).
TEST(MeshBvh, HoldsEveryTriangleOnce) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-5, 5);
  Mesh mesh;
  for (int i = 0; i < 3000; ++i)
    mesh.positions.push_back({coordinate(random), coordinate(random), coordinate(random)});
  std::uniform_int_distribution<std::uint32_t> vertex(0, 2999);
  for (int i = 0; i < 5001; ++i)
    mesh.triangles.push_back({vertex(random), vertex(random), vertex(random)});
  const MeshBvh bvh = build_mesh_bvh(mesh);
  std::vector<int> seen(mesh.triangles.size(), 0);
  const auto holds = [](const MeshBvh::Node& n, const Vec3& p) {
    for (int i = 0; i < 3; ++i)
      if (p[i] < n.lower[i] || p[i] > n.upper[i]) return false;
    return true;
  };
  for (std::size_t k = 0; k < bvh.nodes.size(); ++k) {
    const MeshBvh::Node& n = bvh.nodes[k];
    if (n.count == 0) {
      for (const std::size_t child : {k + 1, static_cast<std::size_t>(n.second)}) {
        ASSERT_LT(child, bvh.nodes.size());
        EXPECT_TRUE(holds(n, bvh.nodes[child].lower) && holds(n, bvh.nodes[child].upper));
      }
      continue;
    }
    EXPECT_LE(n.count, 4);
    for (int i = n.first; i < n.first + n.count; ++i) {
      const std::uint32_t t = bvh.order[static_cast<std::size_t>(i)];
      ++seen[t];
      for (const std::uint32_t v : mesh.triangles[t]) EXPECT_TRUE(holds(n, mesh.positions[v]));
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(seen.size()));
  EXPECT_LE(bvh.depth, 12);  // 5001 triangles: 11 halvings to leaves of four or fewer
}

}  // namespace
}  // namespace lightcone

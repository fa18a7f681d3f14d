// Chords of curved rays near a black hole meet bodies through BodySegments: the ray tracer's on
// Embree, or DirectBodySegments where there is no Embree (the browser's page). On random
// segments through each kind of shape both find the same first point: analytic shapes by the
// same closed forms, meshes (a generated octahedron and the bundled wheel, 1,056 triangles) to
// Embree's single precision, on the same triangle.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include "lightcone/frame/body_segments.hpp"
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

}  // namespace
}  // namespace lightcone

// first_straight_hit, the probes' way to the first body a straight camera ray meets without
// Embree, finds what the ray tracer finds (Tracer::trace): the same body, the same point and
// event, clock, velocity and normal, over a grid of rays through scenes of moving boxes and
// spheres, meshes, and a spinning mesh (the wheel).
#include <gtest/gtest.h>

#include <string>

#include "lightcone/frame/body_segments.hpp"
#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/straight_hit.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

TEST(StraightHit, FindsWhatTheRayTracerFinds) {
  for (const char* name : {"terrell.json", "street.json", "wheel.json", "cubes.json"}) {
    SCOPED_TRACE(name);
    const Scene scene = test::load_repository_scene(name);
    const ResolvedScene resolved = resolve_scene(scene);
    const Tracer tracer(resolved);
    const DirectBodySegments segments(resolved);
    int hits = 0, skies = 0;
    const int columns = 48, rows = 27;
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < columns; ++i) {
        const double x = (i + 0.37) * scene.camera.width / columns;
        const double y = (j + 0.61) * scene.camera.height / rows;
        SCOPED_TRACE(std::to_string(x) + ", " + std::to_string(y));
        const Vec3 u = look_direction(resolved.camera, x, y);
        const std::optional<Hit> traced = tracer.trace(u);
        const std::optional<Hit> direct = first_straight_hit(resolved, segments, u);
        ASSERT_EQ(direct.has_value(), traced.has_value());
        if (!traced) {
          ++skies;
          continue;
        }
        ++hits;
        // The tracer meets meshes in Embree's single precision; analytic shapes in double.
        const double size = resolved.bodies[traced->body].radius;
        EXPECT_EQ(direct->body, traced->body);
        EXPECT_NEAR(direct->s, traced->s, 1e-5 * traced->s);
        EXPECT_LT(length(direct->shape_point - traced->shape_point), 1e-4 * size);
        EXPECT_NEAR(direct->proper_time, traced->proper_time, 1e-5 * traced->s);
        EXPECT_LT(length(direct->velocity - traced->velocity), 1e-5);
        EXPECT_GT(dot(direct->shape_normal, traced->shape_normal), 0.999);
        EXPECT_NEAR(direct->spin_angle, traced->spin_angle, 1e-5);
      }
    EXPECT_GT(hits, 50);
    if (std::string(name) != "street.json") EXPECT_GT(skies, 50);
  }
}

}  // namespace
}  // namespace lightcone

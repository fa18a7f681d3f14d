// The bounds shadow rays are culled with: a labelled light's boxes (interpolated between label
// steps) hold every event where its light can meet a body, checked against each body point's own
// world-line crossing the light's cones or wavefronts; every label Lighting asks with lies in its
// light's range; a lit scene of fast bodies renders the same through the labelled bounds as
// through the swept ones, pixel for pixel; and shadow rays asked together (the renderer's
// packets) find what each finds alone.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <random>
#include <set>
#include <vector>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/lighting.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/sampler.hpp"
#include "lightcone/physics/retarded_time.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/tracer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

using test::make_object;

using test::lit;

Light light_of(std::variant<PointLight, SpotLight, DirectionalLight, SphereLight> kind,
               Vec3 position, Vec3 velocity, double intensity) {
  Light l;
  l.name = "light";
  l.kind = kind;
  l.world_line.position = position;
  l.world_line.velocity = velocity;
  l.intensity = intensity;
  return l;
}

// Fast lit bodies of every shape over a ground, a camera in motion, and lights of every kind:
// a point light at 0.6c, a sphere light, a spot light, and a sun that moves.
Scene fast_lit_scene() {
  Scene s;
  s.camera.world_line.position = {0, 5, 6};
  s.camera.forward = normalize(Vec3{0, -0.6, -1});
  s.camera.world_line.velocity = {0.2, 0, -0.3};
  s.camera.width = 96;
  s.camera.height = 64;
  s.camera.fov_degrees = 75;
  s.render.light_source_delay = LightSourceDelay::kSurface;
  s.render.shadows = true;
  s.objects.push_back(
      make_object("ground", Plane{40, 40}, {0, -1, -4}, {}, lit({0.8f, 0.8f, 0.8f})));
  const std::vector<Vec3> velocities = {{0.99, 0, 0},    {0, 0, 0.95},     {0, 0, -0.95},
                                        {0.5, 0.5, 0.5}, {-0.7, 0.1, 0.6}, {0, 0, 0}};
  for (std::size_t i = 0; i < velocities.size(); ++i) {
    const Shape shape = i % 2 ? Shape{Box{{1.2, 0.8, 1.5}}} : Shape{Sphere{0.7}};
    Object o = make_object("body" + std::to_string(i), shape, {-5.0 + 2 * i, 0.2, -2.0 - i},
                           velocities[i], lit({0.9f, 0.6f, 0.3f}));
    // Where the camera sees it: about its light travel time before the observation.
    o.world_line.time = -length(o.world_line.position - s.camera.world_line.position);
    o.rotation = Mat3::rotation({1, 2, 3}, 0.4 * i);
    s.objects.push_back(o);
  }
  Light flyer = light_of(PointLight{}, {-1, 5, -2}, {0.6, 0, 0.1}, 12);
  flyer.world_line.time = -10;
  s.lights.push_back(flyer);
  s.lights.push_back(light_of(SphereLight{0.8}, {4, 6, 2}, {0, -0.3, 0}, 15));
  SpotLight spot;
  spot.direction = {0, -1, -0.3};
  spot.cone_degrees = 90;
  s.lights.push_back(light_of(spot, {0, 7, -3}, {}, 15));
  DirectionalLight sun;
  sun.direction = normalize(Vec3{0.4, -1, -0.3});
  sun.irradiance = 0.3;
  s.lights.push_back(light_of(sun, {}, {0.3, 0, 0}, 1));
  return s;
}

// The box Embree uses at label `label`: the step boxes on either side, interpolated.
Bounds3 interpolated(const LabelledBounds& bounds, const ShadowLight& light, unsigned steps,
                     double label) {
  const double width = (light.label_max - light.label_min) / (steps - 1);
  const double at = std::clamp((label - light.label_min) / width, 0.0, steps - 1.0);
  const auto step = std::min(static_cast<unsigned>(at), steps - 2);
  const double f = at - step;
  const Bounds3 a = label_step_bounds(bounds, light, steps, step);
  const Bounds3 b = label_step_bounds(bounds, light, steps, step + 1);
  Bounds3 box;
  for (int k = 0; k < 3; ++k) {
    box.lower[k] = (1 - f) * a.lower[k] + f * b.lower[k];
    box.upper[k] = (1 - f) * a.upper[k] + f * b.upper[k];
  }
  return box;
}

TEST(LabelledShadowBounds, HoldEveryEventWhereALightsRaysMeetABody) {
  const Scene s = fast_lit_scene();
  const ResolvedScene r = resolve_scene(s);
  ASSERT_EQ(r.shadow_lights.size(), s.lights.size());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1), fraction(0, 1);
  const auto in_ball = [&]() {
    Vec3 p;
    do p = {unit(rng), unit(rng), unit(rng)};
    while (dot(p, p) > 1);
    return p;
  };
  long long checked = 0;
  for (std::size_t l = 0; l < s.lights.size(); ++l) {
    const ShadowLight& light = r.shadow_lights[l];
    ASSERT_TRUE(light.labelled) << "light " << l;
    for (const ResolvedBody& body : r.bodies) {
      const LabelledBounds bounds = labelled_bounds(r, body, light);
      const AffineMap4 world_to_body = body_frame_map(s.render, body.object->world_line);
      // 17: the tracer's, for a point-type light (8 parts of its labels, 3 steps each).
      for (const unsigned steps : {2u, 9u, 17u}) {
        for (int sample = 0; sample < 400; ++sample) {
          const double label =
              light.label_min + (light.label_max - light.label_min) * fraction(rng);
          // A point of the ball that holds the body, on its own world-line in W.
          const TraceWorldLine point =
              trace_world_line(world_to_body, body.rest_centre + in_ball() * body.radius);
          double t;
          if (light.directional()) {
            // The wavefront of phase `label`: t - n.x(t) = label.
            t = (label + dot(light.direction, point.position_at_zero)) /
                (1 - dot(light.direction, point.velocity));
          } else {
            // Light from an emission point at W-time `label` reaches it at the end of the
            // retarded delay, run forwards: |x(label + tau) - e| = tau.
            const Vec3 emitted = light.line.position_at_zero + light.line.velocity * label +
                                 in_ball() * light.extent;
            const Vec3 x_then = point.position_at_zero + point.velocity * label;
            t = label + retarded_delay(x_then - emitted, -1.0 * point.velocity);
          }
          const Vec3 x = point.position_at_zero + point.velocity * t;
          const Bounds3 box = interpolated(bounds, light, steps, label);
          const double slack = 1e-9 * (1 + length(x));
          for (int k = 0; k < 3; ++k) {
            EXPECT_GE(x[k], box.lower[k] - slack) << "light " << l << " steps " << steps;
            EXPECT_LE(x[k], box.upper[k] + slack) << "light " << l << " steps " << steps;
          }
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 4 * 7 * 3 * 400);
}

TEST(LabelledShadowBounds, ChordGapBoundsHowFarTheNormLiesBelowItsChord) {
  // D(sigma) = |a + b sigma| sampled finely between two labels: its chord never lies more than
  // chord_gap above it, and the bound is met (the gap is exact, up to rounding's reach).
  LabelledBounds bounds;
  bounds.b = {0.6, -0.2, 0.9};
  for (const Vec3 a : {Vec3{3, 1, -2}, Vec3{-0.6, 0.2, -0.9}, Vec3{0.1, 5, 0}}) {
    bounds.early_a = bounds.late_a = a;
    for (const auto& [lo, hi] : {std::pair{-4.0, 3.0}, std::pair{0.5, 0.7}, std::pair{2.0, 9.0}}) {
      const double gap = bounds.chord_gap(lo, hi);
      const double d_lo = length(a + bounds.b * lo), d_hi = length(a + bounds.b * hi);
      double most = 0;
      for (int i = 0; i <= 100000; ++i) {
        const double f = i / 100000.0, sigma = lo + (hi - lo) * f;
        most = std::max(most, (1 - f) * d_lo + f * d_hi - length(a + bounds.b * sigma));
      }
      EXPECT_LE(most, gap);
      // Met to within the sampling's reach (|b| times the spacing, at a vertex where D = 0).
      EXPECT_NEAR(most, gap, length(bounds.b) * (hi - lo) / 1e5 + 1e-6 * gap);
    }
  }
}

// Forwards to a tracer and checks the labels Lighting asks with.
class CheckedShadows : public ShadowQuery {
 public:
  CheckedShadows(const ResolvedScene& scene, const Tracer& tracer)
      : scene_(scene), tracer_(tracer) {}
  void occluded(std::span<const ShadowRay> rays, std::span<bool> blocked) const override {
    for (const ShadowRay& ray : rays) {
      ++asked_;
      const ShadowLight& light = scene_.shadow_lights.at(ray.light);
      if (ray.label < light.label_min || ray.label > light.label_max) ++outside_;
    }
    tracer_.occluded(rays, blocked);
  }
  long long asked() const { return asked_; }
  long long outside() const { return outside_; }

 private:
  const ResolvedScene& scene_;
  const Tracer& tracer_;
  mutable std::atomic<long long> asked_{0}, outside_{0};
};

TEST(LabelledShadowBounds, RenderTheSameShadowsAsTheSweptBounds) {
  const Scene s = fast_lit_scene();
  const ResolvedScene r = resolve_scene(s);
  const Tracer labelled(r), swept(r, ShadowBounds::kSwept);
  const EmissionTable emission(r);
  const CheckedShadows checked(r, labelled);
  const Lighting through_labels(r, &checked), through_sweeps(r, &swept), unshadowed(r, nullptr);
  int shadowed = 0, lit = 0;
  for (int j = 0; j < s.camera.height; ++j)
    for (int i = 0; i < s.camera.width; ++i) {
      const Vec3 u = look_direction(r.camera, i + 0.5, j + 0.5);
      const LinearRgb a = radiance_along(r, emission, labelled, u, &through_labels, {0.3, 0.7});
      const LinearRgb b = radiance_along(r, emission, swept, u, &through_sweeps, {0.3, 0.7});
      const LinearRgb open = radiance_along(r, emission, labelled, u, &unshadowed, {0.3, 0.7});
      ASSERT_EQ(a.r, b.r) << i << ", " << j;
      ASSERT_EQ(a.g, b.g) << i << ", " << j;
      ASSERT_EQ(a.b, b.b) << i << ", " << j;
      lit += open.r > 0;
      shadowed += a.r < open.r * 0.9;
    }
  // The picture is lit and really shadowed, by rays of every light.
  EXPECT_GT(lit, s.camera.width * s.camera.height / 2);
  EXPECT_GT(shadowed, 60);
  EXPECT_GT(checked.asked(), 4 * lit / 2);
  EXPECT_EQ(checked.outside(), 0);
}

// Forwards to a tracer one ray at a time, and keeps the rays.
class RecordedShadows : public ShadowQuery {
 public:
  explicit RecordedShadows(const Tracer& tracer) : tracer_(tracer) {}
  void occluded(std::span<const ShadowRay> rays, std::span<bool> blocked) const override {
    for (std::size_t r = 0; r < rays.size(); ++r) {
      rays_.push_back(rays[r]);
      blocked[r] = tracer_.occluded(rays[r]);
    }
  }
  const std::vector<ShadowRay>& rays() const { return rays_; }

 private:
  const Tracer& tracer_;
  mutable std::vector<ShadowRay> rays_;
};

TEST(ShadowPackets, RaysAskedTogetherFindWhatEachFindsAlone) {
  const Scene s = fast_lit_scene();
  const ResolvedScene r = resolve_scene(s);
  const EmissionTable emission(r);
  for (const ShadowBounds bounds : {ShadowBounds::kLabelled, ShadowBounds::kSwept}) {
    const Tracer tracer(r, bounds);
    // The shadow rays of a picture, in the order its pixels ask them.
    const RecordedShadows recorded(tracer);
    const Lighting lighting(r, &recorded);
    for (int j = 0; j < s.camera.height; ++j)
      for (int i = 0; i < s.camera.width; ++i)
        radiance_along(r, emission, tracer, look_direction(r.camera, i + 0.5, j + 0.5), &lighting,
                       {0.3, 0.7});
    const std::vector<ShadowRay>& rays = recorded.rays();
    std::vector<char> alone(rays.size());
    std::set<int> lights;
    int blocked_alone = 0;
    for (std::size_t k = 0; k < rays.size(); ++k) {
      alone[k] = tracer.occluded(rays[k]);
      blocked_alone += alone[k];
      lights.insert(rays[k].light);
    }
    EXPECT_EQ(lights.size(), s.lights.size());
    EXPECT_GT(blocked_alone, 100);
    EXPECT_LT(blocked_alone, static_cast<int>(rays.size()) - 100);
    // All at once (many packets, rays of every light mixed), and in runs of awkward lengths.
    std::unique_ptr<bool[]> together(new bool[rays.size()]);
    tracer.occluded(rays, std::span(together.get(), rays.size()));
    std::unique_ptr<bool[]> runs(new bool[rays.size()]);
    for (std::size_t first = 0, length = 1; first < rays.size();
         first += length, length = length % 19 + 1) {
      const std::size_t count = std::min(length, rays.size() - first);
      tracer.occluded(std::span(rays).subspan(first, count), std::span(runs.get() + first, count));
    }
    for (std::size_t k = 0; k < rays.size(); ++k) {
      ASSERT_EQ(together[k], static_cast<bool>(alone[k])) << "ray " << k;
      ASSERT_EQ(runs[k], static_cast<bool>(alone[k])) << "ray " << k;
    }
  }
}

TEST(ShadowPackets, RenderedPixelsAreTheirRaysShadedAlone) {
  Scene s = fast_lit_scene();
  s.camera.samples = 1;
  const Image image = render_image(s, {});
  const ResolvedScene r = resolve_scene(s);
  const Tracer tracer(r);
  const EmissionTable emission(r);
  const Lighting lighting(r, &tracer);
  for (int j = 0; j < s.camera.height; ++j)
    for (int i = 0; i < s.camera.width; ++i) {
      const PixelSample ps = pixel_sample(i, j, 0, 1, 0, true);
      const LinearRgb c = radiance_along(
          r, emission, tracer, look_direction(r.camera, i + ps.x, j + ps.y), &lighting, ps.light);
      const std::size_t at = 3 * (static_cast<std::size_t>(j) * s.camera.width + i);
      ASSERT_EQ(image.rgb[at], static_cast<float>(c.r)) << i << ", " << j;
      ASSERT_EQ(image.rgb[at + 1], static_cast<float>(c.g)) << i << ", " << j;
      ASSERT_EQ(image.rgb[at + 2], static_cast<float>(c.b)) << i << ", " << j;
    }
}

TEST(LabelledShadowBounds, FixedEmissionEventsAreNotLabelled) {
  Scene s = fast_lit_scene();
  for (const LightSourceDelay mode : {LightSourceDelay::kCamera, LightSourceDelay::kNone}) {
    s.render.light_source_delay = mode;
    const ResolvedScene r = resolve_scene(s);
    for (std::size_t l = 0; l + 1 < s.lights.size(); ++l) EXPECT_FALSE(r.shadow_lights[l].labelled);
    EXPECT_TRUE(r.shadow_lights.back().labelled) << "a directional light's rays are waves";
  }
}

}  // namespace
}  // namespace lightcone
